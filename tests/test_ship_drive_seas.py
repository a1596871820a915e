"""Gimbal drive machine, seas with heading and speed, hulls (issue 15) against independent truth.

Truths: python-control / scipy.signal step responses of the PI loop's transfer function, RK4's
amplification factor on the linearised system (the dt bound is tight), the general wave field
of `physics.waves` evaluated at the moving ship (encounter frequency, length averaging), the
normalisation and second moment of the cos-2s law, the JONSWAP variance Hs^2/16, navalvessel.m's
restoring formula, and the energy-balance decrement of a linear + quadratic damped roll.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy import signal
from scipy.integrate import quad

from mf_envs.physics.ship import drive as DR
from mf_envs.physics.ship import seas as S
from mf_envs.physics.ship import step_bound as SB
from mf_envs.physics.ship.hulls import Hull, roll_decay
from mf_envs.physics.waves import WaveField

JG, JROLL, H = 14.3, 55_000.0, 9000.0  # gimbal, hull roll inertia (kg m^2), H (N m s)
PLANT = SB.RollGimbal(JG, JROLL, H, 1, 158_922.0, 7480.0)


def _roll_gimbal_rhs(x, u, D, hull_c, hull_b, n=1):
    """Nonlinear 1-DOF roll + gimbal + loop integral x = [r, p, phi, phid, z] (test harness)."""
    r, p, phi, phid, z = x
    g = H * p * math.cos(phi)
    tau, dz = DR.drive_torque(phi, phid, z, u, g, 0.0, math.cos(r), n, D)
    pd = (-hull_c * math.sin(r) - hull_b * p - n * H * phid * math.cos(phi)) / JROLL
    return np.array([p, pd, phid, (g + tau) / JG, dz]), tau


def _rk4(x, u, dt, D, c=158_922.0, b=7480.0):
    k1, tau = _roll_gimbal_rhs(x, u, D, c, b)
    k2, _ = _roll_gimbal_rhs(x + 0.5 * dt * k1, u, D, c, b)
    k3, _ = _roll_gimbal_rhs(x + 0.5 * dt * k2, u, D, c, b)
    k4, _ = _roll_gimbal_rhs(x + dt * k3, u, D, c, b)
    x = x + dt * (k1 + 2 * k2 + 2 * k3 + k4) / 6.0
    phi, phid, _ = DR.end_stop(x[2], x[3], D[DR.DPHIMAX])
    x[2], x[3] = phi, phid
    return x, tau


def test_machine_envelope_never_exceeded():
    d = DR.electric_drive(H)
    D = d.pack(JG)
    rng = np.random.default_rng(0)
    for tau, w in zip(rng.normal(0, 5e3, 20000), rng.normal(0, 3.0, 20000)):
        t = DR.machine_limit(tau, w, D)
        assert abs(t) <= d.max_torque + 1e-9
        if t * w > 0:  # motoring: power and speed limits
            assert t * w <= d.max_power + 1e-9
            assert abs(w) <= 1.1 * d.max_rate
    Db = dataclasses.replace(d, kind="brake").pack(JG)
    for tau, w in zip(rng.normal(0, 5e3, 5000), rng.normal(0, 3.0, 5000)):
        assert DR.machine_limit(tau, w, Db) * w <= 0.0  # a brake never supplies power


def test_rate_loop_matches_its_transfer_function():
    """Free gimbal (no hull), no saturation: phi'/u = (K_p s + K_i) / (J_g s^2 + K_p s + K_i)."""
    d = DR.DriveParams(max_torque=1e9, max_power=1e12, max_rate=10.0, stop_time=1e-3)
    D = d.pack(JG)
    kp, ki = d.gains(JG)
    t = np.linspace(0.0, 0.5, 501)
    _, ref = signal.step(signal.lti([kp, ki], [JG, kp, ki]), T=t)
    x = np.zeros(2)  # [phid, z]
    out = [0.0]
    dt, u = t[1] - t[0], 0.3
    for _ in t[1:]:

        def f(s):
            tau, dz = DR.drive_torque(0.0, s[0], s[1], u, 0.0, 0.0, 1.0, 1, D)
            return np.array([tau / JG, dz])

        k1 = f(x)
        k2 = f(x + 0.5 * dt * k1)
        k3 = f(x + 0.5 * dt * k2)
        k4 = f(x + dt * k3)
        x = x + dt * (k1 + 2 * k2 + 2 * k3 + k4) / 6
        out.append(x[0])
    np.testing.assert_allclose(np.array(out), u * ref, atol=1e-6)


@pytest.mark.parametrize("kind", ["electric", "damper", "spring"])
def test_stable_dt_bound_is_tight(kind):
    """RK4 on the linearised system: decays just below the bound, grows just above it."""
    d = DR.DriveParams(kind, damping=900.0 if kind != "electric" else 0.0, stiffness=2e4)
    D = d.pack(JG)
    h = SB.stable_physics_dt(D, PLANT)
    A = SB.roll_gimbal_matrix(D, PLANT, False)
    lam = np.linalg.eigvals(A)
    assert np.all(lam.real <= 1e-12)
    for s, grows in ((0.97, False), (1.03, True)):
        amp = SB.rk4_amplification(s * h * lam).max()
        if d.active:  # the bound may come from the saturated matrix
            As = SB.roll_gimbal_matrix(D, PLANT, True)
            amp = max(amp, SB.rk4_amplification(s * h * np.linalg.eigvals(As)).max())
        assert (amp > 1.0) == grows


