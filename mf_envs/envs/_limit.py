"""The episode length an env must have to agree with the TimeLimit Gymnasium puts on it.

Every registered id has `max_episode_steps` in its spec: the control steps of the env's default
episode (its declaration's `max_episode_steps`, checked against the env by
tests/test_env_limits.py). Gymnasium acts on it from outside the env:

- `gym.make(id, max_episode_steps=None, **kw)` builds the env from `kw`, then wraps it in
  `TimeLimit(max_episode_steps or spec.max_episode_steps)` (none with -1);
- `gym.make_vec(id, vectorization_mode="vector_entry_point", **kw)` passes
  `max_episode_steps=spec.max_episode_steps` to the vector env unless `kw` has one.

So an env made with a longer `episode_seconds` than the default would be cut at the default
length by the TimeLimit, without a word. To rule that out, the env learns what Gymnasium will
apply, and `MFEnv._episode_length` makes the two agree or refuses:

- a `max_episode_steps` the caller gave (to `gym.make`, `gym.make_vec` or the constructor) is
  the episode length in control steps; with the env's own length argument (`episode_seconds`,
  GOWEC-v0's `n_periods`) both must give the same steps, else ValueError naming both;
- the spec's `max_episode_steps` (applied because the caller gave none) is an upper bound
  that only checks: if the env's episode (its own arguments, or its default at the given
  `control_dt`) is longer, ValueError naming `max_episode_steps` and the argument, with the
  number to pass; a shorter episode the env ends itself, before the TimeLimit.

The env sees neither `gym.make`'s `max_episode_steps` (make keeps it) nor whether make_vec's
came from the spec, so `gym_make_limit` and `make_vec_injected` read them from the calling
`gymnasium.envs.registration.make` / `make_vec` frame, found by its code object (not by name)
right above the env's constructor (and a deprecated id's entry point, `_alias.DeprecatedId`). An
env built any other way (directly, or as a vector env's template) has no TimeLimit and keeps
its own length. tests/test_env_limits.py pins this against the installed Gymnasium.
"""

from __future__ import annotations

import sys
from types import FrameType
from typing import Any

from gymnasium.envs import registration


def _skip_self(obj: Any, frame: FrameType | None) -> FrameType | None:
    """The first frame from `frame` up that is neither a method running on `obj` (the
    constructor chain) nor a deprecated id's entry point."""
    from mf_envs.envs._alias import DeprecatedId

    alias_code = DeprecatedId.__call__.__code__
    while frame is not None and (frame.f_locals.get("self") is obj or frame.f_code is alias_code):
        frame = frame.f_back
    return frame


def gym_make_limit(env: Any) -> tuple[str, Any] | None:
    """While `env` is being constructed: ("given", L) if `gymnasium.make` builds it and will
    wrap it in TimeLimit(L) for a `max_episode_steps=L` its caller gave; ("spec", D) if it will
    apply the spec's D; None otherwise (not built by make, or no TimeLimit)."""
    frame = _skip_self(env, sys._getframe(1))
    if frame is None or frame.f_code is not registration.make.__code__:
        return None
    given = frame.f_locals.get("max_episode_steps")
    if given is not None:
        return None if given == -1 else ("given", given)
    spec = frame.f_locals.get("env_spec")
    limit = getattr(spec, "max_episode_steps", None)
    if limit is None:
        return None
    # a spec whose limit is not the registered one (`gym.make(env.spec)` of an env made with
    # max_episode_steps=N) carries a length someone gave
    return ("spec" if limit == _registered_limit(spec) else "given", limit)


def _registered_limit(spec: Any) -> Any:
    """The registered spec's max_episode_steps for `spec`'s id (None if not registered)."""
    registered = registration.registry.get(getattr(spec, "id", None))
    return None if registered is None else registered.max_episode_steps


def make_vec_injected(venv: Any) -> bool:
    """While the vector env `venv` is being constructed: whether `gymnasium.make_vec` builds it
    and put `max_episode_steps` into its kwargs from the spec (its caller gave none)."""
    frame = _skip_self(venv, sys._getframe(1))
    if frame is None or frame.f_code is not registration.make_vec.__code__:
        return False
    user = frame.f_locals.get("kwargs") or {}
    spec = frame.f_locals.get("env_spec")
    registered = registration.registry.get(getattr(spec, "id", None))
    in_spec = registered is not None and "max_episode_steps" in registered.kwargs
    own = getattr(spec, "max_episode_steps", None) != _registered_limit(spec)  # a spec's given
    return "max_episode_steps" not in user and not in_spec and not own


def check_max_episode_steps(value: Any, high: int) -> int:
    """`max_episode_steps` as given to gym.make, make_vec or the constructor: a Python int in
    [1, high] (what gym.make's TimeLimit takes, so every way of making the env gives the same
    answer); ValueError naming it otherwise (100.0 or numpy integers included)."""
    if isinstance(value, bool) or not isinstance(value, int):
        raise ValueError(
            f"max_episode_steps: expected a whole number of control steps (a Python int, as "
            f"gym.make's TimeLimit takes), got {value!r} ({type(value).__name__})"
        )
    if not 1 <= value <= high:
        raise ValueError(f"max_episode_steps: must be in [1, {high}], got {value}")
    return value
