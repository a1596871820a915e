"""`mf-envs` command line: demo, bench, render, train, evaluate, sweep (docs/api.md, "CLI").

User mistakes (bad ids, bad options, a ValueError that the library raises on purpose, an output
path that cannot be written, a missing optional extra) print one line on stderr and exit with
status 2; Ctrl-C prints one line and exits with 130. Outputs are written into a temporary folder
beside the target and moved into place when complete (`mf_envs._staging`), so an interrupted run
leaves the previous outputs intact; the files written are named on stdout. A deprecated env id
(`GOWEC-v1`) works and prints one note naming its new id.

Everything else is a bug: its traceback is printed, then one line saying so, and the status is
1. A ValueError counts as a user mistake only when a `raise` statement of this package raised it
(the library's validation); one raised inside numpy, scipy or Python itself (for example a
reduction over an empty array) is a bug, not the user's fault.
"""

from __future__ import annotations

import argparse
import dis
import sys
import traceback
import warnings
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from mf_envs._extras import install_hint, missing_extra
from mf_envs._validate import arg_int

BENCH_KINDS = ("accuracy", "speed", "controllers")
# upper bounds of the counts the commands take (docs/api.md, "Command line")
MAX_SEED = 2**32 - 1  # numpy's seeds
MAX_STEPS = 10_000_000  # render --steps
MAX_TIMESTEPS = 10**10  # train --timesteps
MAX_EPISODES = 10_000  # evaluate --episodes, train --eval-episodes


def _cmd_demo(args: argparse.Namespace) -> list[Path]:
    from mf_envs._staging import moved, staged_dir
    from mf_envs.benchmarks import demos

    with staged_dir(Path(args.out)) as tmp:
        files = demos.run(tmp, quick=args.quick, only=args.only)
    return moved(files, tmp, Path(args.out))


def _cmd_bench(args: argparse.Namespace) -> list[Path]:
    import importlib

    from mf_envs._staging import moved, staged_dir

    mod = importlib.import_module(f"mf_envs.benchmarks.{args.kind}")
    with staged_dir(Path(args.out)) as tmp:
        files = mod.run(tmp, quick=args.quick, only=args.scene)
    return moved(files, tmp, Path(args.out))


def _cmd_render(args: argparse.Namespace) -> list[Path]:
    from mf_envs.cli.render import render_command

    return render_command(args)


def _cmd_train(args: argparse.Namespace) -> list[Path]:
    if args.backend == "rllib":
        from mf_envs.train.rllib import train_command
    else:
        from mf_envs.train.cli import train_command

    return train_command(args)


def _cmd_sweep(args: argparse.Namespace) -> list[Path]:
    from mf_envs.sweep.cli import sweep_command

    return sweep_command(args)


def _cmd_evaluate(args: argparse.Namespace) -> list[Path]:
    from mf_envs.train.cli import evaluate_command

    return evaluate_command(args)


