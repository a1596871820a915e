"""Gymnasium wrappers. `register_envs()` registers every declared env id whose module is present.

Each env declares itself once, in its package's `task.py` (`DECLARATION`, see
`mf_envs.envs.declaration`); a package outside mf_envs does so through the `mf_envs.envs`
entry-point group. `ENV_SPECS` and `VECTOR_SPECS` are views of the declarations.

Deprecated ids (`ALIASES`) still make their env: `gym.make("GOWEC-v1")` builds
`FloatingGOWEC-v0` and warns once (`mf_envs.envs._alias`).
"""

from __future__ import annotations

import gymnasium as gym

from mf_envs.envs._alias import ALIASES, DeprecatedIdWarning, canonical_env_id, register_aliases
from mf_envs.envs.declaration import (
    EnvDeclaration,
    declaration,
    declarations,
    load,
    refresh,
    task_declarations,
)

__all__ = [
    "ALIASES",
    "ENV_SPECS",
    "VECTOR_SPECS",
    "DeprecatedIdWarning",
    "EnvDeclaration",
    "available_env_ids",
    "canonical_env_id",
    "declaration",
    "declarations",
    "native_vector_supported",
    "register_envs",
    "task_ids",
]

# id -> "module:Class" of the single env; id -> native batched vector env
# (`gym.make_vec(id, vectorization_mode="vector_entry_point")`); both filled from the declarations
ENV_SPECS: dict[str, str] = {}
VECTOR_SPECS: dict[str, str] = {}


def _views() -> None:
    found = refresh()
    ENV_SPECS.clear()
    ENV_SPECS.update({i: d.entry_point for i, d in found.items()})
    VECTOR_SPECS.clear()
    VECTOR_SPECS.update({i: d.vector_entry_point for i, d in found.items() if d.vector_entry_point})


def available_env_ids() -> list[str]:
    """The declared env ids whose implementation module exists in this install."""
    return [env_id for env_id, d in declarations().items() if d.installed()]


def task_ids(role: str | None = None) -> list[str]:
    """Every registered id of an installed env, its task variants included (`Variant`), or
    those of one role ("easy", "headline"; docs/benchmark.md)."""
    return [i for i, d in task_declarations().items()
            if d.installed() and (role is None or d.role == role)]  # fmt: skip


def register_envs() -> None:
    """Collect the declarations (again) and register their ids, the task variants' included,
    with Gymnasium (idempotent)."""
    _views()
    for env_id, decl in task_declarations().items():
        if decl.installed() and env_id not in gym.registry:
            vec = decl.vector_entry_point if decl.vector_installed() else None
            # no TimeLimit: the env truncates itself at its own length (its default, or its
            # episode_seconds / n_periods / max_episode_steps kwargs); docs/api.md
            gym.register(
                id=env_id,
                entry_point=decl.entry_point,
                vector_entry_point=vec,
                kwargs=dict(decl.kwargs),
            )
    register_aliases()


def native_vector_supported(env_id: str, env_kwargs: dict | None = None) -> bool:
    """Whether `env_id` has a native vector env that runs the single env of `env_kwargs` (the
    inchworm's compiles the friction scene only): our vector env class's `supports`; for an id
    that is not ours, whether its spec has a vector entry point."""
    decl = declaration(env_id)
    if decl is None:
        return gym.spec(env_id).vector_entry_point is not None
    if not decl.vector_installed():
        return False
    cls = load(decl.vector_entry_point)
    supports = getattr(cls, "supports", None)
    kwargs = {**decl.kwargs, **(env_kwargs or {})}  # a variant's scene, then the caller's
    return True if supports is None else bool(supports(**kwargs))


_views()
