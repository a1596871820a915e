"""GyroStabilizer-v0: its Gymnasium class in `env.py`,
declared in `task.py` (docs/adding_an_env.md)."""

from mf_envs.envs._lazy import lazy

__getattr__, __all__ = lazy(__name__, env="GyroStabilizerEnv", spec="OBS")
