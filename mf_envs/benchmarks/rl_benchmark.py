"""RL benchmark on a headline task: algorithms x training seeds, frozen test seeds, one window,
interquartile means with stratified-bootstrap 95 % intervals (Agarwal et al. 2021).

    python -m mf_envs.benchmarks.rl_benchmark --task stabilizer_irregular --out bench_rl
    python -m mf_envs.benchmarks.rl_benchmark --algos sac --seeds 0 1 2 3 4   # more seeds

Protocol (docs/benchmark.md):
- **Training**: `mf_envs.train.train` with the shipped rl-zoo3 entry of each algorithm
  (`configs/<algo>.yml`) plus the task's env kwargs, one run per (algorithm, training seed),
  on the task's budget; a new sea every reset.
- **Test seeds**: `TEST_SEEDS` (20000-20019), frozen, never used by training (training episodes
  draw from the trainer's seeds, its evaluation callback from 10000+): each seed draws a new
  irregular-sea realisation, not just a phase.
- **Window**: every controller, learned or classical, is scored on the same episodes of
  `eval_seconds` and the same window (the env's metric after its settling time).
- **Policies**: the final policy of each run (the `best` checkpoint is not used).
- **Score**: the task's normalised score per episode (the stabilizer: RMS roll reduction
  1 - rms_on / rms_off against the same sea with the rotor off); a run's score is its mean
  over the test seeds; per algorithm the interquartile mean over runs and its stratified
  bootstrap 95 % interval (`interval`, 2000 resamples; with 3
  runs the IQM trims nothing and is the mean). Baselines are deterministic: their interval is
  the bootstrap over the 20 test episodes.

Writes `<out>/<task>/results.json`, `table.md`, `learning_curves.png` and the runs under
`<out>/<task>/runs/`.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import make_dirs, write_atomic

TEST_SEEDS = tuple(range(20_000, 20_020))
TRAIN_SEEDS = (0, 1, 2)
ALGOS = ("sac", "td3", "ppo")


@dataclass(frozen=True)
class Task:
    """A benchmark task on a registered id (its scene: the id's spec kwargs plus `env_kwargs`):
    budgets, baselines, and the normalised score with its ceiling.

    Score per test episode: with `reference_kwargs`, 1 - metric / metric of the same seed in
    the reference scene (the stabilizer: rotor off); without, metric / the id's ceiling for the
    episode's scene (`EnvDeclaration.ceiling`, e.g. a sea's power bound)."""

    name: str
    env_id: str
    env_kwargs: dict[str, Any]
    eval_seconds: float
    budgets: dict[str, int]
    baselines: tuple[str, ...]
    ceiling: float
    ceiling_note: str
    score_name: str
    reference_kwargs: Callable[[dict[str, Any]], dict[str, Any]] | None = field(repr=False)
    metric: str | None = None  # the episode metric scored (None: the env's primary metric)


def rotor_off(kwargs: dict[str, Any]) -> dict[str, Any]:
    """The stabilizer's reference scene: the same sea with the rotor off."""
    return {**kwargs, "effects": tuple(e for e in kwargs["effects"] if e != "gyroscopic")}


def _stabilizer_irregular() -> Task:
    """GyroStabilizer-JONSWAP-v0: its scene's kwargs (the grid cell's; the episode length is
    the protocol's, `eval_seconds`) and its ceiling."""
    from mf_envs.envs import declaration

    env_id = "GyroStabilizer-JONSWAP-v0"
    decl = declaration(env_id)
    kw = {k: v for k, v in decl.kwargs.items() if k != "episode_seconds"}
    return Task(
        name="stabilizer_irregular",
        env_id=env_id,
        env_kwargs=kw,
        eval_seconds=120.0,
        budgets={"ppo": 50_000, "sac": 20_000, "td3": 20_000},
        baselines=("random", "pid", "lqr"),
        ceiling=float(decl.ceiling.value),
        ceiling_note="RMS roll reduction 1 (no roll left); no causal bound computed",
        score_name="rms_roll_reduction",
        reference_kwargs=rotor_off,
    )


