"""`mf-envs bench speed`: throughput as ratios against references run side by side.

A module here defines `rows(quick) -> list[dict]` with at least
`case, variant, steps_per_s, reference, reference_steps_per_s, ratio` and optionally
`plot(out, rows) -> list[Path]`. Bare seconds are never the result: every row carries the
reference it is compared with (Gymnasium's Pendulum-v1/Acrobot-v1, a plain-numpy loop, PyElastica).
"""

from __future__ import annotations

from pathlib import Path

from mf_envs.benchmarks._runner import run_modules

COLUMNS = ("case", "variant", "steps_per_s", "reference", "reference_steps_per_s", "ratio")


def run(out: Path, quick: bool = False, only: list[str] | None = None) -> list[Path]:
    return run_modules(__name__, out, quick, only, "speed.csv", COLUMNS)
