"""`mf-envs` command line: demo, benchmarks (and, as they land, train/evaluate/render).

User mistakes (bad ids, bad options, ValueError from the library) print one clear line on
stderr and exit with status 2; everything else is a real bug and keeps its traceback.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from pathlib import Path

BENCH_KINDS = ("accuracy", "speed", "controllers")


def _cmd_demo(args: argparse.Namespace) -> list[Path]:
    from benchmarks import demos

    return demos.run(Path(args.out), quick=args.quick, only=args.only)


def _cmd_bench(args: argparse.Namespace) -> list[Path]:
    import importlib

    mod = importlib.import_module(f"benchmarks.{args.kind}")
    return mod.run(Path(args.out), quick=args.quick, only=args.scene)


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="mf-envs",
        description="Moving-frame Gymnasium environments (Rios 2017): demo, benchmarks.",
    )
    sub = p.add_subparsers(dest="command", required=True, metavar="COMMAND")

    d = sub.add_parser("demo", help="run every system's showcase on defaults; writes plots + GIFs")
    d.add_argument("--out", default="mf_envs_demo", help="output folder (default: %(default)s)")
    d.add_argument("--quick", action="store_true", help="shorter runs")
    d.add_argument("--only", nargs="+", metavar="SYSTEM", help="run only these demo modules")
    d.set_defaults(func=_cmd_demo)

    b = sub.add_parser("bench", help="benchmarks: accuracy | speed | controllers (CSV + PNG)")
    b.add_argument("kind", choices=BENCH_KINDS)
    b.add_argument("--out", required=True, help="output folder")
    b.add_argument("--quick", action="store_true", help="a reduced ladder that runs in minutes")
    b.add_argument("--scene", nargs="+", metavar="NAME", help="run only these scene modules")
    b.set_defaults(func=_cmd_bench)
    return p


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    func: Callable[[argparse.Namespace], list[Path]] = args.func
    try:
        written = func(args)
    except ValueError as exc:
        print(f"mf-envs {args.command}: error: {exc}", file=sys.stderr)
        return 2
    if written:
        folders = sorted({str(Path(w).parent) for w in written})
        print(f"wrote {len(written)} file(s) into: {', '.join(folders)}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