@pytest.mark.parametrize("pattern", ["bang", "chatter", "random"])
def test_drive_survives_any_action_sequence(pattern):
    """Nonlinear roll + gimbal at half the stable step, 60 s of adversarial commands: finite,
    torque and power within the limits, gimbal inside its stops."""
    d = DR.electric_drive(H)
    D = d.pack(JG)
    dt = 0.5 * SB.stable_physics_dt(D, PLANT)
    rng = np.random.default_rng(3)
    x = np.array([0.3, 0.0, 0.0, 0.0, 0.0])
    for k in range(int(60.0 / dt)):
        if pattern == "bang":
            u = d.max_rate * (1.0 if (k * dt) % 7.0 < 3.5 else -1.0)
        elif pattern == "chatter":
            u = d.max_rate * (-1.0) ** k
        else:
            u = rng.uniform(-1.0, 1.0) * d.max_rate
        rate = x[3]  # the rate at which the stage-1 torque acts
        x, tau = _rk4(x, u, dt, D)
        assert np.all(np.isfinite(x))
        assert abs(tau) <= d.max_torque + 1e-9
        assert tau * rate <= d.max_power * (1 + 1e-9)
        assert abs(x[2]) <= d.max_angle + 1e-12


def test_end_stop_is_inelastic():
    assert DR.end_stop(1.2, 0.5, 1.0) == (1.0, 0.0, -0.5)
    assert DR.end_stop(1.2, -0.5, 1.0) == (1.0, -0.5, 0.0)  # moving back inside: untouched
    assert DR.end_stop(-1.3, -2.0, 1.0) == (-1.0, 0.0, 2.0)


def test_pendulum_torque_is_gravity_about_the_axis():
    """m g l (cos phi R31 - sin phi R33) = e_2 . (p x f) with p = R_2(phi) (0, 0, -l)."""
    rng = np.random.default_rng(1)
    for _ in range(20):
        phi, pitch, roll = rng.uniform(-1, 1, 3)
        cp, sp, cr, sr = math.cos(pitch), math.sin(pitch), math.cos(roll), math.sin(roll)
        R = np.array([[cp, sp * sr, sp * cr], [0, cr, -sr], [-sp, cp * sr, cp * cr]])  # Ry Rx
        grav = R.T @ np.array([0.0, 0.0, -9.81 * 2.0])  # m = 2 kg in the ship frame
        p = np.array([math.sin(phi), 0.0, math.cos(phi)]) * -0.3
        ref = np.cross(p, grav)[1]
        assert DR.pendulum_torque(phi, R[2, 0], R[2, 2], 2.0 * 9.81 * 0.3, 1) == pytest.approx(
            ref, abs=1e-12
        )


# ---------------------------------------------------------------------- seas
def test_encounter_frequency_formula():
    w = np.array([0.5, 1.0, 1.5])
    we = S.encounter_frequency(w, 5.0, math.radians(45.0))
    np.testing.assert_allclose(we, w - w**2 * 5.0 * math.cos(math.pi / 4) / S.G, rtol=1e-15)
    assert S.encounter_frequency(1.0, 5.0, math.pi)[()] > 1.0  # head sea: met more often
    assert S.encounter_frequency(1.0, 5.0, 0.0)[()] < 1.0  # following sea


@pytest.mark.parametrize("heading_deg", [45.0, 90.0, 120.0])
def test_roll_moment_is_the_slope_met_by_the_moving_ship(heading_deg):
    """Table vs the general wave field sampled at the ship's position x1 = U t: transverse slope
    by central differences, averaged over the waterline length, times C44 r_eff."""
    beta, U, L, c44, r = math.radians(heading_deg), 5.0, 20.0, 1e6, 0.8
    sea = S.SeaComponents(
        np.array([0.4, 0.2]), np.array([0.8, 1.3]), np.full(2, beta), np.array([0.3, 2.0])
    )
    field = WaveField(sea.amplitudes, sea.omegas, sea.phases, sea.omegas**2 / S.G, beta)
    h = 0.01
    tab = S.excitation_table(sea, U, c44, 0.0, L, 3.0, 20.0, h, r)
    t = np.arange(0.0, 20.0, 0.37)
    xb = np.linspace(-L / 2, L / 2, 4001)[:, None]
    dy = 1e-4
    slope = (field.elevation(t, U * t + xb, dy) - field.elevation(t, U * t + xb, -dy)) / (2 * dy)
    ref = c44 * r * np.trapezoid(slope, xb[:, 0], axis=0) / L
    idx = np.rint(t / h).astype(int)
    np.testing.assert_allclose(tab[idx, 0], ref, atol=2e-6 * np.abs(ref).max())


