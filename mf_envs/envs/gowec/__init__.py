"""GOWEC-v0: `env.GOWECEnv` (single), `vector.GOWECVectorEnv` (native batched), `spec` (the
observation layout `OBS`, reward, info keys and failure contract both use)."""

from mf_envs.envs.gowec.env import AVAILABLE_EFFECTS, DEFAULT_EFFECTS, GOWECEnv
from mf_envs.envs.gowec.spec import OBS

__all__ = ["AVAILABLE_EFFECTS", "DEFAULT_EFFECTS", "OBS", "GOWECEnv"]
