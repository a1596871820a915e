"""Reliability suite, parametrized over every registered env (`available_env_ids()`): the
Gymnasium and SB3 checkers, seeding, pickling, input validation, the numerical-failure contract,
the info keys of docs/api.md, reward terms, rendering and (slow) a long random-action soak."""

from __future__ import annotations

import os

os.environ.setdefault("MPLBACKEND", "Agg")  # "human" render mode in the checker: no display
os.environ.setdefault("SDL_VIDEODRIVER", "dummy")  # same when pygame (extra "render") is present

import pickle
import warnings
from typing import Any

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs.envs import available_env_ids, declaration

ENV_IDS = available_env_ids()


# docs/api.md: info keys every env reports at reset and at every step (each env's declaration)
def _info_keys(env_id: str) -> tuple[str, ...]:
    return declaration(env_id).info_keys


# docs/api.md kwargs with one physically invalid value each (the ValueError must name the kwarg)
INVALID_KWARGS: dict[str, list[tuple[str, Any]]] = {
    "GOWEC-v0": [
        ("rotor_inertia", -1.0),
        ("wave_period", 0.0),
        ("wave_amplitude", float("nan")),
        ("max_generator_torque", -5.0),
    ],
    "GyroStabilizer-v0": [
        ("ship_inertia", (-1e6, 1e9, 1e10)),
        ("n_gyros", 3),
        ("rotor_inertia", 0.0),
        ("wave_period", -1.0),
    ],
    "Inchworm-v0": [
        ("length", -0.2),
        ("n_elements", 0),
        ("youngs_modulus", -1.0),
        ("mass_per_length", float("inf")),
    ],
    "FloatingGOWEC-v0": [
        ("rotor_inertia", -1.0),
        ("wave_period", 0.0),
        ("generator_efficiency", 1.5),
        ("max_generator_torque", -5.0),
    ],
}

# Steps of the long random-action soak per env: 1e5 where it fits the CI budget. Measured in
# the pytest run (2 shared cores): GOWEC and GyroStabilizer 1e5 steps in 4-25 s each;
# Inchworm 30-110 steps/s (a Newton solve of the C1 beam per step), so 1e5 steps would take
# 15-60 min: it soaks 1 000 steps (2.5 episodes, 9-35 s).
SOAK_STEPS: dict[str, int] = {
    "GOWEC-v0": 100_000,
    "GyroStabilizer-v0": 100_000,
    "Inchworm-v0": 1_000,
    "FloatingGOWEC-v0": 20_000,  # ~1 ms per step (Cummins + gyro, 4 RK4 substeps)
}


# Random-action steps for the determinism/pickling checks ("a few hundred"); an env declared
# `slow` (a nonlinear FE solve per step: the inchworm, the serpentine) gets 60.
def _rollout_steps(env_id: str) -> int:
    return 60 if declaration(env_id).slow else 300


# How each env's physics state is made non-finite through `env.unwrapped` (read from the env
# code: the arrays its step integrates from); an env not listed keeps its state in `state`.
POISON: dict[str, Any] = {
    "GOWEC-v0": lambda raw: raw.state.fill(np.nan),  # (phi, phi')
    "GyroStabilizer-v0": lambda raw: raw._y.fill(np.nan),  # ship rates, phi, phi', ...
    "Inchworm-v0": lambda raw: raw.sim.state.d.fill(np.nan),  # beam nodal dofs (Newmark d)
    # buoy, gimbal, radiation states, energies
    "FloatingGOWEC-v0": lambda raw: raw.state.fill(np.nan),
}


def _reward_terms(info: dict) -> dict[str, float]:
    """The named reward terms every env reports as `info["reward_terms"]` (docs/style.md item 8)."""
    terms = info.get("reward_terms")
    assert isinstance(terms, dict) and terms, f"info['reward_terms'] missing: {sorted(info)}"
    return terms


@pytest.fixture
def make():
    """`make(env_id, **kw)` -> env made with gym.make; every env is closed afterwards."""
    made: list[gym.Env] = []

    def _make(env_id: str, **kwargs):
        env = gym.make(env_id, **kwargs)
        made.append(env)
        return env

    yield _make
    for env in made:
        env.close()


