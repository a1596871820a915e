"""GyroStabilizer-v0 as a native batched vector env: N ships stepped in one compiled call.

`gym.make_vec("GyroStabilizer-v0", num_envs=N, vectorization_mode="vector_entry_point", **kw)`
builds it; `kw` are those of `gym.make("GyroStabilizer-v0", ...)` plus `autoreset_mode`
(`gymnasium.vector.AutoresetMode`, default NEXT_STEP). Trajectories are identical, bit for bit,
to `SyncVectorEnv` over N single `GyroStabilizerEnv`s with the same seeds
(`tests/test_vector_envs.py`): a step is ONE numba call (`step_rows`) that advances every row
with the single env's scalar kernel (`physics.ship.kernels.advance_with`) and forms its
observation (`spec.observe`), reward terms and info columns with the single env's expressions;
seeded resets and resets with options go through a template single env (its public
`batch_row()`); the contract (observation, reward, info keys, failure) is `gyro_stabilizer.spec`.

Compiled resets (regular seas): `GyroStabilizerEnv.reset()` without options draws three doubles,
roll U(-0.05, 0.05), roll rate U(-0.02, 0.02) and the wave phase U(0, 2 pi), and the phase
enters the packed parameters only in the slot WPHASE (sign flipped for a negative encounter
frequency). Autoresets and seedless resets without options therefore run in one numba call
(`reset_rows`) from doubles pre-drawn from each row's generator (`mf_envs.envs._predraw`).
Irregular seas (a new sea of many draws per reset) keep the template path. See
`mf_envs.envs._vector`.

Threads (kwarg `num_threads`, `mf_envs.envs._rows.RowBlocks`): the rows are stepped in
num_threads blocks at once, block 0 in the calling thread and the others on Python worker
threads (`step_rows` releases the GIL), the split adapting so that the blocks end together;
rows are independent, so results are bit-identical to one thread (`tests/test_vector_envs.py`).
Default: one block per CPU once each gets >= 128 rows. The row loop (`_rows`) and the ship's
step are `mf_envs._jit.kernel`s: compiled without reference counting, so the rows' views of the
shared arrays cost nothing. Measured (N = 1024, random actions, autoresets, 2-core machine,
medians of five 3 s runs): 1.12M env-steps/s on one thread, 1.79M on two (runs 1.69-1.88M;
issue 17); with both cores busy elsewhere, two threads gained nothing over one (and lost
< 10 %).
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.envs._predraw import PredrawnResets
from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.gyro_stabilizer import spec, wiring
from mf_envs.envs.gyro_stabilizer.env import GyroStabilizerEnv
from mf_envs.frames.kernels import rk4_work, rkmk4_rwork
from mf_envs.physics.ship import kernels as K
from mf_envs.physics.ship.batch import alloc_batch
from mf_envs.physics.ship.layout import Slot

_ROLL = spec.OBS.index("roll")
# info columns written by step_rows / reset_rows, in spec.INFO_KEYS order up to drive_energy
COLS = spec.INFO_KEYS[:11]
C_ENERGY, C_RROLL, C_REFFORT, C_TIME, N_COLS = 10, 11, 12, 13, 14
ROLL0, RATE0, PHASE0 = (-0.05, 0.05), (-0.02, 0.02), (0.0, 2.0 * math.pi)  # reset's U(lo, hi)


@numba.njit(cache=True, inline="always")
def _info_row(c, roll, y, out, energy):
    """Info columns (COLS order) of one row: roll, body rates, gimbal angle/rate, moments,
    drive torque/power, the step's drive energy (`spec.step_info`)."""
    c[0] = roll
    for j in range(5):
        c[1 + j] = y[j]
    for j in range(4):
        c[6 + j] = out[j]
    c[C_ENERGY] = energy


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, t, y, R, u, dt, n_sub, P, tab, out, steps, last, obs, cols,
              ok_out, reward, roll_scale, effort_weight, control_dt):  # fmt: skip
    """One control step of the active rows lo <= i < hi (GyroStabilizerEnv.step without Python;
    the GIL is released, so threads can step disjoint blocks of rows at once).

    t (N,) s, y (N, N_STATE), R (N, 3, 3), P, tab, out as `physics.ship.batch.alloc_batch`;
    u (N,) rad/s; steps (N,) int64; last (N, 6) float32 the last returned observations; writes
    obs (N, 6) float32, cols (N_COLS, N) (info columns, reward terms, time), ok_out (N,) False
    on a numerical failure (the step then scores 0 and keeps the last observation), reward (N,).
    This task's scratch is allocated here; the rows are stepped by `_rows`.
    """
    work, Rwork = rk4_work(y.shape[1]), rkmk4_rwork()
    ob, c = np.empty(obs.shape[1], dtype=obs.dtype), np.empty(N_COLS)
    _rows(lo, hi, active, t, y, R, u, dt, n_sub, P, tab, out, steps, last, obs, cols, ok_out,
          reward, roll_scale, effort_weight, control_dt, work, Rwork, ob, c)  # fmt: skip


