"""Compiled resets for the native vector envs: each row's reset draws, taken in advance.

A single env's plain `reset()` (no seed, no options) draws a fixed number of doubles from its
generator with `rng.uniform(low, high)`, which numpy computes as low + (high - low) *
next_double. `PredrawnResets` (a mixin for `mf_envs.envs._vector.BatchedVectorEnv`) keeps, per
row, the next `DRAW_BUFFER` resets' doubles, drawn in one `rng.random(k)` right after each
template reset (the same stream in the same order as the single env's calls), so a numba kernel
can reset many rows in one call. Before any template reset without a seed (options, or a
fallback) the row's generator is rewound to where the single env's would be (state snapshot +
the doubles consumed), so any mix of compiled and template resets stays bit-identical to
`SyncVectorEnv`. Used by `gowec.vector` and `gyro_stabilizer.vector`.
"""

from __future__ import annotations

from typing import Any

import numpy as np


class PredrawnResets:
    """Mixin (before `BatchedVectorEnv` in the bases): subclasses set `DRAWS_PER_RESET`, call
    `_predraw_alloc(n, fast)` in `_alloc`, and in `_batch_reset(idx)` call `_predrawn(idx)`
    (None: use the template path) and consume `_ptr[i]`.. of `_draws[i]` in their kernel."""

    DRAWS_PER_RESET: int = 0
    DRAW_BUFFER: int = 16  # resets pre-drawn per row

    def _predraw_alloc(self, n: int, fast: bool) -> None:
        self._fast = fast
        self._draws = np.zeros((n, self.DRAWS_PER_RESET * self.DRAW_BUFFER))
        self._ptr = np.zeros(n, dtype=np.int64)
        self._snap: list[dict[str, Any] | None] = [None] * n

    def _reset_one(self, i: int, seed: int | None, options: dict[str, Any] | None):
        if self._draws_of_rows is not None:  # randomised rows: every reset reseeds (no pre-draw)
            return super()._reset_one(i, seed, options)  # type: ignore[misc]
        rng, snap = self._rngs[i], self._snap[i]
        if seed is None and rng is not None and snap is not None:  # rewind the pre-draw
            rng.bit_generator.state = snap
            rng.random(int(self._ptr[i]))
        info = super()._reset_one(i, seed, options)  # type: ignore[misc]
        if self._fast:
            self._refill(i)
        return info

    def _refill(self, i: int) -> None:
        """Pre-draw row i's next DRAW_BUFFER resets from its generator (its state kept)."""
        rng = self._rngs[i]
        self._snap[i] = rng.bit_generator.state
        self._draws[i] = rng.random(self._draws.shape[1])
        self._ptr[i] = 0

    def _predrawn(self, idx: np.ndarray) -> bool:
        """True if rows idx can reset from their pre-drawn doubles (refilled where spent)."""
        if not self._fast or any(self._snap[i] is None for i in idx):
            return False
        for i in idx[self._ptr[idx] >= self._draws.shape[1]]:
            self._refill(int(i))
        return True
