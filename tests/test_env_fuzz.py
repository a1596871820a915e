"""Fuzz of every registered env: constructor kwargs, reset options and actions drawn from valid,
extreme and wrong-typed values.

The contract (docs/api.md): the only exception an env raises for bad input is a ValueError whose
message names the offending public parameter (a kwarg, an option key, or `action`); a value of
the wrong kind (a string, bool, list, dict, complex number, NaN or inf where a real number
belongs) is never accepted; every observation and reward returned is finite (a blown-up state
ends the episode with info["numerical_failure"], never a NaN).

The env list and the kwargs come from the registry and the constructors' signatures, so an env
added to `mf_envs.envs` is fuzzed without editing this file; `NOT_A_NUMBER` names the kwargs that
legitimately take something other than one real number. Hang detection is left to the runner's
own time limit: no test here asserts on elapsed time.

Three layers:
- `test_every_scalar_kwarg_refuses_every_bad_class`: each real-number kwarg of each env with each
  bad value class (a table, complete and deterministic);
- `test_fuzz_fast` / `test_fuzz_slow`: hypothesis draws whole scenes (several kwargs, options, a
  seed) and runs them; the slow profile draws >= 300 examples per env (CI's second stage);
- `test_bad_actions_are_refused_naming_action`: shapes and types of actions, single and vector.
"""

from __future__ import annotations

import functools
import importlib
import inspect
import math
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs.envs import available_env_ids, declaration

FAST, SLOW = 30, 300
ENV_IDS = available_env_ids()
# kwargs that take something other than one real number (names, tuples, dicts, presets)
NOT_A_NUMBER = {
    "effects", "render_mode", "hull", "coupling", "friction_coefficients", "gimbal_inertia",
    "ship_inertia", "soil", "spectrum", "form", "gimbal_drive", "wave_spreading", "sea", "gyro",
    "pto", "drive",
}  # fmt: skip
# values that are never a real number: each must be refused by every real-number kwarg
NEVER_A_NUMBER: dict[str, Any] = {
    "nan": math.nan,
    "inf": math.inf,
    "-inf": -math.inf,
    "10**400": 10**400,
    "'abc'": "abc",
    "'0.5'": "0.5",
    "True": True,
    "[]": [],
    "[1, 2]": [1.0, 2.0],
    "{}": {},
    "1+1j": 1 + 1j,
    "array(2)": np.array([1.0, 2.0]),
    "object()": object(),
}
# extremes that may be valid or not, but never an exception other than a named ValueError
EXTREMES = [0.0, -1.0, 1e-300, 1e308, -1e308, 1e17, -5.0]
WILD = st.one_of(
    st.sampled_from(EXTREMES),
    st.sampled_from([v for k, v in NEVER_A_NUMBER.items() if k != "object()"] + [None]),
    st.integers(-(2**70), 2**70),
    st.floats(allow_nan=True, allow_infinity=True),
)


@functools.cache
def effects_of(env_id: str) -> tuple[str, ...]:
    """Every effect the env can switch (MFEnv.available_effects of its default instance), built
    when a test first needs it (not at collection)."""
    return gym.make(env_id, disable_env_checker=True).unwrapped.available_effects


# steps per example: 20, or 3 for an env declared `slow` (a nonlinear solve per step)
def _steps(env_id: str) -> int:
    return 3 if declaration(env_id).slow else 20


def env_class(env_id: str) -> type:
    entry = gym.spec(env_id).entry_point
    if callable(entry):
        return entry
    module, _, name = entry.partition(":")
    return getattr(importlib.import_module(module), name)


# gym.make's own parameters: gym.make consumes them, they never reach an env's constructor
MAKE_PARAMS = set(inspect.signature(gym.make).parameters)


def kwarg_defaults(env_id: str) -> dict[str, Any]:
    """The constructor's kwargs and their defaults (render_mode and the names gym.make keeps
    for itself, such as max_episode_steps, left out)."""
    params = list(inspect.signature(env_class(env_id).__init__).parameters.values())[1:]
    return {
        p.name: p.default
        for p in params
        if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)
        and p.name != "render_mode"
        and p.name not in MAKE_PARAMS
    }


def real_kwargs(env_id: str) -> list[str]:
    """Kwargs that take one real number (a number or None by default, not in NOT_A_NUMBER)."""
    return [
        k
        for k, v in kwarg_defaults(env_id).items()
        if k not in NOT_A_NUMBER
        and (v is None or (isinstance(v, (int, float)) and not isinstance(v, bool)))
    ]