@kernel
def _rows(lo, hi, active, t, y, R, u, dt, n_sub, P, tab, out, steps, last, obs, cols, ok_out,
          reward, roll_scale, effort_weight, control_dt, work, Rwork, ob, c):  # fmt: skip
    """The row loop of `step_rows` on the batch arrays in place (a `mf_envs._jit.kernel`: its
    row views cost no reference counts, so threads share the arrays freely); work, Rwork: the
    stepper's scratch, ob (6,) float32 and c (N_COLS,) one row's observation and info columns."""
    for i in range(lo, hi):
        if not active[i]:
            continue
        yi, Ri, oi = y[i], R[i], out[i]
        e0 = yi[K.E_STATE]
        t[i] = K.advance_with(t[i], yi, Ri, u[i], dt, n_sub, P[i], tab[i], oi, work, Rwork)
        steps[i] += 1
        roll = K.roll_of(Ri)
        ok = spec.observe(roll, yi, Ri, ob)
        if not ok:  # the last finite observation stays (and is scored)
            for k in range(ob.shape[0]):
                ob[k] = last[i, k]
        energy = yi[K.E_STATE] - e0
        q = np.float64(ob[_ROLL]) / roll_scale
        c[C_RROLL], c[C_REFFORT] = -(q * q), -effort_weight * energy
        rew = c[C_RROLL] + c[C_REFFORT]
        _info_row(c, roll, yi, oi, energy)
        c[C_TIME] = steps[i] * control_dt
        ok_out[i] = ok and math.isfinite(rew)
        if not ok_out[i]:  # MFEnv._finish_step: last finite obs, reward 0, terminated
            for k in range(ob.shape[0]):
                ob[k] = last[i, k]
            rew = 0.0
        reward[i] = rew
        for k in range(ob.shape[0]):
            obs[i, k] = ob[k]
        for k in range(c.shape[0]):
            cols[k, i] = c[k]


@numba.njit(cache=True)
def reset_rows(idx, draws, ptr, p_sign, t, y, R, P, tab, out, steps, obs, cols):
    """GyroStabilizerEnv.reset() (regular seas, no options) for the rows idx from pre-drawn
    doubles: draws (N, 3 K) next_double()s of each row's generator, ptr (N,) the next unused one.
    Writes roll ~ U(-0.05, 0.05) rad (R = rot_x(roll)), roll rate ~ U(-0.02, 0.02) rad/s, the
    wave phase ~ U(0, 2 pi) into P[WPHASE] (times p_sign), t = 0, the rest of y zero, the
    moments and drive output at t = 0 (out), the observation and the info columns."""
    for j in range(idx.shape[0]):
        i = idx[j]
        p = ptr[i]
        roll = ROLL0[0] + (ROLL0[1] - ROLL0[0]) * draws[i, p]
        rate = RATE0[0] + (RATE0[1] - RATE0[0]) * draws[i, p + 1]
        phase = PHASE0[0] + (PHASE0[1] - PHASE0[0]) * draws[i, p + 2]
        ptr[i] = p + 3
        if p_sign != 0.0:  # 0: the scene has no regular wave (the phase is unused)
            P[i, Slot.WPHASE] = phase if p_sign > 0.0 else -phase
        y[i, :] = 0.0
        y[i, 0] = rate
        c, s = math.cos(roll), math.sin(roll)
        Ri = R[i]
        Ri[0, 0], Ri[0, 1], Ri[0, 2] = 1.0, 0.0, 0.0
        Ri[1, 0], Ri[1, 1], Ri[1, 2] = 0.0, c, -s
        Ri[2, 0], Ri[2, 1], Ri[2, 2] = 0.0, s, c
        t[i], steps[i] = 0.0, 0
        out[i, 0] = 0.0
        out[i, 1] = K.external_moment(0.0, y[i], Ri, P[i], tab[i])[3]
        out[i, 2], out[i, 3] = K.drive_output(0.0, y[i], Ri, 0.0, P[i])
        roll0 = K.roll_of(Ri)
        spec.observe(roll0, y[i], Ri, obs[i])
        _info_row(cols[i], roll0, y[i], out[i], 0.0)
        cols[i, C_RROLL], cols[i, C_REFFORT], cols[i, C_TIME] = 0.0, 0.0, 0.0


