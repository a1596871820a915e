"""Gymnasium wrappers. `register_envs()` registers every env id whose module is present."""

from __future__ import annotations

import warnings

import gymnasium as gym

# GOWEC-v0 (the dissertation's prescribed buoy) stays supported next to GOWEC-v1 (the floating
# buoy): silence gymnasium's "GOWEC-v0 is out of date, upgrade to v1" deprecation warning
warnings.filterwarnings("ignore", message=r".*GOWEC-v0 is out of date")

# id -> (entry point, default max_episode_steps or None); each env module owns its episode length
ENV_SPECS: dict[str, str] = {
    "GOWEC-v0": "mf_envs.envs.gowec.env:GOWECEnv",
    "GyroStabilizer-v0": "mf_envs.envs.gyro_stabilizer.env:GyroStabilizerEnv",
    "Inchworm-v0": "mf_envs.envs.inchworm.env:InchwormEnv",
    "GOWEC-v1": "mf_envs.envs.gowec_v1.env:GOWECV1Env",
}
# id -> native batched vector env (`gym.make_vec(id, vectorization_mode="vector_entry_point")`)
VECTOR_SPECS: dict[str, str] = {
    "GOWEC-v0": "mf_envs.envs.gowec.vector:GOWECVectorEnv",
    "GyroStabilizer-v0": "mf_envs.envs.gyro_stabilizer.vector:GyroStabilizerVectorEnv",
    "GOWEC-v1": "mf_envs.envs.gowec_v1.vector:GOWECV1VectorEnv",
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


def native_vector_supported(env_id: str, env_kwargs: dict | None = None) -> bool:
    """Whether `env_id` has a native vector env that runs the single env of `env_kwargs` (the
    inchworm's compiles the friction scene only): our vector env class's `supports`; for an id
    that is not ours, whether its spec has a vector entry point."""
    import importlib

    entry = VECTOR_SPECS.get(env_id)
    if entry is None:
        return gym.spec(env_id).vector_entry_point is not None
    if importlib.util.find_spec(entry.split(":")[0]) is None:
        return False
    module, name = entry.split(":")
    return bool(getattr(importlib.import_module(module), name).supports(**(env_kwargs or {})))
