"""Inchworm-v0: `env.py` the Gymnasium class, `task.py` its declaration (`DECLARATION`), the
package's other modules as docs/adding_an_env.md lists them. Names below import on first use, so
reading the declaration (`import mf_envs`) does not load the physics."""

from mf_envs.envs._lazy import lazy

__getattr__, __all__ = lazy(
    __name__,
    {
        "AVAILABLE_EFFECTS": "env",
        "DEFAULT_EFFECTS": "env",
        "SEED_SCENE_EFFECTS": "env",
        "LAG_FRICTION_EFFECTS": "build",
        "LAG_FRICTION_SCENE": "build",
        "RIOS2017_BODY": "build",
        "RIOS2017_SCENE": "build",
        "InchwormEnv": "env",
        "observation_layout": "spec",
    },
)
