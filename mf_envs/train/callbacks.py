"""Evaluation during training on vector rows: the learning curve and the best checkpoint.

`PeriodicEvaluation` does what SB3's `EvalCallback` does (the same `evaluations.npz` log:
timesteps, results, ep_lengths; the best policy saved on a new best mean return; the training
env's `VecNormalize` statistics synced into the evaluation env first), with the evaluation
episodes run side by side, one per row of the evaluation env (`model.predict` on the batch).
On a native vector env the evaluation then costs an episode's length of batched steps, not
`n_eval_episodes` episodes of single steps.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
from stable_baselines3.common.callbacks import BaseCallback
from stable_baselines3.common.vec_env import VecEnv, sync_envs_normalization

from mf_envs._files import atomic_path


def row_episodes(act: Callable[[np.ndarray], np.ndarray], venv: VecEnv) -> tuple[np.ndarray, ...]:
    """(returns (n,), lengths (n,)) of the first episode of each of `venv`'s n rows from a
    reset, acting with `act` (raw rewards: an evaluation `VecNormalize` has norm_reward off)."""
    n = venv.num_envs
    ret, length, done = np.zeros(n), np.zeros(n, dtype=int), np.zeros(n, dtype=bool)
    obs = venv.reset()
    while not done.all():
        obs, rew, d, _ = venv.step(act(obs))
        ret[~done] += rew[~done]
        length[~done] += 1
        done |= d
    return ret, length


class PeriodicEvaluation(BaseCallback):
    """Every `eval_freq` calls (vector steps), one episode per row of `eval_env`; the log in
    `log_path/evaluations.npz`, the best policy (with its normalisation statistics) in
    `best_folder` (`train.policy.save_policy_files`)."""

    def __init__(self, eval_env: VecEnv, eval_freq: int, log_path: Path, best_folder: Path):
        super().__init__(verbose=0)
        self.eval_env, self.eval_freq = eval_env, int(eval_freq)
        self.log_path, self.best_folder = Path(log_path), Path(best_folder)
        self.best_mean_reward, self.best_timestep = -np.inf, None
        self.timesteps: list[int] = []
        self.results: list[np.ndarray] = []
        self.lengths: list[np.ndarray] = []

    def _on_step(self) -> bool:
        if self.eval_freq <= 0 or self.n_calls % self.eval_freq:
            return True
        from mf_envs.train.policy import save_policy_files

        if self.model.get_vec_normalize_env() is not None:
            sync_envs_normalization(self.training_env, self.eval_env)
        ret, length = row_episodes(
            lambda obs: self.model.predict(obs, deterministic=True)[0], self.eval_env
        )
        self.timesteps.append(int(self.num_timesteps))
        self.results.append(ret)
        self.lengths.append(length)
        with atomic_path(self.log_path / "evaluations.npz") as tmp, open(tmp, "wb") as f:
            np.savez(f, timesteps=np.array(self.timesteps), results=np.array(self.results),
                     ep_lengths=np.array(self.lengths))  # fmt: skip
        if float(ret.mean()) > self.best_mean_reward:
            self.best_mean_reward, self.best_timestep = float(ret.mean()), self.timesteps[-1]
            save_policy_files(self.best_folder, self.model, self.model.get_vec_normalize_env())
        return True