def _stabilizer_resonance() -> Task:
    """The default scene (regular beam wave at the roll resonance): the easy task, where the
    benchmark's first review saw SAC beat the classical controllers; a test seed sets only the
    wave's phase and the start, so its 20 episodes are nearly one."""
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS

    irregular = _stabilizer_irregular()
    return Task(
        name="stabilizer_resonance",
        env_id="GyroStabilizer-v0",
        env_kwargs={"effects": tuple(DEFAULT_EFFECTS)},
        eval_seconds=120.0,
        budgets=irregular.budgets,
        baselines=irregular.baselines,
        ceiling=1.0,
        ceiling_note=irregular.ceiling_note,
        score_name=irregular.score_name,
        reference_kwargs=rotor_off,
    )


def _gowec_irregular() -> Task:
    """FloatingGOWEC-JONSWAP-v0: mean net electrical power over the episode's second half as a
    fraction of the id's ceiling for that episode's sea (`gowec_v1.task.net_power_ceiling`)."""
    return Task(
        name="gowec_irregular",
        env_id="FloatingGOWEC-JONSWAP-v0",
        env_kwargs={},
        eval_seconds=120.0,
        budgets={"ppo": 100_000, "sac": 20_000, "td3": 20_000},  # fits a 2-core hour
        baselines=(
            "zero",
            "random",
            "bang_bang",
            "linear_pto",
            "passive_damper",
            "efficient_pto",
        ),  # fmt: skip
        ceiling=1.0,
        ceiling_note="net power / the sea's `net_power_ceiling` (loss-inclusive, loose)",
        score_name="net_power_of_ceiling",
        reference_kwargs=None,
        metric="net_power",
    )


def _gowec_regular() -> Task:
    """FloatingGOWEC-v0's default regular sea (a = 1 m, T = 6 s): the GOWEC's easy task, scored
    as `gowec_irregular` (a test seed sets only the wave's phase)."""
    from dataclasses import replace

    return replace(_gowec_irregular(), name="gowec_regular", env_id="FloatingGOWEC-v0")


TASKS: dict[str, Callable[[], Task]] = {
    "stabilizer_irregular": _stabilizer_irregular,
    "stabilizer_resonance": _stabilizer_resonance,
    "gowec_irregular": _gowec_irregular,
    "gowec_regular": _gowec_regular,
}


