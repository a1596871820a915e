"""Domain randomisation in the rows of a native vector env (`DrawnRows`, a base of
`mf_envs.envs._vector.BatchedVectorEnv`; what `train.randomize.randomized_vector_env` installs).

With `randomize_rows(draws)`, every reset of row i (seeded, autoreset, `reset_mask`) draws kwargs
from the row's own randomisation generator (`draws.draw`, `train.randomize.Randomizer`), builds
a single env with them, resets it with a seed drawn from the same generator and loads it into
row i through the template path (`_load`): the rows are then bit-identical to `SyncVectorEnv`
over `train.randomize.DomainRandomization` wrappers with the same seeds (the compiled resets are
off meanwhile). Only the kwargs of the class's `row_kwargs` (`ROW_KWARGS`) may be drawn: those
whose values live in the rows' arrays; what the batch step reads from the template (`_shared`)
must not change, else ValueError naming `ranges`.

Rows may also hold an object each (`_row_held(env)`, e.g. the beam robots' compiled
configuration: stiffness, mass, ground or water laws): once `randomize_rows` is on, `_held[i]`
is row i's (set at its every reset) and `_run_rows_of` steps the rows one by one, each with its
own, in the same blocks on threads (a millisecond row costs its call's dispatch, microseconds,
more); before (`_held` None) the rows are stepped in one call with the template's, as always.
"""

from __future__ import annotations

from typing import Any

import numpy as np


class DrawnRows:
    """Mixin of `BatchedVectorEnv` (module doc); subclasses set `ROW_KWARGS` (and extend
    `_shared` with what their `_step_batch` reads from the template)."""

    # kwargs whose values the rows hold individually (loaded by `_load`): `randomize_rows`
    ROW_KWARGS: frozenset[str] = frozenset()
    _draws_of_rows: Any = None  # `randomize_rows`'s draws (None: off)
    _draw_rngs: list[np.random.Generator | None]
    _held: list[Any] | None = None  # each row's `_row_held` once randomised (module doc)

    @classmethod
    def row_kwargs(cls, **env_kwargs: Any) -> frozenset[str]:
        """The kwargs whose values the rows of this scene hold individually (`ROW_KWARGS`, or
        fewer in some scenes): what `randomize_rows` may draw."""
        return cls.ROW_KWARGS

    def _shared(self, env: Any) -> tuple[Any, ...]:
        """What the batch step reads from the template rather than from a row (scalars, arrays,
        effects): every randomised row's env must have the template's (`randomize_rows`)."""
        return (tuple(sorted(env.effects)), env.control_dt, env.max_steps)

    def _row_held(self, env: Any) -> Any:
        """The object the rows hold each beyond their arrays, of the single env `env` they are
        loaded from (module doc); None: none (the rows are arrays only)."""
        return None

    def _hold(self, i: int) -> None:
        """Row i keeps the template's `_row_held` (after its `_load`), once randomised."""
        if self._held is not None:
            self._held[i] = self._row_held(self.template)

    def _run_rows_of(self, kernel: Any, at: int, *args: Any) -> None:
        """`kernel(lo, hi, *args)` over the rows in blocks (`blocks.run`, args[0] the active
        mask), args[at] the template's `_row_held`; with held rows (module doc) row by row,
        args[at] each row's own."""
        if self._held is None:
            self.blocks.run(kernel, *args)
        else:
            self.blocks.run(_each_row, kernel, self._held, at, *args)

    def randomize_rows(self, draws: Any) -> None:
        """Domain randomisation in the rows (module doc): `draws.draw(rng, seed)` returns (the
        row's generator for its next reset, the kwargs drawn, the single env's reset seed), the
        contract of `train.randomize.Randomizer`; `draws.names` are the kwargs it draws, all in
        `row_kwargs` (ValueError naming `ranges` otherwise). None: off. Takes effect from the
        next reset of each row."""
        if draws is not None:
            held = self.row_kwargs(**self.env_kwargs)
            extra = sorted(set(draws.names) - set(held))
            if extra:
                raise ValueError(
                    f"ranges: {extra} cannot differ between the rows of "
                    f"{type(self).__name__} (in this scene its rows hold {sorted(held)}); use "
                    "SyncVectorEnv over DomainRandomization"
                )
        self._draws_of_rows = draws
        self._draw_rngs = [None] * self.num_envs
        held = self._row_held(self.template)
        if draws is not None and held is not None and self._held is None:
            self._held = [held] * self.num_envs  # the rows loaded so far hold the template's
        if hasattr(self, "_snap"):  # compiled resets (`_predraw`): none from before the switch
            self._snap = [None] * self.num_envs

    def _reset_drawn(self, i: int, seed: int | None, options: dict[str, Any] | None):
        """Row i's reset under `randomize_rows`: kwargs and seed drawn, a single env of them
        reset and loaded through the template path (the template itself is left unchanged)."""
        rng, drawn, env_seed = self._draws_of_rows.draw(self._draw_rngs[i], seed)
        self._draw_rngs[i] = rng
        env = self.single_env_cls(**{**self.env_kwargs, **drawn})
        if env.observation_space != self.single_observation_space or not _same(
            self._shared(env), self._shared(self.template)
        ):
            raise ValueError(
                f"ranges: the draw {drawn} changes what the rows of {type(self).__name__} share "
                "(its observation space or the step's parameters, `_shared`); use SyncVectorEnv "
                "over DomainRandomization"
            )
        obs, info = env.reset(seed=env_seed, options=options)
        info["randomized"] = dict(drawn)
        template, self.template = self.template, env
        try:
            self._load(i)
            self._hold(i)
        finally:
            self.template = template
        self._rngs[i] = env.np_random
        self._obs[i] = obs
        return info


def _each_row(lo: int, hi: int, kernel: Any, held: list[Any], at: int, *args: Any) -> None:
    """`kernel(i, i + 1, *args)` for the active rows lo <= i < hi (args[0] the mask), args[at]
    replaced by held[i] (`DrawnRows._run_rows_of`; a Python block: the kernel releases the GIL
    for the row's work)."""
    active = args[0]
    for i in range(lo, hi):
        if active[i]:
            kernel(i, i + 1, *args[:at], held[i], *args[at + 1 :])


def _same(a: Any, b: Any) -> bool:
    """Equal, element by element for arrays (tuples compared item by item)."""
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.shape(a) == np.shape(b) and bool(np.array_equal(a, b))
    return bool(a == b)
