"""Domain randomisation of physical parameters, and parameter shifts for robustness evaluation.

`DomainRandomization(env)` re-makes the wrapped env with `gym.make(env_id, **kwargs)` at every
reset, each randomised kwarg drawn uniformly in [lo, hi] x its nominal value (the value the env was
made with, else the constructor default). A kwarg whose value is a dict of numbers (Inchworm-v0's
`friction_coefficients`) is randomised by one factor drawn in [lo, hi] multiplying every number
of its nominal dict. Only kwargs the env's constructor really takes are randomised; the draws
come from the wrapper's own seeded generator, so `reset(seed=s)` is deterministic. The env's own
validation still applies to every draw.

Default ranges (factors of the nominal value), discrete choices (one value drawn uniformly per
reset, after the ranges) and robustness scenes are each env's declaration's
(`randomize`, `choices`, `shifts` in `envs/<env>/task.py`; docs/<env> pages list them), e.g.
GOWEC-v0's wave period +-20 %, FloatingGOWEC-v0's regular or JONSWAP seas of Hs 1-3 m, the
inchworm's feet's friction and body. An env without a declaration has none.

Use it in training through the YAML `env_wrapper: train.randomize.DomainRandomization`; it must
be the first wrapper (it is applied to the bare `gym.make` env, below SB3's Monitor).

On a native vector env (`randomized_vector_env`, what training uses when it is the only wrapper
and the env's vector class holds every drawn kwarg per row, `ROW_KWARGS`) the same draws run
inside the vector env (`BatchedVectorEnv.randomize_rows`): each row has its own randomisation
generator, seeded as the wrapper's, so the rows are bit-identical to `SyncVectorEnv` over
`DomainRandomization` wrappers with the same seeds (tests/test_randomize_vector.py). One
`Randomizer` makes the draws in both.
"""

from __future__ import annotations

import inspect
import numbers
from typing import Any

import gymnasium as gym
import numpy as np
from gymnasium.utils import seeding

Ranges = dict[str, tuple[float, float]]
Choices = dict[str, tuple[Any, ...]]
Nominal = float | dict[str, float]  # a real kwarg's value, or a dict-valued kwarg's numbers


def _declared(env_id: str, what: str) -> dict[str, Any]:
    from mf_envs.envs import declaration

    decl = declaration(env_id)
    return {} if decl is None else dict(getattr(decl, what))


def default_ranges(env_id: str) -> Ranges:
    """The declared randomisation ranges of `env_id` (kwarg -> (lo, hi) factors)."""
    return _declared(env_id, "randomize")


def default_choices(env_id: str) -> Choices:
    """The declared discrete choices of `env_id` (kwarg -> candidate values)."""
    return _declared(env_id, "choices")


def shifts(env_id: str) -> dict[str, dict[str, float]]:
    """The declared robustness scenes of `env_id`: name -> {kwarg: factor}."""
    return {k: dict(v) for k, v in _declared(env_id, "shifts").items()}


def nominal_kwargs(env_id: str, env_kwargs: dict[str, Any] | None = None) -> dict[str, Nominal]:
    """Real-number constructor kwargs of `env_id` -> nominal value, and dict-valued ones (every
    value a real number) -> their nominal dict.

    Given kwargs win over constructor defaults; a kwarg whose value is not a number (e.g.
    `wave_period=None`, "resonance"; Inchworm-v0's `friction_coefficients`, None, a partial dict
    or 4 numbers) takes the value the env resolved it to, read from the attribute of the same
    name on a freshly made env, if it has one (a given dict of numbers otherwise).
    """
    spec = gym.spec(env_id)
    params = _constructor_params(env_id)
    given = {**spec.kwargs, **(env_kwargs or {})}
    out: dict[str, Nominal] = {}
    unresolved = []
    for name, p in params.items():
        value = given.get(name, p.default)
        if _is_real(value):
            out[name] = float(value)
        elif name not in ("self", "render_mode") and p.kind is p.POSITIONAL_OR_KEYWORD:
            unresolved.append(name)
            if _nominal(value) is not None:
                out[name] = _nominal(value)  # unless the env resolved it (below)
    if unresolved:  # (no TimeLimit unless given: only attributes are read)
        env = gym.make(env_id, **{"max_episode_steps": -1, **(env_kwargs or {})})
        for name in unresolved:
            value = _nominal(getattr(env.unwrapped, name, None))
            if value is not None:
                out[name] = value
        env.close()
    return out


