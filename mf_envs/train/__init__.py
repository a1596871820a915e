"""Stable-Baselines3 PPO training and evaluation for the mf_envs environments.

- `mf-envs train ENV_ID` / `mf-envs evaluate ENV_ID` (`train.cli`), hyperparameters in
  `mf_envs/train/configs/ppo.yml` (rl-zoo3 format);
- `train.load_policy(env_id, path=None)`: a shipped (or given) policy acting on raw observations;
- `train.randomize.DomainRandomization`: physical-parameter randomisation at every reset.

Importing `train` is light; SB3 and torch are imported when a policy is loaded or trained.
"""

from __future__ import annotations

from mf_envs.train.policy import PPOPolicy, load_policy

__all__ = ["PPOPolicy", "load_policy"]
