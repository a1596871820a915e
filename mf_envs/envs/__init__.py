"""Gymnasium wrappers. `register_envs()` registers every env id whose module is present.

Deprecated ids (`ALIASES`) still make their env: `gym.make("GOWEC-v1")` builds
`FloatingGOWEC-v0` and warns once (`mf_envs.envs._alias`).
"""

from __future__ import annotations

import gymnasium as gym

from mf_envs.envs._alias import ALIASES, DeprecatedIdWarning, canonical_env_id, register_aliases

__all__ = [
    "ALIASES",
    "ENV_SPECS",
    "VECTOR_SPECS",
    "DeprecatedIdWarning",
    "available_env_ids",
    "canonical_env_id",
    "native_vector_supported",
    "register_envs",
]

# id -> (entry point, default max_episode_steps or None); each env module owns its episode length
ENV_SPECS: dict[str, str] = {
    "GOWEC-v0": "mf_envs.envs.gowec.env:GOWECEnv",
    "GyroStabilizer-v0": "mf_envs.envs.gyro_stabilizer.env:GyroStabilizerEnv",
    "Inchworm-v0": "mf_envs.envs.inchworm.env:InchwormEnv",
    "FloatingGOWEC-v0": "mf_envs.envs.gowec_v1.env:GOWECV1Env",
}
# id -> native batched vector env (`gym.make_vec(id, vectorization_mode="vector_entry_point")`)
VECTOR_SPECS: dict[str, str] = {
    "GOWEC-v0": "mf_envs.envs.gowec.vector:GOWECVectorEnv",
    "GyroStabilizer-v0": "mf_envs.envs.gyro_stabilizer.vector:GyroStabilizerVectorEnv",
    "FloatingGOWEC-v0": "mf_envs.envs.gowec_v1.vector:GOWECV1VectorEnv",
    "Inchworm-v0": "mf_envs.envs.inchworm.vector:InchwormVectorEnv",
}


def available_env_ids() -> list[str]:
    """The env ids whose implementation module exists in this install."""
    import importlib.util

    return [
        env_id
        for env_id, entry in ENV_SPECS.items()
        if importlib.util.find_spec(entry.split(":")[0]) is not None
    ]


def register_envs() -> None:
    """Register the available env ids with Gymnasium (idempotent)."""
    import importlib.util

    for env_id in available_env_ids():
        if env_id not in gym.registry:
            vec = VECTOR_SPECS.get(env_id)
            if vec is not None and importlib.util.find_spec(vec.split(":")[0]) is None:
                vec = None
            gym.register(id=env_id, entry_point=ENV_SPECS[env_id], vector_entry_point=vec)
    register_aliases()


def native_vector_supported(env_id: str, env_kwargs: dict | None = None) -> bool:
    """Whether `env_id` has a native vector env that runs the single env of `env_kwargs` (the
    inchworm's compiles the friction scene only): our vector env class's `supports`; for an id
    that is not ours, whether its spec has a vector entry point."""
    import importlib

    env_id = canonical_env_id(env_id, notice_alias=False)
    entry = VECTOR_SPECS.get(env_id)
    if entry is None:
        return gym.spec(env_id).vector_entry_point is not None
    if importlib.util.find_spec(entry.split(":")[0]) is None:
        return False
    module, name = entry.split(":")
    return bool(getattr(importlib.import_module(module), name).supports(**(env_kwargs or {})))
