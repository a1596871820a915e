"""Serpentine-v0's declaration: what the layers above the env read of it (`envs.declaration`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mf_envs.envs.declaration import EnvDeclaration, Metric, shipped

WARMUP_SHARE = 0.25  # share of the episode left out of `speed` (the gait starts from rest)


def episode_metrics(
    env: Any, rewards: Sequence[float], infos: Sequence[Mapping[str, Any]]
) -> dict[str, float]:
    """`speed`: mean forward speed of the centre of mass along the target direction after the
    first quarter of the episode [m/s] (the mean of the steps' `speed`); `speed_all` over the
    whole episode; `energy_per_distance` [J/m] over the whole episode."""
    speed = np.array([i["speed"] for i in infos[1:]])
    energy = float(sum(i["actuation_energy"] for i in infos[1:]))
    start = int(len(speed) * WARMUP_SHARE)
    dt = float(env.unwrapped.control_dt)
    distance = float(speed.sum()) * dt
    return {
        "speed": float(speed[start:].mean()),
        "speed_all": float(speed.mean()),
        "energy_per_distance": energy / distance if distance > 0 else float("inf"),
    }


DECLARATION = EnvDeclaration(
    **shipped("Serpentine-v0", __package__, "SerpentineEnv", "serpentine", demos=False),
    max_episode_steps=400,  # the default episode: 20 s of 0.05 s
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
    randomize={"friction_coefficient": (0.7, 1.3), "youngs_modulus": (0.7, 1.3)},
    shifts={
        "friction_coefficient x0.7": {"friction_coefficient": 0.7},
        "friction_coefficient x1.3": {"friction_coefficient": 1.3},
        "youngs_modulus x0.7": {"youngs_modulus": 0.7},
    },
    # ~1 ms steps, 400-step episodes (20 s): small batches, a horizon of a few gait periods
    rllib={"num_envs_per_env_runner": 1, "train_batch_size_per_learner": 2000, "gamma": 0.99},
    # rl-zoo3 keys (train.config reads them when ppo.yml has no entry): the inchworm's recipe
    hyperparams={
        "ppo": {
            "normalize": "{'norm_obs': True, 'norm_reward': True}",
            "n_envs": 2,
            "policy": "MlpPolicy",
            "n_timesteps": 1e5,
            "n_steps": 1024,
            "batch_size": 64,
            "gae_lambda": 0.95,
            "gamma": 0.99,
            "n_epochs": 10,
            "ent_coef": 0.0,
            "learning_rate": "lin_3e-4",
            "clip_range": 0.2,
            "policy_kwargs": "dict(log_std_init=-0.5, ortho_init=False, activation_fn=nn.Tanh, "
            "net_arch=dict(pi=[64, 64], vf=[64, 64]))",
        },
    },  # fmt: skip
    vector_target=(64, 5.0e3),
    single_target=("steps_per_s", 1000.0),
    vector_n_max=256,
    slow=True,
    role="headline",
    summary=(
        "a soft serpentine robot on anisotropic Coulomb friction: crawl along +x from a random "
        "heading"
    ),
    headroom=(
        "no ceiling stated: no speed bound of a curvature-actuated body on Coulomb friction is "
        "derived here (the serpenoid's wave speed bounds travelling waves only). Evidence of "
        "headroom: a PPO policy (100k steps, on an earlier version of this env) swam 31 % "
        "faster than the best baseline, `heading` (docs/serpentine.md); the default baseline's "
        "speed today: docs/results/headline.json"
    ),
)
