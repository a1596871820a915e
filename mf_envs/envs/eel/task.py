"""Eel-v0's declaration: what the layers above the env read of it (`envs.declaration`)."""

from __future__ import annotations

from dataclasses import replace

from mf_envs.envs.declaration import shipped
from mf_envs.envs.serpentine.task import DECLARATION as SERPENTINE

# the serpentine's declaration (metrics: speed after the first quarter of the episode, energy per
# distance; info keys, bad reset options, RLlib and rl-zoo3 settings, throughput goals): the
# same reward structure on the same beam; its own ids, baselines and randomised parameters
DECLARATION = replace(
    SERPENTINE,
    **shipped("Eel-v0", __package__, "EelEnv", "eel", demos=False),
    max_episode_steps=500,  # the default episode: 10 s of 0.02 s
    randomize={"drag_normal": (0.7, 1.3), "youngs_modulus": (0.7, 1.3)},
    choices={},
    shifts={
        "drag_normal x0.7": {"drag_normal": 0.7},
        "drag_normal x1.3": {"drag_normal": 1.3},
        "youngs_modulus x0.7": {"youngs_modulus": 0.7},
    },
    role="headline",
    summary=(
        "an anguilliform swimmer (resistive and reactive forces): swim along +x from a random "
        "heading"
    ),
    headroom=(
        "no ceiling stated: the speed of this model grows with the undulation frequency until "
        "the period bound and the muscles' rate limit stop it, and no bound over every command "
        "sequence is derived. The best baseline (`heading`) rides the speed-tuned wave; a PPO "
        "policy (on an earlier version of this env) had a 24 % higher return at 19 % less "
        "energy per metre (docs/eel.md); the default baseline's speed today: "
        "docs/results/headline.json"
    ),
)
