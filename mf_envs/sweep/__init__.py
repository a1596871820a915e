"""Sweeps over env kwargs x controllers x seeds, on Ray or in-process: `mf-envs sweep CONFIG`.

- `config`: the YAML format (`load_config`) and its expansion into `Trial`s with stable ids;
- `run`: `run_trial` (one episode -> one CSV row), `run_sweep` (Ray core tasks or `serial`);
- `store`: the results CSV, appended atomically per trial, so an interrupted sweep resumes;
- `plots`: a controller x scene table or per-controller heatmaps over two swept axes.

Example configs ship in `sweep/configs/` (run one by name: `mf-envs sweep stabilizer_table`).
Ray is optional (the `ray` extra); `--serial` runs the same trials without it.
"""

from __future__ import annotations

from mf_envs.sweep.config import ControllerSpec, SweepConfig, Trial, load_config, parse_config
from mf_envs.sweep.run import run_sweep, run_trial

__all__ = [
    "ControllerSpec",
    "SweepConfig",
    "Trial",
    "load_config",
    "parse_config",
    "run_sweep",
    "run_trial",
]
