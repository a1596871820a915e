"""Eel-v0's declaration: what the layers above the env read of it (`envs.declaration`)."""

from __future__ import annotations

from mf_envs.envs.declaration import EnvDeclaration, Metric
from mf_envs.envs.serpentine.task import DECLARATION as SERPENTINE
from mf_envs.envs.serpentine.task import episode_metrics

# the serpentine's metrics (speed after the first quarter of the episode, energy per distance)
# and its PPO recipe: same reward structure, same beam
DECLARATION = EnvDeclaration(
    env_id="Eel-v0",
    entry_point="mf_envs.envs.eel.env:EelEnv",
    vector_entry_point="mf_envs.envs.eel.vector:EelVectorEnv",
    baselines="mf_envs.controllers.eel",
    metric=Metric("speed", True, "m/s"),
    episode_metrics=episode_metrics,
    info_keys=("x", "y", "heading", "speed", "actuation_energy", "actuation_net_work", "time"),
    bad_reset_options=(
        ("heading", float("nan")),
        ("heading", "1"),
        ("heading", 1e3),
        ("kappa", [1.0, 2.0]),
        ("kappa", [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1e3]),
    ),
    randomize={"drag_normal": (0.7, 1.3), "youngs_modulus": (0.7, 1.3)},
    shifts={
        "drag_normal x0.7": {"drag_normal": 0.7},
        "drag_normal x1.3": {"drag_normal": 1.3},
        "youngs_modulus x0.7": {"youngs_modulus": 0.7},
    },
    rllib={"num_envs_per_env_runner": 1, "train_batch_size_per_learner": 2000, "gamma": 0.99},
    hyperparams=SERPENTINE.hyperparams,  # rl-zoo3 keys when ppo.yml has no entry
    vector_target=(64, 5.0e3),
    single_target=("steps_per_s", 1000.0),
    vector_n_max=256,
    slow=True,
)
