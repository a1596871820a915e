"""GyroStabilizer-v0's default device (issue 30): a Seakeeper Model 7000 on the 18 t yacht, its
hydraulic brake (no motoring, the precession-rate cap), cushioned stops, the mount moment and
rotor power in the info, the sizing of the MSS vessel's units, the Ikeda hull damping.

The acceptance stress test (`test_unit_holds_its_limits_under_abusive_actions`): 20 seeds each of
bang-bang, chatter and random actions on the default scene and in JONSWAP Hs 1.5 m (Tp 5 s): the
precession rate never exceeds the cap by more than 10 %, the gimbal never passes the cushion's
travel, no numerical failure, the mount moment below the documented bound
(`ship.unit.unit_drive`). Stepped on the native vector env (20 rows, one per seed), which equals
the single env bit for bit (tests/test_vector_envs.py).
"""

from __future__ import annotations

import math
import warnings

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401
from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS
from mf_envs.envs.gyro_stabilizer.build import CUSHION_START, CUSHION_TRAVEL
from mf_envs.physics.ship import seakeeper as SK
from mf_envs.physics.ship.brake import BrakeParams, stop_torque
from mf_envs.physics.ship.drive import cushion_torque
from mf_envs.physics.ship.hulls import YACHT_IKEDA, Hull, yacht_ikeda_damping
from mf_envs.physics.ship.roll_damping import HullParticulars, roll_damping

ENV_ID = "GyroStabilizer-v0"
IRREGULAR = (*DEFAULT_EFFECTS, "irregular_waves")
HS15 = {"effects": IRREGULAR, "significant_wave_height": 1.5, "wave_period": 5.0}


def _actions(pattern: str, rng: np.random.Generator, n: int) -> np.ndarray:
    """bang: +-1 held for 1-40 steps at random; chatter: +-1 alternating every step;
    random: uniform in [-1, 1]."""
    if pattern == "chatter":
        return np.where(np.arange(n) % 2 == 0, 1.0, -1.0)
    if pattern == "random":
        return rng.uniform(-1.0, 1.0, n)
    out: list[float] = []
    s = 1.0
    while len(out) < n:
        out += [s] * int(rng.integers(1, 41))
        s = -s
    return np.array(out[:n])


def test_default_is_a_seakeeper_7000_on_a_boat_it_is_sold_for():
    env = gym.make(ENV_ID).unwrapped
    unit = SK.SEAKEEPER_7000
    assert env.preset == "seakeeper_7000" and env.unit_name == unit.name
    # Seakeeper's theory page: J = 6.7 kg m^2 at 10,000 rpm
    assert env.gyro.rotor_inertia == pytest.approx(6.7, rel=1e-12)
    assert env.gyro.rotor_speed * 60 / (2 * math.pi) == pytest.approx(10_000.0, rel=1e-12)
    assert env.angular_momentum == pytest.approx(7016.2, abs=0.1)
    lo, hi = unit.displacement_range  # 35,000-55,000 lb (one gyro), sizing page
    assert lo <= env.hull.mass <= hi
    # the manual's +-60 deg precession is the end of the cushion's travel
    assert CUSHION_START + CUSHION_TRAVEL == pytest.approx(unit.max_precession, rel=1e-12)
    assert env.max_gimbal_angle == pytest.approx(CUSHION_START)
    m = env.drive.machine
    assert m.kind == "brake" and m.rate_cap == env.max_precession_rate
    assert m.stop_stiffness > 0 and m.stop_damping > 0
    assert env.rotor_power == 2000.0 and env.hull_damping == "ikeda"
    # physics_dt: two RK4 steps per 0.05 s control step with the cushion's stiffness in
    assert env.n_substeps == 2 and env.physics_dt <= env.scene.dt_max
    assert 0.5 <= SK.capacity(unit, env.hull, max_precession_rate=2.0) <= 2.0


