"""References that bound the headroom: the oracle and the causal MPC of the marine headline ids,
the soft robots' best-known gaits, scored on the RL benchmark's test conditions and written as
its "reference" records.

    python -m mf_envs.benchmarks.references --out bench_rl                  # every reference
    python -m mf_envs.benchmarks.references --refs oracle --ids GyroStabilizer-JONSWAP-v0 \\
        --test-seeds 3 --out smoke

Each marine reference (`REFERENCES`) is a `controllers.planner.SamplingPlanner` with the
budget below, each soft robot's `best_gait` the gait `benchmarks.gait_search` found; all are
scored exactly as the baselines (`rl_tasks.test_episodes`: the task's test seeds and scene,
its score); its record (`rl_results`, kind "reference") goes into `<out>/records/<id>/`
beside the baselines' and learners', so `rl_results.collect` puts it on the normalised scale
(0 = the zero action, 1 = the best classical baseline) and states the headroom: oracle - best
baseline. `docs/results/references.json` is the copy the README's table and docs cite.
Budgets (CPU: a shared 2-core machine; per 120 s episode, measured in docs/benchmark.md):
- GyroStabilizer-JONSWAP-v0 (control step 0.05 s): H = 30 steps (1.5 s, a quarter of the
  peak period), replanned every 3 steps, guided by the default baseline `scheduled_lqr` (its
  continuation is the search's starting mean and candidate 0); the MPC K = 64 rows and 2 CEM
  rounds, the oracle K = 128 rows and 3 rounds.
- FloatingGOWEC-JONSWAP-v0 (control step 0.02 s): H = 40 knots of 15 steps (12 s, two peak
  periods: a shorter horizon buys energy now at the next swing's expense), K = 32 rows, 2
  rounds, replanned every 4 knots (1.2 s); on top of `efficient_pto`'s linear PTO (`base`),
  so the zero correction (candidate 0) is the best baseline itself. The MPC plans the same
  way on its forecast sea (on training seeds 1 and 2 a 6 s horizon lost to the baseline, 12 s
  beat it).
"""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

from mf_envs._files import make_dirs, write_atomic

RESULTS = Path("docs/results/references.json")
PLANNER: dict[Any, dict[str, Any]] = {  # id, or (id, reference): the planner's budget
    "GyroStabilizer-JONSWAP-v0": dict(horizon=30, samples=64, iterations=2, replan=3,
                                      base="scheduled_lqr"),
    # the oracle: a horizon of 3 s (K = 128 x 3 rounds at 1.5 s scored no higher: 0.901)
    ("GyroStabilizer-JONSWAP-v0", "oracle"): dict(horizon=60, samples=64, iterations=2,
                                                  replan=3, base="scheduled_lqr"),
    # 12 s (two peak periods): at 6 s the oracle lost to the baseline with its flywheel speed
    # scheduled on 3 of seeds 20000-20004 (a window's energy taken at the next one's expense)
    "FloatingGOWEC-JONSWAP-v0": dict(horizon=40, hold=15, samples=32, iterations=2, replan=4,
                                     base="efficient_pto"),
}  # fmt: skip
# id -> reference name -> what it knows (docs/benchmark.md, "References")
REFERENCES: dict[str, dict[str, str]] = {
    "GyroStabilizer-JONSWAP-v0": {
        "oracle": "the episode's whole sea and the env's state; plans on the env's own rows",
        "mpc": "the env's state and the wave excitation met so far; an AR forecast ahead",
    },
    "FloatingGOWEC-JONSWAP-v0": {
        "oracle": "the episode's whole sea and the env's state; plans on the env's own rows",
        "mpc": "the env's state and the elevation at the hull met so far; an AR forecast "
        "ahead, fitted as a sea (`planner.causal_forecast_floating`)",
    },
    **{
        soft: {
            "best_gait": "what the default baseline observes; the gait family's parameters "
            "found by a global search on training conditions (`gait_search`): a best-known "
            "gait, not a bound"
        }
        for soft in ("Serpentine-v0", "Eel-v0", "Inchworm-v0")
    },
}


