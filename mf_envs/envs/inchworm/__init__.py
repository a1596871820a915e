"""Inchworm-v0: its Gymnasium class in `env.py`, declared in `task.py` (docs/adding_an_env.md)."""

from mf_envs.envs._lazy import lazy

__getattr__, __all__ = lazy(
    __name__,
    env="InchwormEnv SEED_SCENE_EFFECTS",
    spec="observation_layout",
    build="LAG_FRICTION_EFFECTS LAG_FRICTION_SCENE RIOS2017_BODY RIOS2017_SCENE",
)
