"""Tuning the stabilizer's classical baselines on GyroStabilizer-JONSWAP-v0 (training seeds only).

    python -m mf_envs.benchmarks.stabilizer_tuning [--kind lqr|pid|all] [--budget N]
    python -m mf_envs.benchmarks.stabilizer_tuning --check      # the tuned defaults, test seeds

Protocol (docs/benchmark.md, "Tuned baselines"):
- **Objective**: mean RMS roll reduction (RR, `rl_tasks.score_episode`: 1 - RMS roll after the
  10 s settling time / that of the same sea with the rotor off) over the training seeds
  `TUNE_SEEDS` (0-7: the seeds training runs use, never a test seed 20000-20019), in the
  condition `TUNED` names: the headline task's sea (`rl_tasks` "stabilizer_irregular": JONSWAP
  Hs 0.8 m, Tp 5.92 s, beam, 120 s) for "lqr" and "pid", the same sea above the roll
  resonance (Tp 3 s) for "lqr_high", the scheduled LQR's roll-rate weighting.
- **Search** (`SPACES`): scipy's differential evolution over the log10 of each gain (bounds in
  `SPACES`), popsize 8 per dimension, `--budget` generations (12: 312 candidates, 2496
  episodes), seed 0, polish off (the objective is noisy in its last digit over a few seeds: a
  local polish only refits that noise).
- **Check** (`--check`): the defaults on the 20 test seeds in the headline sea, above the
  roll resonance (Tp 3 s) and with `sensor_noise` + `sensor_delay`, beside the passive brake
  (`gimbal_drive="damper"`, a fixed valve) and the other baselines.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

TUNE_SEEDS = tuple(range(8))
# kind -> {parameter: (low, high)}: searched in log10 between these bounds
SPACES: dict[str, dict[str, tuple[float, float]]] = {
    # the LQR's Bryson scales (rad, rad/s, rad, rad/s: Q = diag(1/roll^2, 1/roll_rate^2,
    # 1/gimbal^2), R = 1/rate^2; only their ratios matter, so one is redundant: kept to let the
    # search move freely)
    "lqr": {"roll_scale": (1e-3, 1e-1), "gimbal_scale": (0.1, 10.0), "rate_scale": (0.2, 20.0)},
    # the schedule's high-frequency weighting: the roll rate instead of the roll angle
    "lqr_high": {"roll_rate_scale": (1e-3, 1.0), "gimbal_scale": (0.1, 10.0),
                 "rate_scale": (0.2, 20.0)},
    "pid": {"zeta_g": (0.1, 10.0), "ki_ratio": (1e-3, 1.0), "centering_ratio": (0.01, 3.0)},
}  # fmt: skip
# kind -> (the baseline kind built, the `CONDITIONS` entry it is tuned in, fixed parameters)
TUNED: dict[str, tuple[str, str, dict[str, Any]]] = {
    "lqr": ("lqr", "headline", {}),
    "lqr_high": ("lqr", "above_resonance", {"roll_scale": math.inf}),
    "pid": ("pid", "headline", {}),
}
# the conditions of `--check` (kwargs over the headline task's scene)
CONDITIONS: dict[str, dict[str, Any]] = {
    "headline": {},
    "above_resonance": {"wave_period": 3.0},
    "sensors": {"sensor": ("sensor_noise", "sensor_delay")},
}


def scene(condition: str = "headline") -> dict[str, Any]:
    """The env kwargs of a `CONDITIONS` entry: the headline task's scene, 120 s, changed."""
    from mf_envs.benchmarks.rl_tasks import TASKS, test_kwargs

    task = TASKS["stabilizer_irregular"]()
    kw = test_kwargs(task, 0)  # the marine ids' scene does not depend on the seed
    extra = dict(CONDITIONS[condition])
    kw["effects"] = tuple(kw["effects"]) + tuple(extra.pop("sensor", ()))
    return {**kw, **extra}


