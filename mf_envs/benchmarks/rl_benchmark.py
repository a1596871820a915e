"""RL benchmark: every headline id x algorithm x training seed x budget, scored on frozen test
conditions, one results file, docs/benchmark.md's tables and figures generated from it.

    mf-envs bench rl --all --out bench_rl --docs docs/benchmark.md      # the whole grid (hours)
    python -m mf_envs.benchmarks.rl_benchmark --all --out bench_rl      # the same
    mf-envs bench rl --ids GyroStabilizer-JONSWAP-v0 --seeds 0 1 --algos ppo --out b
    mf-envs bench rl --all --budget-scale 0.001 --test-seeds 2 --out smoke   # a smoke run

Protocol (docs/benchmark.md):
- **Grid** (`rl_tasks.HEADLINE`, `Task.budgets`): PPO at 1M and 10M env-steps on the marine
  headline ids and 1M on the soft robots, SBX's SAC at 1M on the marine ids; training seeds
  `TRAIN_SEEDS` (0-4). Each run is `train.trainer.train` with the shipped rl-zoo3 entry of its
  algorithm (native vector rows) and the task's scene, no evaluation checks during training;
  the final policy is scored.
- **Test conditions** (`rl_tasks`): test seeds 20000-20019, each a new sea (marine ids) or a
  draw of the declared randomisation ranges (soft robots), never seen by training.
- **Resume**: each run and each controller writes one record file (`rl_results`) inside
  `--out` only, atomically; a record on disk is not recomputed (a trained run whose record is
  missing is scored, not retrained). Rerun the command after the envs change in a new folder.
- **Results**: `<out>/results.json` (`rl_results.collect`: the records, the score per test
  condition, the normalised scale per id) and, with `--docs`, the generated block of that page,
  its two figures (score against env-steps and against wall-clock seconds) and a copy of the
  results file beside it (`docs/results/rl_benchmark.json`).
- `--budget-scale` multiplies every budget (a smoke or reduced run: its records name the
  budgets trained, so they never stand in for the full grid's).
"""

from __future__ import annotations

import argparse
import json
import platform
import shlex
import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from mf_envs._files import make_dirs, write_atomic
from mf_envs.benchmarks import rl_results as res
from mf_envs.benchmarks.rl_results import interval  # noqa: F401  (the protocol's estimator)
from mf_envs.benchmarks.rl_tasks import (  # noqa: F401  (the protocol's names, importers')
    HEADLINE,
    TASKS,
    TEST_SEEDS,
    RandomAction,
    Task,
    ZeroAction,
    episode_scores,
    rotor_off,
    test_episodes,
)

TRAIN_SEEDS = (0, 1, 2, 3, 4)
ALGOS = ("ppo", "sbx_sac")  # the learners the grid gives budgets (rl_tasks)


def write_config(task: Task, algo: str, budget: int, folder: Path) -> Path:
    """The shipped rl-zoo3 entry of `algo` for the env plus the task's env kwargs and budget,
    written as `folder/<algo>-<budget>.yml` (the file `mf-envs train --config` reads)."""
    import yaml

    from mf_envs.train.config import config_entry, default_config

    entry = config_entry(task.env_id, default_config(algo))  # a variant's: its env's
    entry["n_timesteps"] = int(budget)
    entry["env_kwargs"] = {k: list(v) if isinstance(v, tuple) else v
                           for k, v in task.env_kwargs.items()}  # fmt: skip
    make_dirs(folder, folder)
    text = yaml.safe_dump({task.env_id: entry}, sort_keys=False)
    return write_atomic(folder / f"{algo}-{budget}.yml", text)


def _stamp(command: str) -> dict[str, Any]:
    from mf_envs import __version__

    machine = f"{platform.machine()}, {platform.system()}, Python {platform.python_version()}"
    return {"machine": machine, "version": __version__, "command": command,
            "date": time.strftime("%Y-%m-%dT%H:%MZ", time.gmtime())}  # fmt: skip


