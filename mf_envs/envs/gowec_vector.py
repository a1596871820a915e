"""GOWEC-v0 as a native batched vector env: N gyroscopes stepped in one compiled call.

`gym.make_vec("GOWEC-v0", num_envs=N, vectorization_mode="vector_entry_point", **kwargs)` builds
it; `kwargs` are those of `gym.make("GOWEC-v0", ...)` plus `autoreset_mode`
(`gymnasium.vector.AutoresetMode`, default NEXT_STEP). Trajectories are identical, bit for bit,
to `SyncVectorEnv` over N single `GOWECEnv`s with the same seeds (`tests/test_vector_envs.py`):
resets go through a template single env, steps through `physics.gowec_batch.batch_fast_step`,
which calls the single env's scalar kernel for every row. See `mf_envs.envs._vector`.
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.gowec import MAX_BUOY_RATE, GOWECEnv
from mf_envs.physics.gowec.batch import alloc_batch, batch_fast_step


@numba.njit(cache=True)
def _observe(active, phi, phid, w, g, b, out):
    """GOWECEnv._get_obs row by row: (sin phi, cos phi, phi', w1, w2, w3), rates clipped."""
    for i in range(phi.shape[0]):
        if not active[i]:
            continue
        out[i, 0] = math.sin(phi[i])
        out[i, 1] = math.cos(phi[i])
        out[i, 2] = min(max(phid[i], -g), g)
        for j in range(3):
            out[i, 3 + j] = min(max(w[i, j], -b), b)


class GOWECVectorEnv(BatchedVectorEnv):
    """N independent `GOWEC-v0` envs (same kwargs, own seeds) stepped in one numba call.

    Observations (N, 6) float32, actions (N, 1) in [-1, 1], rewards (N,) float64, infos batched
    as Gymnasium does ({key: (N,) array, "_key": mask}): `power`, `gimbal_angle`, `gimbal_rate`,
    `buoy_rate`, `wave_elevation`, `time`, `reward_terms` {`energy`}, `numerical_failure`,
    `overspeed` (the gimbal overspeed trip, which terminates the row as in the single env).
    Memory: `state_nbytes()` bytes for the batch state.
    """

    single_env_cls = GOWECEnv

    def _alloc(self, n: int) -> None:
        env = self.template
        m = env.n_components if "irregular_waves" in env.effects else 1
        self.b = alloc_batch(n, m)
        self._steps = np.zeros(n, dtype=np.int64)
        self._fresh = np.zeros((n, *self.single_observation_space.shape), dtype=np.float32)
        self.max_steps = env.max_steps
        self.control_dt = env.control_dt
        self._scale = env._energy_scale
        self._torque_scale = env.max_generator_torque

    def _load(self, i: int) -> None:
        env, b = self.template, self.b
        model = env.model
        self._inert, self._psid = model.inert, model.psid
        self._cth, self._sth, self._two_d = model._cth, model._sth, model._two_d
        b["phi"][i], b["phid"][i] = env.state
        b["t"][i] = 0.0
        wave = env.wave
        b["amp"][i], b["om"][i] = wave.amplitudes, wave.omegas
        b["eps"][i], b["k"][i] = wave.phases, model._k  # slope wavenumbers k F(k r)
        b["w"][i] = env._w
        b["eta"][i] = env._eta
        self._steps[i] = 0

    def state_nbytes(self) -> int:
        """Bytes of the per-env batch state (physics arrays, step counters, observations)."""
        arrays = [*self.b.values(), self._steps, self._obs, self._fresh]
        return int(sum(a.nbytes for a in arrays))

    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        b, env = self.b, self.template
        Mg = actions[:, 0] * self._torque_scale
        b["t"][:] = self._steps * self.control_dt
        batch_fast_step(
            active, b["t"], b["phi"], b["phid"], Mg, env.physics_dt, env.n_substeps,
            self._inert, self._psid, b["amp"], b["om"], b["eps"], b["k"],
            self._cth, self._sth, self._two_d, b["energy"], b["w"], b["eta"],
        )  # fmt: skip
        self._steps[active] += 1
        t = self._steps * self.control_dt
        energy = b["energy"]
        reward = energy * self._scale
        terms = {"energy": reward.copy()}
        trunc = self._steps >= self.max_steps
        obs = self._fresh
        g = env.max_gimbal_rate
        _observe(active, b["phi"], b["phid"], b["w"], g, MAX_BUOY_RATE, obs)
        ok = np.isfinite(b["phi"]) & np.isfinite(b["phid"]) & np.isfinite(energy)
        overspeed = (np.abs(b["phid"]) > g) & active & ok
        masks = np.ones((10, self.num_envs), dtype=bool)  # one row per info key
        info: dict[str, Any] = {
            "power": energy / self.control_dt,
            "gimbal_angle": b["phi"].copy(),
            "gimbal_rate": b["phid"].copy(),
            "buoy_rate": b["w"][:, 0].copy(),
            "wave_elevation": b["eta"].copy(),
            "time": t,
            "reward_terms": terms,
            "numerical_failure": ~ok,
            "overspeed": overspeed,
        }
        terms["_energy"] = masks[9]
        for j, key in enumerate(list(info)):
            info[f"_{key}"] = masks[j]
        term = overspeed.copy()
        if not ok[active].all():  # MFEnv._finish_step: last finite obs, reward 0, terminated
            bad = ~ok & active
            obs[bad] = self._obs[bad]
            reward[bad], term[bad] = 0.0, True
            info["power"][bad] = 0.0
            for key in ("gimbal_angle", "gimbal_rate", "buoy_rate", "wave_elevation", "time"):
                info[f"_{key}"][bad] = False
        return obs, reward, term, trunc, info