def test_electric_option_sized_for_the_design_roll_rate():
    env = gym.make(ENV_ID, gimbal_drive="electric").unwrapped
    m, h = env.drive.machine, env.angular_momentum
    p_d = math.radians(10.0) * math.sqrt(env.hull.roll_stiffness / env.hull.roll_inertia())
    assert env.design_roll_rate == pytest.approx(p_d, rel=1e-12)
    assert m.max_torque == pytest.approx(h * p_d, rel=1e-12)  # holds H x design roll rate
    assert m.max_power == pytest.approx(h * p_d * m.max_rate, rel=1e-12)
    env.reset(seed=1)
    for a in _actions("random", np.random.default_rng(1), 200):
        info = env.step(np.array([a], np.float32))[4]
        assert abs(info["drive_torque"]) <= m.max_torque * (1 + 1e-12)


def test_brake_never_motors_and_reports_mount_moment_and_rotor_power():
    env = gym.make(ENV_ID).unwrapped
    h = env.angular_momentum
    env.reset(seed=4)
    worst_power = -math.inf
    for a in _actions("random", np.random.default_rng(4), 600):
        info = env.step(np.array([a], np.float32))[4]
        worst_power = max(worst_power, info["drive_power"])
        # mount moment >= the precession moment H phi' of the unit (its other part: the
        # gimbal-axis torque)
        assert info["mount_moment"] >= abs(h * info["gimbal_rate"]) * (1 - 1e-12)
        assert info["mount_moment"] >= abs(info["drive_torque"]) * (1 - 1e-12) or (
            abs(info["gimbal_angle"]) > env.max_gimbal_angle  # a cushion may push back
        )
        assert info["rotor_power"] == 2000.0
    assert worst_power <= 1e-9  # tau phi' <= 0: the closed-circuit brake only dissipates


@pytest.mark.parametrize("scene", ["default", "hs1.5"])
@pytest.mark.parametrize("pattern", ["bang", "chatter", "random"])
def test_unit_holds_its_limits_under_abusive_actions(scene, pattern):
    kw = {} if scene == "default" else HS15
    n = 20
    envs = gym.make_vec(ENV_ID, num_envs=n, vectorization_mode="vector_entry_point", **kw)
    single = gym.make(ENV_ID, **kw).unwrapped
    cap = single.drive.machine.rate_cap
    travel = single.max_gimbal_angle + CUSHION_TRAVEL
    bound = single.mount_moment_bound
    envs.reset(seed=list(range(n)))
    acts = np.stack([_actions(pattern, np.random.default_rng(s), single.max_steps)
                     for s in range(n)], axis=1)  # fmt: skip
    worst = np.zeros(3)
    for k in range(single.max_steps):
        _, r, term, trunc, info = envs.step(acts[k][:, None].astype(np.float32))
        assert not info["numerical_failure"].any() and not term.any()
        assert np.all(np.isfinite(r))
        worst = np.maximum(worst, [np.max(np.abs(info["gimbal_rate"])) / cap,
                                   np.max(np.abs(info["gimbal_angle"])) / travel,
                                   np.max(info["mount_moment"]) / bound])  # fmt: skip
    envs.close()
    assert worst[0] <= 1.1, worst  # precession rate within 10 % of the cap
    assert worst[1] <= 1.0, worst  # never past the cushion's travel
    assert worst[2] <= 1.0, worst  # mount moment within the documented bound


def test_mount_moment_bound_is_the_documented_sum():
    env = gym.make(ENV_ID).unwrapped
    m, c = env.drive.machine, env.cushion
    h = env.angular_momentum
    expect = BrakeParams.design(h, env.gyro.gimbal_inertia + env.gyro.rotor_j1,
                                env.design_roll_rate, m.rate_cap, CUSHION_TRAVEL,
                                CUSHION_START)  # fmt: skip
    assert c == expect
    assert m.max_torque == pytest.approx(c.relief_torque)
    assert env.mount_moment_bound == pytest.approx(
        math.hypot(h * m.rate_cap, c.relief_torque + c.stop_moment_bound)
    )


