"""Ship + gyro physics (ch. 3 §3.3, Eqs. 98-128) against independent truth.

Truths used: the general multibody engine (a second formulation, B-matrix route), conservation
of the total angular momentum, the exact first integral J_xx(phi) w1 = -n H sin(phi) of the
two-gyro roll equation, the damped linear oscillator, and the waves module's own elevation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import curve_fit

from mf_envs.frames import orthonormality_error
from mf_envs.physics.ship import (
    RPM,
    SEED_EFFECTS,
    GimbalDrive,
    GyroParams,
    ShipParams,
    WaveLoad,
    capacity_ratio,
    initial_state,
    pack_params,
    roll_inertia,
    seed_test_hull,
    simulate,
    simulate_engine,
    small_yacht,
    wave_table,
)
from mf_envs.physics.ship.drive import DriveParams

# parameters nobody tuned anything on (the seed used 1e6/1e9/1e10, 50 kg m^2, 8050 rpm)
HULL = ShipParams(inertia=(3.7e5, 2.2e6, 2.9e6))
GYRO = GyroParams(rotor_inertia=23.0, gimbal_inertia=4.0, rotor_speed=6130.0 * RPM)


@pytest.mark.parametrize("n_gyros", [1, 2])
def test_slope_law_peak_roll_rate(n_gyros):
    """Figs. 3-12/3-13: peak roll rate x J_roll / (J3 psi') = n sin(a) (2 sin a for the pair)."""
    ratios = []
    amps = np.array([0.15, 0.4, 0.7, 1.0, 1.3, 1.5])
    for a in amps:
        drive = GimbalDrive("sinusoidal", amplitude=a, frequency=1.0 / 7.0)
        run = simulate(pack_params(HULL, GYRO, n_gyros, SEED_EFFECTS, drive), 14.0, 0.01)
        j_roll = roll_inertia(0.0, HULL, GYRO, n_gyros)
        ratio = np.abs(run.omega[:, 0]).max() * j_roll / GYRO.angular_momentum
        ratios.append(ratio)
        assert ratio == pytest.approx(n_gyros * math.sin(a), rel=0.02)
    # the seed's fit f(a) = 2.003 sin(1.002 a) (two gyros): refit A sin(B a)
    (A, B), _ = curve_fit(lambda x, A, B: A * np.sin(B * x), amps, ratios, p0=(n_gyros, 1.0))
    assert A == pytest.approx(n_gyros, rel=0.01)
    assert B == pytest.approx(1.0, rel=0.01)


def test_two_gyro_first_integral():
    """Pair, no load: d/dt (J_xx(phi) w1) = -2 H phi' cos(phi) exactly -> J_xx w1 = -2 H sin phi."""
    drive = GimbalDrive("sinusoidal", amplitude=1.2, frequency=0.2)
    run = simulate(pack_params(HULL, GYRO, 2, SEED_EFFECTS, drive), 10.0, 0.005)
    jxx = np.array([roll_inertia(p, HULL, GYRO, 2) for p in run.phi])
    expected = -2.0 * GYRO.angular_momentum * np.sin(run.phi)
    np.testing.assert_allclose(jxx * run.omega[:, 0], expected, atol=1e-9 * GYRO.angular_momentum)
    assert np.abs(run.omega[:, 1:]).max() == 0.0  # the pair leaves pitch and yaw untouched


@pytest.mark.parametrize("n_gyros", [1, 2])
def test_fast_path_matches_engine(n_gyros):
    """Exact fast path == multibody engine (prescribed gimbal, external roll moment)."""
    drive = GimbalDrive("sinusoidal", amplitude=math.pi / 4, frequency=0.25)
    wave = WaveLoad(moment_amplitude=2.0e4, period=4.0)
    eff = SEED_EFFECTS + ("wave_moment",)
    fast = simulate(
        pack_params(HULL, GYRO, n_gyros, eff, drive, wave),
        6.0,
        0.004,
        *initial_state(0.0, (0.01, 0.02, -0.01)),
    )
    eng = simulate_engine(
        HULL, GYRO, n_gyros, eff, drive, 6.0, 0.004, wave, omega0=(0.01, 0.02, -0.01)
    )
    scale = np.abs(eng.omega).max()
    # engine loads are held over a step (midpoint wave moment): agreement is O(dt^2)
    assert np.abs(fast.omega - eng.omega).max() < 1e-5 * scale
    assert np.abs(fast.R - eng.R).max() < 5e-7  # both RKMK4 attitude updates


@pytest.mark.parametrize("n_gyros", [1, 2])
def test_seed_form_differences(n_gyros):
    """Seed's Eqs. 123-125 (frozen roll inertia) and 126-128 (2 J2^(2) slip): stated bounds."""
    ship, gyro = seed_test_hull()
    drive = GimbalDrive("sinusoidal", amplitude=math.pi / 2, frequency=0.1)
    runs = {
        form: simulate(pack_params(ship, gyro, n_gyros, SEED_EFFECTS, drive, form=form), 20.0, 0.01)
        for form in ("exact", "seed")
    }
    rel = (
        np.abs(runs["seed"].omega[:, 0] - runs["exact"].omega[:, 0]).max()
        / np.abs(runs["exact"].omega[:, 0]).max()
    )
    if n_gyros == 2:
        # J_xx(phi) - J_xx(0) = J3^(3) sin^2(phi) = 50 kg m^2 on 1e6: relative 5e-5 at most
        assert 1e-5 < rel < 6e-5
    else:
        assert rel < 1e-5


def test_angular_momentum_conserved_without_loads():
    """No external moment: R (J(phi) w + h) is constant in the inertial frame (single gyro)."""
    drive = GimbalDrive("sinusoidal", amplitude=1.0, frequency=0.3)
    y0, R0 = initial_state(0.1, (0.02, -0.01, 0.03))
    run = simulate(pack_params(HULL, GYRO, 1, SEED_EFFECTS, drive), 8.0, 0.002, y0, R0)
    d1 = GYRO.gimbal_inertia + GYRO.rotor_j1
    d3 = GYRO.gimbal_inertia + GYRO.rotor_inertia
    H = GYRO.angular_momentum
    L = []
    for w, R, phi, phid in zip(run.omega, run.R, run.phi, run.phi_rate):
        c, s = math.cos(phi), math.sin(phi)
        J = np.diag(HULL.inertia) + np.array(
            [
                [c * c * d1 + s * s * d3, 0, s * c * (d3 - d1)],
                [0, d1, 0],
                [s * c * (d3 - d1), 0, s * s * d1 + c * c * d3],
            ]
        )
        h = np.array([H * s, d1 * phid, H * c])
        L.append(R @ (J @ w + h))
    L = np.array(L)
    assert np.abs(L - L[0]).max() < 2e-5 * np.abs(L[0]).max()
    assert max(orthonormality_error(R) for R in run.R) < 1e-12


def test_free_decay_matches_damped_oscillator():
    """Rotor off, linear restoring + linear damping: roll = damped oscillator (closed form)."""
    ship = ShipParams(
        inertia=(4.0e4, 1.5e5, 1.6e5),
        added_roll_inertia=8.0e3,
        roll_stiffness=1.6e5,
        roll_damping=6.0e3,
    )
    eff = ("added_inertia", "hydrostatic_restoring", "roll_damping")
    P = pack_params(ship, GYRO, 1, eff, GimbalDrive("servo"))
    run = simulate(P, 10.0, 0.01, *initial_state(0.1))
    J = 4.8e4
    wn = math.sqrt(1.6e5 / J)
    zeta = 6.0e3 / (2.0 * math.sqrt(1.6e5 * J))
    wd = wn * math.sqrt(1 - zeta**2)
    exact = (
        0.1
        * np.exp(-zeta * wn * run.t)
        * (np.cos(wd * run.t) + zeta * wn / wd * np.sin(wd * run.t))
    )
    # small-angle roll: sin/tan nonlinearity of the attitude is O(0.1^3)
    assert np.abs(run.roll - exact).max() < 3e-4


def test_capacity_bound():
    """Above capacity 1 the residual roll cannot vanish; below it the gyro can cancel M0."""
    ship, gyro = seed_test_hull()
    w = 2 * math.pi / 10.0
    H = gyro.angular_momentum
    assert capacity_ratio(2 * H * w, H, w, 2, math.pi / 2) == pytest.approx(1.0)
    assert capacity_ratio(1e5, H, w, 2, math.pi / 3.6) > 1.0  # the seed's Fig. 3-11 case
    with pytest.raises(ValueError, match="n_gyros"):
        capacity_ratio(1.0, H, w, 3, 1.0)


def test_wave_table_matches_sea_slope():
    """Roll moment = C44 r slope, heave force = rho g A_wp eta, with eta from waves.IrregularSea."""
    from mf_envs.physics.waves import IrregularSea, jonswap_spectrum

    sea = IrregularSea(jonswap_spectrum, 0.6, 3.7, 32, np.random.default_rng(3))
    tab = wave_table(*sea.components, 1.5e5, 3.6e5, 20.0, 0.01, r_eff=0.7)
    t = np.arange(tab.shape[0]) * 0.01
    eta = sea.elevation(t, 0.0, 0.0)
    slope = (sea.elevation(t, 0.0, 1e-4) - sea.elevation(t, 0.0, -1e-4)) / 2e-4
    np.testing.assert_allclose(tab[:, 1], 3.6e5 * eta, atol=1e-9 * 3.6e5)
    np.testing.assert_allclose(tab[:, 0], 1.5e5 * 0.7 * slope, atol=1e-5 * 1.5e5)


def test_translation_heave_decouples():
    """Heave with restoring and damping: the CM height is the damped oscillator; attitude same."""
    ship = small_yacht()
    eff = SEED_EFFECTS + ("translation",)
    drive = GimbalDrive("sinusoidal", amplitude=0.5, frequency=0.3)
    y0, R0 = initial_state(0.0)
    y0[7] = 0.05  # heave 5 cm
    with_t = simulate(pack_params(ship, GYRO, 1, eff, drive), 5.0, 0.005, y0, R0)
    without = simulate(
        pack_params(ship, GYRO, 1, SEED_EFFECTS, drive), 5.0, 0.005, *initial_state()
    )
    np.testing.assert_allclose(with_t.omega, without.omega, atol=1e-14)
    m, k, c = ship.mass, ship.heave_stiffness, ship.heave_damping
    wn = math.sqrt(k / m)
    z = c / (2 * math.sqrt(k * m))
    wd = wn * math.sqrt(1 - z * z)
    t = with_t.t
    exact = 0.05 * np.exp(-z * wn * t) * (np.cos(wd * t) + z * wn / wd * np.sin(wd * t))
    assert np.abs(with_t.x[:, 2] - exact).max() < 1e-7


@pytest.mark.parametrize("n_gyros", [1, 2])
def test_hard_case_8050rpm_big_hull_gimbal_through_90(n_gyros):
    """Seed hull (J3 = 1e10 kg m^2), 8050 rpm, continuous gimbal (Eq. 118) through +-90 deg."""
    ship, gyro = seed_test_hull()
    drive = GimbalDrive("continuous", amplitude=math.pi / 2, frequency=0.1)
    run = simulate(pack_params(ship, gyro, n_gyros, SEED_EFFECTS, drive), 200.0, 0.01)
    assert np.all(np.isfinite(run.omega)) and np.all(np.isfinite(run.R))
    assert run.phi[-1] == pytest.approx(4 * (math.pi / 2) * 0.1 * 200.0)  # 20 gimbal turns
    assert max(orthonormality_error(R) for R in run.R[::100]) < 1e-12
    # roll rate stays the analytic -n H sin(phi) / J_xx(phi) (no secular growth)
    jxx = np.array([roll_inertia(p, ship, gyro, n_gyros) for p in run.phi])
    expected = -n_gyros * gyro.angular_momentum * np.sin(run.phi) / jxx
    assert np.abs(run.omega[:, 0] - expected).max() < 1e-3 * np.abs(expected).max()
    eng = simulate_engine(ship, gyro, n_gyros, SEED_EFFECTS, drive, 10.0, 0.01)
    assert np.all(np.isfinite(eng.omega))
    np.testing.assert_allclose(
        eng.omega[:, 0], run.omega[:1001, 0], atol=1e-6 * np.abs(expected).max()
    )


def test_bad_parameters_raise():
    with pytest.raises(ValueError, match="inertia"):
        ShipParams(inertia=(1.0, -2.0, 3.0))
    with pytest.raises(ValueError, match="rotor_inertia"):
        GyroParams(rotor_inertia=0.0)
    with pytest.raises(ValueError, match="mode"):
        GimbalDrive("wobble")
    with pytest.raises(ValueError, match="effects"):
        pack_params(HULL, GYRO, 1, ("gyroscopic", "warp_drive"), GimbalDrive())
    with pytest.raises(ValueError, match="n_gyros"):
        pack_params(HULL, GYRO, 3, None, GimbalDrive())
    with pytest.raises(ValueError, match="table_dt"):
        pack_params(HULL, GYRO, 1, ("irregular_waves",), GimbalDrive())


@pytest.mark.parametrize("n_gyros", [1, 2])
def test_free_gimbal_torque_drive_matches_engine(n_gyros):
    """Torque drive with no torque = free gimbals (phi-row of Eq. 74) == engine, 8050 rpm."""
    from mf_envs.physics.ship.engine import simulate_free_gimbal

    ship, gyro = seed_test_hull()
    P = pack_params(ship, gyro, n_gyros, SEED_EFFECTS, GimbalDrive("torque"))
    fast = simulate(P, 6.0, 0.01, *initial_state(0.0, (0.005, 0.0, 0.0)))
    eng = simulate_free_gimbal(ship, gyro, 6.0, 0.01, (0.005, 0.0, 0.0), n_gyros=n_gyros)
    assert np.abs(fast.phi).max() > 0.1  # the gimbal really nutates
    np.testing.assert_allclose(fast.phi, eng.phi, atol=1e-12)
    np.testing.assert_allclose(fast.omega, eng.omega, atol=1e-14)


def test_gimbal_damping_dissipates_kinetic_energy():
    """Passive gimbal with damping c_g: dK/dt = -n c_g phi'^2 (power balance, no other loads)."""
    ship = ShipParams(inertia=(2.0e5, 6.0e5, 7.0e5))
    drive = GimbalDrive("torque", machine=DriveParams("damper", damping=400.0))
    P = pack_params(ship, GYRO, 2, SEED_EFFECTS + ("gimbal_damping",), drive)
    dt = 0.002
    run = simulate(P, 6.0, dt, *initial_state(0.0, (0.02, 0.0, 0.0)))
    d1 = GYRO.gimbal_inertia + GYRO.rotor_j1
    d3 = GYRO.gimbal_inertia + GYRO.rotor_inertia
    s2 = np.sin(run.phi) ** 2
    jxx = ship.inertia[0] + 2 * (d1 * (1 - s2) + d3 * s2)
    # the gyroscopic couple does no net work (-2 H phi' cos(phi) w1 on the roll, +2 H cos(phi) w1
    # phi' on the gimbals), so hull-roll + gimbal kinetic energy only loses the damper power
    K = 0.5 * jxx * run.omega[:, 0] ** 2 + 0.5 * 2 * d1 * run.phi_rate**2
    dKdt = np.gradient(K, dt)
    expect = -2 * 400.0 * run.phi_rate**2
    scale = np.abs(expect).max()
    assert scale > 0
    np.testing.assert_allclose(dKdt[5:-5], expect[5:-5], atol=2e-3 * scale)


def test_mss_naval_vessel_roll_decay_matches_mss_model():
    """Preset vs the MSS navalvessel.m roll equation at zero speed (solve_ivp, rotor off)."""
    from scipy.integrate import solve_ivp

    from mf_envs.physics.ship import mss_naval_vessel

    ship = mss_naval_vessel()
    eff = ("added_inertia", "hydrostatic_restoring", "roll_damping", "quadratic_roll_damping")
    run = simulate(pack_params(ship, GYRO, 1, eff, GimbalDrive()), 20.0, 0.01, *initial_state(0.05))
    m = 357.0 * 1014.0

    def mss(t, x):  # (Ixx - Kpdot) p' = Kp p + Kpap p|p| + Kbbb b^3 - rho g GM V b
        b, p = x
        k = -5.0e5 * p - 4.16e5 * p * abs(p) - 0.325 * m * 9.81 * b**3
        k -= 1014.0 * 9.81 * 1.1 * 357.0 * b
        return [p, k / (2.3763e6 + 7.74e5)]

    ref = solve_ivp(mss, (0, 20.0), [0.05, 0.0], t_eval=run.t, rtol=1e-10, atol=1e-12)
    # the GZ curves differ at O(roll^3): wall-sided vs MSS's cubic term (< 0.5 % at 0.05 rad)
    assert np.abs(run.roll - ref.y[0]).max() < 0.01 * 0.05


@pytest.mark.slow
def test_translation_engine_matches_fast_path():
    """6-DOF hull on the engine (Free joint, gyros at offsets with mass) vs the fast path."""
    ship = small_yacht()
    eff = SEED_EFFECTS + ("translation", "hydrostatic_restoring", "roll_damping", "wave_moment")
    drive = GimbalDrive("sinusoidal", amplitude=0.5, frequency=0.3)
    wave = WaveLoad(5000.0, 3.7, heave_force=2.0e4)
    dt = 0.002
    y0, R0 = initial_state(0.05)
    y0[7] = 0.05
    fast = simulate(pack_params(ship, GYRO, 2, eff, drive, wave), 4.0, dt, y0, R0)
    eng = simulate_engine(
        ship,
        GYRO,
        2,
        eff,
        drive,
        4.0,
        dt,
        wave,
        roll0=0.05,
        heave0=0.05,
        gyro_mass=400.0,
        offset=(1.0, -0.5),
    )
    # composite CM fixed in the hull: sway to round-off; heave and roll agree to the engine's
    # O(dt) load error (7e-3 and 3e-3 relative at dt = 2 ms, halving with dt)
    assert np.abs(fast.x[:, 1] - eng.x[:, 1]).max() < 1e-12
    assert np.abs(fast.x[:, 2] - eng.x[:, 2]).max() < 0.015 * 0.05
    assert np.abs(fast.roll - eng.roll).max() < 0.006 * np.abs(fast.roll).max()


def test_hard_case_free_gimbal_flips_through_90_at_8050rpm():
    """Free gimbal at 8050 rpm on the seed hull, released at 0.05 rad/s roll: the gimbal swings
    through +-90 deg (cos(phi) -> 0 in the gyro moment) without blow-up; fast == engine."""
    from mf_envs.physics.ship.engine import simulate_free_gimbal

    ship, gyro = seed_test_hull()
    P = pack_params(ship, gyro, 1, SEED_EFFECTS, GimbalDrive("torque"))
    fast = simulate(P, 30.0, 0.01, *initial_state(0.0, (0.05, 0.0, 0.0)))
    assert np.abs(fast.phi).max() > math.pi / 2
    assert np.all(np.isfinite(fast.omega)) and np.all(np.isfinite(fast.phi))
    eng = simulate_free_gimbal(ship, gyro, 5.0, 0.01, (0.05, 0.0, 0.0))
    np.testing.assert_allclose(fast.phi[:501], eng.phi, atol=1e-10)
