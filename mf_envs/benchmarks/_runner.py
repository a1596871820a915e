"""Shared runner: discover scene modules, gather their rows, write one CSV, let each plot."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from mf_envs.benchmarks._io import write_csv
from mf_envs.benchmarks._registry import discover


def run_modules(
    package: str,
    out: Path,
    quick: bool,
    only: list[str] | None,
    csv_name: str,
    columns: Sequence[str],
) -> list[Path]:
    """Each module in `package` defines `rows(quick) -> list[dict]` and optionally
    `plot(out, rows) -> list[Path]` (it receives only its own rows)."""
    from tqdm import tqdm

    out.mkdir(parents=True, exist_ok=True)
    all_rows: list[dict] = []
    written: list[Path] = []
    for mod in tqdm(discover(package, only), desc=csv_name, unit="module"):
        rows = mod.rows(quick)
        all_rows.extend(rows)
        if hasattr(mod, "plot"):
            written.extend(mod.plot(out, rows))
    written.insert(0, write_csv(out / csv_name, all_rows, columns))
    return written
