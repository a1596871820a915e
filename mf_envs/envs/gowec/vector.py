"""GOWEC-v0 as a native batched vector env: N gyroscopes stepped in one compiled call.

`gym.make_vec("GOWEC-v0", num_envs=N, vectorization_mode="vector_entry_point", **kwargs)` builds
it; `kwargs` are those of `gym.make("GOWEC-v0", ...)` plus `autoreset_mode`
(`gymnasium.vector.AutoresetMode`, default NEXT_STEP). Trajectories are identical, bit for bit,
to `SyncVectorEnv` over N single `GOWECEnv`s with the same seeds (`tests/test_vector_envs.py`):
seeded resets and resets with options go through a template single env (its row 0, `rows`,
copied into the batch), steps through `rows.step_rows`, the single env's own step (the single env
is row 0 of a batch of one), and the info and failure contract come from `gowec.spec`, as in the
single env. See `mf_envs.envs._vector`.

Compiled resets (regular waves): autoresets and seedless resets without options run in one
numba call (`rows.reset_rows`). `GOWECEnv.reset()` draws exactly two doubles from its generator,
phi = U(-0.1, 0.1) then the wave phase U(0, 2 pi) (numpy: low + (high - low) * next_double),
so each row pre-draws future resets' doubles (`mf_envs.envs._predraw.PredrawnResets`: same
stream, same order as the single env's calls, the generator rewound before any template reset)
and the kernel consumes them, so any mix of resets stays bit-identical to `SyncVectorEnv`.
Irregular seas (many draws per reset) keep the template path.

Domain randomisation (`randomize_rows`, `mf_envs.envs._drawn_rows`): besides its wave, every
row holds its control step (wave_period / steps_per_period), physics substep and count, rotor
speed, reward scale and episode length, so the declared wave_period, wave_amplitude and
rotor_speed differ between rows (the kernel reads the row's; without randomisation they are
the template's in every row).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mf_envs.envs._predraw import PredrawnResets
from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.gowec import rows, spec
from mf_envs.envs.gowec.env import GOWECEnv


class GOWECVectorEnv(PredrawnResets, BatchedVectorEnv):
    """N independent `GOWEC-v0` envs (same kwargs, own seeds) stepped in one numba call.

    Observations (N, 6) float32 (`spec.OBS`), actions (N, 1) in [-1, 1], rewards (N,) float64,
    infos batched as Gymnasium does ({key: (N,) array, "_key": mask}) with the single env's
    keys (`spec.INFO_KEYS`). Memory: `state_nbytes()` bytes for the batch state.
    """

    single_env_cls = GOWECEnv
    DRAWS_PER_RESET = 2  # wave phase and gimbal angle
    # held per row (the wave, the reward scale 1 / (P_ref control_dt), control and physics
    # steps, rotor speed, episode length): `randomize_rows`
    ROW_KWARGS = frozenset(("wave_amplitude", "wave_period", "rotor_speed"))

    def _shared(self, env: Any) -> tuple[Any, ...]:
        """The step's template scalars (`_step_batch`) and the kernel's shared arrays (`_load`:
        rotor and gimbal inertia, wave direction) through the parameters that set them (not
        the base's control_dt and max_steps: the rows hold them)."""
        p = env.params
        return (tuple(sorted(env.effects)), env.max_generator_torque, env.max_gimbal_rate,
                p.rotor_inertia, p.transverse, p.gimbal_inertia, env.wave_direction,
                env.n_components, env.gamma, env.buoy_radius)  # fmt: skip

    def _alloc(self, n: int) -> None:
        env = self.template
        self.b = rows.alloc_rows(n, env.rows.amp.shape[1])
        self._max_steps = np.full(n, env.max_steps, dtype=np.int64)  # each row's episode
        self._predraw_alloc(n, "irregular_waves" not in env.effects)

    def _batch_reset(self, idx: np.ndarray) -> dict[str, Any] | None:
        if not self._predrawn(idx):
            return None
        rows.reset_rows(idx, self._draws, self._ptr, self.b, self.template.site)
        self._obs[idx] = self.b.obs[idx]
        return self._reset_infos(idx)

    def _reset_infos(self, idx: np.ndarray) -> dict[str, Any]:
        """The batched reset infos of rows idx (GOWECEnv.reset's keys, dtypes and values)."""
        n, b = self.num_envs, self.b
        zero, mask = np.zeros(n), np.zeros(n, dtype=bool)
        mask[idx] = True
        phi, w1, eta = zero.copy(), zero.copy(), zero.copy()
        phi[idx], w1[idx], eta[idx] = b.x[idx, 0], b.w[idx, 0], b.eta[idx]
        info = spec.step_info(zero.copy(), phi, zero.copy(), w1, eta, zero.copy(), zero.copy())
        info["reward_terms"]["_energy"] = mask.copy()
        info["overspeed"] = np.zeros(n, dtype=bool)
        for key in list(info):
            info[f"_{key}"] = mask.copy()
        return info

    def _load(self, i: int) -> None:
        b, row = self.b, self.template.rows
        for key, dst in zip(rows.Rows._fields, b):
            dst[i] = getattr(row, key)[0]
        self._max_steps[i] = self.template.max_steps

    def state_nbytes(self) -> int:
        """Bytes of the per-env batch state (physics arrays, step counters, observations)."""
        return int(sum(a.nbytes for a in self.b)) + self._obs.nbytes + self._max_steps.nbytes

    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        b, env = self.b, self.template
        b.Mg[:] = actions[:, 0] * env.max_generator_torque
        self.blocks.run(rows.step_rows, active, b, env.site)
        reward, ok, overspeed = b.reward.copy(), b.ok, b.overspeed
        ok[~active], overspeed[~active] = True, False
        info = spec.step_info(
            b.energy / b.cdt, b.x[:, 0].copy(), b.x[:, 1].copy(), b.w[:, 0].copy(),
            b.eta.copy(), b.t.copy(), reward.copy(),
        )  # fmt: skip
        info["numerical_failure"] = ~ok
        info["overspeed"] = overspeed.copy()
        masks = np.ones((len(spec.INFO_KEYS) + 1, self.num_envs), dtype=bool)  # one per key
        info["reward_terms"]["_energy"] = masks[-1]
        for j, key in enumerate(spec.INFO_KEYS):
            info[f"_{key}"] = masks[j]
        term, trunc = overspeed.copy(), b.steps >= self._max_steps
        obs = b.obs
        if not ok[active].all():  # MFEnv._finish_step: last finite obs, reward 0, terminated
            bad = ~ok & active
            obs[bad] = self._obs[bad]
            reward[bad], term[bad] = 0.0, True
            info["power"][bad] = 0.0
            for key in set(spec.INFO_KEYS) - set(spec.FAILURE_KEYS):
                info[f"_{key}"][bad] = False
        return obs, reward, term, trunc, info