def reset_options(env_id: str) -> tuple[str, ...]:
    """The env's documented reset option keys (its class's `RESET_OPTIONS`)."""
    return tuple(env_class(env_id).RESET_OPTIONS)


def message(exc: BaseException) -> str:
    """The env's own message (gymnasium appends the kwargs to errors raised in make)."""
    return str(exc).split(" was raised from the environment creator")[0]


def assert_named(exc: BaseException, names: list[str]) -> None:
    assert type(exc) is ValueError, f"{type(exc).__name__}, not ValueError: {exc}"
    text = message(exc)
    assert any(n in text for n in names), f"{text!r} names none of {names}"


# ---------------------------------------------------------------------- the table
@pytest.mark.parametrize("env_id", ENV_IDS)
def test_every_scalar_kwarg_refuses_every_bad_class(env_id):
    cls = env_class(env_id)
    accepted, wrong = [], []
    for name in real_kwargs(env_id):
        for label, value in NEVER_A_NUMBER.items():
            try:
                cls(**{name: value}).close()
                accepted.append(f"{name}={label}")
            except ValueError as exc:
                if name not in str(exc):
                    wrong.append(f"{name}={label}: unnamed: {exc}")
            except Exception as exc:  # noqa: BLE001 - any other type is the defect counted
                wrong.append(f"{name}={label}: {type(exc).__name__}: {exc}")
    assert not accepted, f"{env_id} accepted nonsense: {accepted}"
    assert not wrong, f"{env_id}: {wrong}"


def test_the_table_covers_the_kwargs_the_reviewers_named():
    """The kwargs the last review found unchecked are among those the table sweeps."""
    assert {"gimbal_stiffness", "max_drive_power", "drive_bandwidth", "effort_weight"} <= set(
        real_kwargs("GyroStabilizer-v0")
    )
    assert {"peak_period", "significant_wave_height"} <= set(real_kwargs("FloatingGOWEC-v0"))


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_every_reset_option_refuses_every_bad_class(env_id):
    env = gym.make(env_id, disable_env_checker=True)
    for key in reset_options(env_id):
        for label, value in NEVER_A_NUMBER.items():
            if isinstance(value, (list, np.ndarray)) and key == "kappa":
                continue  # kappa takes an array: its wrong shapes are checked below
            with pytest.raises(ValueError, match=key) as info:
                env.reset(seed=0, options={key: value})
            assert type(info.value) is ValueError, label
    with pytest.raises(ValueError, match="options"):
        env.reset(seed=0, options={"nonsense": 1.0})
    with pytest.raises(ValueError, match="options"):
        env.reset(seed=0, options=[("a", 1)])
    env.close()


# ---------------------------------------------------------------------- actions
BAD_ACTIONS: dict[str, Any] = {
    "'0.5'": "0.5",
    "['0.5']": ["0.5"],
    "True": True,
    "[True]": np.array([True]),
    "None": None,
    "{}": {},
    "object": object(),
    "complex": np.array([1 + 1j]),
    "nan": np.array([math.nan]),
    "ragged": [[1.0], [1.0, 2.0]],
}


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_bad_actions_are_refused_naming_action(env_id):
    env = gym.make(env_id, disable_env_checker=True)
    env.reset(seed=0)
    n = int(np.prod(env.action_space.shape))
    cases = {
        **BAD_ACTIONS,
        "too long": np.zeros(n + 1),
        "empty": np.zeros(0),
        "2-D too big": np.zeros((2, n + 1)),
    }
    for label, action in cases.items():
        with pytest.raises(ValueError, match="action") as info:
            env.step(action)
        assert type(info.value) is ValueError, label
    # a valid action in another real dtype or as a list still works
    env.step(np.zeros(n, dtype=np.float64))
    env.step([0.0] * n)
    env.close()


@pytest.mark.parametrize("env_id", [e for e in ENV_IDS if gym.spec(e).vector_entry_point])
def test_bad_vector_actions_are_refused_naming_actions(env_id):
    from mf_envs.envs import native_vector_supported

    if not native_vector_supported(env_id):
        pytest.skip(f"{env_id}'s default scene has no native vector env")
    envs = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point")
    envs.reset(seed=0)
    n = int(np.prod(envs.single_action_space.shape))
    for label, action in {**BAD_ACTIONS, "one row short": np.zeros((1, n))}.items():
        with pytest.raises(ValueError, match="actions") as info:
            envs.step(action)
        assert type(info.value) is ValueError, label
    envs.close()