def score_controllers(task: Task, out: Path, seeds: tuple[int, ...], command: str) -> None:
    """A record per classical baseline, the zero and the random action (unless on disk)."""
    for kind in task.baselines:
        tag = kind if kind in ("zero", "random") else "baseline"
        if _done(out, res.record_path(out, task.env_id, kind, None, None), seeds):
            continue
        scores, returns = test_episodes(task, kind, seeds=seeds)
        res.write_record(out, {"env_id": task.env_id, "kind": tag, "name": kind, "seed": None,
                               "budget": None, "score_name": task.score_name,
                               "test_seeds": list(seeds), "scores": scores.tolist(),
                               "returns": returns.tolist(), **_stamp(command)})  # fmt: skip


def _done(out: Path, path: Path, seeds: tuple[int, ...]) -> bool:
    """Whether the record at `path` is on disk, scored on these test seeds (a record of other
    test conditions is scored again and replaced)."""
    rec = res.read_record(out, path)
    return rec is not None and rec["test_seeds"] == list(seeds)


def train_and_score(
    task: Task, algo: str, budget: int, seed: int, out: Path, seeds: tuple[int, ...],
    command: str,
) -> dict[str, Any] | None:  # fmt: skip
    """One learner cell of `budget` env-steps: train (unless its policy is on disk), score,
    write its record. None if the record was already on disk."""
    from mf_envs.train import policy
    from mf_envs.train.trainer import train

    if _done(out, res.record_path(out, task.env_id, algo, budget, seed), seeds):
        return None
    runs = make_dirs(out, out / "runs" / f"{algo}-{budget}")
    final = runs / task.env_id / ("" if algo == "ppo" else algo) / f"seed{seed}"
    if not (final / policy.POLICY_FILE).is_file():
        cfg = write_config(task, algo, budget, out / "configs")
        train(task.env_id, seed=seed, config=cfg, out=runs, algo=algo, evaluations=0,
              final_eval_seeds=(), force=True)  # fmt: skip
    meta = policy.read_meta(final)
    scores, returns = test_episodes(task, algo, final, seeds)
    rec = {"env_id": task.env_id, "kind": "learner", "name": algo, "seed": seed,
           "budget": budget, "env_steps": int(meta["timesteps"]), "score_name": task.score_name,
           "test_seeds": list(seeds), "scores": scores.tolist(), "returns": returns.tolist(),
           "wall_s": float(meta["wall_time_s"]), "steps_per_s": float(meta["steps_per_s"]),
           "vectorization": meta.get("vectorization"), **_stamp(command)}  # fmt: skip
    res.write_record(out, rec)
    return rec


def cells(
    names: Sequence[str], algos: Sequence[str], seeds: Sequence[int], scale: float = 1.0
) -> list[tuple]:
    """(task, algo, budget, seed) of the grid: every budget each task gives each algorithm,
    times `scale` (the budget a record names is the one trained)."""
    out = []
    for name in names:
        task = TASKS[name]()
        for algo in algos:
            for budget in task.budgets.get(algo, ()):
                out += [(task, algo, max(1, round(budget * scale)), s) for s in seeds]
    return out


def run(
    names: Sequence[str], algos: Sequence[str], seeds: Sequence[int], out: Path,
    scale: float = 1.0, n_test: int = len(TEST_SEEDS), docs: Path | None = None,
    command: str = "",
) -> dict[str, Any]:  # fmt: skip
    """Run the grid of the tasks `names` (`TASKS`; resuming), write `out/results.json`, and
    with `docs` regenerate that page's block and its figures (in `docs`' folder's `img/`)."""
    from tqdm import tqdm

    out = make_dirs(out, out)  # a planted link there is refused
    test = TEST_SEEDS[:n_test]
    for name in tqdm(names, desc="baselines", unit="task"):
        score_controllers(TASKS[name](), out, test, command)
    grid = cells(names, algos, seeds, scale)
    bar = tqdm(grid, desc="runs", unit="run")
    for task, algo, budget, seed in bar:
        bar.set_postfix_str(f"{task.env_id} {algo} {budget:.0e} seed {seed}")
        train_and_score(task, algo, budget, seed, out, test, command)
    result = res.collect(out, scale)
    result["command"] = command
    write_atomic(out / "results.json", json.dumps(result, indent=1, default=float) + "\n")
    if docs is not None:
        generate_docs(result, docs)
    return result