def factory(env_id: str, name: str) -> Callable[[Any], Any]:
    """The reference `name` of `env_id` as a factory env -> controller."""
    from mf_envs.controllers.planner import SamplingPlanner

    if name not in REFERENCES.get(env_id, {}):
        raise ValueError(f"refs: no reference {name!r} for {env_id}")
    if name == "best_gait":
        from mf_envs.benchmarks.gait_search import best_factory

        return best_factory(env_id)
    kw = dict(PLANNER.get((env_id, name), PLANNER[env_id]), causal=name == "mpc")
    return lambda env: SamplingPlanner(env, **kw)


def score(env_id: str, name: str, out: Path, seeds: tuple[int, ...], command: str) -> dict:
    """Score reference `name` of `env_id` on `seeds` and write its record into `out` (unless
    one of these seeds is there)."""
    from mf_envs.benchmarks import rl_results as res
    from mf_envs.benchmarks.rl_benchmark import _stamp
    from mf_envs.benchmarks.rl_tasks import HEADLINE, TASKS, test_episodes

    task = TASKS[HEADLINE[env_id]]()
    on_disk = res.read_record(out, res.record_path(out, env_id, name, None, None))
    if on_disk is not None and on_disk["test_seeds"] == list(seeds):
        return on_disk  # resume: a record of these test seeds is not recomputed
    scores, returns = test_episodes(task, factory(env_id, name), seeds=seeds)
    rec = {"env_id": env_id, "kind": "reference", "name": name, "seed": None, "budget": None,
           "score_name": task.score_name, "test_seeds": list(seeds), "scores": scores.tolist(),
           "returns": returns.tolist(), "knows": REFERENCES[env_id][name],
           **_stamp(command)}  # fmt: skip
    if name == "best_gait":
        from mf_envs.benchmarks.gait_search import BEST

        rec["gait"] = dict(BEST[env_id])
    else:
        rec["planner"] = dict(PLANNER.get((env_id, name), PLANNER[env_id]))
    res.write_record(out, rec)
    return rec


def copy_results(out: Path, dest: Path = RESULTS) -> Path:
    """`dest`: every reference record under `out` with the same ids' baseline, zero and best
    (`rl_results.collect`), the file the README's table reads; the ids `dest` already holds
    and `out` does not keep their rows (the marine references and the soft robots' gaits
    can be scored in different folders)."""
    from mf_envs.benchmarks import rl_results as res

    result = res.collect(out)
    rows = [r for r in result["rows"] if r["kind"] in ("reference", "baseline", "zero")]
    keep = {"schema": result["schema"], "ids": dict(result["ids"]), "rows": rows}
    if dest.is_file():
        old = json.loads(dest.read_text())
        others = {i: v for i, v in old["ids"].items() if i not in keep["ids"]}
        keep["ids"] = dict(sorted({**others, **keep["ids"]}.items()))
        keep["rows"] = [r for r in old["rows"] if r["env_id"] in others] + rows
    make_dirs(dest.parent, dest.parent)
    return write_atomic(dest, json.dumps(keep, indent=1, default=float) + "\n")


def main(argv: Sequence[str] | None = None) -> int:
    from mf_envs.benchmarks.rl_benchmark import score_controllers
    from mf_envs.benchmarks.rl_tasks import HEADLINE, TASKS, TEST_SEEDS

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--ids", nargs="+", choices=sorted(REFERENCES), default=sorted(REFERENCES))
    refs = ("oracle", "mpc", "best_gait")
    p.add_argument("--refs", nargs="+", choices=refs, default=list(refs))
    p.add_argument("--out", type=Path, default=Path("bench_rl"))
    p.add_argument("--test-seeds", type=int, default=len(TEST_SEEDS))
    p.add_argument("--results", type=Path, help="write the references' copy here too")
    a = p.parse_args(argv)
    seeds = TEST_SEEDS[: a.test_seeds]
    cmd = "python -m mf_envs.benchmarks.references " + " ".join(argv or sys.argv[1:])
    for env_id in a.ids:
        score_controllers(TASKS[HEADLINE[env_id]](), a.out, seeds, cmd)  # zero, baselines
        for name in a.refs:
            if name in REFERENCES[env_id]:
                rec = score(env_id, name, a.out, seeds, cmd)
                print(env_id, name, sum(rec["scores"]) / len(rec["scores"]), flush=True)
    if a.results is not None:
        copy_results(a.out, a.results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