def test_regular_roll_moment_doppler_and_heading():
    amp, we = S.regular_roll_moment(8000.0, 3.7, math.radians(45.0), 5.0, 11.5)
    w = 2 * math.pi / 3.7
    assert we == pytest.approx(w - w * w * 5.0 * math.cos(math.pi / 4) / S.G, rel=1e-14)
    k = w * w / S.G
    x = 0.5 * k * 11.5 * math.cos(math.pi / 4)
    assert amp == pytest.approx(8000.0 * math.sin(math.pi / 4) * math.sin(x) / x, rel=1e-12)
    assert S.regular_roll_moment(8000.0, 3.7, math.pi / 2, 0.0, 11.5) == (8000.0, w)
    assert abs(S.regular_roll_moment(8000.0, 3.7, math.pi, 5.0, 11.5)[0]) < 1e-9  # head sea


@pytest.mark.parametrize("s", [1.0, 2.0, 7.5])
def test_cos2s_spreading(s):
    total, _ = quad(lambda th: float(S.spreading_density(th, s)), -math.pi / 2, math.pi / 2)
    assert total == pytest.approx(1.0, abs=1e-9)
    th = S.sample_spreading(s, 40000, np.random.default_rng(2))
    assert np.all(np.abs(th) <= math.pi / 2)
    # E[cos^2] = int cos^(2s+2) / int cos^(2s) = (s + 1/2) / (s + 1)
    assert np.mean(np.cos(th) ** 2) == pytest.approx((s + 0.5) / (s + 1.0), abs=0.004)


def test_jonswap_sea_variance_and_spreading():
    rng = np.random.default_rng(5)
    sea = S.jonswap_sea(1.2, 4.0, math.pi / 2, rng, n_components=400)
    assert np.sum(sea.amplitudes**2) / 2 == pytest.approx(1.2**2 / 16, rel=0.03)
    assert np.all(sea.headings == math.pi / 2)
    short = S.jonswap_sea(1.2, 4.0, math.pi / 2, np.random.default_rng(5), 400, spreading=2.0)
    assert np.std(short.headings) > 0.2
    # short-crested beam sea excites less roll than long-crested (sin beta < 1)
    g_long = np.sum(S.roll_moment_gains(sea, 1e6, 11.5) ** 2)
    g_short = np.sum(S.roll_moment_gains(short, 1e6, 11.5) ** 2)
    assert g_short < g_long


# ---------------------------------------------------------------------- hulls
def test_mss_restoring_is_navalvessel_formula():
    hull = Hull.mss_naval_vessel()
    m = 1014.0 * 357.0
    phi = np.linspace(-0.6, 0.6, 13)
    ref = -(1014.0 * 9.81 * 1.1 * 357.0) * phi + (-0.325 * m * 9.81) * phi**3
    np.testing.assert_allclose(hull.restoring_moment(phi), ref, rtol=1e-13, atol=1e-6)


def test_roll_stiffness_keeps_gz_consistent():
    for hull in (Hull.yacht(), Hull.mss_naval_vessel()):
        new = dataclasses.replace(hull, roll_stiffness=2.0 * hull.roll_stiffness)
        eps = 1e-6
        slope = -(new.restoring_moment(eps) - new.restoring_moment(-eps)) / (2 * eps)
        assert slope == pytest.approx(new.roll_stiffness, rel=1e-9)
        ratio = new.restoring_moment(0.4) / hull.restoring_moment(0.4)
        assert ratio == pytest.approx(2.0, rel=1e-12)  # same GZ shape


def test_every_field_is_the_users():
    with pytest.raises(TypeError):
        Hull(mass=1.0)  # no silent preset values
    with pytest.raises(ValueError, match="roll_damping_quadratic"):
        dataclasses.replace(Hull.yacht(), roll_damping_quadratic=-1.0)


def test_mss_decay_matches_energy_balance_decrement():
    """Peaks of the DOP853 decay vs d(phi)/cycle = -(pi B w phi + 8/3 Bq w^2 phi^2) / C,
    linear restoring (gz_cubic 0) so w is exact; small damping so the balance is accurate."""
    hull = dataclasses.replace(Hull.mss_naval_vessel(), gz_cubic=0.0)
    j = hull.inertia[0] + hull.added_roll_inertia
    w = math.sqrt(hull.roll_stiffness / j)
    t, r = roll_decay(hull, 0.3, 6 * 2 * math.pi / w, 60001)
    peaks = [r[i] for i in range(1, len(r) - 1) if r[i - 1] < r[i] > r[i + 1]]
    amps = np.array([r[0]] + peaks)
    dec = -np.diff(amps)
    mid = 0.5 * (amps[1:] + amps[:-1])
    model = (
        math.pi * hull.roll_damping * w * mid
        + 8.0 / 3.0 * hull.roll_damping_quadratic * w * w * mid**2
    ) / hull.roll_stiffness
    np.testing.assert_allclose(dec, model, rtol=0.06)