def _rollout(env: gym.Env, actions: list[np.ndarray], seed: int) -> list[tuple]:
    """(obs, reward, terminated, truncated, numeric info) per step; resets on episode end."""
    out = []
    obs, info = env.reset(seed=seed)
    out.append((obs, 0.0, False, False, _numeric(info)))
    for a in actions:
        obs, r, term, trunc, info = env.step(a)
        out.append((obs, r, term, trunc, _numeric(info)))
        if term or trunc:
            obs, info = env.reset()
    return out


def _numeric(info: dict) -> dict:
    return {k: np.asarray(v) for k, v in info.items() if np.asarray(v).dtype.kind in "biuf"}


def _assert_same(a: list[tuple], b: list[tuple]) -> None:
    assert len(a) == len(b)
    for i, (x, y) in enumerate(zip(a, b)):
        np.testing.assert_array_equal(x[0], y[0], err_msg=f"obs differs at step {i}")
        assert x[1:4] == y[1:4], f"reward/termination differs at step {i}"
        assert x[4].keys() == y[4].keys()
        for k in x[4]:
            np.testing.assert_array_equal(x[4][k], y[4][k], err_msg=f"info[{k!r}] step {i}")


def _actions(env: gym.Env, n: int, seed: int = 0) -> list[np.ndarray]:
    space = env.action_space
    space.seed(seed)
    return [space.sample() for _ in range(n)]


def _checker_warnings(record) -> list[str]:
    return [
        str(w.message)
        for w in record
        if "non-interactive" not in str(w.message) and "FigureCanvasAgg" not in str(w.message)
    ]


# ----------------------------------------------------------------------------- checkers
@pytest.mark.parametrize("env_id", ENV_IDS)
def test_gymnasium_check_env(env_id, make):
    from gymnasium.utils.env_checker import check_env

    env = make(env_id)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        check_env(env.unwrapped)
    assert not _checker_warnings(record), _checker_warnings(record)


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_sb3_check_env(env_id, make):
    sb3_checker = pytest.importorskip(
        "stable_baselines3.common.env_checker",
        reason="needs the train extra: pip install -e '.[train]'",
    )
    env = make(env_id)
    with warnings.catch_warnings(record=True) as record:
        warnings.simplefilter("always")
        sb3_checker.check_env(env.unwrapped, warn=True)
    assert not _checker_warnings(record), _checker_warnings(record)


