"""`mf-envs sweep CONFIG.yml [--out DIR] [--serial | --address ADDR] [--num-cpus N]`."""

from __future__ import annotations

import argparse
from pathlib import Path

from mf_envs._validate import arg_int

CONFIG_DIR = Path(__file__).parent / "configs"
MAX_CPUS = 1024


def resolve_config(name: str) -> Path:
    """A path, or the name of a shipped config (`gowec_power_map` -> `configs/...yml`)."""
    p = Path(name)
    if p.is_file():
        return p
    shipped = CONFIG_DIR / f"{p.stem}.yml"
    if p.parent == Path(".") and shipped.is_file():
        return shipped
    names = sorted(f.stem for f in CONFIG_DIR.glob("*.yml"))
    raise ValueError(f"config: no such file {name!r} (shipped configs: {names})")


def add_arguments(s: argparse.ArgumentParser) -> None:
    """The `sweep` subcommand's options (the parser itself lives in `mf_envs/cli/__init__.py`)."""
    s.add_argument("config", help="sweep YAML, or the name of a shipped one (sweep/configs)")
    s.add_argument("--out", default=None, help="output folder (default: sweeps/<config name>)")
    s.add_argument("--serial", action="store_true", help="run in this process, without Ray")
    s.add_argument("--address", default=None, help="Ray cluster address (default: local Ray)")
    s.add_argument(
        "--num-cpus", type=arg_int(1, MAX_CPUS), default=2,
        help=f"local Ray CPUs, 1..{MAX_CPUS} (default: 2)",
    )  # fmt: skip
    s.add_argument("--no-progress", action="store_true", help="no progress bar")


def sweep_command(args: argparse.Namespace) -> list[Path]:
    """Run (or resume) the sweep, then write its CSV and picture(s)."""
    from mf_envs.sweep.config import load_config
    from mf_envs.sweep.plots import plot_sweep
    from mf_envs.sweep.run import run_sweep
    from mf_envs.sweep.store import ResultStore

    if args.num_cpus < 1:
        raise ValueError(f"num-cpus: must be >= 1, got {args.num_cpus}")
    cfg = load_config(resolve_config(args.config))
    out = Path(args.out) if args.out else Path("sweeps") / cfg.name
    csv_path, n_run = run_sweep(
        cfg, out, serial=args.serial, address=args.address, num_cpus=args.num_cpus,
        progress=not args.no_progress,
    )  # fmt: skip
    ids = {t.trial_id for t in cfg.trials}
    rows = [r for r in ResultStore(csv_path).rows() if r["trial_id"] in ids]
    print(f"{cfg.name}: {n_run} trial(s) run, {len(cfg.trials) - n_run} already in {csv_path}")
    return [csv_path, *plot_sweep(cfg, rows, out)]
