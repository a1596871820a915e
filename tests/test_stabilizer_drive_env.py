"""GyroStabilizer-v0 with the torque-limited drive, heading and speed, hulls (issue 15).

Truths: the encounter-frequency formula (the roll answers at w_e, not w), scipy's DOP853 roll
decay of the MSS naval vessel with MSS's coefficients, the drive's limits, and the RK4 step
bound (`ship.step_bound.stable_physics_dt`).
"""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401
from mf_envs.physics.ship import GimbalDrive, GyroParams, initial_state, pack_params, simulate
from mf_envs.physics.ship.hulls import Hull, roll_decay
from mf_envs.physics.ship.seas import G

ENV_ID = "GyroStabilizer-v0"


def _actions(pattern: str, rng: np.random.Generator, n: int) -> np.ndarray:
    if pattern == "bang":  # full command, switching at random dwell times
        out, sign, k = np.empty(n), 1.0, 0
        while k < n:
            m = int(rng.integers(1, 40))
            out[k : k + m], sign, k = sign, -sign, k + m
        return out
    if pattern == "chatter":
        return np.where(np.arange(n) % 2 == 0, 1.0, -1.0)
    return rng.uniform(-1.0, 1.0, n)


@pytest.mark.parametrize("pattern", ["bang", "chatter", "random"])
def test_drive_survives_20_seeds_at_defaults(pattern):
    """The seed preset's electric drive (issue 15's default); the Seakeeper preset's unit:
    tests/test_stabilizer_unit.py."""
    env = gym.make(ENV_ID, preset="seed")
    drive = env.unwrapped.drive.machine
    failures = 0
    for seed in range(20):
        env.reset(seed=seed)
        acts = _actions(pattern, np.random.default_rng(seed), 600)
        for a in acts:
            _, r, term, _, info = env.step(np.array([a], np.float32))
            failures += int(info["numerical_failure"] or term or not math.isfinite(r))
            assert abs(info["drive_torque"]) <= drive.max_torque + 1e-9
            assert info["drive_power"] <= drive.max_power * (1 + 1e-9)
            assert abs(info["gimbal_angle"]) <= drive.max_angle + 1e-12
            assert info["drive_energy"] >= 0.0
    assert failures == 0


def test_encounter_frequency_heading_45_deg_at_5_m_s():
    """A regular wave met at beta = 45 deg, U = 5 m/s rolls the (gyro-off) hull at
    w_e = w - w^2 U cos(beta) / g, not at w: least-squares frequency of the steady roll."""
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS

    eff = tuple(e for e in DEFAULT_EFFECTS if e != "gyroscopic")
    T, U, beta = 6.0, 5.0, math.pi / 4
    env = gym.make(ENV_ID, effects=eff, wave_period=T, heading=beta, ship_speed=U,
                   episode_seconds=200.0, max_episode_steps=4000)  # fmt: skip
    env.reset(seed=0)
    t, roll = [], []
    for _ in range(4000):
        info = env.step(np.zeros(1, np.float32))[4]
        t.append(info["time"])
        roll.append(info["roll"])
    t, roll = np.array(t)[2000:], np.array(roll)[2000:]  # 100 s of transient left out
    w = 2 * math.pi / T
    we = w - w * w * U * math.cos(beta) / G
    grid = np.linspace(0.3, 1.6, 2601)
    power = [
        np.linalg.lstsq(np.c_[np.cos(g * t), np.sin(g * t)], roll, rcond=None)[1] for g in grid
    ]
    best = grid[int(np.argmin(power))]
    assert best == pytest.approx(we, abs=2e-3)
    assert abs(best - w) > 0.3  # clearly not the wave's own frequency


def test_mss_decay_kernel_matches_mss_coefficients():
    """Ship kernel (3-DOF rotation, rotor stopped) vs the 1-DOF MSS roll decay by DOP853:
    (I_xx - K_pdot) p' = K_p p + K_|p|p |p| p - rho g GM V phi + K_phiphiphi phi^3."""
    hull = Hull.mss_naval_vessel()
    eff = ("added_inertia", "hydrostatic_restoring", "roll_damping", "quadratic_roll_damping")
    tiny = GyroParams(rotor_inertia=1e-12, gimbal_inertia=0.0)  # no gyro inertia on the roll
    P = pack_params(hull.ship_params(), tiny, 1, eff, GimbalDrive(), None, "exact", 0.0,
                    hull.gz_cubic)  # fmt: skip
    run = simulate(P, 30.0, 0.01, *initial_state(0.4))
    t, ref = roll_decay(hull, 0.4, 30.0, 3001)
    assert np.abs(run.roll).max() == pytest.approx(0.4)
    np.testing.assert_allclose(run.roll, ref, atol=1e-8)


