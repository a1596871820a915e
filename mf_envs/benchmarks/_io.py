"""CSV writing and work-precision plots shared by the benchmarks."""

from __future__ import annotations

import csv
import math
import time
from collections import defaultdict
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import atomic_path, save_figure


def timed(fn: Any, *args: Any, repeat: int = 1, **kwargs: Any) -> tuple[Any, float]:
    """(fn(*args, **kwargs), best wall seconds over `repeat` calls) with time.perf_counter."""
    best, out = math.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn(*args, **kwargs)
        best = min(best, time.perf_counter() - t0)
    return out, best


def accuracy_row(
    scene: str, method: str, h: float, err: float, sec: float, param: str, **extra: Any
) -> dict[str, Any]:
    """One `accuracy.csv` row: scene, method, dt (the step or element length h), error, seconds,
    param (what h is), plus any extra columns."""
    return {
        "scene": scene,
        "method": method,
        "dt": h,
        "error": err,
        "seconds": sec,
        "param": param,
        **extra,
    }


def write_csv(path: Path, rows: Sequence[dict[str, Any]], first: Sequence[str]) -> Path:
    """Write dict rows with the `first` columns in order, then any other keys alphabetically."""
    path.parent.mkdir(parents=True, exist_ok=True)
    extra = sorted({k for r in rows for k in r} - set(first))
    with atomic_path(path) as tmp, tmp.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=[*first, *extra])
        w.writeheader()
        for r in rows:
            w.writerow({k: _fmt(v) for k, v in r.items()})
    return path


def _fmt(v: Any) -> Any:
    if isinstance(v, float):
        return f"{v:.6g}"
    return v


def observed_order(h: Sequence[float], err: Sequence[float]) -> float:
    """Least-squares slope of log(err) against log(h) (NaN if fewer than 2 usable points)."""
    h = np.asarray(h, dtype=float)
    e = np.asarray(err, dtype=float)
    ok = (h > 0) & (e > 0) & np.isfinite(e)
    if ok.sum() < 2:
        return math.nan
    return float(np.polyfit(np.log(h[ok]), np.log(e[ok]), 1)[0])


def _sparse_log_ticks(axis: Any, limits: tuple[float, float]) -> None:
    """Readable ticks on a log axis whose range lies inside about one decade (matplotlib then
    labels every 1..9 x 10^k and the labels run into each other): labelled ticks at 1, 2 and
    5 x 10^k only (1, 2, 3, 5 if that gives fewer than two), no minor labels."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter

    lo, hi = sorted(limits)  # get_xlim/get_ylim: autoscaled to the data
    if not (lo > 0 and hi / lo < 20.0):
        return
    for mantissas in ((1, 2, 5), (1, 2, 3, 5), (1, 1.5, 2, 3, 4, 5, 7)):
        ticks = [
            m * 10.0**k
            for k in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1)
            for m in mantissas
            if lo <= m * 10.0**k <= hi
        ]
        if len(ticks) >= 2:
            break
    axis.set_major_locator(FixedLocator(ticks))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:.3g}"))
    axis.set_minor_formatter(NullFormatter())


def work_precision_plot(path: Path, rows: Sequence[dict[str, Any]], title: str) -> Path:
    """Log-log error vs seconds, one line per (method, quantity), observed order in the legend.

    Rows need `method`, `dt` (the refinement parameter), `error`, `seconds`; optional
    `quantity` (one panel each) and `param` (what `dt` means, e.g. 'dt', 'h', 'tol').
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels: dict[str, list[dict[str, Any]]] = defaultdict(list)
    for r in rows:
        panels[str(r.get("quantity", "error"))].append(r)
    fig, axes = plt.subplots(1, len(panels), figsize=(5.2 * len(panels), 4.2), squeeze=False)
    for ax, (quantity, prow) in zip(axes[0], sorted(panels.items())):
        lines: dict[str, list[dict[str, Any]]] = defaultdict(list)
        for r in prow:
            lines[str(r["method"])].append(r)
        for method, lrows in sorted(lines.items()):
            lrows = sorted(lrows, key=lambda r: r["seconds"])
            p = lrows[0].get("param", "dt")
            order = observed_order([r["dt"] for r in lrows], [r["error"] for r in lrows])
            label = method if math.isnan(order) else f"{method} (order {order:.2f} in {p})"
            ax.loglog(
                [r["seconds"] for r in lrows],
                [max(r["error"], 1e-17) for r in lrows],
                "o-",
                label=label,
            )
        ax.set_xlabel("wall time [s]")
        ax.set_ylabel(f"max error: {quantity}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        _sparse_log_ticks(ax.xaxis, ax.get_xlim())
        _sparse_log_ticks(ax.yaxis, ax.get_ylim())
    fig.suptitle(title)
    fig.tight_layout()
    return save_figure(fig, path)