class _OneLineParser(argparse.ArgumentParser):
    """argparse with usage errors as one line on stderr (status 2), pointing to --help."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(2, f"{self.prog}: error: {message} (see --help)\n")


def build_parser() -> argparse.ArgumentParser:
    p = _OneLineParser(prog="mf-envs")
    sub = p.add_subparsers(
        dest="command", required=True, metavar="COMMAND", parser_class=_OneLineParser
    )

    _add_run_commands(sub)
    _add_train_commands(sub)
    s = sub.add_parser("sweep", help="env kwargs x controllers x seeds on Ray (CSV + PNG)")
    from mf_envs.sweep.cli import add_arguments

    add_arguments(s)
    s.set_defaults(func=_cmd_sweep)
    p.description = (
        f"Moving-frame Gymnasium environments (Rios 2017). Commands: {', '.join(sub.choices)}."
    )
    p.add_argument("--version", action="version", version=f"%(prog)s {package_version()}")
    return p


def _add_run_commands(sub: Any) -> None:
    """demo, bench, render."""
    d = sub.add_parser("demo", help="run every system's showcase on defaults; writes plots + GIFs")
    d.add_argument("--out", default="mf_envs_demo", help="output folder (default: %(default)s)")
    d.add_argument("--quick", action="store_true", help="shorter runs")
    d.add_argument("--only", nargs="+", metavar="SYSTEM", help="run only these demo modules")
    d.set_defaults(func=_cmd_demo)

    b = sub.add_parser(
        "bench",
        help="benchmarks: accuracy | speed | controllers (CSV + PNG); rl: `mf-envs bench rl "
        "--help`",
    )
    b.add_argument("kind", choices=BENCH_KINDS)
    b.add_argument("--out", required=True, help="output folder")
    b.add_argument("--quick", action="store_true", help="a reduced ladder that runs in minutes")
    b.add_argument("--scene", nargs="+", metavar="NAME", help="run only these scene modules")
    b.set_defaults(func=_cmd_bench)

    r = sub.add_parser("render", help="render an episode of an env to a GIF (headless)")
    r.add_argument("env_id")
    r.add_argument("--policy", default="baseline", help="baseline | baseline:KIND | ppo | PATH")
    r.add_argument("--out", required=True, help="output .gif path")
    r.add_argument(
        "--steps", type=arg_int(1, MAX_STEPS), default=None,
        help=f"number of env steps, 1..{MAX_STEPS} (default: env's)",
    )  # fmt: skip
    r.add_argument(
        "--seed", type=arg_int(0, MAX_SEED), default=0,
        help="reset seed, 0..2**32-1 (default: %(default)s)",
    )  # fmt: skip
    r.set_defaults(func=_cmd_render)


def _add_train_commands(sub: Any) -> None:
    """train, evaluate."""
    t = sub.add_parser("train", help="train a PPO agent (Stable-Baselines3) on an env")
    t.add_argument("env_id")
    t.add_argument(
        "--algo", choices=("ppo", "sac", "td3", "sbx_sac"), default="ppo",
        help="Stable-Baselines3 algorithm, or sbx_sac: SBX's SAC (JAX; the sbx extra) "
        "(default: %(default)s); config: configs/ALGO.yml (sbx_sac: sac.yml)",
    )  # fmt: skip
    t.add_argument(
        "--timesteps", type=arg_int(1, MAX_TIMESTEPS), default=None,
        help="1..1e10 (default: from the env's config)",
    )  # fmt: skip
    t.add_argument("--seed", type=arg_int(0, MAX_SEED - 10_000), default=0, help="0..2**32-10001")
    t.add_argument("--config", default=None, help="YAML hyperparameters (rl-zoo3 format)")
    t.add_argument(
        "--out", default="runs", help="writes OUT/ENV_ID/seedSEED/ (default: %(default)s)"
    )
    t.add_argument("--force", action="store_true", help="replace an existing run folder")
    t.add_argument("--tensorboard", action="store_true", help="write TensorBoard logs")
    t.add_argument(
        "--eval-episodes",
        type=arg_int(1, MAX_EPISODES),
        default=5,
        help=f"episodes per evaluation, 1..{MAX_EPISODES} (default: 5)",
    )
    t.add_argument(
        "--vec-env",
        choices=("auto", "dummy"),
        default="auto",
        help="auto: the env's native vector env where it has one (default); dummy: DummyVecEnv",
    )
    t.add_argument("--backend", choices=("sb3", "rllib"), default="sb3", help="sb3 | rllib (Ray)")
    t.set_defaults(func=_cmd_train)

    e = sub.add_parser("evaluate", help="PPO vs every classical baseline on unseen seeds")
    e.add_argument("env_id")
    e.add_argument("--policy", default=None, help="policy path (default: the shipped policy)")
    e.add_argument("--episodes", type=arg_int(1, MAX_EPISODES), default=5, help="1..10000")
    e.add_argument(
        "--seed", type=arg_int(0, MAX_SEED - MAX_EPISODES), default=1000,
        help="first evaluation seed, 0..2**32-10001",
    )  # fmt: skip
    e.add_argument(
        "--out",
        default="mf_envs_eval",
        help="writes OUT/ENV_ID/evaluate.csv (default: %(default)s)",
    )
    e.add_argument("--force", action="store_true", help="replace an existing OUT/ENV_ID folder")
    e.set_defaults(func=_cmd_evaluate)


def package_version() -> str:
    """The installed distribution's version (`importlib.metadata`), else the package's own."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("mf-envs")
    except PackageNotFoundError:  # run from a source tree that is not installed
        from mf_envs import __version__

        return __version__