# ----------------------------------------------------------------------------- seeding, pickling
@pytest.mark.parametrize("env_id", ENV_IDS)
def test_same_seed_same_trajectory(env_id, make):
    a, b = make(env_id), make(env_id)
    actions = _actions(a, _rollout_steps(env_id))
    _assert_same(_rollout(a, actions, seed=7), _rollout(b, actions, seed=7))


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_different_seed_different_start(env_id, make):
    env = make(env_id)
    obs = [env.reset(seed=s)[0] for s in range(4)]
    info = [_numeric(env.reset(seed=s)[1]) for s in range(4)]
    differs = any(not np.array_equal(obs[0], o) for o in obs[1:]) or any(
        any(not np.array_equal(info[0][k], i[k]) for k in i) for i in info[1:]
    )
    if not differs:
        pytest.skip(f"{env_id}: deterministic initial state (no randomness at reset)")


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_pickle_round_trip_continues_identically(env_id, make):
    env = make(env_id)
    clone = pickle.loads(pickle.dumps(env))  # a fresh env
    actions = _actions(
        env,
        min(40, _rollout_steps(env_id) // 3),
        seed=1,
    )
    half = len(actions) // 2
    _assert_same(_rollout(env, actions, seed=3), _rollout(clone, actions, seed=3))
    # a stepped env: pickle in the middle of an episode, both continue identically
    env.reset(seed=5)
    for a in actions[:half]:
        env.step(a)
    twin = pickle.loads(pickle.dumps(env))
    for i, a in enumerate(actions[half:]):
        x, y = env.step(a), twin.step(a)
        np.testing.assert_array_equal(x[0], y[0], err_msg=f"obs after unpickling, step {i}")
        assert x[1:4] == y[1:4]
        if x[2] or x[3]:
            break


# ----------------------------------------------------------------------------- bad input
@pytest.mark.parametrize("env_id", ENV_IDS)
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_nonfinite_action_raises(env_id, bad, make):
    env = make(env_id)
    env.reset(seed=0)
    action = np.zeros(env.action_space.shape, dtype=np.float32)
    action.flat[0] = bad
    with pytest.raises(ValueError, match="action"):
        env.step(action)


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_unknown_effect_raises_naming_it(env_id):
    with pytest.raises(ValueError, match="nope"):
        gym.make(env_id, effects=("nope",))


@pytest.mark.parametrize(
    "env_id, kwarg, value",
    [(e, k, v) for e in ENV_IDS for k, v in INVALID_KWARGS.get(e, [])],
)
def test_invalid_parameter_raises_naming_it(env_id, kwarg, value):
    with pytest.raises(ValueError, match=kwarg):
        gym.make(env_id, **{kwarg: value})


@pytest.mark.filterwarnings("ignore:.*render_mode")
@pytest.mark.parametrize("env_id", ENV_IDS)
def test_bad_render_mode_raises(env_id):
    with pytest.raises(ValueError, match="render_mode"):
        gym.make(env_id, render_mode="svg")


def _available_effects(env_id: str) -> list[str]:
    """The env's effect vocabulary, as listed by its own unknown-effect error message."""
    with pytest.raises(ValueError, match="available: ") as err:
        gym.make(env_id, effects=("nope",))
    return [e.strip() for e in str(err.value).split("available: ")[1].split(",")]


def _effect_sets(env_id: str) -> list[tuple[str, ...]]:
    """All effects, none, the default minus each one, the default plus each other one."""
    env = gym.make(env_id)
    default = sorted(env.unwrapped.effects)
    exclusive = getattr(env.unwrapped, "exclusive_effects", ())  # documented pairs (a, b)
    env.close()
    avail = _available_effects(env_id)
    sets = [tuple(avail), ()]
    sets += [tuple(e for e in default if e != d) for d in default]
    sets += [(*default, a) for a in avail if a not in default]
    # a set holding both of an exclusive pair drops the first (the env rejects the pair)
    return [tuple(e for e in s if not any(e == a and b in s for a, b in exclusive)) for s in sets]


@pytest.mark.parametrize("env_id", ENV_IDS)
@pytest.mark.slow
def test_every_effect_set_runs_random_actions(env_id):
    """Each effect switched on/off alone (and all, and none): the env builds, resets and takes
    20 random actions with finite observations, the docs/api.md info keys and no numerical
    failure."""
    failures = []
    for effects in _effect_sets(env_id):
        env = gym.make(env_id, effects=effects)
        env.reset(seed=0)
        for i, a in enumerate(_actions(env, 20, seed=0)):
            obs, r, term, trunc, info = env.step(a)
            assert set(_info_keys(env_id)) <= set(info), effects
            if info["numerical_failure"] or not np.all(np.isfinite(obs)):
                failures.append(f"effects={effects}: numerical failure at step {i + 1}")
                break
            if term or trunc:
                env.reset()
        env.close()
    assert not failures, "\n".join(failures)


# docs/api.md: reset(options=...) initial-state overrides, checked through the info key of the
# same name
RESET_OPTIONS: dict[str, dict[str, float]] = {
    "GOWEC-v0": {"gimbal_angle": 0.3, "gimbal_rate": -0.5},
    "GyroStabilizer-v0": {"roll": 0.1, "roll_rate": 0.05, "gimbal_angle": 0.2},
    "FloatingGOWEC-v0": {
        "buoy_pitch": 0.1,
        "buoy_roll": -0.05,
        "gimbal_angle": 0.3,
        "gimbal_rate": -0.5,
    },
}


@pytest.mark.parametrize(
    "env_id, key, value",
    [(e, k, v) for e in ENV_IDS for k, v in RESET_OPTIONS.get(e, {}).items()],
)
def test_reset_options_override_the_initial_state(env_id, key, value, make):
    env = make(env_id)
    _, info = env.reset(seed=0, options={key: value})
    assert np.isclose(info[key], value, rtol=1e-6, atol=1e-9), (key, info[key])
    with pytest.raises(ValueError, match=key):
        env.reset(seed=0, options={key: float("nan")})


# ----------------------------------------------------------------------------- numerics
def _poison(env: gym.Env) -> None:
    """Make the env's physics state non-finite through `env.unwrapped`."""
    POISON.get(env.spec.id, lambda raw: raw.state.fill(np.nan))(env.unwrapped)


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_nonfinite_state_ends_episode_with_numerical_failure(env_id, make):
    env = make(env_id)
    obs0, _ = env.reset(seed=0)
    obs, reward, terminated, _, info = env.step(env.action_space.sample())
    assert info["numerical_failure"] is False
    _poison(env)
    obs, reward, terminated, _, info = env.step(np.zeros(env.action_space.shape, np.float32))
    assert info["numerical_failure"] is True
    assert terminated is True
    assert np.all(np.isfinite(obs)) and np.isfinite(reward)
    # a reset recovers: finite start, healthy steps
    obs, _ = env.reset(seed=1)
    assert np.all(np.isfinite(obs))
    _, _, _, _, info = env.step(np.zeros(env.action_space.shape, np.float32))
    assert info["numerical_failure"] is False


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_info_keys_at_reset_and_every_step(env_id, make):
    env = make(env_id)
    keys = _info_keys(env_id)
    _, info = env.reset(seed=0)
    assert set(keys) <= set(info), sorted(set(keys) - set(info))
    for a in _actions(env, 60):
        obs, r, term, trunc, info = env.step(a)
        assert set(keys) <= set(info), sorted(set(keys) - set(info))
        assert info["numerical_failure"] is False
        assert obs.dtype == np.float32 and env.observation_space.contains(obs)
        for k in keys:
            assert np.all(np.isfinite(np.asarray(info[k], dtype=float))), k
        if term or trunc:
            env.reset()


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_reward_terms_sum_to_reward(env_id, make):
    env = make(env_id)
    env.reset(seed=2)
    checked = 0
    for a in _actions(env, 40, seed=2):
        _, r, term, trunc, info = env.step(a)
        terms = _reward_terms(info)
        assert np.isclose(sum(float(v) for v in terms.values()), r, rtol=1e-6, atol=1e-9)
        checked += 1
        if term or trunc:
            break
    assert checked


# ----------------------------------------------------------------------------- rendering
@pytest.mark.parametrize("env_id", ENV_IDS)
def test_rgb_array_render_is_nonblank_and_moves(env_id, make):
    env = make(env_id, render_mode="rgb_array")
    env.reset(seed=0)
    first = env.render()
    assert isinstance(first, np.ndarray) and first.dtype == np.uint8
    assert first.ndim == 3 and first.shape[2] == 3 and first.std() > 10
    for a in _actions(env, 25):
        env.step(a)
    later = env.render()
    assert later.shape == first.shape and not np.array_equal(first, later)


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_human_render_headless(env_id, make):
    env = make(env_id, render_mode="human")
    env.reset(seed=0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # matplotlib: Agg is non-interactive
        for a in _actions(env, 3):
            env.step(a)
            assert env.render() is None
    env.close()


# ----------------------------------------------------------------------------- soak
@pytest.mark.slow
@pytest.mark.parametrize("env_id", ENV_IDS)
def test_random_action_soak(env_id, make):
    env = make(env_id)
    rng = np.random.default_rng(0)
    env.reset(seed=0)
    low, high = env.action_space.low, env.action_space.high
    for i in range(SOAK_STEPS.get(env_id, 1_000 if declaration(env_id).slow else 100_000)):
        a = rng.uniform(low, high).astype(np.float32)
        obs, r, term, trunc, info = env.step(a)
        assert not info["numerical_failure"], f"numerical failure at step {i}"
        assert np.all(np.isfinite(obs)) and np.isfinite(r), f"non-finite at step {i}"
        if term or trunc:
            env.reset(seed=int(rng.integers(1 << 31)))


@pytest.mark.parametrize("theta", [np.pi / 2, np.pi / 3])
def test_gowec_analytic_max_power_is_eq95(theta, make):
    """docs/api.md: `analytic_max_power()` is ch.3 Eq. 95,
    P = 1/2 |psi'| J3 (a / g) (2 pi / T)^4 sin(theta) (Eq. 86 for theta = pi/2)."""
    J3, psid, a, T = 40.0, 600.0, 0.8, 5.0
    env = make(
        "GOWEC-v0",
        rotor_inertia=J3,
        rotor_speed=psid,
        wave_amplitude=a,
        wave_period=T,
        wave_direction=theta,
    )
    expected = 0.5 * psid * J3 * (a / 9.81) * (2 * np.pi / T) ** 4 * np.sin(theta)
    assert np.isclose(env.unwrapped.analytic_max_power(), expected, rtol=2e-3)