def rr_scores(
    factory: Callable[[Any], Any] | None, kw: dict[str, Any], seeds: Sequence[int]
) -> np.ndarray:
    """RR of the controller `factory(env)` (None: the zero action) in scene `kw` per seed
    (`rl_tasks.score_episode`, reference: the same seed's sea with the rotor off)."""
    import gymnasium as gym

    from mf_envs.benchmarks.rl_tasks import TASKS, ZeroAction, score_episode
    from mf_envs.train.evaluate import run_episode

    task = TASKS["stabilizer_irregular"]()
    env = gym.make(task.env_id, **kw)
    try:
        ctrl = ZeroAction(env.action_space, 0) if factory is None else factory(env)
        out = []
        for s in seeds:
            m = run_episode(task.env_id, env, ctrl, s)
            out.append(score_episode(task, m, {k: v for k, v in kw.items()
                                               if k != "gimbal_drive"}, s))  # fmt: skip
        return np.array(out)
    finally:
        env.close()


def factory_of(kind: str, **params: Any) -> Callable[[Any], Any]:
    """`make_baseline(env, kind, **params)` as a factory."""
    from mf_envs.controllers import make_baseline

    return lambda env: make_baseline(env, kind, **params)


def tune(kind: str, budget: int = 12, seeds: Sequence[int] = TUNE_SEEDS) -> dict[str, Any]:
    """Differential evolution over `SPACES[kind]` in the condition `TUNED[kind]` names (module
    doc); the best gains, their training RR and the number of episodes run."""
    from scipy.optimize import differential_evolution

    space = SPACES[kind]
    base, condition, fixed = TUNED[kind]
    names = list(space)
    bounds = [(math.log10(lo), math.log10(hi)) for lo, hi in space.values()]
    kw = scene(condition)
    calls = [0]

    def loss(x: np.ndarray) -> float:
        calls[0] += 1
        params = {**fixed, **{n: float(10.0**v) for n, v in zip(names, x)}}
        try:
            return -float(np.mean(rr_scores(factory_of(base, **params), kw, seeds)))
        except (ValueError, np.linalg.LinAlgError):  # a weighting without a stabilising gain
            return 1.0

    res = differential_evolution(loss, bounds, popsize=8, maxiter=budget, seed=0, polish=False,
                                 tol=1e-4)  # fmt: skip
    best = {n: float(10.0**v) for n, v in zip(names, res.x)}
    return {"kind": kind, "condition": condition, "params": best, "train_rr": -float(res.fun),
            "episodes": calls[0] * len(seeds), "seeds": list(seeds)}  # fmt: skip


def check(seeds: Sequence[int]) -> dict[str, dict[str, float]]:
    """Mean RR per condition (`CONDITIONS`) of every baseline at its defaults and the passive
    brake, on `seeds` (the test seeds by default)."""
    from mf_envs.controllers import baseline_kinds

    out: dict[str, dict[str, float]] = {}
    kinds = [
        k for k in baseline_kinds("GyroStabilizer-v0") if k not in ("sinusoidal", "continuous")
    ]
    for cond in CONDITIONS:
        kw = scene(cond)
        row = {k: float(np.mean(rr_scores(factory_of(k), kw, seeds))) for k in kinds}
        row["passive_brake"] = float(np.mean(rr_scores(None, {**kw, "gimbal_drive": "damper"},
                                                       seeds)))  # fmt: skip
        out[cond] = row
    return out


def main(argv: Sequence[str] | None = None) -> int:
    from mf_envs.benchmarks.rl_tasks import TEST_SEEDS

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--kind", choices=[*SPACES, "all"], default="all")
    p.add_argument("--budget", type=int, default=12, help="generations of the evolution")
    p.add_argument("--check", action="store_true", help="the defaults on the test seeds")
    p.add_argument("--test-seeds", type=int, default=len(TEST_SEEDS))
    a = p.parse_args(argv)
    if a.check:
        print(json.dumps(check(TEST_SEEDS[: a.test_seeds]), indent=1))
        return 0
    for kind in SPACES if a.kind == "all" else [a.kind]:
        print(json.dumps(tune(kind, a.budget), indent=1), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