# ---------------------------------------------------------------------- hypothesis scenes
def _near(default: Any) -> st.SearchStrategy[Any]:
    """A sane value near a real default (x 0.5-2, same sign; ints stay ints >= 1), 49 times in
    50; else a wild value (so that about half the scenes get past make and are stepped)."""
    if isinstance(default, int) and not isinstance(default, bool):
        sane: st.SearchStrategy[Any] = st.integers(max(1, default // 2), max(1, default * 2))
    elif default == 0.0:
        sane = st.floats(-1.0, 1.0)
    else:
        sane = st.floats(-0.7, 0.7).map(lambda x, d=default: d * math.exp(x))
    return st.integers(0, 49).flatmap(lambda i: WILD if i == 0 else sane)


def _kwarg(env_id: str, name: str, default: Any) -> st.SearchStrategy[Any]:
    if name == "effects":
        names = list(effects_of(env_id))
        valid = st.one_of(
            st.none(),
            st.lists(st.sampled_from(names), max_size=len(names), unique=True).map(tuple),
        )
        return st.integers(0, 19).flatmap(
            lambda i: st.sampled_from(["bogus", ("gravity", 3), 7, {}]) if i == 0 else valid
        )
    if name in NOT_A_NUMBER or not (default is None or isinstance(default, (int, float))):
        return _mostly(st.just(default))
    if default is None:
        return _mostly(st.none())
    return _near(default)


def _mostly(sane: st.SearchStrategy[Any]) -> st.SearchStrategy[Any]:
    """`sane` 19 times in 20, else a wild value."""
    return st.integers(0, 19).flatmap(lambda i: WILD if i == 0 else sane)


def _scene(env_id: str) -> st.SearchStrategy[tuple[dict, dict, int]]:
    defaults = kwarg_defaults(env_id)
    optional = {k: _kwarg(env_id, k, v) for k, v in defaults.items()}
    kw = st.fixed_dictionaries({}, optional=optional)
    opts = st.fixed_dictionaries(
        {},
        optional={
            **{k: st.one_of(st.floats(-2.0, 2.0), WILD) for k in reset_options(env_id)},
            "nonsense": st.just(1),
        },
    )
    return st.tuples(kw, opts, st.integers(0, 2**31 - 1))


def _refused_nonsense(kwargs: dict[str, Any], real: set[str]) -> list[str]:
    """Real-number kwargs given a value that is never a real number."""
    out = []
    for k, v in kwargs.items():
        if k in real and v is not None:
            if isinstance(v, (str, bool, list, dict, complex, np.ndarray)) or (
                isinstance(v, float) and not math.isfinite(v)
            ):
                out.append(f"{k}={v!r}")
            elif isinstance(v, int) and abs(v) > 1.8e308:
                out.append(f"{k}=<huge int>")
    return out


def check_scene(env_id: str, kwargs: dict, options: dict, seed: int) -> None:
    """One fuzz example: make, reset and step; only named ValueErrors, nonsense never accepted,
    everything returned finite."""
    try:
        env = gym.make(env_id, disable_env_checker=True, **kwargs)
    except Exception as exc:  # noqa: BLE001 - the contract is what is checked
        assert_named(exc, list(kwargs))
        return
    nonsense = _refused_nonsense(kwargs, set(real_kwargs(env_id)))
    assert not nonsense, f"{env_id} accepted {nonsense}"
    try:
        obs, _ = env.reset(seed=seed, options=options)
    except Exception as exc:  # noqa: BLE001
        assert_named(exc, [*options, "options"])
        obs, _ = env.reset(seed=seed)
    assert np.isfinite(obs).all() and env.observation_space.contains(obs)
    rng = np.random.default_rng(seed)
    for _ in range(_steps(env_id)):
        action = rng.uniform(-1.5, 1.5, env.action_space.shape).astype(np.float32)
        obs, r, term, trunc, info = env.step(action)
        assert np.isfinite(obs).all() and math.isfinite(r), info
        if term or trunc:
            obs, _ = env.reset()
            assert np.isfinite(obs).all()
    env.close()


def _fuzz(env_id: str, n: int):
    @settings(
        max_examples=n,
        deadline=None,
        derandomize=True,
        database=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )
    @given(_scene(env_id))
    def run(scene):
        check_scene(env_id, *scene)

    return run


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_fuzz_fast(env_id):
    _fuzz(env_id, FAST // 2 if declaration(env_id).slow else FAST)()


@pytest.mark.slow
@pytest.mark.parametrize("env_id", ENV_IDS)
def test_fuzz_slow(env_id):
    _fuzz(env_id, SLOW)()