def _nominal(value: Any) -> Nominal | None:
    """A real number as float, a non-empty dict of real numbers as a new dict of floats; else
    None (not randomisable)."""
    if _is_real(value):
        return float(value)
    if isinstance(value, dict) and value and all(_is_real(v) for v in value.values()):
        return {k: float(v) for k, v in value.items()}
    return None


def scaled(factor: float, nominal: Nominal) -> Nominal:
    """factor x a nominal value: a number, or every number of a dict-valued kwarg's dict."""
    if isinstance(nominal, dict):
        return {k: factor * v for k, v in nominal.items()}
    return factor * nominal


def _constructor_params(env_id: str) -> dict[str, inspect.Parameter]:
    """The env class's constructor parameters (name -> inspect.Parameter)."""
    spec = gym.spec(env_id)
    cls = spec.entry_point if callable(spec.entry_point) else _load(spec.entry_point)
    return dict(inspect.signature(cls.__init__).parameters)


def _is_real(value: Any) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def applicable_ranges(env_id: str, ranges: Ranges | None = None) -> Ranges:
    """The subset of `ranges` (default the env's declared `randomize`) that are real (or
    dict-of-reals) kwargs of the env (`nominal_kwargs`)."""
    ranges = default_ranges(env_id) if ranges is None else ranges
    nominal = nominal_kwargs(env_id)
    for name, (lo, hi) in ranges.items():
        if not 0 < lo <= hi:
            raise ValueError(f"ranges: {name} needs 0 < lo <= hi, got ({lo}, {hi})")
    return {k: tuple(map(float, v)) for k, v in ranges.items() if k in nominal}


def shifted_kwargs(env_id: str, factors: dict[str, float]) -> dict[str, Nominal]:
    """Absolute kwargs for factors x nominal value (`scaled`: a dict-valued kwarg's every
    number), for the kwargs `env_id` really has."""
    nominal = nominal_kwargs(env_id)
    return {k: scaled(f, nominal[k]) for k, f in factors.items() if k in nominal}


def shift_scenes(env_id: str) -> dict[str, dict[str, Nominal]]:
    """Robustness scenes of `env_id`: name -> absolute gym.make kwargs (empty ones dropped)."""
    scenes = {name: shifted_kwargs(env_id, f) for name, f in shifts(env_id).items()}
    return {name: kw for name, kw in scenes.items() if kw}


class Randomizer:
    """The draws of domain randomisation for `env_id` made with `base_kwargs`: validates
    `ranges` (kwarg -> (lo, hi) factors of the nominal value, a dict-valued kwarg's every number
    by the same factor; default the declared `randomize`; names the env does not take are
    dropped, ValueError naming `ranges` if none is left) and
    `choices` (kwarg -> candidate values; default the declared; unknown names: ValueError naming
    `choices`). `names`: the kwargs drawn."""

    def __init__(
        self,
        env_id: str,
        base_kwargs: dict[str, Any] | None = None,
        ranges: Ranges | None = None,
        choices: Choices | None = None,
    ) -> None:
        self.env_id = env_id
        self.ranges = applicable_ranges(env_id, ranges)
        if not self.ranges:
            raise ValueError(
                f"ranges: none of {list(ranges or default_ranges(env_id))}"
                f" is a real-valued (or dict-of-reals) kwarg of {env_id}"
            )
        self.nominal = {
            k: v for k, v in nominal_kwargs(env_id, base_kwargs).items() if k in self.ranges
        }
        self.choices = dict(default_choices(env_id) if choices is None else choices)
        unknown = sorted(set(self.choices) - set(_constructor_params(env_id)))
        if unknown:
            raise ValueError(f"choices: {unknown} are not kwargs of {env_id}")
        self.names = frozenset(self.ranges) | frozenset(self.choices)

    def sample(self, rng: np.random.Generator) -> dict[str, Any]:
        """One set of kwargs from `rng`: uniform factors x nominal (in `ranges` order, one
        factor per kwarg, `scaled`), then the discrete choices."""
        out: dict[str, Any] = {
            k: scaled(float(rng.uniform(lo, hi)), self.nominal[k])
            for k, (lo, hi) in self.ranges.items()
        }
        for k, values in self.choices.items():
            out[k] = values[int(rng.integers(len(values)))]
        return out

    def draw(
        self, rng: np.random.Generator | None, seed: int | None
    ) -> tuple[np.random.Generator, dict[str, Any], int]:
        """One reset's draws: (the generator, new from `seed` if given or none yet, kept for the
        next reset; the kwargs, `sample`; the env's reset seed, drawn after them)."""
        if seed is not None or rng is None:
            rng, _ = seeding.np_random(seed)
        kwargs = self.sample(rng)
        return rng, kwargs, int(rng.integers(2**31 - 1))