def test_cushion_kernel_matches_the_brake_module():
    """The env's cushion (drive.cushion_torque) is brake.stop_torque's law: only pushes."""
    env = gym.make(ENV_ID).unwrapped
    D = env.drive.machine.pack(env.gyro.gimbal_inertia + env.gyro.rotor_j1)
    B = env.cushion.pack()
    rng = np.random.default_rng(0)
    for a, ad in zip(rng.uniform(-1.2, 1.2, 400), rng.uniform(-3, 3, 400)):
        assert cushion_torque(a, ad, D) == pytest.approx(stop_torque(a, ad, B), abs=1e-9)
        assert cushion_torque(a, ad, D) * a <= 0.0  # pushes the gimbal back, never pulls in


def test_mss_vessel_units_sized_and_capacity_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a sensible capacity: no warning
        env = gym.make(ENV_ID, hull="mss_naval_vessel").unwrapped
    assert env.n_gyros == 2 and env.units == 4  # 2 x 4 Seakeeper 35 (seed Table 3-1)
    unit = SK.SEED_TABLE_3_1["35"]
    cap = SK.capacity(unit, env.hull, 8, max_precession=env.max_gimbal_angle)
    assert 0.9 <= cap <= 1.2  # 0.97 with the cushions engaging at 50 deg
    assert env.angular_momentum == pytest.approx(4 * 35_000.0, rel=1e-9)
    with pytest.warns(UserWarning, match="capacity 0.0"):  # one Seakeeper 9 on 362 t
        gym.make(ENV_ID, hull="mss_naval_vessel", preset="seed")


def test_ikeda_hull_damping_is_the_method_at_the_stated_particulars():
    hull = Hull.yacht(roll_damping_method="ikeda")
    rule = Hull.yacht()
    j, c = hull.roll_inertia(), hull.roll_stiffness
    tn = 2 * math.pi * math.sqrt(j / c)
    p = YACHT_IKEDA
    h = HullParticulars(hull.length, hull.beam, hull.beam / p["b_over_d"], p["cb"], p["cm"],
                        p["og"], tn, math.radians(p["amplitude_deg"]))  # fmt: skip
    lin, quad = roll_damping(h, validity="ignore").linear_quadratic()
    f = hull.mass / 1025.0 / h.displacement_volume
    assert (hull.roll_damping, hull.roll_damping_quadratic) == pytest.approx((lin * f, quad * f))
    # equivalent damping ratio at a 10 deg roll: Ikeda 0.056, the rule of thumb 0.065
    w, a = math.sqrt(c / j), math.radians(10.0)

    def zeta(x: Hull) -> float:
        beq = x.roll_damping + 8 / (3 * math.pi) * w * a * x.roll_damping_quadratic
        return beq / (2 * math.sqrt(c * j))

    assert 0.04 <= zeta(hull) <= 0.08 and zeta(hull) == pytest.approx(zeta(rule), rel=0.2)
    # forward speed adds lift and wave damping (Ikeda, Himeno & Tanaka 1978)
    assert yacht_ikeda_damping(hull.length, hull.beam, hull.mass, tn, 5.0)[0] > 2 * lin * f
    env = gym.make(ENV_ID, ship_speed=5.0).unwrapped
    assert env.ship.roll_damping > 2 * hull.roll_damping
    assert gym.make(ENV_ID, hull_damping="rule_of_thumb").unwrapped.ship.roll_damping == (
        rule.roll_damping
    )


SENSED = (*DEFAULT_EFFECTS, "sensor_noise", "sensor_delay")


