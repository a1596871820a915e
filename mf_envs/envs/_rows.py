"""Rows of a native vector env stepped in blocks on threads at once (`RowBlocks`).

The kernels release the GIL (numba `nogil=True`), so blocks of rows run truly in parallel on a
shared pool of Python worker threads; rows are independent, so no result depends on the split.
"""

from __future__ import annotations

import os
import threading
import time
from typing import Any

import numpy as np

# a single env is row SINGLE of a batch of one, stepped with the active mask ONE_ROW
SINGLE, ONE_ROW = 0, np.ones(1, dtype=bool)
_POOL: dict[str, Any] = {"pid": None, "workers": [], "lock": None}  # `_workers`


class _Worker:
    """A thread that runs one job at a time: `submit(fn, *args)`, then `wait()` returns
    (True, its result) or (False, the exception it raised). Two plain locks hand the job over
    and back: lighter than `concurrent.futures` (queue, work item, future and its condition)."""

    def __init__(self) -> None:
        self._go, self._done = threading.Lock(), threading.Lock()
        self._go.acquire()
        self._done.acquire()
        self._job: Any = None
        self._out: Any = None
        threading.Thread(target=self._loop, name="mf_envs-rows", daemon=True).start()

    def _loop(self) -> None:
        while True:
            self._go.acquire()
            fn, args = self._job
            try:
                self._out = (True, fn(*args))
            except BaseException as e:  # noqa: BLE001 (handed to the waiting thread)
                self._out = (False, e)
            self._done.release()

    def submit(self, fn: Any, *args: Any) -> None:
        self._job = (fn, args)
        self._go.release()

    def wait(self) -> tuple[bool, Any]:
        self._done.acquire()
        out, self._job, self._out = self._out, None, None
        return out


def _workers(n: int) -> tuple[list[_Worker], threading.Lock]:
    """At least n worker threads of this process and the lock that gives one caller at a time
    the use of them (a forked child, which has none of its parent's threads, makes its own)."""
    if _POOL["pid"] != os.getpid():
        _POOL.update(pid=os.getpid(), workers=[], lock=threading.Lock())
    while len(_POOL["workers"]) < n:
        _POOL["workers"].append(_Worker())
    return _POOL["workers"], _POOL["lock"]


def _timed(kernel: Any, lo: int, hi: int, *args: Any) -> tuple[float, float]:
    """kernel(lo, hi, *args) and its (start, end) on time.perf_counter (a worker's block)."""
    t0 = time.perf_counter()
    kernel(lo, hi, *args)
    return t0, time.perf_counter()


class RowBlocks:
    """Runs kernel(lo, hi, *args) over n_rows rows split in n_blocks contiguous blocks at once:
    block 0 in the calling thread, the others on the shared worker pool (the kernel must release
    the GIL: numba `nogil=True`). Rows are independent, so no result depends on the split.

    Not numba's `parallel=True`: its OpenMP threads spin, and with another process busy on one
    of 2 cores they ran 2.7-10x slower than one thread (measured); these wait. With
    one of 2 cores busy elsewhere two blocks cost GOWEC-v0 (N = 1024) 7.5 % against one and
    gained the inchworm (N = 64) 6 %; on a quiet machine they gain 1.5-1.9x.

    The split adapts so that the blocks end together: a worker starts its block after the
    calling thread (wake-up, then the GIL until the caller's kernel releases it: ~20 us with
    `_Worker`, 50-120 us with `concurrent.futures`), which with equal blocks left the caller
    waiting (GyroStabilizer-v0, N = 1024: 120 us of a 0.7 ms step with the latter). After each
    run, the rows are shared out again from the blocks' measured start times and mean row cost
    (block j gets (T - start_j) / cost rows, all ending at T), smoothed by SMOOTH."""

    SMOOTH = 0.3  # weight of the latest run's balanced shares

    def __init__(self, n_rows: int, n_blocks: int) -> None:
        self.n_rows = int(n_rows)
        self.k = max(1, min(int(n_blocks), self.n_rows))
        self.shares = [self.n_rows / self.k] * self.k  # rows per block (floats)
        self._edges = self.bounds()

    def bounds(self) -> list[int]:
        """Block edges 0 = b_0 < b_1 < ... < b_k = n_rows from the shares (each block >= 1 row)."""
        b, acc = [0], 0.0
        for j in range(self.k):
            acc += self.shares[j]
            b.append(max(b[-1] + 1, min(round(acc), self.n_rows - (self.k - 1 - j))))
        b[-1] = self.n_rows
        return b

    def run(self, kernel: Any, *args: Any) -> None:
        """kernel(lo, hi, *args) over all rows (class doc)."""
        if self.k == 1:
            kernel(0, self.n_rows, *args)
            return
        b = self._edges
        workers, lock = _workers(self.k - 1)
        with lock:
            for j in range(1, self.k):
                workers[j - 1].submit(_timed, kernel, b[j], b[j + 1], *args)
            try:
                spans = [_timed(kernel, b[0], b[1], *args)]
            finally:  # every worker is waited for, whatever happened here
                outs = [workers[j].wait() for j in range(self.k - 1)]
        for ok, value in outs:
            if not ok:
                raise value
            spans.append(value)
        self._rebalance(spans)

    def _rebalance(self, spans: list[tuple[float, float]]) -> None:
        """New shares from the last run's block (start, end) times (class doc). Each block's
        row cost is its own (busy time / its rows): a thread on a slower or shared core (the
        VM's second vCPU ran its block up to 1.4x slower per row, measured) gets fewer rows."""
        rows = [hi - lo for lo, hi in zip(self._edges[:-1], self._edges[1:])]
        costs = [(e - s) / r for (s, e), r in zip(spans, rows)]  # seconds per row, per block
        if min(costs) <= 0.0:
            return
        # all blocks end together at T: sum_j (T - start_j) / cost_j = n_rows
        rate = sum(1.0 / c for c in costs)
        end = (self.n_rows + sum(s / c for (s, _), c in zip(spans, costs))) / rate
        target = [max((end - s) / c, 1.0) for (s, _), c in zip(spans, costs)]
        norm = self.n_rows / sum(target)
        w = self.SMOOTH
        self.shares = [(1.0 - w) * x + w * norm * y for x, y in zip(self.shares, target)]
        self._edges = self.bounds()
