"""Deprecated env ids that still make their env, outside their old id's version family.

`GOWEC-v1` was the first id of the floating GOWEC. That env is a different system from
`GOWEC-v0` (one gyroscope on a buoy whose rocking is prescribed), not its next version, so it is
now `FloatingGOWEC-v0`. Gymnasium warns "GOWEC-v0 is out of date" whenever a higher version of
the same name is registered (`gymnasium.envs.registration._find_spec` compares the requested
version with the highest `EnvSpec.version` among `registry.values()` of that namespace and name),
so `gym.register("GOWEC-v1", ...)` would bring that warning back for every `GOWEC-v0` user.

Instead, `register_aliases` stores under the key "GOWEC-v1" of `gym.registry` (the dict that
`gym.make`, `gym.make_vec` and `gym.spec` look ids up in) a copy of the target's spec: its id is
`FloatingGOWEC-v0`, so no spec of name GOWEC above v0 exists, and an env made through the alias
reports the new id as its `spec.id`. Only its entry points differ: the `DeprecatedId` objects
below (string entry points, so the spec pickles and serialises like any other), which emit
`DeprecatedIdWarning` naming the new id (shown once per calling line under Python's default
filters), then build the target's env or native vector env. One visible trace: as
`gym.pprint_registry()` prints each spec's id, it lists `FloatingGOWEC-v0` a second time (under
`_alias`).
"""

from __future__ import annotations

import dataclasses
import warnings
from typing import Any

import gymnasium as gym
from gymnasium.envs.registration import load_env_creator

# deprecated id -> the id that replaces it (the same env)
ALIASES: dict[str, str] = {"GOWEC-v1": "FloatingGOWEC-v0"}


class DeprecatedIdWarning(FutureWarning):
    """An env id that still works but has been renamed (FutureWarning: shown by default)."""


def notice(old_id: str, stacklevel: int = 2) -> None:
    """Warn that `old_id` is deprecated, naming its replacement (once per calling line).
    `stacklevel` as `warnings.warn`'s, counted from the caller of `notice` (2: that caller's
    caller)."""
    warnings.warn(
        f"env id {old_id!r} is deprecated: use {ALIASES[old_id]!r} (the same env, renamed)",
        DeprecatedIdWarning,
        stacklevel=stacklevel + 1,
    )


def canonical_env_id(env_id: str, *, notice_alias: bool = True) -> str:
    """`env_id`, or the id that replaces it if it is a deprecated alias (warns unless told not)."""
    if env_id not in ALIASES:
        return env_id
    if notice_alias:
        notice(env_id, stacklevel=3)  # the line that called canonical_env_id's caller
    return ALIASES[env_id]


class DeprecatedId:
    """Entry point of a deprecated id: `notice`, then the target id's (vector) entry point."""

    def __init__(self, old_id: str, *, vector: bool) -> None:
        self.old_id, self.vector = old_id, vector

    def _target(self) -> Any:
        spec = gym.spec(ALIASES[self.old_id])
        entry = spec.vector_entry_point if self.vector else spec.entry_point
        return load_env_creator(entry) if isinstance(entry, str) else entry

    @property
    def metadata(self) -> dict[str, Any]:
        """The target class's metadata (`gym.make` reads `render_modes` from its entry point)."""
        return self._target().metadata

    def __call__(self, **kwargs: Any) -> Any:
        notice(self.old_id, stacklevel=3)  # gym.make's (or make_vec's) caller
        return self._target()(**kwargs)


# one pair of module-level entry points per alias ("module:name" strings in the spec)
gowec_v1 = DeprecatedId("GOWEC-v1", vector=False)
gowec_v1_vector = DeprecatedId("GOWEC-v1", vector=True)
_ENTRY_POINTS = {"GOWEC-v1": ("gowec_v1", "gowec_v1_vector")}


def register_aliases() -> None:
    """Put each alias whose target is registered into `gym.registry` (idempotent)."""
    for old_id, new_id in ALIASES.items():
        if old_id in gym.registry or new_id not in gym.registry:
            continue
        target = gym.registry[new_id]
        single, vector = (f"{__name__}:{name}" for name in _ENTRY_POINTS[old_id])
        gym.registry[old_id] = dataclasses.replace(
            target,
            entry_point=single,
            vector_entry_point=vector if target.vector_entry_point is not None else None,
        )
