"""Inchworm-v0: API contract, determinism, reward terms, the seed gaits, numerical failure."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import mf_envs  # noqa: F401  (registers the ids)
from mf_envs.controllers import baseline_kinds, make_baseline
from mf_envs.envs.inchworm import LAG_FRICTION_SCENE, RIOS2017_BODY, RIOS2017_SCENE
from mf_envs.physics.beam import NewtonSettings

L = 0.3


def test_gymnasium_and_sb3_checkers():
    check_env(gym.make("Inchworm-v0").unwrapped, skip_render_check=True)
    sb3 = pytest.importorskip(
        "stable_baselines3.common.env_checker",
        reason="needs the train extra: pip install -e '.[train]'",
    )
    sb3.check_env(gym.make("Inchworm-v0", effects=("gravity", "inertia", "anchor_switching")))


def test_deterministic_under_seed():
    def roll(seed):
        env = gym.make("Inchworm-v0")
        obs, _ = env.reset(seed=seed)
        rng = np.random.default_rng(5)
        out = [obs]
        for _ in range(5):
            obs, *_ = env.step(rng.uniform(-1, 1, env.action_space.shape).astype(np.float32))
            out.append(obs)
        return np.array(out)

    assert np.array_equal(roll(3), roll(3))
    assert not np.array_equal(roll(3), roll(4))  # the initial actuation noise differs


def test_info_keys_and_reward_terms_sum():
    env = gym.make("Inchworm-v0")
    _, info = env.reset(seed=0)
    assert {"x_head", "x_tail", "centerline"} <= set(info)
    assert info["centerline"].ndim == 2 and info["centerline"].shape[1] == 2
    _, reward, _, _, info = env.step(env.action_space.sample())
    assert reward == pytest.approx(
        info["reward_terms"]["progress"] + info["reward_terms"]["effort"], abs=1e-12
    )
    assert info["reward_terms"]["effort"] <= 0.0


@pytest.mark.parametrize("kind, per_cycle", [("seed_uniform", 0.5235), ("seed_linear", 0.2170)])
def test_seed_gaits_advance_head_and_tail(kind, per_cycle):
    """Both seed gaits (kappa0# = 13) advance head and tail by the stated distance per cycle
    (body lengths) through the action interface, with no numerical failure (the seed's scene)."""
    env = gym.make("Inchworm-v0", **RIOS2017_SCENE)
    ctrl = make_baseline(env, kind)
    obs, info = env.reset(seed=0, options={"kappa": np.zeros(3)})
    x0 = np.array([info["x_tail"], info["x_head"]])
    total = 0.0
    for _ in range(ctrl.steps_per_cycle):
        obs, r, term, trunc, info = env.step(ctrl.predict(obs)[0])
        assert not info["numerical_failure"] and not term
        total += info["reward_terms"]["progress"]
    adv = (np.array([info["x_tail"], info["x_head"]]) - x0) / L
    assert adv == pytest.approx([per_cycle, per_cycle], rel=2e-3)
    assert total == pytest.approx(adv[0], rel=1e-9)


def test_baselines_registered():
    assert baseline_kinds("Inchworm-v0")[:1] == ["tuned"]  # the strongest is the default
    assert "seed_linear" in baseline_kinds("Inchworm-v0")


def test_newton_failure_ends_episode():
    env = gym.make("Inchworm-v0")
    obs0, _ = env.reset(seed=0)
    env.unwrapped.sim.settings = NewtonSettings(1e-12, 1e-12, 1, 0)  # no budget at all
    obs, reward, term, _, info = env.step(np.ones(env.action_space.shape, np.float32))
    assert info["numerical_failure"] and term and reward == 0.0
    assert np.all(np.isfinite(obs))


def test_bad_inputs_name_the_parameter():
    env = gym.make("Inchworm-v0")
    env.reset(seed=0)
    with pytest.raises(ValueError, match="action"):
        env.step(np.array([np.nan, 0, 0, 0], np.float32))
    for kwargs, name in [
        ({"n_elements": 0}, "n_elements"),
        ({"max_curvature": -1.0}, "max_curvature"),
        ({"youngs_modulus": 0.0}, "youngs_modulus"),
        ({"effects": ("magnetism",)}, "effects"),
    ]:
        with pytest.raises(ValueError, match=name):
            gym.make("Inchworm-v0", **kwargs)


def test_action_shape_follows_anchor_effect_and_inertia_runs():
    env = gym.make("Inchworm-v0", **RIOS2017_BODY, effects=("gravity", "inertia"))
    assert env.action_space.shape == (3,)
    env.reset(seed=1)
    for _ in range(3):
        obs, _, term, _, info = env.step(np.array([-0.5, -0.5, -0.5], np.float32))
        assert not info["numerical_failure"]
    assert info["x_head"] == pytest.approx(L, abs=1e-9)  # no switching: the head stays put


def test_render_rgb_array():
    env = gym.make("Inchworm-v0", render_mode="rgb_array")
    env.reset(seed=0)
    env.step(-np.ones(4, np.float32) * 0.2)
    frame = env.render()
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[2] == 3
    assert frame.std() > 1.0
    env.close()


@pytest.mark.parametrize(
    "scene, crawl", [(RIOS2017_SCENE, 0.5 * L), (LAG_FRICTION_SCENE, 0.01 * L), ({}, -np.inf)]
)
def test_reset_far_from_origin_is_a_translated_copy(scene, crawl):
    """reset(options={"x_tail": 9.0}) must not raise (it did: NewtonDivergence, round-off of
    absolute nodal x); the episode is the x = 0 episode shifted by 9 m, in the seed's scene and
    with the default actuators and friction feet (which work in the local coordinates too)."""

    def roll(x_tail):
        env = gym.make("Inchworm-v0", **scene)
        ctrl = make_baseline(env, "seed_uniform", steps_per_cycle=4)
        obs, info = env.reset(seed=2, options={"x_tail": x_tail})
        out, xs = [obs], [info["x_tail"]]
        for _ in range(8):
            obs, _, term, _, info = env.step(ctrl.predict(obs)[0])
            assert not info["numerical_failure"] and not term
            out.append(obs)
            xs.append(info["x_tail"])
        return np.array(out), np.array(xs)

    obs0, x0 = roll(0.0)
    obs9, x9 = roll(9.0)
    assert np.array_equal(obs9, obs0)
    assert np.allclose(x9 - 9.0, x0, rtol=0, atol=1e-12)
    assert x0[-1] - x0[0] > crawl  # two cycles of crawling
    with pytest.raises(ValueError, match="x_tail"):
        gym.make("Inchworm-v0").reset(seed=0, options={"x_tail": np.nan})


def test_render_after_numerical_failure_shows_last_finite_frame():
    env = gym.make("Inchworm-v0", render_mode="rgb_array")
    env.reset(seed=0)
    env.step(-np.ones(4, np.float32) * 0.2)
    before = env.render()
    env.unwrapped.sim.state.d.fill(np.nan)  # the physics state blows up
    *_, term, _, info = env.step(-np.ones(4, np.float32) * 0.5)
    assert info["numerical_failure"] and term
    after = env.render()  # no ValueError: the last finite state is drawn
    # the same picture below the caption (rows < 40: "step ..., last finite state")
    assert np.array_equal(after[40:], before[40:]) and after.std() > 1.0
    env.close()


@pytest.mark.slow
def test_long_seed_gait_episode_crawls_past_10_m():
    """The training helper's failure (numerical_failure at x_tail ~ 8-10 m): the coarsest seed
    gait through the env from x = 0 to past 10 m, every cycle advancing by the same distance."""
    env = gym.make("Inchworm-v0", episode_seconds=1000.0, **RIOS2017_SCENE)  # 10 000 steps
    ctrl = make_baseline(env, "seed_uniform", steps_per_cycle=2)
    obs, info = env.reset(seed=0, options={"kappa": np.zeros(3)})
    xs = [info["x_tail"]]
    while xs[-1] < 10.5:
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        assert not info["numerical_failure"] and not term and not trunc, info["x_tail"]
        xs.append(info["x_tail"])
    per_cycle = np.diff(np.array(xs)[::2])
    assert len(per_cycle) > 50 and per_cycle[0] > 0.5 * L
    assert np.allclose(per_cycle, per_cycle[0], rtol=1e-9, atol=0)
