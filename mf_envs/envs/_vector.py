"""Shared machinery of the native batched vector envs (`gowec.vector`, `gyro_stabilizer.vector`).

A native vector env steps all N sub-envs in ONE compiled call over a batch axis, and reproduces
`gymnasium.vector.SyncVectorEnv` over N copies of the single env exactly (same observations,
rewards, flags and batched infos, bit for bit) for the same seeds:

- seeding: `reset(seed=s)` gives sub-env i the seed s + i, `reset(seed=[s_0, ...])` seed s_i, and
  each sub-env keeps its own `np.random.Generator` for the resets that follow (autoreset);
- resets go through one "template" instance of the single env: its generator is swapped for
  sub-env i's, `reset` is called, and the subclass copies the resulting state into row i of the
  batch arrays (`_load`), so reset semantics cannot drift from the single env's; a subclass may
  add a compiled path for the hot case (autoresets and seedless resets without options,
  `_batch_reset`) that draws the same numbers from the same generators (GOWEC-v0);
- steps (hot) call a batched numba kernel over the active rows, in blocks on threads
  (`_rows.RowBlocks`): the single env's own step, the single env being row 0 of a batch of one
  (`gowec.rows.step_rows`, `gyro_stabilizer.rows.step_rows`, `gowec_v1.rows.step_rows`), or a
  row loop around the single env's scalar physics kernel (`inchworm.rows.step_rows`);
- autoreset: `AutoresetMode.NEXT_STEP` (Gymnasium's default: the step after a done one resets that
  sub-env, ignores its action, returns reward 0 and flags False), `SAME_STEP` (reset in the same
  step; `final_obs`/`final_info` in the info) and `DISABLED` (reset with `options={"reset_mask":
  m}`), as in `SyncVectorEnv`;
- infos: Gymnasium's batched layout, {key: (N,) array, "_key": (N,) bool mask}, nested dicts
  (`reward_terms`) batched recursively;
- domain randomisation in the rows (`randomize_rows`): `mf_envs.envs._drawn_rows`.

Rendering is not supported (`render_mode` must be None): render a single env instead.
"""

from __future__ import annotations

import abc
from collections.abc import Mapping
from typing import Any

import gymnasium as gym
import numba
import numpy as np
from gymnasium.vector import AutoresetMode, VectorEnv
from gymnasium.vector.utils import batch_space

from mf_envs._validate import as_action, check_int
from mf_envs.envs._drawn_rows import DrawnRows
from mf_envs.envs._rows import RowBlocks
from mf_envs.envs._snapshot import SnapshotRows

# rows per thread below which more threads do not pay (`resolve_threads`' automatic choice)
MIN_ROWS_PER_THREAD = {"light": 128, "heavy": 1}


