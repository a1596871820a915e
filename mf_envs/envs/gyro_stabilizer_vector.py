"""GyroStabilizer-v0 as a native batched vector env: N ships stepped in one compiled call.

`gym.make_vec("GyroStabilizer-v0", num_envs=N, vectorization_mode="vector_entry_point", **kw)`
builds it; `kw` are those of `gym.make("GyroStabilizer-v0", ...)` plus `autoreset_mode`
(`gymnasium.vector.AutoresetMode`, default NEXT_STEP). Trajectories are identical, bit for bit,
to `SyncVectorEnv` over N single `GyroStabilizerEnv`s with the same seeds
(`tests/test_vector_envs.py`): resets go through a template single env, steps through
`physics.ship_batch.batch_env_advance`, which calls the single env's scalar kernel for every row.
See `mf_envs.envs._vector`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.gyro_stabilizer import GyroStabilizerEnv
from mf_envs.physics.ship import kernels as K
from mf_envs.physics.ship.batch import alloc_batch, batch_env_advance, batch_roll

INFO_KEYS = (
    "roll",
    "roll_rate",
    "pitch_rate",
    "yaw_rate",
    "gimbal_angle",
    "gimbal_rate",
    "gyro_moment",
    "wave_moment",
    "time",
)


class GyroStabilizerVectorEnv(BatchedVectorEnv):
    """N independent `GyroStabilizer-v0` envs (same kwargs, own seeds) in one numba call.

    Observations (N, 6) float32, actions (N, 1) in [-1, 1], rewards (N,) float64, infos batched
    as Gymnasium does ({key: (N,) array, "_key": mask}) with the single env's keys: `roll`,
    `roll_rate`, `pitch_rate`, `yaw_rate`, `gimbal_angle`, `gimbal_rate`, `gyro_moment`,
    `wave_moment`, `time`, `reward_terms` {`roll`, `effort`},
    `numerical_failure`.
    Memory: `state_nbytes()` bytes for the batch state (irregular seas add a wave table per env).
    """

    single_env_cls = GyroStabilizerEnv

    def _alloc(self, n: int) -> None:
        env = self.template
        self.b = alloc_batch(n, K.N_STATE, K.N_PARAMS, (1, 2))
        self._fresh = np.zeros((n, *self.single_observation_space.shape), dtype=np.float32)
        self._roll = np.zeros(n)
        self._high = np.asarray(env._high, dtype=np.float64)
        self._rate_scale = env.max_precession_rate

    def _load(self, i: int) -> None:
        env, b = self.template, self.b
        if b["tab"].shape[1:] != env._tab.shape:  # irregular seas: a table per env
            b["tab"] = np.zeros((self.num_envs, *env._tab.shape))
        b["t"][i] = env._t
        b["y"][i], b["R"][i] = env._y, env._R
        b["P"][i], b["tab"][i], b["out"][i] = env._P, env._tab, env._out

    def state_nbytes(self) -> int:
        """Bytes of the per-env batch state (physics arrays, observations)."""
        arrays = [*self.b.values(), self._obs, self._fresh, self._roll]
        return int(sum(a.nbytes for a in arrays))

    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        b, env = self.b, self.template
        a0 = actions[:, 0]
        obs = self._fresh
        batch_env_advance(
            active, b["t"], b["y"], b["R"], a0 * self._rate_scale, env.physics_dt,
            env.n_substeps, b["P"], b["tab"], b["out"], obs, self._high, b["ok"],
        )  # fmt: skip
        # reward terms exactly as GyroStabilizerEnv._get_rew (q * q on the float32 roll)
        s, w = env.roll_scale, env.effort_weight
        q = obs[:, 0].astype(np.float64) / s
        r_roll = -(q * q)
        r_effort = -w * a0 * a0
        reward = r_roll + r_effort
        batch_roll(b["R"], self._roll)
        y, out = b["y"], b["out"]
        values = (
            self._roll.copy(), y[:, 0].copy(), y[:, 1].copy(), y[:, 2].copy(), y[:, 3].copy(),
            y[:, 4].copy(), out[:, 0].copy(), out[:, 1].copy(), b["t"].copy(),
        )  # fmt: skip
        masks = np.ones((len(INFO_KEYS) + 4, self.num_envs), dtype=bool)  # one row per key
        info: dict[str, Any] = {}
        for j, (key, value) in enumerate(zip(INFO_KEYS, values)):
            info[key], info[f"_{key}"] = value, masks[j]
        terms = {"roll": r_roll, "_roll": masks[-4], "effort": r_effort}
        terms["_effort"] = masks[-3]
        info["reward_terms"], info["_reward_terms"] = terms, masks[-2]
        trunc = b["t"] >= env.episode_seconds - 1e-9
        fail = active & ~(b["ok"] & np.isfinite(reward))
        info["numerical_failure"], info["_numerical_failure"] = fail.copy(), masks[-1]
        term = np.zeros(self.num_envs, dtype=bool)
        if fail.any():  # MFEnv._finish_step: last finite obs, reward 0, terminated
            obs = obs.copy()  # _fresh mirrors the single env's buffer: kernel writes only
            obs[fail] = self._obs[fail]
            reward[fail], term[fail] = 0.0, True
        return obs, reward, term, trunc, info