def native_randomization_supported(env_id: str, names: Any, env_kwargs: dict | None = None) -> bool:
    """Whether the native vector env of `env_id` runs these kwargs (`env_kwargs`) and holds
    every drawn kwarg in `names` per row (its class's `row_kwargs`)."""
    from mf_envs.envs import declaration, native_vector_supported
    from mf_envs.envs.declaration import load

    decl = declaration(env_id)
    if decl is None or not decl.vector_installed():
        return False
    cls = load(decl.vector_entry_point)
    if not hasattr(cls, "row_kwargs") or not native_vector_supported(env_id, env_kwargs):
        return False
    return set(names) <= set(cls.row_kwargs(**(env_kwargs or {})))


def randomized_vector_env(
    env_id: str,
    num_envs: int,
    env_kwargs: dict[str, Any] | None = None,
    ranges: Ranges | None = None,
    choices: Choices | None = None,
    **vector_kwargs: Any,
) -> gym.vector.VectorEnv:
    """The native vector env of `env_id` (`gym.make_vec(..., vectorization_mode=
    "vector_entry_point")` with `env_kwargs` and `vector_kwargs` such as `autoreset_mode`) with
    domain randomisation in its rows (`Randomizer(env_id, env_kwargs, ranges, choices)`, module
    doc). ValueError naming `ranges` if its rows cannot hold a drawn kwarg."""
    kwargs = dict(env_kwargs or {})
    draws = Randomizer(env_id, kwargs, ranges, choices)
    venv = gym.make_vec(
        env_id, num_envs, vectorization_mode="vector_entry_point", **vector_kwargs, **kwargs
    )
    try:
        venv.unwrapped.randomize_rows(draws)
    except BaseException:
        venv.close()
        raise
    return venv


class DomainRandomization(gym.Wrapper):
    """Re-make the env with randomised physical kwargs at every reset.

    Args:
        env: an env made with `gym.make(env_id, **kwargs)` (its spec names the id and kwargs).
        ranges: kwarg -> (lo, hi) factors of the nominal value (a dict-valued kwarg: one factor
            for every number of its dict); default the env's declared `randomize`.
            Names the env does not take are ignored; ValueError if none is left.
        choices: kwarg -> candidate values, one drawn uniformly at every reset (None allowed,
            e.g. regular vs irregular sea); default the declared `choices`; names the
            env does not take -> ValueError naming `choices`.

    `info["randomized"]` at reset holds the drawn kwargs (SI units); `self.current` too.
    """

    def __init__(
        self, env: gym.Env, ranges: Ranges | None = None, choices: Choices | None = None
    ) -> None:
        super().__init__(env)
        if env.spec is None:
            raise ValueError("env: must be made with gymnasium.make (it has no spec)")
        self.env_id = env.spec.id
        self.base_kwargs = dict(env.spec.kwargs)
        self.randomizer = Randomizer(self.env_id, self.base_kwargs, ranges, choices)
        self.ranges, self.nominal = self.randomizer.ranges, self.randomizer.nominal
        self.choices = self.randomizer.choices
        # the re-made env gets the TimeLimit gym.make put on `env` when it is not the registered
        # one (a max_episode_steps given to gym.make is passed on; None: no TimeLimit, -1); the
        # mf_envs ids register none and truncate themselves
        limit = env.spec.max_episode_steps
        self._limit = {}
        if limit != gym.spec(self.env_id).max_episode_steps:
            self._limit = {"max_episode_steps": -1 if limit is None else limit}
        self.current: dict[str, Any] = {k: scaled(1.0, v) for k, v in self.nominal.items()}
        self._rng: np.random.Generator | None = None

    def sample(self) -> dict[str, Any]:
        """Draw one set of kwargs (uniform factors x nominal, then the discrete choices) from the
        wrapper's generator (`Randomizer.sample`)."""
        assert self._rng is not None
        return self.randomizer.sample(self._rng)

    def reset(self, *, seed: int | None = None, options: dict[str, Any] | None = None):
        self._rng, self.current, env_seed = self.randomizer.draw(self._rng, seed)
        old = self.env
        self.env = gym.make(self.env_id, **self._limit, **{**self.base_kwargs, **self.current})
        old.close()
        if self.env.observation_space != old.observation_space:
            raise ValueError(
                f"ranges: {self.current} changed the observation space of {self.env_id}"
            )
        obs, info = self.env.reset(seed=env_seed, options=options)
        info["randomized"] = dict(self.current)
        return obs, info


def _load(entry_point: str) -> Any:
    import importlib

    module, _, name = entry_point.partition(":")
    return getattr(importlib.import_module(module), name)
