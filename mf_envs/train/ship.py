"""Ship a training run as the env's policy: `python -m train.ship RUN_DIR [--force]`.

Refuses (exit 2) unless the run's `meta.json` evaluation shows PPO at least as good as the env's
default classical baseline on the primary metric (same unseen seeds); `--force` overrides (and
says so). Copies the policy files into `train/policies/<env_id>/` and the learning curve to
`docs/img/train_<env_id>_learning_curve.png`.
"""

from __future__ import annotations

import argparse
import shutil
import sys
from pathlib import Path
from typing import Any

from mf_envs.train.policy import POLICY_ROOT, read_meta, write_meta
from mf_envs.train.trainer import ship_run

DOCS_IMG = Path(__file__).resolve().parents[2] / "docs" / "img"


def verdict(meta: dict[str, Any]) -> tuple[bool, str]:
    """(PPO at least matches the default baseline?, one-line explanation) from meta.json."""
    ev = meta.get("evaluation")
    algo = meta.get("algo", "ppo")  # the trained policy's rows: "ppo", "sac" or "td3"
    if not ev or algo not in ev:
        return False, "meta.json has no evaluation"
    base = [k for k in ev if k.startswith("baseline:")]
    ppo = ev[algo]["mean"]
    if not base:
        return True, f"{ev['metric']}: {algo} {ppo:.4g} (no baseline to compare with)"
    b = ev[base[0]]["mean"]
    ok = ppo >= b if ev["higher_is_better"] else ppo <= b
    return ok, f"{ev['metric']}: {algo} {ppo:.4g} vs {base[0]} {b:.4g} on seeds {ev['seeds']}"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(prog="python -m train.ship", description=__doc__.splitlines()[0])
    p.add_argument("run_dir")
    p.add_argument("--force", action="store_true", help="ship even if worse than the baseline")
    p.add_argument("--note", default=None, help="a caveat stored in the shipped meta.json")
    args = p.parse_args(argv)
    try:
        return _ship(args)
    except ValueError as exc:  # bad meta.json, env_id, files: one line, no traceback
        print(f"ship: error: {exc}", file=sys.stderr)
        return 2


def _ship(args: argparse.Namespace) -> int:
    run_dir = Path(args.run_dir)
    meta = read_meta(run_dir)
    if "env_id" not in meta:
        print(f"ship: error: {run_dir} has no meta.json with an env_id", file=sys.stderr)
        return 2
    ok, why = verdict(meta)
    print(why)
    if not ok and not args.force:
        print("ship: refused: PPO does not match the default baseline", file=sys.stderr)
        return 2
    files = ship_run(run_dir)
    if args.note:
        dest = POLICY_ROOT / meta["env_id"]
        write_meta(dest, {**read_meta(dest), "note": args.note})
    curve = run_dir / "learning_curve.png"
    if curve.is_file():
        DOCS_IMG.mkdir(parents=True, exist_ok=True)
        dest = DOCS_IMG / f"train_{meta['env_id']}_learning_curve.png"
        files.append(Path(shutil.copy2(curve, dest)))
    print(
        ("FORCED: " if not ok else "") + f"shipped {len(files)} file(s): {[str(f) for f in files]}"
    )
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
