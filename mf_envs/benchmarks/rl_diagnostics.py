"""Diagnostics of what a learner is given, per headline id (measurements, not fixes):

- **Return vs score**: Spearman's rank correlation, across the controllers of an RL benchmark
  results file (classical baselines, zero and random actions, every trained run), of the mean
  episode return and the mean score over the same test conditions (`rl_results` records hold
  both). 1: the reward ranks controllers as the score does.
- **Observation scales**: each observation slot's standard deviation over episodes under
  uniform random actions and under the id's default baseline, on the first test conditions
  (`rl_tasks.test_kwargs`), with the slots outside [`LOW`, `HIGH`] and the constant ones named.

    python -m mf_envs.benchmarks.rl_diagnostics --results bench_rl/results.json --out diag
    python -m mf_envs.benchmarks.rl_diagnostics --obs --out diag        # observation scales

Writes `<out>/diagnostics.json` and prints a table per part.
"""

from __future__ import annotations

import argparse
import json
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import make_dirs, write_atomic

LOW, HIGH = 0.05, 20.0  # the O(1) band of a slot's std
CONSTANT = 1e-9  # a slot whose std is below this is constant
# a score's resolution: mean scores closer than this are ties in the ranking (a soft robot's
# speed: 1 um/s; the controllers that do not move differ by nanometres per second, noise)
SCORE_RESOLUTION = {"speed_m_s": 1e-6}


def rank_agreement(result: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """Per id: Spearman's rho of mean return vs mean score across its controllers (each
    trained run one point), the scores rounded to their resolution (`SCORE_RESOLUTION`; ties
    share a rank), with the points and the rho of the unrounded scores (`spearman_raw`)."""
    from scipy.stats import spearmanr

    out: dict[str, dict[str, Any]] = {}
    for env_id in result["ids"]:
        pts = [(_label(r), float(np.mean(r["returns"])), float(np.mean(r["scores"])))
               for r in result["rows"] if r["env_id"] == env_id]  # fmt: skip
        step = SCORE_RESOLUTION.get(result["ids"][env_id].get("score_name", ""), 0.0)
        rets, scores = [p[1] for p in pts], [p[2] for p in pts]
        tied = [round(x / step) * step for x in scores] if step else scores
        rho, raw = (
            (spearmanr(rets, tied).statistic, spearmanr(rets, scores).statistic)
            if len(pts) > 2
            else (math.nan, math.nan)
        )
        out[env_id] = {"spearman": float(rho), "spearman_raw": float(raw), "n": len(pts),
                       "score_resolution": step,
                       "points": [{"controller": c, "return": ret, "score": sc}
                                  for c, ret, sc in pts]}  # fmt: skip
    return out


def _label(r: dict[str, Any]) -> str:
    if r.get("seed") is None:
        return r["name"]
    return f"{r['name']}-{r['budget']:.0e}-seed{r['seed']}"


def observation_std(env_id: str, kind: str, seeds: Sequence[int]) -> np.ndarray:
    """(obs_dim,) std of every observation slot over the episodes of `kind` ("random" or a
    baseline kind) on test conditions `seeds` (all steps of all episodes pooled)."""
    import gymnasium as gym

    from mf_envs.benchmarks.rl_benchmark import HEADLINE, TASKS
    from mf_envs.benchmarks.rl_tasks import RandomAction, test_kwargs
    from mf_envs.controllers import make_baseline

    task = TASKS[HEADLINE[env_id]]()
    obs_all = []
    for s in seeds:
        env = gym.make(env_id, **test_kwargs(task, s))
        ctrl = RandomAction(env.action_space, s) if kind == "random" else make_baseline(env, kind)
        obs, _ = env.reset(seed=s)
        ctrl.reset()
        done = False
        while not done:
            obs_all.append(obs)
            obs, _, term, trunc, _ = env.step(ctrl.predict(obs, deterministic=True)[0])
            done = term or trunc
        env.close()
    return np.asarray(obs_all, dtype=float).std(axis=0)


def observation_scales(ids: Sequence[str], seeds: Sequence[int]) -> dict[str, dict[str, Any]]:
    """Per id: the slot stds under random actions and the default baseline, and the slots
    outside [LOW, HIGH] (constant ones apart)."""
    from mf_envs.controllers import baseline_kinds

    out = {}
    for env_id in ids:
        base = baseline_kinds(env_id)[0]
        d: dict[str, Any] = {"baseline_kind": base}
        for label, kind in (("random", "random"), ("baseline", base)):
            std = observation_std(env_id, kind, seeds)
            d[label] = {"std": std.tolist(),
                        "constant": np.flatnonzero(std < CONSTANT).tolist(),
                        "below": np.flatnonzero((std >= CONSTANT) & (std < LOW)).tolist(),
                        "above": np.flatnonzero(std > HIGH).tolist()}  # fmt: skip
        out[env_id] = d
    return out


def _fmt_slots(d: dict[str, Any]) -> str:
    std = d["std"]
    parts = [f"{k} {', '.join(f'{i} ({std[i]:.2g})' for i in d[k])}" for k in
             ("constant", "below", "above") if d[k]]  # fmt: skip
    return "; ".join(parts) or "all in band"


def main(argv: Sequence[str] | None = None) -> int:
    from mf_envs.benchmarks.rl_tasks import HEADLINE, TEST_SEEDS

    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--results", type=Path, help="an RL benchmark results.json: return vs score")
    p.add_argument("--obs", action="store_true", help="observation slot scales per headline id")
    p.add_argument("--ids", nargs="+", choices=sorted(HEADLINE), default=list(HEADLINE))
    p.add_argument("--episodes", type=int, default=3, help="test conditions per controller")
    p.add_argument("--out", type=Path, default=Path("rl_diagnostics"))
    a = p.parse_args(argv)
    report: dict[str, Any] = {}
    if a.results is not None:
        report["rank_agreement"] = rank_agreement(json.loads(a.results.read_text()))
        print("| id | controllers | Spearman rho (return vs score; unrounded) |\n|---|---|---|")
        for env_id, d in report["rank_agreement"].items():
            print(f"| `{env_id}` | {d['n']} | {d['spearman']:.3f} ({d['spearman_raw']:.3f}) |")
    if a.obs:
        report["observation_scales"] = observation_scales(a.ids, TEST_SEEDS[: a.episodes])
        print(f"\n| id | random actions: slots outside [{LOW}, {HIGH}] | default baseline |")
        print("|---|---|---|")
        for env_id, d in report["observation_scales"].items():
            print(f"| `{env_id}` | {_fmt_slots(d['random'])} | `{d['baseline_kind']}`: "
                  f"{_fmt_slots(d['baseline'])} |")  # fmt: skip
    out = make_dirs(a.out, a.out)
    write_atomic(out / "diagnostics.json", json.dumps(report, indent=1) + "\n")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
