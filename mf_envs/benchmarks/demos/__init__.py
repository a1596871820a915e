"""`mf-envs demo`: the showcase. A module here defines

    ORDER: int
    TITLE: str
    def run(out: Path, quick: bool) -> tuple[list[Path], list[str]]

writing plots/GIFs into `out` and returning (files written, summary lines for the terminal).
"""

from __future__ import annotations

from pathlib import Path

from mf_envs.benchmarks._registry import discover


def run(out: Path, quick: bool = False, only: list[str] | None = None) -> list[Path]:
    from tqdm import tqdm

    out.mkdir(parents=True, exist_ok=True)
    written: list[Path] = []
    mods = discover(__name__, only)
    for mod in tqdm(mods, desc="demo", unit="system"):
        files, lines = mod.run(out, quick)
        written.extend(files)
        tqdm.write(f"== {getattr(mod, 'TITLE', mod.__name__)}")
        for line in lines:
            tqdm.write(f"   {line}")
    return written
