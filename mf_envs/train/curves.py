"""Learning curves from SB3 `EvalCallback` logs (`evaluations.npz`: timesteps, results)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from mf_envs._files import save_figure


def load_curve(folder: Path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(timesteps (k,), mean return (k,), std return (k,)) of the eval episodes at each check."""
    with np.load(Path(folder) / "evaluations.npz") as d:
        results = np.asarray(d["results"], dtype=float)  # (k, n_eval_episodes)
        return np.asarray(d["timesteps"]), results.mean(axis=1), results.std(axis=1)


def plot_learning_curves(
    folders: Sequence[Path],
    path: Path,
    title: str,
    labels: Sequence[str] | None = None,
    references: dict[str, float] | None = None,
) -> Path:
    """PNG of evaluation return vs training steps, one line (mean ± std band) per run folder.

    `references`: horizontal lines (e.g. a baseline's episode return), label -> value.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    spans = []
    for i, folder in enumerate(folders):
        t, mean, std = load_curve(folder)
        spans.append(np.abs(mean))
        label = labels[i] if labels else Path(folder).name
        ax.plot(t, mean, "o-", ms=3, label=label)
        ax.fill_between(t, mean - std, mean + std, alpha=0.2)
    for j, (label, value) in enumerate((references or {}).items()):
        ax.axhline(value, ls="--", color=f"C{j + len(folders)}", label=label)
    mags = np.concatenate([*spans, np.abs(list((references or {}).values()))])
    mags = mags[np.isfinite(mags) & (mags > 0)]
    if mags.size and mags.max() > 30 * mags.min():  # returns over decades: symmetric log axis
        ax.set_yscale("symlog", linthresh=float(mags.min()))
    ax.set_xlabel("training steps")
    ax.set_ylabel("evaluation episode return (deterministic)")
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save_figure(fig, path)
