"""`mf-envs bench accuracy`: work-precision data (error vs wall seconds) for every scene.

A scene module in this package defines

    ORDER: int                      # sort key (optional)
    def rows(quick: bool) -> list[dict]

returning rows with at least `scene, method, dt, error, seconds` (plus optional `quantity`,
`param` = what `dt` means, and anything else). The runner writes `accuracy.csv` and one log-log
PNG per scene (`accuracy_<scene>.png`). A module may also define `plot(out, rows) -> list[Path]`
for figures of its own (it receives only its own rows).
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

from mf_envs.benchmarks._io import work_precision_plot, write_csv
from mf_envs.benchmarks._registry import discover

COLUMNS = ("scene", "method", "dt", "error", "seconds")


def run(out: Path, quick: bool = False, only: list[str] | None = None) -> list[Path]:
    """Run every scene module (or `only` these), write CSV + PNGs into `out`; return the paths."""
    from tqdm import tqdm

    rows: list[dict] = []
    extra: list[Path] = []
    mods = discover(__name__, only)
    for mod in tqdm(mods, desc="accuracy scenes", unit="module"):
        mod_rows = mod.rows(quick)
        rows.extend(mod_rows)
        if hasattr(mod, "plot"):  # a module's own figures beside the generic ones
            extra.extend(mod.plot(out, mod_rows))
    written = [write_csv(out / "accuracy.csv", rows, COLUMNS), *extra]
    by_scene: dict[str, list[dict]] = defaultdict(list)
    for r in rows:
        by_scene[str(r["scene"])].append(r)
    for scene, srows in by_scene.items():
        written.append(work_precision_plot(out / f"accuracy_{scene}.png", srows, scene))
    return written
