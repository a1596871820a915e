"""Inchworm-v0 baselines: the seed gaits (Eqs. 101, 103) through the env's action interface.

Scene `seed_section`: Inchworm-v0 defaults (L = 0.3 m, kappa0# = max_curvature = 13 1/m, gravity,
shear deformation, kinematic anchor switching, quasi-static), 40 steps per gait cycle. Seeds
differ by the small random initial actuation. Metrics: tail and head advance per cycle (body
lengths), tail advance per step (m), episode return, numerical failures.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401
from mf_envs.controllers import make_baseline

ENV_ID = "Inchworm-v0"


def _episode(kind: str, seed: int, n_cycles: int) -> dict[str, float]:
    env = gym.make(ENV_ID)
    ctrl = make_baseline(env, kind)
    obs, info = env.reset(seed=seed)
    ctrl.reset()
    x0t, x0h, ret, fails = info["x_tail"], info["x_head"], 0.0, 0
    steps = n_cycles * ctrl.steps_per_cycle
    for _ in range(steps):
        obs, r, term, trunc, info = env.step(ctrl.predict(obs)[0])
        ret += r
        fails += int(info["numerical_failure"])
        if term or trunc:
            break
    L = env.unwrapped.params.length
    return {
        "tail_advance_per_cycle_L": (info["x_tail"] - x0t) / L / n_cycles,
        "head_advance_per_cycle_L": (info["x_head"] - x0h) / L / n_cycles,
        "tail_advance_per_step_m": (info["x_tail"] - x0t) / steps,
        "episode_return": ret,
        "numerical_failures": float(fails),
    }


def rows(quick: bool) -> list[dict]:
    seeds = (0, 1) if quick else (0, 1, 2, 3, 4)
    n_cycles = 1 if quick else 3
    out = []
    for kind in ("seed_uniform", "seed_linear"):
        runs = [_episode(kind, s, n_cycles) for s in seeds]
        for metric in runs[0]:
            vals = np.array([r[metric] for r in runs])
            out.append(
                {
                    "env_id": ENV_ID,
                    "scene": "seed_section",
                    "controller": kind,
                    "metric": metric,
                    "mean": float(vals.mean()),
                    "std": float(vals.std()),
                    "n_seeds": len(seeds),
                }
            )
    return out
