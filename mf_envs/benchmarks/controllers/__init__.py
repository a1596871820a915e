"""`mf-envs bench controllers`: every baseline (and PPO where shipped) on every env's scenes.

A module here defines `rows(quick) -> list[dict]` with at least
`env_id, scene, controller, metric, mean, std, n_seeds` (plus e.g. `reference`, `ceiling`)
and optionally `plot(out, rows) -> list[Path]`.
"""

from __future__ import annotations

from pathlib import Path

from mf_envs.benchmarks._runner import run_modules

COLUMNS = ("env_id", "scene", "controller", "metric", "mean", "std", "n_seeds")


def run(out: Path, quick: bool = False, only: list[str] | None = None) -> list[Path]:
    return run_modules(__name__, out, quick, only, "controllers.csv", COLUMNS)
