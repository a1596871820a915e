"""GyroStabilizer-v0: API contract, determinism, reward terms, bad inputs, hard cases."""

from __future__ import annotations

import math
import pickle

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import mf_envs  # noqa: F401  (registers the ids)
from mf_envs.envs import declaration
from mf_envs.envs.gyro_stabilizer.spec import OBS

ENV_ID = "GyroStabilizer-v0"
INFO_KEYS = declaration(ENV_ID).info_keys  # docs/api.md's, from the env's declaration


def test_checkers_pass():
    env = gym.make(ENV_ID)
    check_env(env.unwrapped, skip_render_check=True)
    sb3 = pytest.importorskip(
        "stable_baselines3.common.env_checker",
        reason="needs the train extra: pip install -e '.[train]'",
    )
    sb3.check_env(gym.make(ENV_ID).unwrapped, warn=True)


def test_spaces_info_and_reward_terms():
    env = gym.make(ENV_ID, n_gyros=2)
    obs, info = env.reset(seed=1)
    assert obs.dtype == np.float32 and obs.shape == (6,)
    assert env.action_space.dtype == np.float32
    for k in INFO_KEYS:
        assert k in info
    for _ in range(20):
        obs, r, term, trunc, info = env.step(env.action_space.sample())
        assert r == pytest.approx(
            info["reward_terms"]["roll"] + info["reward_terms"]["effort"], abs=1e-12
        )
        o = OBS.unpack(obs)  # physical values: slot x its fixed scale
        assert info["roll"] == pytest.approx(o["roll"], abs=1e-6)
        assert info["roll_rate"] == pytest.approx(o["roll_rate"], rel=1e-6, abs=1e-7)
        # gyro roll moment is -n H phi' cos(phi) of the current state (Eq. 123)
        H = env.unwrapped.gyro.angular_momentum
        assert info["gyro_moment"] == pytest.approx(
            -2 * H * info["gimbal_rate"] * math.cos(info["gimbal_angle"]), rel=1e-9
        )


def test_deterministic_under_seed_and_picklable():
    def rollout(seed):
        env = gym.make(
            ENV_ID,
            effects=(
                "gyroscopic",
                "hydrostatic_restoring",
                "roll_damping",
                "irregular_waves",
                "gimbal_limits",
            ),
        )
        env.reset(seed=seed)
        env.action_space.seed(seed)
        return np.array([env.step(env.action_space.sample())[0] for _ in range(50)])

    np.testing.assert_array_equal(rollout(3), rollout(3))
    assert not np.array_equal(rollout(3), rollout(4))
    env = gym.make(ENV_ID)
    env.reset(seed=0)
    env2 = pickle.loads(pickle.dumps(env))
    a = np.array([0.3], dtype=np.float32)
    np.testing.assert_array_equal(env.step(a)[0], env2.step(a)[0])


def test_reset_options_and_episode_length():
    env = gym.make(ENV_ID, episode_seconds=2.0)
    obs, info = env.reset(seed=0, options={"roll": 0.2, "roll_rate": -0.1, "gimbal_angle": 0.3})
    o = OBS.unpack(obs)
    assert o["roll"] == pytest.approx(0.2) and o["roll_rate"] == pytest.approx(-0.1)
    assert o["gimbal_angle"] == pytest.approx(0.3)
    n, done = 0, False
    while not done:
        _, _, term, trunc, _ = env.step(np.zeros(1, np.float32))
        n, done = n + 1, term or trunc
    assert n == 40 and trunc and not term
    with pytest.raises(ValueError, match="options"):
        env.reset(options={"pitch": 1.0})


def test_seed_model_no_restoring_no_waves():
    """effects=("gyroscopic",), counter-rotating pair with the gimbals at rest: the spins cancel
    (h = 2 H sin(phi) e1 = 0), no moments act, so the hull keeps its roll rate exactly."""
    env = gym.make(ENV_ID, effects=("gyroscopic",), n_gyros=2)
    env.reset(seed=0, options={"roll": 0.0, "roll_rate": 0.05})
    for _ in range(40):
        obs, _, _, _, info = env.step(np.zeros(1, np.float32))
    assert info["roll_rate"] == pytest.approx(0.05, rel=1e-12)
    assert info["roll"] == pytest.approx(0.05 * 2.0, rel=1e-9)
    assert info["wave_moment"] == 0.0


@pytest.mark.parametrize("drive", ["kinematic", "electric"])
def test_gimbal_limits_hold(drive):
    """The kinematic servo holds the rate limit exactly; the torque drive cannot motor beyond
    its no-load speed 1.1 max_rate and both stop at the end stops (the seed preset's inelastic
    stops; the Seakeeper preset's cushions: tests/test_stabilizer_unit.py)."""
    env = gym.make(ENV_ID, gimbal_drive=drive, preset="seed")
    env.reset(seed=0)
    slack = 1.0 + 1e-9 if drive == "kinematic" else 1.1
    for _ in range(100):
        _, _, _, _, info = env.step(np.ones(1, np.float32))
        assert abs(info["gimbal_rate"]) <= env.unwrapped.max_precession_rate * slack
        if drive == "electric":  # inelastic hard stop
            assert abs(info["gimbal_angle"]) <= math.pi / 3 + 1e-12
    # the servo's envelope brings it to the stop; the drive is held off it by the gyroscopic
    # torque of the rolling hull, which its 900 N m cannot overcome
    assert info["gimbal_angle"] == pytest.approx(math.pi / 3, abs=0.01 if slack < 1.1 else 0.15)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"n_gyros": 3}, "n_gyros"),
        ({"ship_inertia": (1.0, -1.0, 1.0)}, "ship_inertia"),
        ({"rotor_inertia": -1.0}, "rotor_inertia"),
        ({"effects": ("gyroscopic", "teleport")}, "effects"),
        ({"wave_period": 0.0}, "wave_period"),
        ({"max_precession_rate": float("nan")}, "max_precession_rate"),
        ({"form": "rk45"}, "form"),
    ],
)
def test_bad_kwargs_raise(kwargs, name):
    with pytest.raises(ValueError, match=name):
        gym.make(ENV_ID, **kwargs)