# ------------------------------------------------------------------------------- evaluation
class RandomAction:
    """Uniform random actions from a seeded generator (one per episode)."""

    def __init__(self, space: Any, seed: int) -> None:
        self.space, self.rng = space, np.random.default_rng(seed)

    def reset(self) -> None:
        return None

    def predict(self, obs: Any, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return self.rng.uniform(self.space.low, self.space.high).astype(self.space.dtype), None


class ZeroAction(RandomAction):
    def predict(self, obs: Any, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return np.zeros(self.space.shape, self.space.dtype), None


def _metric(
    task: Task, kwargs: dict[str, Any], kind: str, seed: int, run: Path | None
) -> tuple[float, float]:
    """The scored metric of one test episode of `kind` (a baseline, "random", "zero", or the
    policy in `run`; the env's primary metric unless `task.metric`) and the id's ceiling for
    that episode's scene (nan without one)."""
    import gymnasium as gym

    from mf_envs.controllers import make_baseline
    from mf_envs.envs import declaration
    from mf_envs.train.evaluate import primary_metric, run_episode
    from mf_envs.train.policy import load_policy

    env = gym.make(task.env_id, **kwargs)
    try:
        if run is not None:
            ctrl: Any = load_policy(task.env_id, run)
        elif kind in ("random", "zero"):
            ctrl = (RandomAction if kind == "random" else ZeroAction)(env.action_space, seed)
        else:
            ctrl = make_baseline(env, kind)
        name = task.metric or primary_metric(task.env_id).name
        value = float(run_episode(task.env_id, env, ctrl, seed)[name])
        ceiling = declaration(task.env_id).ceiling
        return value, (math.nan if ceiling is None else ceiling.of(env))
    finally:
        env.close()


def episode_scores(task: Task, kind: str, run: Path | None = None) -> np.ndarray:
    """Normalised score of `kind` (a baseline, "random", or the policy in `run`) on each test
    seed (`Task`): 1 - metric / metric of the same seed in the reference scene, or metric / the
    episode's ceiling."""
    # longer than the spec's episode: gym.make without its TimeLimit (episode_seconds ends it)
    kw = {**task.env_kwargs, "episode_seconds": task.eval_seconds, "max_episode_steps": -1}
    out = []
    for s in TEST_SEEDS:
        value, ceiling = _metric(task, kw, kind, s, run)
        if task.reference_kwargs is None:
            out.append(value / ceiling)
        else:
            out.append(1.0 - value / _metric(task, task.reference_kwargs(kw), "zero", s, None)[0])
    return np.array(out)


def interval(scores: np.ndarray, reps: int = 2000, seed: int = 0) -> dict[str, float]:
    """IQM and stratified-bootstrap 95 % percentile interval of `scores` (runs,) or (runs, tasks),
    as in Agarwal et al. (NeurIPS 2021): each bootstrap sample redraws the runs of every task
    (column) with replacement, and its IQM is the 25 % trimmed mean of all the drawn scores. The
    mean and its sample std beside them. Written with numpy and scipy (rliable's
    `get_interval_estimates` with `aggregate_iqm` computes the same statistic)."""
    from scipy.stats import trim_mean

    m = np.atleast_2d(np.asarray(scores, dtype=float))
    if m.shape[0] == 1:
        m = m.T
    runs, tasks = m.shape
    rng = np.random.default_rng(seed)
    rows = rng.integers(0, runs, size=(reps, runs, tasks))  # per task, its own draw of runs
    drawn = m[rows, np.arange(tasks)]
    boot = trim_mean(drawn.reshape(reps, -1), 0.25, axis=1)
    lo, hi = np.percentile(boot, [2.5, 97.5])
    flat = m.ravel()
    return {"iqm": float(trim_mean(flat, 0.25)), "lo": float(lo), "hi": float(hi),
            "mean": float(flat.mean()), "std": float(flat.std(ddof=1)) if flat.size > 1 else 0.0,
            "n": int(runs)}  # fmt: skip


# ------------------------------------------------------------------------------- training
def write_config(task: Task, algo: str, folder: Path) -> Path:
    """The shipped rl-zoo3 entry of `algo` for the env plus the task's env kwargs and budget,
    written as `folder/<algo>.yml` (the file `mf-envs train --config` reads)."""
    import yaml

    from mf_envs.train.config import config_entry, default_config

    entry = config_entry(task.env_id, default_config(algo))  # a variant's: its env's
    entry["n_timesteps"] = int(task.budgets[algo])
    entry["env_kwargs"] = {k: list(v) if isinstance(v, tuple) else v
                           for k, v in task.env_kwargs.items()}  # fmt: skip
    folder.mkdir(parents=True, exist_ok=True)
    return write_atomic(
        folder / f"{algo}.yml", yaml.safe_dump({task.env_id: entry}, sort_keys=False)
    )


def train_runs(task: Task, algos: Sequence[str], seeds: Sequence[int], out: Path) -> dict:
    """Train every (algorithm, seed) not already on disk; {algo: [(seed, run_dir, wall_s)]}."""
    from mf_envs.train import policy
    from mf_envs.train.trainer import train

    runs: dict[str, list[tuple[int, Path, float]]] = {}
    for algo in algos:
        cfg = write_config(task, algo, out / "configs")
        for s in seeds:
            final = out / "runs" / task.env_id / ("" if algo == "ppo" else algo) / f"seed{s}"
            if not (final / policy.POLICY_FILE).is_file():
                t0 = time.time()
                train(task.env_id, seed=s, config=cfg, out=out / "runs", algo=algo,
                      final_eval_seeds=(), force=True)  # fmt: skip
                print(f"{algo} seed {s}: trained in {time.time() - t0:.0f} s", flush=True)
            runs.setdefault(algo, []).append(
                (s, final, float(policy.read_meta(final)["wall_time_s"]))
            )
    return runs


# ------------------------------------------------------------------------------- report
def table(task: Task, rows: dict[str, dict[str, Any]]) -> str:
    head = (f"| controller | runs | {task.score_name}: IQM [95 % CI] | mean ± std | "
            "of ceiling | budget (steps) | wall per run (s) |")  # fmt: skip
    lines = [head, "|---|---|---|---|---|---|---|"]
    for name, r in rows.items():
        lines.append(
            f"| {name} | {r['n']} | {r['iqm']:.3f} [{r['lo']:.3f}, {r['hi']:.3f}] | "
            f"{r['mean']:.3f} ± {r['std']:.3f} | {r['iqm'] / task.ceiling:.0%} | "
            f"{r.get('budget', '-')} | {r.get('wall', '-')} |"
        )
    lines.append(f"| ceiling | | {task.ceiling:g} ({task.ceiling_note}) | | 100% | | |")
    return "\n".join(lines)


def curves(task: Task, runs: dict, path: Path) -> Path:
    from mf_envs.train.curves import plot_learning_curves

    folders, labels = [], []
    for algo, items in runs.items():
        for s, run, _ in items:
            if (run / "evaluations.npz").is_file():
                folders.append(run)
                labels.append(f"{algo} seed {s}")
    return plot_learning_curves(folders, path, f"{task.env_id}: {task.name}", labels)


def run(task_name: str, algos: Sequence[str], seeds: Sequence[int], out: Path) -> dict[str, Any]:
    task = TASKS[task_name]()
    folder = make_dirs(out, out / task.name)  # a planted link there is refused
    runs = train_runs(task, algos, seeds, folder)
    rows: dict[str, dict[str, Any]] = {}
    for kind in task.baselines:
        rows[kind] = interval(episode_scores(task, kind))
        print(f"{kind}: {rows[kind]}", flush=True)
    for algo, items in runs.items():
        per_run = np.array([episode_scores(task, algo, run).mean() for _, run, _ in items])
        rows[algo] = {**interval(per_run), "budget": task.budgets[algo],
                      "wall": f"{np.median([w for *_, w in items]):.0f}",
                      "per_run": per_run.tolist()}  # fmt: skip
        print(f"{algo}: {rows[algo]}", flush=True)
    md = table(task, rows)
    write_atomic(folder / "table.md", md + "\n")
    result = {"task": task.name, "env_id": task.env_id, "env_kwargs": task.env_kwargs,
              "eval_seconds": task.eval_seconds, "test_seeds": list(TEST_SEEDS),
              "train_seeds": list(seeds), "rows": rows}  # fmt: skip
    write_atomic(folder / "results.json", json.dumps(result, indent=1, default=str))
    if any(items for items in runs.values()):
        curves(task, runs, folder / "learning_curves.png")
    print(md)
    return result


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--task", choices=sorted(TASKS), default="stabilizer_irregular")
    p.add_argument("--algos", nargs="*", choices=ALGOS, default=list(ALGOS))
    p.add_argument("--seeds", nargs="+", type=int, default=list(TRAIN_SEEDS))
    p.add_argument("--out", type=Path, default=Path("bench_rl"))
    a = p.parse_args(argv)
    if any(s < 0 or math.isnan(s) for s in a.seeds):
        raise SystemExit("--seeds: training seeds must be >= 0")
    run(a.task, a.algos, a.seeds, a.out)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
