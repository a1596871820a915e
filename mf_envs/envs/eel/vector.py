"""Eel-v0 as a native batched vector env: N eels stepped in one compiled call.

It is the serpentine's (`mf_envs.envs.serpentine.vector`, whose module docstring says how
`gym.make_vec("Eel-v0", num_envs=N, vectorization_mode="vector_entry_point", **kwargs)` builds
it, its threads, its bit-identity with `SyncVectorEnv` over single `EelEnv`s and its domain
randomisation) stepping the eel's own compiled step (`envs.eel.rows.step_rows`, each row with
the water's drag laws); the reward, info and failure contract are the beam robots' shared step
on (N,) arrays (`tests/test_vector_envs.py`).
"""

from __future__ import annotations

import numpy as np

from mf_envs.envs.eel import rows
from mf_envs.envs.eel.env import EelEnv
from mf_envs.envs.serpentine.vector import SerpentineVectorEnv


class EelVectorEnv(SerpentineVectorEnv):
    """N independent `Eel-v0` envs (same kwargs, own seeds) stepped in one numba call.

    Observations (N, 2 n + 6) float32, actions (N, n) in [-1, 1], rewards (N,) float64, infos
    batched as Gymnasium does with the single env's keys (`spec.INFO_KEYS`). The batch loop,
    rewards, infos and failure contract are the serpentine's (`SerpentineVectorEnv`); the rows
    also carry the wave phase."""

    single_env_cls = EelEnv
    row_cost = "heavy"  # a Newton solve per row: one block per CPU from N = 2
    # held per row in its compiled configuration `cfg` (`_row_held`): `randomize_rows`
    ROW_KWARGS = frozenset(
        ("youngs_modulus", "shear_modulus", "drag_normal", "drag_tangential", "drag_form")
    )

    def _alloc(self, n: int) -> None:
        super()._alloc(n)
        self._phase = np.zeros((n, 1))

    def _load(self, i: int) -> None:
        super()._load(i)
        self._phase[i] = self.template.phase

    def _row_arrays(self) -> list[np.ndarray]:
        return [self._phase]

    def _run_rows(self, actions: np.ndarray, active: np.ndarray) -> None:
        self._run_rows_of(
            rows.step_rows, 5, active, actions, self._state, self._cmd, self._phase,
            self.template.cfg, self._body, self._fresh, self._rep,
        )  # fmt: skip

    def _headings(self) -> np.ndarray:
        return self._body[:, 4].copy()
