"""GyroStabilizer-v0 as a native batched vector env: N ships stepped in one compiled call.

`gym.make_vec("GyroStabilizer-v0", num_envs=N, vectorization_mode="vector_entry_point", **kw)`
builds it; `kw` are those of `gym.make("GyroStabilizer-v0", ...)` plus `autoreset_mode`
(`gymnasium.vector.AutoresetMode`, default NEXT_STEP). Trajectories are identical, bit for bit,
to `SyncVectorEnv` over N single `GyroStabilizerEnv`s with the same seeds
(`tests/test_vector_envs.py`): resets go through a template single env (its public
`batch_row()`), steps through `physics.ship.batch.batch_advance`, which calls the single env's
scalar kernel for every row, and observation, reward, info and failure contract come from
`gyro_stabilizer.spec`, as in the single env. See `mf_envs.envs._vector`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.gyro_stabilizer import spec
from mf_envs.envs.gyro_stabilizer.env import GyroStabilizerEnv
from mf_envs.physics.ship import kernels as K
from mf_envs.physics.ship.batch import alloc_batch, batch_advance, batch_roll


class GyroStabilizerVectorEnv(BatchedVectorEnv):
    """N independent `GyroStabilizer-v0` envs (same kwargs, own seeds) in one numba call.

    Observations (N, 6) float32 (`spec.OBS`), actions (N, 1) in [-1, 1], rewards (N,) float64,
    infos batched as Gymnasium does ({key: (N,) array, "_key": mask}) with the single env's keys
    (`spec.INFO_KEYS`). Memory: `state_nbytes()` bytes for the batch state (irregular seas add
    a wave table per env).
    """

    single_env_cls = GyroStabilizerEnv

    def _alloc(self, n: int) -> None:
        self.b = alloc_batch(n, K.N_STATE, K.N_PARAMS, (1, 2))
        self._fresh = np.zeros((n, spec.OBS.size), dtype=np.float32)
        self._roll = np.zeros(n)
        self._ok = np.ones(n, dtype=bool)
        self._steps = np.zeros(n, dtype=np.int64)

    def _load(self, i: int) -> None:
        row, b = self.template.batch_row(), self.b
        if b["tab"].shape[1:] != row["tab"].shape:  # irregular seas: a table per env
            b["tab"] = np.zeros((self.num_envs, *row["tab"].shape))
        for key in ("t", "y", "R", "P", "tab", "out"):
            b[key][i] = row[key]
        self._steps[i] = 0

    def state_nbytes(self) -> int:
        """Bytes of the per-env batch state (physics arrays, observations)."""
        arrays = [*self.b.values(), self._obs, self._fresh, self._roll, self._ok, self._steps]
        return int(sum(a.nbytes for a in arrays))

    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        b, env = self.b, self.template
        a0 = actions[:, 0]
        obs, ok = self._fresh, self._ok
        e0 = b["y"][:, K.E_STATE].copy()
        batch_advance(
            active, b["t"], b["y"], b["R"], a0 * env.max_precession_rate, env.physics_dt,
            env.n_substeps, b["P"], b["tab"], b["out"],
        )  # fmt: skip
        self._steps[active] += 1
        batch_roll(b["R"], self._roll)
        ok[~active] = True
        spec.observe_rows(active, self._roll, b["y"], b["R"], obs, ok)
        if not ok.all():  # as the single env: the last finite observation stays (and is scored)
            obs[~ok] = self._obs[~ok]
        roll_obs = obs[:, spec.OBS.index("roll")].astype(np.float64)
        energy = b["y"][:, K.E_STATE] - e0
        terms = spec.reward_terms(roll_obs, energy, env.roll_scale, env.effort_weight)
        reward = terms["roll"] + terms["effort"]
        time = self._steps * env.control_dt
        info = spec.step_info(self._roll.copy(), b["y"], b["out"], time, terms, energy)
        masks = np.ones((len(spec.INFO_KEYS) + 2, self.num_envs), dtype=bool)  # one per key
        terms["_roll"], terms["_effort"] = masks[-2], masks[-1]
        fail = active & ~(ok & np.isfinite(reward))
        info["numerical_failure"] = fail.copy()
        for j, key in enumerate(spec.INFO_KEYS):
            info[f"_{key}"] = masks[j]
        trunc = self._steps >= env.max_steps
        term = np.zeros(self.num_envs, dtype=bool)
        if fail.any():  # MFEnv._finish_step: last finite obs, reward 0, terminated
            obs = obs.copy()
            obs[fail] = self._obs[fail]
            reward[fail], term[fail] = 0.0, True
        return obs, reward, term, trunc, info