def _written(paths: list[Path]) -> str:
    """The files a command wrote, named: one path, or a count and one path a line."""
    names = [str(p) for p in paths]
    if len(names) == 1:
        return f"wrote {names[0]}"
    return "\n  ".join([f"wrote {len(names)} files:", *names])


def main(argv: Sequence[str] | None = None) -> int:
    rest = list(sys.argv[1:] if argv is None else argv)
    if rest[:2] == ["bench", "rl"]:  # the RL benchmark has its own options
        from mf_envs.benchmarks import rl_benchmark

        return rl_benchmark.main(rest[2:])
    parser = build_parser()
    args = parser.parse_args(argv)
    func: Callable[[argparse.Namespace], list[Path]] = args.func
    who = f"mf-envs {args.command}"
    with warnings.catch_warnings():
        warnings.showwarning = _one_line_notes(who, warnings.showwarning)
        return _run(func, args, who)


def _one_line_notes(who: str, shown: Callable[..., None]) -> Callable[..., None]:
    """A `warnings.showwarning` that prints a `DeprecatedIdWarning` (a renamed env id) as one
    line `WHO: note: ...` and a `PolicyEnvWarning` (a policy used on an env that differs from
    the one it was trained on) as `WHO: warning: ...` on stderr, and passes every other warning
    to `shown`."""
    from mf_envs.envs import DeprecatedIdWarning
    from mf_envs.train.provenance import PolicyEnvWarning

    def show(message, category, filename, lineno, file=None, line=None):
        if issubclass(category, DeprecatedIdWarning):
            print(f"{who}: note: {message}", file=sys.stderr)
        elif issubclass(category, PolicyEnvWarning):
            print(f"{who}: warning: {message}", file=sys.stderr)
        else:
            shown(message, category, filename, lineno, file, line)

    return show


def _run(
    func: Callable[[argparse.Namespace], list[Path]], args: argparse.Namespace, who: str
) -> int:
    from mf_envs.envs import canonical_env_id

    if isinstance(getattr(args, "env_id", None), str):  # a deprecated id: its new id, noted
        args.env_id = canonical_env_id(args.env_id)
    try:
        written = func(args)
    except ValueError as exc:
        if not raised_by_package(exc):
            return _bug(who)
        print(f"{who}: error: {exc}", file=sys.stderr)
        return 2
    except ModuleNotFoundError as exc:
        extra = missing_extra(exc)
        if extra is None:
            return _bug(who)
        print(f"{who}: needs the {extra} extra: {install_hint(extra)} ({exc})", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"{who}: interrupted; previous outputs left unchanged", file=sys.stderr)
        return 130
    except OSError as exc:
        if exc.filename is None:
            return _bug(who)
        print(f"{who}: error: {exc.strerror}: {exc.filename}", file=sys.stderr)
        return 2
    except Exception:
        return _bug(who)
    if written:
        print(_written(written))
    return 0


_PACKAGE_DIR = Path(__file__).resolve().parents[1]
_RAISE = dis.opmap["RAISE_VARARGS"]


def raised_by_package(exc: BaseException) -> bool:
    """Whether `exc` was raised by a `raise` statement in this package's own code: the innermost
    frame of its traceback is in `mf_envs/` and the instruction there is a raise (not a call
    into C that failed, such as `np.max` of an empty array)."""
    tb = exc.__traceback__
    if tb is None:
        return False
    while tb.tb_next is not None:
        tb = tb.tb_next
    code = tb.tb_frame.f_code
    if not Path(code.co_filename).resolve().is_relative_to(_PACKAGE_DIR):
        return False
    return 0 <= tb.tb_lasti < len(code.co_code) and code.co_code[tb.tb_lasti] == _RAISE


def _bug(who: str) -> int:
    """An internal error: its traceback, one line that says it is a bug, status 1."""
    traceback.print_exc()
    print(
        f"{who}: internal error (a bug in mf_envs, not in what you typed); the traceback above "
        "says where. Please report it with the command you ran.",
        file=sys.stderr,
    )
    return 1
