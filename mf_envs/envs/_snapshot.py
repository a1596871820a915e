"""The native vector envs' snapshot, restore and load (`SnapshotRows`, a base of
`envs._vector.BatchedVectorEnv`): a planner copies a single env's episode into rows, rolls
them forward and rewinds them (`mf_envs.controllers.planner`)."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import gymnasium as gym
import numpy as np


class SnapshotRows:
    """`snapshot`, `restore` and `load_env` of a batched vector env (the batch's arrays come
    from its `_state_arrays`; `_obs`, `_done`, `_rngs`, `_is_reset`, `_draws_of_rows`,
    `template`, `single_env_cls`, `num_envs` and `_load` are `BatchedVectorEnv`'s)."""

    _obs: np.ndarray
    _done: np.ndarray
    _rngs: list[Any]
    _is_reset: bool
    _draws_of_rows: Any
    template: Any
    single_env_cls: type
    num_envs: int

    # a vector env that supports snapshots defines `_state_arrays()`: every batch array a step
    # reads or writes, by name (the arrays themselves, not copies), what `snapshot` copies and
    # `restore` writes back in place; None: no snapshots (`_arrays` says so)
    _state_arrays: Any = None
    _load: Any  # (row) -> None: the template env's state into the row

    def _arrays(self, what: str) -> dict[str, np.ndarray]:
        """`_state_arrays()`; TypeError naming `what` for a vector env without it."""
        if self._state_arrays is None:
            raise TypeError(
                f"{type(self).__name__}.{what}: this vector env keeps no snapshot of its rows "
                "(GyroStabilizer-v0's and FloatingGOWEC-v0's do)"
            )
        return self._state_arrays()

    def _load_live(self, i: int, env: gym.Env) -> None:
        """Subclass hook: copy the single env `env`'s current (mid-episode) state into row i
        (`load_env`); the default is `_load` with `env` as the template."""
        template, self.template = self.template, env
        try:
            self._load(i)
        finally:
            self.template = template

    def snapshot(self) -> dict[str, Any]:
        """A copy of the whole batch state: the rows' arrays (`_state_arrays`: physics state,
        sea, step counters), the last observations and done flags, each row's generator state
        and pre-drawn resets. `restore(s)` puts it back, after which the same actions give the
        same bits as from the moment of the snapshot (a planner rolls rows forward and rewinds).
        Not with `randomize_rows` (its draws are not copied)."""
        if not self._is_reset:
            raise gym.error.ResetNeeded("call reset() before snapshot()")
        if self._draws_of_rows is not None:
            raise ValueError("snapshot: not supported with randomize_rows")
        snap: dict[str, Any] = {k: a.copy() for k, a in self._arrays("snapshot").items()}
        snap.update(_obs=self._obs.copy(), _done=self._done.copy())
        snap["_rngs"] = [None if r is None else r.bit_generator.state for r in self._rngs]
        if hasattr(self, "_draws"):  # `_predraw.PredrawnResets`
            snap.update(_draws=self._draws.copy(), _ptr=self._ptr.copy(), _snap=list(self._snap))
        return snap

    def restore(self, snap: Mapping[str, Any]) -> None:
        """Write a `snapshot()` of this env back (in place, so the compiled kernels' views stay
        valid); ValueError if it comes from a vector env of other shapes or kind."""
        arrays = {**self._arrays("restore"), "_obs": self._obs, "_done": self._done}
        if hasattr(self, "_draws"):
            arrays.update(_draws=self._draws, _ptr=self._ptr)
        for key, a in arrays.items():
            if key not in snap or np.shape(snap[key]) != a.shape:
                raise ValueError(f"snap: not a snapshot of this vector env (key {key!r})")
            np.copyto(a, snap[key])
        for i, state in enumerate(snap["_rngs"]):
            if state is None:
                self._rngs[i] = None
            else:
                if self._rngs[i] is None:
                    self._rngs[i] = np.random.Generator(np.random.PCG64())
                self._rngs[i].bit_generator.state = state
        if hasattr(self, "_draws"):
            self._snap = list(snap["_snap"])
        self._is_reset = True

    def load_env(self, env: gym.Env, rows: Any = None) -> None:
        """Copy a single env's current state (mid-episode: physics, sea realisation, step
        count) into `rows` (an index array or slice; None: all), so the rows continue its
        episode: the same actions give them the single env's rewards, bit for bit, as long as
        the single env was built with this vector env's kwargs and has no sensor model. Their
        generators are not touched (they only draw at a reset)."""
        env = getattr(env, "unwrapped", env)
        if not isinstance(env, self.single_env_cls):
            raise ValueError(f"env: expected a {self.single_env_cls.__name__}, got {env!r}")
        if self._draws_of_rows is not None:
            raise ValueError("env: load_env is not supported with randomize_rows")
        idx = np.arange(self.num_envs)[slice(None) if rows is None else rows]
        for i in np.atleast_1d(idx):
            self._load_live(int(i), env)
            if env._last_obs is not None:
                self._obs[i] = env._last_obs
        self._done[idx] = False
        self._is_reset = True