def resolve_threads(num_threads: Any, num_envs: int, rows: str = "light") -> int:
    """The number of row blocks stepped at once: num_threads as given (an int >= 1), or with
    None one per CPU of numba's count, fewer when a block would hold fewer than
    MIN_ROWS_PER_THREAD[rows] rows ("light": microsecond rows, "heavy": millisecond rows)."""
    if num_threads is not None:
        if isinstance(num_threads, bool):
            raise ValueError(f"num_threads: must be an integer >= 1, got {num_threads!r}")
        return check_int("num_threads", num_threads, 1)
    per = MIN_ROWS_PER_THREAD[rows]
    return max(1, min(numba.get_num_threads(), num_envs // per))


def seed_list(seed: int | list[int | None] | None, n: int) -> list[int | None]:
    """SyncVectorEnv's convention: None -> [None]*n, int s -> [s, s+1, ...], list -> as is."""
    if seed is None:
        return [None] * n
    if isinstance(seed, (int, np.integer)):
        return [int(seed) + i for i in range(n)]
    seeds = list(seed)
    if len(seeds) != n:
        raise ValueError(f"seed: a list of seeds must have num_envs={n} entries, got {len(seeds)}")
    return seeds


def parse_autoreset_mode(mode: AutoresetMode | str) -> AutoresetMode:
    """AutoresetMode from the enum or its value ("NextStep", "SameStep", "Disabled")."""
    try:
        return AutoresetMode(mode)
    except ValueError:
        raise ValueError(
            f"autoreset_mode: one of {[m.value for m in AutoresetMode]}, got {mode!r}"
        ) from None


class BatchedVectorEnv(DrawnRows, SnapshotRows, VectorEnv, metaclass=abc.ABCMeta):
    """Base class (kwargs: num_envs, autoreset_mode, render_mode None, num_threads: blocks of
    rows stepped at once, None = automatic, `resolve_threads`; the rest go to the single env):
    subclasses set `single_env_cls`, allocate their batch arrays in `_alloc(n)`,
    copy the freshly reset template into row i in `_load(i)`, and implement
    `_step_batch(actions, active) -> (obs, reward, terminated, truncated, info)` for the rows in
    `active`: actions (N, *act) float64 already clipped; the batched info must hold every key
    the single env's step info can have, with its "_key" mask (False where the single env
    would not report the key, e.g. after a numerical failure); this class merges the resets
    in and drops keys no row has, as SyncVectorEnv does."""

    single_env_cls: type[gym.Env]
    row_cost = "light"  # microsecond rows; "heavy": millisecond rows (`resolve_threads`)
    metadata: dict[str, Any] = {"render_modes": [], "autoreset_mode": AutoresetMode.NEXT_STEP}

    def __init__(
        self,
        num_envs: int = 1,
        *,
        autoreset_mode: AutoresetMode | str = AutoresetMode.NEXT_STEP,
        render_mode: str | None = None,
        num_threads: int | None = None,
        **env_kwargs: Any,
    ) -> None:
        if isinstance(num_envs, bool):
            raise ValueError(f"num_envs: must be an integer >= 1, got {num_envs!r}")
        self.num_envs = check_int("num_envs", num_envs, low=1)
        # blocks of rows stepped at once on threads (`_rows.RowBlocks`); results do not depend on it
        self.num_threads = resolve_threads(num_threads, self.num_envs, self.row_cost)
        if render_mode is not None:
            raise ValueError(
                f"render_mode: the native vector env does not render (got {render_mode!r}); "
                "render a single env from gym.make instead"
            )
        self.render_mode = None
        self.autoreset_mode = parse_autoreset_mode(autoreset_mode)
        self.metadata = {**type(self).metadata, "autoreset_mode": self.autoreset_mode}
        # validates every kwarg once; a `max_episode_steps` given is the rows' episode length
        self.template = self.single_env_cls(**env_kwargs)
        self.env_kwargs = dict(env_kwargs)
        self.single_observation_space = self.template.observation_space
        self.single_action_space = self.template.action_space
        self.observation_space = batch_space(self.single_observation_space, self.num_envs)
        self.action_space = batch_space(self.single_action_space, self.num_envs)
        n = self.num_envs
        self._rngs: list[np.random.Generator | None] = [None] * n
        self._done = np.zeros(n, dtype=bool)  # terminated or truncated at the last step
        self._obs = np.zeros((n, *self.single_observation_space.shape), dtype=np.float32)
        self._all = np.ones(n, dtype=bool)
        self._is_reset = False
        self.blocks = RowBlocks(n, self.num_threads)  # the split over threads
        self._alloc(n)

    @classmethod
    def supports(cls, **env_kwargs: Any) -> bool:
        """Whether this vector env runs the single env of these kwargs (all of them, unless a
        subclass compiles only some scenes)."""
        return True

    # ------------------------------------------------------------------ subclass hooks
    @abc.abstractmethod
    def _alloc(self, n: int) -> None:
        """Allocate the batch state arrays for n envs."""

    @abc.abstractmethod
    def _load(self, i: int) -> None:
        """Copy the template env's freshly reset state into row i."""

    @abc.abstractmethod
    def _step_batch(self, actions: np.ndarray, active: np.ndarray) -> tuple[Any, ...]:
        """Advance the active rows: (obs, reward, terminated, truncated, info)."""

    def _close_rows(self, obs, reward, finite, active, info, max_steps) -> tuple[Any, ...]:
        """The end of `_step_batch` for envs whose rows report finiteness (the beam robots):
        `MFEnv._finish_step`'s contract row by row (a row not finite, of the active ones, keeps
        its last observation, scores 0 and terminates; the others' observations are clipped to
        the bounds), every info key present in every row, truncation after max_steps steps."""
        n = self.num_envs
        info["numerical_failure"] = ~finite
        for key in list(info):
            info[f"_{key}"] = np.ones(n, bool)
        terms = info["reward_terms"]
        terms.update({f"_{key}": np.ones(n, bool) for key in list(terms)})
        space = self.single_observation_space
        obs_out = np.clip(obs, space.low, space.high)
        term = ~finite & active
        obs_out[term] = self._obs[term]  # last finite obs, reward 0, terminated
        reward[term] = 0.0
        return obs_out, reward, term, self._steps >= max_steps, info

    def _batch_reset(self, idx: np.ndarray) -> dict[str, Any] | None:
        """Optional fast path: reset rows `idx` (no seed, no options) in one compiled call and
        return their batched reset infos (masks True on idx only), drawing from each row's
        generator exactly what the single env's `reset()` draws; None: no fast path, reset
        row by row through the template."""
        return None

    # ------------------------------------------------------------------ resets
    def _reset_one(self, i: int, seed: int | None, options: dict[str, Any] | None):
        if self._draws_of_rows is not None:
            return self._reset_drawn(i, seed, options)
        env = self.template
        env._np_random = self._rngs[i]  # None: a fresh unseeded generator, as in a new env
        obs, info = env.reset(seed=seed, options=options)
        self._rngs[i] = env.np_random
        self._load(i)
        self._hold(i)
        self._obs[i] = obs
        return info

    def reset(
        self,
        *,
        seed: int | list[int | None] | None = None,
        options: dict[str, Any] | None = None,
    ) -> tuple[np.ndarray, dict[str, Any]]:
        """Reset all sub-envs, or those in `options["reset_mask"]` ((N,) bool array)."""
        seeds = seed_list(seed, self.num_envs)
        if options is not None and not isinstance(options, Mapping):
            raise ValueError(f"options: expected a dict or None, got {type(options).__name__}")
        options = dict(options) if options is not None else None
        mask = self._all
        if options is not None and "reset_mask" in options:
            mask = np.asarray(options.pop("reset_mask"))
            if mask.shape != (self.num_envs,) or mask.dtype != np.bool_ or not mask.any():
                raise ValueError(
                    f"options: reset_mask must be a ({self.num_envs},) bool array with a True"
                )
            if not options:
                options = None
        idx = np.flatnonzero(mask)
        fresh = options is None and all(seeds[i] is None for i in idx)
        fresh = fresh and self._draws_of_rows is None
        infos = self._batch_reset(idx) if fresh else None
        if infos is None:
            infos = {}
            for i in idx:
                infos = self._add_info(infos, self._reset_one(int(i), seeds[i], options), int(i))
        self._done[mask] = False
        self._is_reset = True
        return self._obs.copy(), infos

    # ------------------------------------------------------------------ steps
    def _check_actions(self, actions: Any) -> np.ndarray:
        shape = (self.num_envs, *self.single_action_space.shape)
        a = as_action("actions", actions, shape)
        return np.clip(a, -1.0, 1.0)

    def step(self, actions: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, dict]:
        if not self._is_reset:
            raise gym.error.ResetNeeded("call reset() before step()")
        a = self._check_actions(actions)
        mode = self.autoreset_mode
        redo = self._done if mode == AutoresetMode.NEXT_STEP else None
        active = self._all if redo is None or not redo.any() else ~redo
        obs, rew, term, trunc, info = self._step_batch(a, active)
        if active is self._all:  # np.copyto: a boolean-mask copy took 27 us of a 0.6 ms step
            np.copyto(self._obs, obs)
        else:
            np.copyto(self._obs, obs, where=active.reshape(-1, *[1] * (obs.ndim - 1)))
        masked = bool(term.any())  # failures mask keys out
        if redo is not None and redo.any():
            rew[redo], term[redo], trunc[redo] = 0.0, False, False
            self._merge_resets(info, np.flatnonzero(redo))
            masked = True
        done = term | trunc
        if mode == AutoresetMode.SAME_STEP and done.any():
            masked = True
            idx = np.flatnonzero(done)
            final_obs = np.full(self.num_envs, None, dtype=object)
            for i in idx:
                final_obs[i] = self._obs[i].copy()
            info["final_info"] = _select(info, done)
            info["_final_info"] = done.copy()
            info["final_obs"], info["_final_obs"] = final_obs, done.copy()
            self._merge_resets(info, idx)
            done = np.zeros_like(done)
        self._done = done
        return self._obs.copy(), rew, term, trunc, _prune(info) if masked else info

    def _merge_resets(self, info: dict[str, Any], idx: np.ndarray) -> None:
        """Reset the sub-envs `idx` now and put their reset infos in place of the step infos."""
        resets = self._batch_reset(idx) if self._draws_of_rows is None else None
        if resets is None:
            resets = {}
            for i in idx:
                resets = self._add_info(resets, self._reset_one(int(i), None, None), int(i))
        _overwrite(info, resets, idx)


def _select(info: dict[str, Any], rows: np.ndarray) -> dict[str, Any]:
    """The batched `info` restricted to `rows`, laid out as SyncVectorEnv's `final_info`: values
    of the other rows are the zero of the dtype (None for objects), masks False there."""
    out: dict[str, Any] = {}
    for key, value in info.items():
        if key.startswith("_") or key in ("final_obs", "final_info"):
            continue
        if isinstance(value, dict):
            out[key] = _select(value, rows)
        else:
            empty = np.full(value.shape, None, dtype=object) if value.dtype == object else None
            out[key] = np.zeros_like(value) if empty is None else empty
            out[key][rows] = value[rows]
        out[f"_{key}"] = info[f"_{key}"] & rows
    return out


def _overwrite(info: dict[str, Any], resets: dict[str, Any], idx: np.ndarray) -> None:
    """Rows `idx` of `info` take the reset infos: keys absent from a reset info are masked out."""
    for key in list(info):
        if key.startswith("_") or key in ("final_obs", "final_info"):
            continue
        if key in resets:
            if isinstance(info[key], dict):
                _overwrite(info[key], resets[key], idx)
            else:
                info[key][idx] = resets[key][idx]
            info[f"_{key}"][idx] = resets[f"_{key}"][idx]
        else:
            info[f"_{key}"][idx] = False
    for key in [k for k in resets if not k.startswith("_") and k not in info]:
        info[key], info[f"_{key}"] = resets[key], resets[f"_{key}"]  # a reset-only key


def _prune(info: dict[str, Any]) -> dict[str, Any]:
    """Drop the keys no sub-env has (all-False mask), as SyncVectorEnv never creates them, and
    zero a key's value in the rows whose mask is False (None for objects), as SyncVectorEnv
    leaves a row whose info lacks the key: a failed or reset row keeps no stale value (e.g. a
    SAME_STEP reset row's numerical_failure)."""
    for key in [k for k in info if not k.startswith("_")]:
        if isinstance(info[key], dict):
            _prune(info[key])
        mask = info[f"_{key}"]
        if not mask.any():
            del info[key], info[f"_{key}"]
        elif not isinstance(info[key], dict) and not mask.all():
            info[key][~mask] = None if info[key].dtype == object else 0
    return info
