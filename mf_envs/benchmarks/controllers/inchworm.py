"""Inchworm-v0 baselines: the seed gaits (Eqs. 101, 103) and the tuned gait, through the actions.

Scenes: `seed_section` = the Inchworm-v0 defaults (L = 0.3 m, kappa0# = max_curvature = 13 1/m,
gravity, shear deformation, anchor switching, SMA-class actuator dynamics, friction feet);
`seed_scene` = the seed's kinematic anchors without actuator dynamics (Eq. 102, kappa# as
commanded, quasi-static). Each episode: one warm-up cycle, then 3 measured cycles of the gait's
period; seeds 1000-1004 (unseen: the tuned gait is optimised from a straight body at rest, not
on any seed; seeds differ by the small random initial actuation). Metrics: speed (body lengths
per second), cost of transport = actuation energy / (m_A g L x tail distance), advance per cycle
(body lengths), the gait period (s); and, as before, tail/head advance per cycle, tail advance
per step, numerical failures.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401
from mf_envs.controllers import make_baseline
from mf_envs.envs.inchworm import SEED_SCENE_EFFECTS

ENV_ID = "Inchworm-v0"
SCENES = {"seed_section": {}, "seed_scene": {"effects": SEED_SCENE_EFFECTS}}
KINDS = ("seed_uniform", "seed_linear", "tuned")
SEEDS = tuple(range(1000, 1005))


def _episode(kind: str, seed: int, kwargs: dict, n_cycles: int = 3) -> dict[str, float]:
    env = gym.make(ENV_ID, **kwargs)
    base = env.unwrapped
    ctrl = make_baseline(env, kind)
    obs, info = env.reset(seed=seed)
    ctrl.reset()
    dt, L = base.control_dt, base.params.length
    n_warm = int(round(ctrl.period / dt))
    n_meas = int(round(n_cycles * ctrl.period / dt))
    fails, energy = 0, 0.0
    x0t = x0h = 0.0
    for k in range(n_warm + n_meas):
        if k == n_warm:
            x0t, x0h, energy = info["x_tail"], info["x_head"], 0.0
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        energy += info.get("actuation_energy", 0.0)
        fails += int(info["numerical_failure"])
        if term:
            break
    dist = info["x_tail"] - x0t
    span = n_meas * dt
    weight = base.params.mass_per_length * base.params.gravity * L
    env.close()
    return {
        "speed_L_per_s": dist / L / span,
        "cost_of_transport": energy / (weight * dist) if dist > 0 else float("inf"),
        "advance_per_cycle_L": dist / L / n_cycles,
        "period_s": ctrl.period,
        "tail_advance_per_cycle_L": dist / L / n_cycles,
        "head_advance_per_cycle_L": (info["x_head"] - x0h) / L / n_cycles,
        "tail_advance_per_step_m": dist / n_meas,
        "numerical_failures": float(fails),
    }


def rows(quick: bool) -> list[dict]:
    seeds = SEEDS[:2] if quick else SEEDS
    n_cycles = 1 if quick else 3
    out = []
    for scene, kwargs in SCENES.items():
        for kind in KINDS:
            runs = [_episode(kind, s, kwargs, n_cycles) for s in seeds]
            for metric in runs[0]:
                vals = np.array([r[metric] for r in runs])
                out.append(
                    {
                        "env_id": ENV_ID,
                        "scene": scene,
                        "controller": kind,
                        "metric": metric,
                        "mean": float(vals.mean()),
                        "std": float(vals.std()),
                        "n_seeds": len(seeds),
                    }
                )
    return out