def generate_docs(result: dict[str, Any], docs: Path) -> list[Path]:
    """Regenerate `docs`' block and its figures (`docs`' folder/img/rl_benchmark_*.png), with a
    copy of the results file beside the page (`results/rl_benchmark.json`) that it cites."""
    folder = docs.parent
    copy = write_atomic(make_dirs(folder, folder / "results") / "rl_benchmark.json",
                        json.dumps(result, indent=1, default=float) + "\n")  # fmt: skip
    figs = res.figures(result, folder / "img")
    block = res.markdown(result, "results/rl_benchmark.json", [f"img/{p.name}" for p in figs])
    text = docs.read_text() if docs.is_file() else ""
    return [write_atomic(docs, res.splice(text, block)), copy, *figs]


def parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="mf-envs bench rl", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)  # fmt: skip
    p.add_argument("--all", action="store_true", help="every headline id (rl_tasks.HEADLINE)")
    p.add_argument("--ids", nargs="+", choices=sorted(HEADLINE), help="these headline ids")
    p.add_argument(
        "--task",
        nargs="+",
        choices=sorted(TASKS),
        default=[],
        help="these tasks (the easy ids' too: stabilizer_resonance, gowec_regular)",
    )
    p.add_argument("--algos", nargs="*", choices=ALGOS, default=["ppo", "sbx_sac"],
                   help="none: score the classical controllers only")  # fmt: skip
    p.add_argument("--seeds", nargs="+", type=int, default=list(TRAIN_SEEDS))
    p.add_argument("--out", type=Path, default=Path("bench_rl"))
    p.add_argument("--budget-scale", type=float, default=1.0, help="x every budget (smoke run)")
    p.add_argument("--test-seeds", type=int, default=len(TEST_SEEDS),
                   help=f"the first N of the {len(TEST_SEEDS)} test conditions")  # fmt: skip
    p.add_argument("--docs", type=Path, help="regenerate this page's block (docs/benchmark.md)")
    p.add_argument("--from-results", action="store_true",
                   help="with --docs: regenerate from OUT/results.json only (no runs)")  # fmt: skip
    return p


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(argv) if argv is not None else sys.argv[1:]
    a = parser().parse_args(argv)
    if a.from_results:
        if a.docs is None:
            raise SystemExit("--from-results needs --docs")
        result = json.loads((a.out / "results.json").read_text())
        generate_docs(result, a.docs)
        return 0
    if not a.all and not a.ids and not a.task:
        raise SystemExit("give --all, --ids or --task")
    if any(s < 0 for s in a.seeds):
        raise SystemExit("--seeds: training seeds must be >= 0")
    if not (0 < a.budget_scale <= 1) or not (1 <= a.test_seeds <= len(TEST_SEEDS)):
        raise SystemExit(f"--budget-scale in (0, 1], --test-seeds in 1..{len(TEST_SEEDS)}")
    ids = list(HEADLINE) if a.all else (a.ids or [])
    names = list(dict.fromkeys([HEADLINE[i] for i in ids] + a.task))
    cmd = "mf-envs bench rl " + " ".join(shlex.quote(x) for x in argv)
    result = run(names, a.algos, a.seeds, a.out, a.budget_scale, a.test_seeds, a.docs, cmd)
    print(res.aggregate_table(result))
    for env_id in result["ids"]:
        print(f"\n{env_id}\n{res.id_table(result, env_id)}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