class GyroStabilizerVectorEnv(PredrawnResets, BatchedVectorEnv):
    """N independent `GyroStabilizer-v0` envs (same kwargs, own seeds) in one numba call.

    Observations (N, 6) float32 (`spec.OBS`), actions (N, 1) in [-1, 1], rewards (N,) float64,
    infos batched as Gymnasium does ({key: (N,) array, "_key": mask}) with the single env's keys
    (`spec.INFO_KEYS`). Memory: `state_nbytes()` bytes for the batch state (irregular seas add
    a wave table per env).
    """

    single_env_cls = GyroStabilizerEnv
    DRAWS_PER_RESET = 3

    def _alloc(self, n: int) -> None:
        env = self.template
        self.b = alloc_batch(n, K.N_STATE, K.N_PARAMS, (1, 2))
        self._fresh = np.zeros((n, spec.OBS.size), dtype=np.float32)
        self._cols = np.zeros((n, N_COLS))
        self._ok = np.ones(n, dtype=bool)
        self._reward = np.zeros(n)
        self._steps = np.zeros(n, dtype=np.int64)
        # the phase is the only reset-dependent parameter of a regular sea (module doc)
        p1, p2 = wiring.pack(env, 1.0), wiring.pack(env, 2.0)
        same = set(np.flatnonzero(p1 != p2).tolist()) <= {int(Slot.WPHASE)}
        self._p_sign = float(np.sign(p1[Slot.WPHASE]))
        self._predraw_alloc(n, same and "irregular_waves" not in env.effects)

    def _load(self, i: int) -> None:
        row, b = self.template.batch_row(), self.b
        if b["tab"].shape[1:] != row["tab"].shape:  # irregular seas: a table per env
            b["tab"] = np.zeros((self.num_envs, *row["tab"].shape))
        for key in ("t", "y", "R", "P", "tab", "out"):
            b[key][i] = row[key]
        self._steps[i] = 0

    def state_nbytes(self) -> int:
        """Bytes of the per-env batch state (physics arrays, observations, info columns)."""
        arrays = [*self.b.values(), self._obs, self._fresh, self._cols, self._ok, self._steps]
        return int(sum(a.nbytes for a in arrays)) + self._reward.nbytes + self._draws.nbytes

    def _batch_reset(self, idx: np.ndarray) -> dict[str, Any] | None:
        if not self._predrawn(idx):
            return None
        b = self.b
        reset_rows(
            idx, self._draws, self._ptr, self._p_sign, b["t"], b["y"], b["R"], b["P"],
            b["tab"], b["out"], self._steps, self._obs, self._cols,
        )  # fmt: skip
        mask = np.zeros(self.num_envs, dtype=bool)
        mask[idx] = True
        cols = np.zeros((N_COLS, self.num_envs))
        cols[:, idx] = self._cols[idx].T
        info: dict[str, Any] = dict(zip(COLS, cols))
        info["time"] = cols[C_TIME]
        info["reward_terms"] = {"roll": cols[C_RROLL], "effort": cols[C_REFFORT]}
        info["reward_terms"].update({"_roll": mask.copy(), "_effort": mask.copy()})
        for key in spec.INFO_KEYS[:-1]:
            info[f"_{key}"] = mask.copy()
        return info

    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        b, env = self.b, self.template
        u = actions[:, 0] * env.max_precession_rate
        # fresh info columns (N_COLS, N), written by the kernel (rows not stepped: reset infos)
        cols = np.empty((N_COLS, self.num_envs))
        args = (
            active, b["t"], b["y"], b["R"], u, env.physics_dt, env.n_substeps, b["P"], b["tab"],
            b["out"], self._steps, self._obs, self._fresh, cols, self._ok, self._reward,
            env.roll_scale, env.effort_weight, env.control_dt,
        )  # fmt: skip
        self.blocks.run(step_rows, *args)
        info: dict[str, Any] = dict(zip(COLS, cols))
        info["time"] = cols[C_TIME]
        info["reward_terms"] = {"roll": cols[C_RROLL], "effort": cols[C_REFFORT]}
        fail = active & ~self._ok
        info["numerical_failure"] = fail
        masks = np.ones((len(spec.INFO_KEYS) + 2, self.num_envs), dtype=bool)  # one per key
        info["reward_terms"]["_roll"], info["reward_terms"]["_effort"] = masks[-2], masks[-1]
        for j, key in enumerate(spec.INFO_KEYS):
            info[f"_{key}"] = masks[j]
        trunc = self._steps >= env.max_steps
        return self._fresh, self._reward.copy(), fail.copy(), trunc, info
