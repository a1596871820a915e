"""GyroStabilizer-v0 as a native batched vector env: N ships stepped in one compiled call.

`gym.make_vec("GyroStabilizer-v0", num_envs=N, vectorization_mode="vector_entry_point", **kw)`
builds it; `kw` are those of `gym.make("GyroStabilizer-v0", ...)` plus `autoreset_mode`
(`gymnasium.vector.AutoresetMode`, default NEXT_STEP). Trajectories are identical, bit for bit,
to `SyncVectorEnv` over N single `GyroStabilizerEnv`s with the same seeds
(`tests/test_vector_envs.py`): a step is ONE numba call (`rows.step_rows`), the single env's own
step (the single env is row 0 of a batch of one): the ship's step (`physics.ship.kernels.
advance_with`), the observation (`rows.observe`), reward terms and info columns of every row;
seeded resets and resets with options go through a template single env (its row 0, `rows`,
copied into the batch); the contract (observation, reward, info keys, failure) is
`gyro_stabilizer.spec`.

Compiled resets (regular seas): `GyroStabilizerEnv.reset()` without options draws three doubles,
roll U(-0.05, 0.05), roll rate U(-0.02, 0.02) and the wave phase U(0, 2 pi), and the phase
enters the packed parameters only in the slot WPHASE (sign flipped for a negative encounter
frequency). Autoresets and seedless resets without options therefore run in one numba call
(`rows.reset_rows`, each row by the single env's `rows.reset_row`) from doubles
pre-drawn from each row's generator (`mf_envs.envs._predraw`).
Irregular seas (a new sea of many draws per reset) keep the template path. See
`mf_envs.envs._vector`.

Threads (kwarg `num_threads`, `mf_envs.envs._rows.RowBlocks`): the rows are stepped in
num_threads blocks at once, block 0 in the calling thread and the others on Python worker
threads (`step_rows` releases the GIL), the split adapting so that the blocks end together;
rows are independent, so results are bit-identical to one thread (`tests/test_vector_envs.py`).
Default: one block per CPU once each gets >= 128 rows. The row loop (`_rows`) and the ship's
step are `mf_envs._jit.kernel`s: compiled without reference counting, so the rows' views of the
shared arrays cost nothing.

Each row takes the single env's step (`physics.ship.kernels.advance_with`), so it keeps the
single env's bits; docs/stabilizer_physics.md "Throughput" has the measured rates.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mf_envs.envs._predraw import PredrawnResets
from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.gyro_stabilizer import rows, spec
from mf_envs.envs.gyro_stabilizer.env import GyroStabilizerEnv
from mf_envs.envs.gyro_stabilizer.rows import (
    N_COLS,
    reset_rows,
    step_rows,
)
from mf_envs.physics.ship.layout import Slot


class GyroStabilizerVectorEnv(PredrawnResets, BatchedVectorEnv):
    """N independent `GyroStabilizer-v0` envs (same kwargs, own seeds) in one numba call.

    Observations (N, 6) float32 (`spec.OBS`), actions (N, 1) in [-1, 1], rewards (N,) float64,
    infos batched as Gymnasium does ({key: (N,) array, "_key": mask}) with the single env's keys
    (`spec.INFO_KEYS`). Memory: `state_nbytes()` bytes for the batch state (irregular seas add
    a wave table per env).
    """

    single_env_cls = GyroStabilizerEnv
    DRAWS_PER_RESET = 3
    # held per row (packed parameters P, the sea's table, the physics step): `randomize_rows`
    ROW_KWARGS = frozenset(
        ("wave_period", "wave_moment_amplitude", "significant_wave_height", "rotor_speed")
    )

    @classmethod
    def row_kwargs(cls, **env_kwargs: Any) -> frozenset[str]:
        """In irregular seas without a given physics_dt, not rotor_speed: the default physics
        step follows it, and with it the sea table's step and length (`_shared`)."""
        from mf_envs.effects import resolve_effects
        from mf_envs.envs.gyro_stabilizer.env import AVAILABLE_EFFECTS, DEFAULT_EFFECTS

        eff = resolve_effects(env_kwargs.get("effects"), AVAILABLE_EFFECTS, DEFAULT_EFFECTS)
        if "irregular_waves" in eff and env_kwargs.get("physics_dt") is None:
            return cls.ROW_KWARGS - {"rotor_speed"}
        return cls.ROW_KWARGS

    def _shared(self, env: Any) -> tuple[Any, ...]:
        """The step's template scalars (`_step_batch`) and, in irregular seas, the step of the
        sea table (its length: one batch array holds every row's table)."""
        table = env.scene.table_dt if "irregular_waves" in env.effects else None
        return (*super()._shared(env), env.max_precession_rate, env.roll_scale,
                env.effort_weight, table, env._P.shape)  # fmt: skip

    @classmethod
    def supports(cls, **env_kwargs: Any) -> bool:
        """The compiled rows have no sensor model: `sensor_noise`/`sensor_delay` run on the
        single env (`vectorization_mode="sync"`)."""
        from mf_envs.effects import resolve_effects
        from mf_envs.envs.gyro_stabilizer.env import AVAILABLE_EFFECTS, DEFAULT_EFFECTS

        eff = resolve_effects(env_kwargs.get("effects"), AVAILABLE_EFFECTS, DEFAULT_EFFECTS)
        return not ({"sensor_noise", "sensor_delay"} & set(eff))

    def _alloc(self, n: int) -> None:
        env = self.template
        if {"sensor_noise", "sensor_delay"} & set(env.effects):
            raise ValueError(
                "effects: the native GyroStabilizer-v0 vector env has no sensor model; use "
                "vectorization_mode='sync' for sensor_noise / sensor_delay"
            )
        self.b = rows.alloc_rows(n, (1, 2), env.physics_dt, env.n_substeps)._replace(last=self._obs)
        self.task = rows.Task(env.roll_scale, env.effort_weight, env.control_dt)
        # the phase is the only reset-dependent parameter of a regular sea (module doc)
        p1, p2 = rows.pack(env.scene, 1.0), rows.pack(env.scene, 2.0)
        same = set(np.flatnonzero(p1 != p2).tolist()) <= {int(Slot.WPHASE)}
        self._p_sign = float(np.sign(p1[Slot.WPHASE]))
        self._predraw_alloc(n, same and "irregular_waves" not in env.effects)

    def _load(self, i: int) -> None:
        env, b = self.template, self.b
        if b.tab.shape[1:] != env.rows.tab.shape[1:]:  # irregular seas: a table per env
            self.b = b = b._replace(tab=np.zeros((self.num_envs, *env.rows.tab.shape[1:])))
        for key in ("t", "y", "R", "P", "tab", "out", "dt", "n_sub", "steps"):
            getattr(b, key)[i] = getattr(env.rows, key)[0]

    def _state_arrays(self) -> dict[str, np.ndarray]:
        """The rows' arrays a step reads or writes (`snapshot`); `last` is the base's `_obs`."""
        return {k: getattr(self.b, k) for k in self.b._fields if k != "last"}

    def state_nbytes(self) -> int:
        """Bytes of the per-env batch state (physics arrays, observations, info columns)."""
        return int(sum(a.nbytes for a in self.b)) + self._draws.nbytes

    def _batch_reset(self, idx: np.ndarray) -> dict[str, Any] | None:
        if not self._predrawn(idx):
            return None
        reset_rows(idx, self._draws, self._ptr, self._p_sign, self.b)
        mask = np.zeros(self.num_envs, dtype=bool)
        mask[idx] = True
        cols = np.zeros((N_COLS, self.num_envs))
        cols[:, idx] = self.b.cols[:, idx]
        info = rows.info_of(cols)
        info["reward_terms"].update({"_roll": mask.copy(), "_effort": mask.copy()})
        for key in spec.INFO_KEYS[:-1]:
            info[f"_{key}"] = mask.copy()
        return info

    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        b, env = self.b, self.template
        b.u[:] = spec.precession_command(actions[:, 0], env.max_precession_rate)
        self.blocks.run(step_rows, active, b, self.task)
        info = rows.info_of(b.cols)
        fail = active & ~b.ok
        info["numerical_failure"] = fail
        masks = np.ones((len(spec.INFO_KEYS) + 2, self.num_envs), dtype=bool)  # one per key
        info["reward_terms"]["_roll"], info["reward_terms"]["_effort"] = masks[-2], masks[-1]
        for j, key in enumerate(spec.INFO_KEYS):
            info[f"_{key}"] = masks[j]
        trunc = b.steps >= env.max_steps
        return b.obs, b.reward.copy(), fail.copy(), trunc, info
