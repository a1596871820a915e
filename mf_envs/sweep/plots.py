"""Pictures of a sweep's results CSV: mean over seeds of one metric.

- no `plot.x/y` in the config: a controller x scene table (heatmap annotated mean ± std over
  seeds), the sweep counterpart of `mf-envs bench controllers`' bar charts;
- `plot: {x: AXIS, y: AXIS}`: one heatmap per controller over the two swept axes (e.g. the
  Fig. 3-5 power map of GOWEC-v0 over wave period and amplitude); `log: true` for a logarithmic
  colour scale.
The metric defaults to the env's primary metric (`mf_envs.train.evaluate.primary_metric`).
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import inside, safe_name, save_figure
from mf_envs.sweep.config import SweepConfig

UNITS = {
    "wave_period": "s",
    "wave_amplitude": "m",
    "wave_moment_amplitude": "N m",
    "significant_wave_height": "m",
    "wave_direction": "rad",
    "max_generator_torque": "N m",
    "mean_power": "W",
    "rms_roll": "rad",
    "rms_roll_all": "rad",
    "max_abs_roll": "rad",
    "tail_advance": "m",
    "tail_advance_per_step": "m",
    "wall_s": "s",
}


def label(name: str) -> str:
    """`name [unit]` for the known SI quantities, else `name`."""
    unit = UNITS.get(name)
    return f"{name} [{unit}]" if unit else name


def _cells(rows: list[dict[str, Any]], keys: tuple[str, ...], metric: str) -> dict:
    """(values of `keys`) -> (mean, sample std) of `metric` over the seeds of that cell."""
    groups: dict[tuple, list[float]] = defaultdict(list)
    for r in rows:
        groups[tuple(r[k] for k in keys)].append(float(r[metric]))
    return {
        k: (float(np.mean(v)), float(np.std(v, ddof=1)) if len(v) > 1 else 0.0)
        for k, v in groups.items()
    }


def plot_sweep(cfg: SweepConfig, rows: list[dict[str, Any]], out: Path) -> list[Path]:
    """Write the sweep's picture(s) into `out`; their paths."""
    import matplotlib

    matplotlib.use("Agg")
    from mf_envs.train.evaluate import primary_metric

    if not rows:
        return []
    metric = cfg.plot.get("metric", primary_metric(cfg.env_id).name)
    if metric not in rows[0]:
        raise ValueError(f"config: plot.metric: {metric!r} is not a column of the results")
    if "x" in cfg.plot:
        return [_heatmaps(cfg, rows, metric, out)]
    return [_table(cfg, rows, metric, out)]


def _table(cfg: SweepConfig, rows: list[dict[str, Any]], metric: str, out: Path) -> Path:
    import matplotlib.pyplot as plt

    cols = ("scene", *cfg.axes)
    cells = _cells(rows, ("controller", *cols), metric)
    ctrls = list(dict.fromkeys(r["controller"] for r in rows))
    scenes = list(dict.fromkeys(tuple(r[c] for c in cols) for r in rows))
    grid = np.array([[cells.get((c, *s), (np.nan, 0))[0] for s in scenes] for c in ctrls])
    fig, ax = plt.subplots(figsize=(1.6 + 1.55 * len(scenes), 1.2 + 0.55 * len(ctrls)))
    im = ax.imshow(grid, cmap="viridis", aspect="auto")
    for i, c in enumerate(ctrls):
        for j, s in enumerate(scenes):
            m, sd = cells.get((c, *s), (np.nan, 0.0))
            bright = im.norm(m) > 0.6 if np.isfinite(m) else False
            ax.text(j, i, f"{m:.3g}\n± {sd:.2g}", ha="center", va="center", fontsize=8,
                    color="k" if bright else "w")  # fmt: skip
    names = [" ".join(str(v) for v in s if v != "default") or "default" for s in scenes]
    ax.set_xticks(range(len(scenes)), names, rotation=20, ha="right", fontsize=8)
    ax.set_yticks(range(len(ctrls)), ctrls, fontsize=8)
    ax.set_xlabel("scene" if not cfg.axes else " / ".join(label(c) for c in cols))
    ax.set_ylabel("controller")
    n = len({r["seed"] for r in rows})
    ax.set_title(f"{cfg.env_id}: {metric}, mean ± std over {n} seeds", fontsize=10)
    fig.colorbar(im, ax=ax, label=label(metric))
    return _save(fig, out, f"{cfg.name}_{metric}.png")


def _heatmaps(cfg: SweepConfig, rows: list[dict[str, Any]], metric: str, out: Path) -> Path:
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm, Normalize

    x, y = cfg.plot["x"], cfg.plot["y"]
    cells = _cells(rows, ("controller", x, y), metric)
    ctrls = list(dict.fromkeys(r["controller"] for r in rows))
    xs = sorted({r[x] for r in rows})
    ys = sorted({r[y] for r in rows})
    vals = [[[cells.get((c, a, b), (np.nan,))[0] for a in xs] for b in ys] for c in ctrls]
    lo, hi = np.nanmin(vals), np.nanmax(vals)
    norm = LogNorm(lo, hi) if cfg.plot.get("log") and lo > 0 else Normalize(lo, hi)
    fig, axes = plt.subplots(1, len(ctrls), figsize=(5.2 * len(ctrls), 4.2), squeeze=False)
    for ax, c, v in zip(axes[0], ctrls, vals):
        im = ax.pcolormesh(_edges(xs), _edges(ys), np.array(v), cmap="viridis", norm=norm)
        ax.set_xlabel(label(x))
        ax.set_ylabel(label(y))
        ax.set_title(f"{c}", fontsize=10)
        fig.colorbar(im, ax=ax, label=label(metric))
    n = len({r["seed"] for r in rows})
    fig.suptitle(f"{cfg.env_id}: {metric}, mean over {n} seed(s)", fontsize=11)
    return _save(fig, out, f"{cfg.name}_{metric}_{x}_{y}.png")


def _edges(v: list[float]) -> np.ndarray:
    """Cell edges around the (sorted) centres `v` for pcolormesh."""
    c = np.asarray(v, dtype=float)
    if len(c) == 1:
        return np.array([c[0] - 0.5, c[0] + 0.5])
    mid = 0.5 * (c[1:] + c[:-1])
    return np.concatenate([[2 * c[0] - mid[0]], mid, [2 * c[-1] - mid[-1]]])


def _save(fig: Any, out: Path, name: str) -> Path:
    """Write the figure as `out/name`; the name (from the config) must stay inside `out`."""
    path = inside(out, Path(out) / safe_name("config: name", name), "config: name")
    fig.tight_layout()
    return save_figure(fig, path)  # no link at its name; old or new picture