def test_hull_kwargs_reach_every_field():
    """A hull set completely (Hull) and the same hull by kwargs roll identically; a preset
    name (its sway-roll-yaw coupling off, the Hull carries none) and a dict of fields too."""
    h = Hull.mss_naval_vessel()
    # the same gyros for all three (the Seakeeper preset picks its units by the hull's name)
    gyros = dict(rotor_inertia=50.0, gimbal_inertia=50.0, rotor_speed=600.0, n_gyros=1)
    a = gym.make(ENV_ID, hull=h, wave_moment_amplitude=2e5, **gyros)
    b = gym.make(ENV_ID, hull="mss_naval_vessel", coupling=False, wave_moment_amplitude=2e5,
                 units_per_gyro=1, **gyros)  # fmt: skip
    c = gym.make(ENV_ID, hull={f: getattr(h, f) for f in h.__dataclass_fields__},
                 wave_moment_amplitude=2e5, **gyros)  # fmt: skip
    outs = []
    for env in (a, b, c):
        env.reset(seed=3)
        outs.append([env.step(np.ones(1, np.float32))[0] for _ in range(50)])
    np.testing.assert_array_equal(outs[0], outs[1])
    np.testing.assert_array_equal(outs[0], outs[2])
    assert a.unwrapped.wave_period == pytest.approx(h.natural_roll_period())
    with pytest.raises(ValueError, match="hull"):
        gym.make(ENV_ID, hull={"mass": 1.0, "teleport": 2.0})


def test_kinematic_servo_kept_for_the_seed_scenes():
    env = gym.make(ENV_ID, gimbal_drive="kinematic")
    env.reset(seed=0)
    info = env.step(np.ones(1, np.float32))[4]
    assert env.unwrapped.drive.mode == "servo" and "drive_torque" in info
    assert gym.make(ENV_ID, gimbal_drive="servo").unwrapped.gimbal_drive == "kinematic"


def test_short_crested_sea_excites_less_roll():
    """Same seed: the cos-2s spread turns components away from the beam (|sin beta| < 1), so
    the roll-moment variance met by the ship falls (the frequencies and phases are shared)."""
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS

    eff = tuple(e for e in DEFAULT_EFFECTS if e != "wave_moment") + ("irregular_waves",)
    var = {}
    for s in (None, 2.0):
        env = gym.make(ENV_ID, effects=eff, wave_spreading=s)
        env.reset(seed=4)
        var[s] = float(np.var(env.unwrapped._tab[:, 0]))
    assert 0.3 * var[None] < var[2.0] < 0.95 * var[None]


def _navalvessel_reference(c, U, ts, x0, roll_moment=lambda t: 0.0):
    """navalvessel.m's sway-roll-yaw equations in MSS axes (x fwd, y stbd, z down), surge held
    at U, integrated by scipy's DOP853 from x0 = (v, p, r, phi) at the times ts; roll_moment(t)
    (N m) is an extra roll moment (a prescribed gyro's). Returns the (4, len(ts)) solution."""
    from scipy.integrate import solve_ivp

    m, xg, zg, g, rho = c.mass, c.x_g, c.z_g, 9.81, 1014.0
    M = np.array([
        [m - c.y_vdot, -(m * zg + c.y_pdot), m * xg - c.y_rdot],
        [-(m * zg + c.k_vdot), 2.3763e6 - (-7.74e5), -c.k_rdot],
        [m * xg - c.n_vdot, -c.n_pdot, 47.934e6 - c.n_rdot],
    ])  # fmt: skip

    def rhs(t, x):  # navalvessel.m with u = U (surge held), phi' = p
        v, p, r, b = x
        au, av, ar, ap = U, abs(v), abs(r), abs(p)
        Y = (c.y_auv * au * v + c.y_ur * U * r + c.y_vav * v * av + c.y_var * v * ar
             + c.y_rav * r * av + c.y_bauv * b * abs(U * v) + c.y_baur * b * abs(U * r)
             + c.y_buu * b * U**2 - m * U * r)  # fmt: skip
        Kx = (c.k_auv * au * v + c.k_ur * U * r + c.k_vav * v * av + c.k_var * v * ar
              + c.k_rav * r * av + c.k_bauv * b * abs(U * v) + c.k_baur * b * abs(U * r)
              + c.k_buu * b * U**2 - 15500.0 * au * p - 416000.0 * p * ap - 500000.0 * p
              - 0.325 * m * g * b**3 - rho * g * 1.1 * 357.0 * b + m * zg * U * r
              + roll_moment(t))  # fmt: skip
        N = (c.n_auv * au * v + c.n_aur * au * r + c.n_rar * r * ar + c.n_rav * r * av
             + c.n_bauv * b * abs(U * b) + c.n_buar * b * U * ar + c.n_buau * b * U * au
             - m * xg * U * r)  # fmt: skip
        acc = np.linalg.solve(M, [Y, Kx, N])
        return [acc[0], acc[1], acc[2], p]

    t_end = float(ts[-1])
    return solve_ivp(rhs, (0, t_end), x0, "DOP853", ts, rtol=1e-11, atol=1e-13).y


