"""Inchworm-v0: `env.InchwormEnv` and `spec` (observation layout `observation_layout(n)`, reward
terms, info keys, failure contract)."""

from mf_envs.envs.inchworm.env import DEFAULT_EFFECTS, SEED_SCENE_EFFECTS, InchwormEnv
from mf_envs.envs.inchworm.spec import observation_layout

__all__ = ["DEFAULT_EFFECTS", "SEED_SCENE_EFFECTS", "InchwormEnv", "observation_layout"]
