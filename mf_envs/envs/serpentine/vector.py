"""Serpentine-v0 as a native batched vector env: N snakes stepped in one compiled call.

`gym.make_vec("Serpentine-v0", num_envs=N, vectorization_mode="vector_entry_point", **kwargs)`
builds it; `kwargs` are those of `gym.make("Serpentine-v0", ...)` plus `autoreset_mode`
(default NEXT_STEP) and `num_threads` (blocks of rows stepped at once on threads, default: one
per CPU; a row's arithmetic does not depend on it). Every scene (every effect set) is compiled.

Trajectories are identical, bit for bit, to `SyncVectorEnv` over N single `SerpentineEnv`s with
the same seeds (`tests/test_vector_envs.py`): resets go through a template single env whose
state is copied into the row (`_load`); steps through `envs.serpentine.rows.step_rows`, which
runs the single env's own compiled step (`rows.step_row`) for every row, and the reward, info
and failure contract repeat `SerpentineEnv.step`'s expressions on (N,) arrays.
See `mf_envs.envs._vector`.

Domain randomisation (`randomize_rows`, `mf_envs.envs._drawn_rows`): each row holds its
compiled configuration (`rows.pack`: stiffness, ground law, ...; `_row_held`), so the body's
material and the ground's coefficients differ between rows (`ROW_KWARGS`); the randomised
rows are stepped one by one with their own (`DrawnRows._run_rows_of`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mf_envs.envs import _beam_rows as br
from mf_envs.envs._beam_robot import step_terms
from mf_envs.envs._vector import BatchedVectorEnv
from mf_envs.envs.serpentine import rows, spec
from mf_envs.envs.serpentine.env import SerpentineEnv


class SerpentineVectorEnv(BatchedVectorEnv):
    """N independent `Serpentine-v0` envs (same kwargs, own seeds) stepped in one numba call.

    Observations (N, 2 n + 4) float32, actions (N, n) in [-1, 1], rewards (N,) float64, infos
    batched as Gymnasium does with the single env's keys (`spec.INFO_KEYS`)."""

    single_env_cls = SerpentineEnv
    row_cost = "heavy"  # ~1 ms per row: one block per CPU from N = 2
    # held per row in its compiled configuration `cfg` (`_row_held`): `randomize_rows`
    ROW_KWARGS = frozenset(
        ("youngs_modulus", "shear_modulus", "friction_coefficient", "backward_ratio",
         "lateral_ratio", "viscous_tangential", "viscous_normal", "material_damping")
    )  # fmt: skip

    def _row_held(self, env: Any) -> Any:
        return env.cfg

    def _shared(self, env: Any) -> tuple[Any, ...]:
        """The step's template values (`_step_batch`) and the rows' array shapes."""
        return (*super()._shared(env), env.scene.length, env.effort_weight,
                env.target_direction, env.model.n_dof, env.n_ctrl)  # fmt: skip

    def _alloc(self, n: int) -> None:
        env = self.template
        nd, nc = env.model.n_dof, env.n_ctrl
        self._state = np.zeros((n, 2, nd))
        self._cmd = np.zeros((n, nc))
        self._body = np.zeros((n, 5))
        self._fresh = np.zeros((n, env.obs_layout.size), np.float32)
        self._rep = np.zeros((n, br.N_REPORT))
        self._steps = np.zeros(n, np.int64)

    def _load(self, i: int) -> None:
        env = self.template
        self._state[i] = env.state
        self._cmd[i] = env.cmd
        self._steps[i] = 0

    def state_nbytes(self) -> int:
        """Bytes of the per-env batch state (physics, scratch, outputs, observations)."""
        arrays = [self._state, self._cmd, *self._row_arrays(), self._body, self._fresh, self._rep]
        return int(sum(a.nbytes for a in arrays)) + self._steps.nbytes + self._obs.nbytes

    def _row_arrays(self) -> list[np.ndarray]:
        """Per-row arrays beyond the state and command (Eel-v0: its wave phase)."""
        return []

    def _run_rows(self, actions: np.ndarray, active: np.ndarray) -> None:
        """The compiled batched step of the active rows (`rows.step_rows`)."""
        self._run_rows_of(
            rows.step_rows, 4, active, actions, self._state, self._cmd, self.template.cfg,
            self._body, self._fresh, self._rep,
        )  # fmt: skip

    def _headings(self) -> np.ndarray:
        """(N,) the heading each row reports: the head's frame angle."""
        return self._state[:, 0, -1].copy()

    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        env, rep, body, obs = self.template, self._rep, self._body, self._fresh
        rep[~active, br.REP_OK] = 1.0
        self._run_rows(actions, active)
        self._steps[active] += 1
        along, terms = step_terms(body, rep, env.target_direction, env.scene.length,
                                  env.effort_weight)  # fmt: skip
        energy = rep[:, br.REP_ENERGY].copy()
        progress, effort = terms["progress"], terms["effort"]
        reward = progress + effort
        info = spec.step_info(
            body[:, 0].copy(), body[:, 1].copy(), self._headings(),
            along / env.control_dt, self._cmd.copy(), energy, rep[:, br.REP_NET].copy(),
            env.control_dt,
            rep[:, br.REP_ITER].astype(np.int64), self._steps * env.control_dt,
            {"progress": progress, "effort": effort},
        )  # fmt: skip
        finite = (rep[:, br.REP_OK] > 0.0) & np.isfinite(self._state).all(axis=(1, 2))
        finite &= np.isfinite(obs).all(axis=1) & np.isfinite(reward)
        return self._close_rows(obs, reward, finite, active, info, env.max_steps)
