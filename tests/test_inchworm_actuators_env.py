"""Inchworm-v0 with actuator dynamics and friction feet (issue 16): limits through the actions,
the kwargs, info keys, the reward's effort = actuation energy, the seed's scene, the baselines."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the ids)
from mf_envs.controllers import make_baseline
from mf_envs.envs.inchworm import LAG_FRICTION_SCENE, RIOS2017_SCENE

L = 0.3


def test_bang_bang_actions_respect_the_actuator_and_grip_limits():
    """Bang-bang actions (every control point and the grip flipping at random every step):
    the realised kappa# (info['kappa_sharp']) never changes faster than the rate limit, and the
    feet's engagement never faster than 1 / grip_time_constant."""
    scene = {**LAG_FRICTION_SCENE, "grip_time_constant": 0.15}
    env = gym.make("Inchworm-v0", actuator_rate_limit=10.0, **scene)
    base = env.unwrapped
    assert base.actuator_rate_limit == 10.0
    _, info = env.reset(seed=0)
    rng, dt = np.random.default_rng(2), base.control_dt
    worst_k = worst_g = 0.0
    for _ in range(60):
        a = np.where(rng.random(env.action_space.shape) < 0.5, -1.0, 1.0).astype(np.float32)
        k0, g0 = info["kappa_sharp"], info["grip"]
        _, _, term, _, info = env.step(a)
        assert not term
        assert info["kappa_sharp"].shape == (base.n_ctrl,)
        worst_k = max(worst_k, float(np.max(np.abs(info["kappa_sharp"] - k0))) / dt)
        worst_g = max(worst_g, float(np.max(np.abs(info["grip"] - g0))) / dt * 0.15)
    assert worst_k <= 10.0 * (1 + 1e-9) and worst_k > 9.0
    assert worst_g <= 1.0 + 1e-12 and worst_g > 0.3


def test_effort_is_the_actuation_energy():
    env = gym.make("Inchworm-v0", effort_weight=2.0)
    env.reset(seed=0)
    energy = 0.0
    for _ in range(10):
        _, r, _, _, info = env.step(np.ones(env.action_space.shape, np.float32))  # curl
        assert info["reward_terms"]["effort"] == pytest.approx(-2.0 * info["actuation_energy"])
        assert info["actuation_energy"] >= 0.0
        energy += info["actuation_energy"]
        dt = env.unwrapped.control_dt
        assert info["actuation_power"] * dt <= info["actuation_energy"] + 1e-15
    assert energy > 0.0  # curling against gravity and the feet costs work


def test_episode_seconds_sets_the_length():
    env = gym.make("Inchworm-v0", episode_seconds=1.0)
    env.reset(seed=0)
    for k in range(10):
        *_, trunc, _ = env.step(np.zeros(env.action_space.shape, np.float32))
        assert trunc == (k == 9)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"actuator_time_constant": 0.0}, "actuator_time_constant"),
        ({"actuator_rate_limit": -1.0}, "actuator_rate_limit"),
        ({"grip_time_constant": float("nan")}, "grip_time_constant"),
        ({"friction_coefficients": {"grip_forward": -0.1}}, "friction_coefficients"),
        ({"friction_coefficients": {"sticky": 1.0}}, "friction_coefficients"),
        ({"episode_seconds": 0.0}, "episode_seconds"),
        ({"effects": ("gravity", "inertia", "friction")}, "effects"),
    ],
)
def test_bad_kwargs_name_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=name):
        gym.make("Inchworm-v0", **kwargs)


def test_seed_scene_still_crawls_the_seed_gait():
    """The seed's scene (kinematic anchors, kappa# as commanded, quasi-static): seed_uniform at
    40 steps per cycle advances 0.5235 L per cycle, as before issue 16."""
    env = gym.make("Inchworm-v0", **RIOS2017_SCENE)
    ctrl = make_baseline(env, "seed_uniform")
    obs, info = env.reset(seed=0, options={"kappa": np.zeros(3)})
    ctrl.reset()
    assert ctrl.steps_per_cycle == 40
    x0 = info["x_tail"]
    for _ in range(40):
        obs, *_, info = env.step(ctrl.predict(obs)[0])
    assert (info["x_tail"] - x0) / L == pytest.approx(0.5235, rel=2e-3)


def test_seed_gait_runs_at_the_fastest_cycle_the_actuator_allows():
    env = gym.make("Inchworm-v0", **LAG_FRICTION_SCENE)
    ctrl = make_baseline(env, "seed_uniform")
    act = env.unwrapped.actuator
    assert ctrl.period == pytest.approx(np.ceil(act.fastest_cycle(13.0) / 0.1 - 1e-9) * 0.1)
    obs, info = env.reset(seed=0)
    ctrl.reset()
    x0 = info["x_tail"]
    for _ in range(2 * ctrl.steps_per_cycle):
        obs, *_, info = env.step(ctrl.predict(obs)[0])
        assert not info["numerical_failure"]
    assert info["x_tail"] - x0 > 0.3 * L


@pytest.mark.slow
def test_tuned_gait_is_at_least_the_seed_gait_and_keeps_the_limits():
    """The tuned two-level square wave (period, amplitude, curl bias by scipy) crawls at least
    as fast as the seed's gait at its fastest cycle on issue 16's scene, and its realised kappa#
    never moves faster than the actuator's rate limit."""
    from mf_envs.benchmarks.controllers import inchworm as b

    scene = LAG_FRICTION_SCENE  # the lag actuator's tuned gait (issue 16's robot)
    tuned = b._episode("tuned", 1000, scene, 2)
    seed = b._episode("seed_uniform", 1000, scene, 2)
    assert tuned["speed_L_per_s"] > seed["speed_L_per_s"]
    env = gym.make("Inchworm-v0", **scene)
    gait = make_baseline(env, "tuned")
    assert gait.amplitude + gait.bias <= env.unwrapped.max_curvature + 1e-9
    obs, info = env.reset(seed=1)
    gait.reset()
    k0, r = info["kappa_sharp"], env.unwrapped.actuator_rate_limit
    for _ in range(30):
        obs, _, _, _, info = env.step(gait.predict(obs)[0])
        rate = np.abs(info["kappa_sharp"] - k0) / env.unwrapped.control_dt
        assert np.all(rate <= r * (1 + 1e-9))
        k0 = info["kappa_sharp"]
    with pytest.raises(ValueError, match="bias"):
        make_baseline(env, "tuned", period=0.5, amplitude=5.0, bias=-1.0)