def test_nan_action_raises():
    env = gym.make(ENV_ID)
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action"):
        env.step(np.array([np.nan], dtype=np.float32))


def test_numerical_failure_contract():
    env = gym.make(ENV_ID)
    env.reset(seed=0)
    env.unwrapped._y[0] = np.inf  # a state gone non-finite
    obs, r, term, _, info = env.step(np.zeros(1, np.float32))
    assert info["numerical_failure"] and term and r == 0.0 and np.all(np.isfinite(obs))


def test_hard_case_seed_hull_8050rpm_continuous_gimbal():
    """Seed hull (J3 = 1e10 kg m^2), 8050 rpm, two gyros, gimbal spun through +-90 deg."""
    from mf_envs.controllers import make_baseline

    env = gym.make(
        ENV_ID,
        ship_inertia=(1e6, 1e9, 1e10),
        n_gyros=2,
        rotor_inertia=50.0,
        gimbal_inertia=10.0,
        rotor_speed=8050 * 2 * math.pi / 60,
        effects=("gyroscopic", "gimbal_inertia", "wave_moment"),
        wave_moment_amplitude=1e5,
        wave_period=10.0,
        episode_seconds=60.0,
        max_episode_steps=1200,
    )
    ctrl = make_baseline(env, "continuous")
    obs, _ = env.reset(seed=0, options={"wave_phase": 0.0, "roll": 0.0, "roll_rate": 0.0})
    seen = []
    done = False
    while not done:
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        assert not info["numerical_failure"]
        seen.append(info["gimbal_angle"])
        done = term or trunc
    assert max(seen) > 2 * math.pi  # several full turns: through +-90 deg many times


def test_render_rgb_array():
    env = gym.make(ENV_ID, render_mode="rgb_array", n_gyros=2)
    env.reset(seed=0)
    env.step(np.ones(1, np.float32))
    frame = env.render()
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[2] == 3
    assert frame.std() > 0
    env.close()


@pytest.mark.parametrize("drive", ["damper", "pendulous", "spring"])
def test_passive_gyro_reduces_roll(drive):
    """Passive stabilizers (braked, pendulous, spring-restored gimbal): the action is ignored."""
    rms = {}
    for name, eff in (("on", None), ("off", "no_rotor")):
        kw: dict = {"gimbal_drive": drive}
        if eff:
            from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS

            kw["effects"] = tuple(e for e in DEFAULT_EFFECTS if e != "gyroscopic")
        env = gym.make(ENV_ID, **kw)
        env.reset(seed=0)
        rolls = [env.step(np.ones(1, np.float32))[4]["roll"] for _ in range(600)]
        rms[name] = float(np.sqrt(np.mean(np.square(rolls[200:]))))
    assert rms["on"] < 0.7 * rms["off"]


def test_unstable_steps_refused():
    with pytest.raises(ValueError, match="physics_dt"):
        gym.make(ENV_ID, gimbal_drive="torque", gimbal_loop_gain=1e6, physics_dt=0.05)
    with pytest.raises(ValueError, match="physics_dt"):
        gym.make(ENV_ID, gimbal_drive="damper", gimbal_damping=1e5, physics_dt=0.05)
    with pytest.raises(ValueError, match="control_dt"):
        gym.make(ENV_ID, control_dt=1e3, physics_dt=0.01)
    env = gym.make(ENV_ID, gimbal_drive="torque", gimbal_loop_gain=1e4)  # default dt adapts
    assert env.unwrapped.physics_dt <= 0.5 * 2.8 * 14.33 * 2 / 1e4 * 1.01


def test_grouped_drive_is_the_flat_kwargs(sine_rollout):
    from mf_envs.envs.gyro_stabilizer.spec import Drive

    def rollout(**kwargs):
        return sine_rollout(ENV_ID, 2, 40, 0.3, **kwargs)

    flat = rollout(gimbal_drive="electric", max_gimbal_torque=5000.0, drive_bandwidth=15.0)
    grouped = rollout(drive=Drive(kind="electric", max_torque=5000.0, bandwidth=15.0))
    mixed = rollout(drive={"kind": "electric", "bandwidth": 15.0}, gimbal_drive="electric",
                    max_gimbal_torque=5000.0)  # fmt: skip
    assert np.array_equal(flat, grouped) and np.array_equal(flat, mixed)
    assert not np.array_equal(flat, rollout())  # the preset's brake
    with pytest.raises(ValueError, match="^gimbal_drive: given twice"):
        gym.make(ENV_ID, drive={"kind": "brake"}, gimbal_drive="electric")
    with pytest.raises(ValueError, match=r"^drive: unknown fields \['torque'\]"):
        gym.make(ENV_ID, drive={"torque": 1.0})
    with pytest.raises(ValueError, match="^max_gimbal_torque: "):
        gym.make(ENV_ID, drive=Drive(max_torque=-1.0))
