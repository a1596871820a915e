"""GyroStabilizer-v0: `env.GyroStabilizerEnv` (single), `vector.GyroStabilizerVectorEnv` (native
batched), `spec` (observation layout `OBS`, reward terms, info keys, failure contract), `wiring`
(the ship physics parameters from the env arguments)."""

from mf_envs.envs.gyro_stabilizer.env import DEFAULT_EFFECTS, GyroStabilizerEnv
from mf_envs.envs.gyro_stabilizer.spec import OBS

__all__ = ["DEFAULT_EFFECTS", "OBS", "GyroStabilizerEnv"]