def test_sensor_noise_has_the_documented_spread_and_keeps_the_true_reward():
    from mf_envs.envs.gyro_stabilizer.spec import OBS, sensor_sigma

    kw = {"episode_seconds": 200.0, "max_episode_steps": 4000}
    env = gym.make(ENV_ID, effects=(*DEFAULT_EFFECTS, "sensor_noise"), **kw)
    clean = gym.make(ENV_ID, **kw)
    sigma = sensor_sigma(0.05)
    # 0.007 deg/s/sqrt(Hz) (BMI270) over the 10 Hz Nyquist band of a 20 Hz control rate
    assert sigma[1] == pytest.approx(math.radians(0.007) * math.sqrt(10.0))
    o1, _ = env.reset(seed=7)
    o2, _ = clean.reset(seed=7)
    err, rew = [], []
    for _ in range(4000):
        a = np.zeros(1, np.float32)
        n1, r1, _, _, _ = env.step(a)
        n2, r2, _, _, _ = clean.step(a)
        err.append(OBS.physical(n1) - OBS.physical(n2))  # SI
        rew.append(r1 - r2)
    err = np.array(err)
    # the same physics (noise only on what the controller sees): the spread is the noise's
    np.testing.assert_allclose(err.std(0), sigma, rtol=0.1)
    assert np.max(np.abs(rew)) == 0.0  # the reward scores the true roll
    env.reset(seed=7)
    again = [env.step(np.zeros(1, np.float32))[0] for _ in range(5)]
    env.reset(seed=7)
    np.testing.assert_array_equal(again, [env.step(np.zeros(1, np.float32))[0] for _ in range(5)])


def test_sensor_delay_returns_the_reading_of_whole_control_steps_ago():
    env = gym.make(ENV_ID, effects=(*DEFAULT_EFFECTS, "sensor_delay"), sensor_delay_time=0.1)
    clean = gym.make(ENV_ID)
    assert env.unwrapped._delay == 2  # 0.1 s = two 0.05 s control steps
    rng = np.random.default_rng(0)
    d0, _ = env.reset(seed=3)
    c0, _ = clean.reset(seed=3)
    np.testing.assert_array_equal(d0, c0)
    seen, true = [d0], [c0]
    for a in rng.uniform(-1, 1, 50):
        act = np.array([a], np.float32)
        seen.append(env.step(act)[0])
        true.append(clean.step(act)[0])
    np.testing.assert_array_equal(seen[3:], true[1:-2])  # obs at step k = state at k - 2
    np.testing.assert_array_equal(seen[1], true[0])  # before the delay has passed: the start
    with pytest.raises(ValueError, match="effects"):
        gym.make_vec(ENV_ID, 2, vectorization_mode="vector_entry_point", effects=SENSED)


def test_spool_up_reset_option_slows_the_rotor_and_draws_spool_up_power():
    env = gym.make(ENV_ID).unwrapped
    h = env.angular_momentum
    env.reset(seed=2, options={"spool_up": 0.4})
    for a in np.random.default_rng(2).uniform(-1, 1, 40):
        info = env.step(np.array([a], np.float32))[4]
        expect = -0.4 * h * info["gimbal_rate"] * math.cos(info["gimbal_angle"])
        assert info["gyro_moment"] == pytest.approx(expect, rel=1e-12, abs=1e-9)
        assert info["rotor_power"] == env.spool_up_power == 2000.0
    env.reset(seed=2)  # a reset without the option: full speed, running power
    info = env.step(np.ones(1, np.float32))[4]
    assert info["gyro_moment"] == pytest.approx(
        -h * info["gimbal_rate"] * math.cos(info["gimbal_angle"]), rel=1e-12
    )
    for bad in (0.0, 1.5, -0.1, math.nan):
        with pytest.raises(ValueError, match="spool_up"):
            env.reset(options={"spool_up": bad})


def test_gyro_unit_names_the_seed_table_units_and_the_7000():
    for name, unit in (("16", SK.SEED_TABLE_3_1["16"]), ("7000", SK.SEAKEEPER_7000)):
        env = gym.make(ENV_ID, gyro_unit=name).unwrapped
        assert env.angular_momentum == pytest.approx(unit.angular_momentum, rel=1e-12)
        assert env.unit_name == unit.name and env.drive.machine.kind == "brake"
    seed9 = gym.make(ENV_ID, preset="seed", gyro_unit="9").unwrapped
    assert seed9.gyro == gym.make(ENV_ID, preset="seed").unwrapped.gyro
    with pytest.raises(ValueError, match="gyro_unit"):
        gym.make(ENV_ID, gyro_unit="99")