def _mss_coupled_params(gyro, n_gyros, drive, extra_effects=()):
    """Packed parameters of the MSS naval vessel at U = 8 m/s with the coupling on (the hull's
    MSS roll damping 5e5 + 1.55e4 U), and U."""
    from mf_envs.physics.ship.coupling import SwayRollYaw

    U = 8.0
    hull = Hull.mss_naval_vessel()
    ship = hull.ship_params()
    ship = ship.__class__(**{**ship.__dict__, "roll_damping": 5.0e5 + 1.55e4 * U})
    c = SwayRollYaw.mss_naval_vessel()
    eff = ("added_inertia", "hydrostatic_restoring", "roll_damping", "quadratic_roll_damping")
    eff += tuple(extra_effects)
    P = pack_params(ship, gyro, n_gyros, eff, drive, None, "exact", 0.0, hull.gz_cubic, c, U)
    return P, c, U


def test_sway_yaw_coupling_matches_navalvessel_equations():
    """Kernel (3-D rotation + sway, rotor stopped) vs navalvessel.m's sway-roll-yaw equations in
    MSS axes (x fwd, y stbd, z down) by DOP853, at U = 8 m/s from v = 0.5 m/s, r = 0.02 rad/s,
    roll 0.1 rad: roll, yaw rate and sway velocity (ours: v = -v_MSS, r = -r_MSS)."""
    from mf_envs.physics.ship import kernels as K

    tiny = GyroParams(rotor_inertia=1e-12, gimbal_inertia=0.0)
    P, c, U = _mss_coupled_params(tiny, 1, GimbalDrive())
    y, R = initial_state(0.1, (0.0, 0.0, -0.02))
    y[K.V_STATE] = -0.5
    t_end, dt = 20.0, 0.005
    ts, ys, Rs, _ = K.simulate_kernel(y, R, t_end, dt, P, np.zeros((1, 2)))
    roll = np.arctan2(Rs[:, 2, 1], Rs[:, 2, 2])
    ref = _navalvessel_reference(c, U, ts, [0.5, 0.0, 0.02, 0.1])
    assert np.abs(ys[:, K.V_STATE]).max() > 0.1 and np.abs(roll).max() == pytest.approx(0.1)
    np.testing.assert_allclose(-ys[:, K.V_STATE], ref[0], atol=2e-3 * 0.5)
    np.testing.assert_allclose(roll, ref[3], atol=2e-3 * 0.1)
    # yaw: the kernel's 3-D rigid body (pitch, Euler products w1 w2) is absent from the planar
    # navalvessel.m; they differ by 0.2 % of the initial yaw rate
    np.testing.assert_allclose(-ys[:, 2], ref[2], atol=5e-3 * 0.02)


def test_prescribed_gimbal_keeps_sway_yaw_coupling():
    """A prescribed gimbal (Eq. 119, phi = a sin(2 pi f t), a counter-rotating pair) on the
    coupled MSS vessel: the sway still evolves (it was held at its initial value) and roll,
    sway and yaw follow navalvessel.m's equations with the pair's roll moment -2 H phi' cos phi
    (Eq. 123) added, by DOP853 (gyro inertia 1e-6 of the hull's: the 3-D terms are small)."""
    from mf_envs.physics.ship import kernels as K

    gyro = GyroParams(rotor_inertia=1.0, gimbal_inertia=0.0, rotor_speed=1.0e5)  # H = 1e5 N m s
    a, f = 0.5, 0.2
    drive = GimbalDrive("sinusoidal", amplitude=a, frequency=f)
    P, c, U = _mss_coupled_params(gyro, 2, drive, ("gyroscopic",))
    y, R = initial_state(0.05, (0.0, 0.0, -0.02))
    y[K.V_STATE] = -0.5
    t_end, dt = 20.0, 0.005
    ts, ys, Rs, _ = K.simulate_kernel(y, R, t_end, dt, P, np.zeros((1, 2)))
    roll = np.arctan2(Rs[:, 2, 1], Rs[:, 2, 2])
    w = 2.0 * math.pi * f
    h = gyro.angular_momentum

    def gyro_moment(t):  # Eq. 123 for the pair
        return -2.0 * h * a * w * math.cos(w * t) * math.cos(a * math.sin(w * t))

    ref = _navalvessel_reference(c, U, ts, [0.5, 0.0, 0.02, 0.05], gyro_moment)
    np.testing.assert_allclose(ys[:, 3], a * np.sin(w * ts), atol=1e-12)  # the prescription
    assert np.ptp(ys[:, K.V_STATE]) > 0.1 and np.abs(roll).max() > 0.05
    np.testing.assert_allclose(-ys[:, K.V_STATE], ref[0], atol=2e-3 * 0.5)
    np.testing.assert_allclose(roll, ref[3], atol=2e-3 * np.abs(ref[3]).max())
    np.testing.assert_allclose(-ys[:, 2], ref[2], atol=5e-3 * 0.02)
