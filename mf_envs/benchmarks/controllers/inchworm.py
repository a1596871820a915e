"""Inchworm-v0 baselines: the seed gaits (Eqs. 101, 103), the tuned gait and (SMA robot) the
validation gait, through the actions.

Scenes: `pdms_sma` = the Inchworm-v0 defaults (the buildable PDMS robot, L = 50 mm, Flexinol wires
heated by duty cycles, gripping feet); `lag_friction` = the lag-friction robot (the seed's section,
L = 0.3 m, kappa0# = 13 1/m through the rate-limited lag on Coulomb friction feet,
`LAG_FRICTION_SCENE`); `seed_scene` = the dissertation's scene (kinematic anchors, kappa# as
commanded, quasi-static, `RIOS2017_SCENE`). Each episode: a warm-up of one cycle and at least
`WARMUP_SECONDS` (SMA wires: two cycles and at least `WIRE_WARMUP_SECONDS`), then 3 measured
cycles of the gait's period; the shipped PPO policy (trained on the lag-friction robot, so scored
there) over `PPO_SECONDS`, its cycles counted as head -> tail grip switches; seeds 1000-1004.
Metrics: speed of the feet's midpoint (body lengths per second; equal to the tail's over whole
cycles of a periodic gait, but a body still curling up does not count), cost of transport =
the effort's energy (electrical with SMA wires, else positive actuation work) / (m_A g L x
distance), mechanical cost of transport (info `mechanical_work`), advance per cycle (body
lengths), the gait period (s), the largest `quasi_static_error`; and, as before, tail/head
advance per cycle, tail advance per step, numerical failures.
"""

from __future__ import annotations

from pathlib import Path

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401
from mf_envs._files import save_figure
from mf_envs.benchmarks.controllers.ppo import make_controller, with_ppo
from mf_envs.controllers.inchworm import WARMUP_SECONDS, WIRE_WARMUP_SECONDS
from mf_envs.envs.inchworm import LAG_FRICTION_SCENE, RIOS2017_SCENE
from mf_envs.envs.inchworm.task import DECLARATION

ENV_ID = DECLARATION.env_id
SCORES_PPO = True  # PPO rows beside the baselines here, not in ppo.py
SCENES = {"pdms_sma": {}, "lag_friction": LAG_FRICTION_SCENE, "seed_scene": RIOS2017_SCENE}
KINDS = ("seed_uniform", "seed_linear", "tuned")
SMA_KINDS = (*KINDS, "heat_cool")
PPO_SCENE = "lag_friction"  # the shipped policy's training scene
SEEDS = tuple(range(1000, 1005))
PPO_SECONDS = 6.0  # PPO's measured span (s) after the warm-up


def controllers() -> tuple[str, ...]:
    """The baselines, plus "ppo" when the shipped policy and the train extra are there."""
    return with_ppo(ENV_ID, KINDS)


def _controller(env: gym.Env, kind: str):
    return make_controller(env, ENV_ID, kind)


def _episode(kind: str, seed: int, kwargs: dict, n_cycles: int = 3) -> dict[str, float]:
    """One episode: warm-up of max(one period, WARMUP_SECONDS), then n_cycles periods (PPO,
    which has no period: PPO_SECONDS, its cycles counted as head -> tail grip switches)."""
    env = gym.make(ENV_ID, **kwargs)
    base = env.unwrapped
    ctrl = _controller(env, kind)
    obs, info = env.reset(seed=seed)
    ctrl.reset()
    dt, L = base.control_dt, base.params.length
    period = getattr(ctrl, "period", None)
    if base.sma:
        warm = max(2.0 * (period or 0.0), WIRE_WARMUP_SECONDS)
    else:
        warm = max(period or 0.0, WARMUP_SECONDS)
    n_warm = int(round(warm / dt))
    n_meas = int(round((n_cycles * period if period else PPO_SECONDS) / dt))
    fails, energy, mech, qse, switches = 0, 0.0, 0.0, 0.0, 0
    x0t = x0h = 0.0
    for k in range(n_warm + n_meas):
        if k == n_warm:
            x0t, x0h, energy, mech, qse = info["x_tail"], info["x_head"], 0.0, 0.0, 0.0
        before = info.get("anchor")
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        switches += int(k >= n_warm and before == "head" and info.get("anchor") == "tail")
        energy += info.get("actuation_energy", 0.0)
        mech += info.get("mechanical_work", 0.0)
        qse = max(qse, info.get("quasi_static_error", 0.0))
        fails += int(info["numerical_failure"])
        if term:
            break
    if not period:  # PPO: cycles = head -> tail switches in the measured span
        n_cycles = max(switches, 1)
        period = n_meas * dt / n_cycles
    tail = info["x_tail"] - x0t
    dist = 0.5 * (tail + info["x_head"] - x0h)  # the feet's midpoint
    span = n_meas * dt
    weight = base.params.mass_per_length * base.params.gravity * L
    env.close()
    return {
        "speed_L_per_s": dist / L / span,
        "speed_mm_per_s": dist / span * 1e3,
        "cost_of_transport": energy / (weight * dist) if dist > 0 else float("inf"),
        "mechanical_cost_of_transport": mech / (weight * dist) if dist > 0 else float("inf"),
        "quasi_static_error_max": qse,
        "advance_per_cycle_L": dist / L / n_cycles,
        "period_s": period,
        "tail_advance_per_cycle_L": tail / L / n_cycles,
        "head_advance_per_cycle_L": (info["x_head"] - x0h) / L / n_cycles,
        "tail_advance_per_step_m": tail / n_meas,
        "numerical_failures": float(fails),
    }


def rows(quick: bool) -> list[dict]:
    seeds = SEEDS[:2] if quick else SEEDS
    n_cycles = 1 if quick else 3
    out = []
    for scene, kwargs in SCENES.items():
        kinds = SMA_KINDS if scene == "pdms_sma" else KINDS
        for kind in with_ppo(ENV_ID, kinds) if scene == PPO_SCENE else kinds:
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


def _trace(kind: str, seed: int, seconds: float, kwargs: dict) -> dict[str, np.ndarray]:
    """Time series on the scene `kwargs` after the warm-up: t (s), kappa# at the control points
    (1/m, (n, 3)), grip engagement (tail, head) (n, 2), x_tail, x_head (m)."""
    env = gym.make(ENV_ID, **kwargs)
    ctrl = _controller(env, kind)
    obs, info = env.reset(seed=seed)
    ctrl.reset()
    dt = env.unwrapped.control_dt
    period = getattr(ctrl, "period", 0.0)
    warm = max(2 * period, WIRE_WARMUP_SECONDS) if env.unwrapped.sma else max(period, 1.5)
    n_warm = int(round(warm / dt))
    out: dict[str, list] = {k: [] for k in ("t", "kappa", "grip", "x_tail", "x_head")}
    for k in range(n_warm + int(round(seconds / dt))):
        obs, _, _, _, info = env.step(ctrl.predict(obs)[0])
        if k >= n_warm:
            out["t"].append((k + 1 - n_warm) * dt)
            out["kappa"].append(info["kappa_sharp"])
            out["grip"].append(info["grip"])
            out["x_tail"].append(info["x_tail"])
            out["x_head"].append(info["x_head"])
    env.close()
    return {k: np.array(v) for k, v in out.items()}


def plot(out, rows: list[dict]) -> list:
    """`inchworm_gaits.png`: realised kappa#, grips and tail/head positions after the warm-up
    (seed 1000): the SMA robot's validation and tuned gaits over 12 s on the default scene,
    the lag-friction robot's tuned gait and PPO (when shipped) over 3 s on its scene."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    cases = [("heat_cool", {}, 12.0), ("tuned", {}, 12.0), ("tuned", LAG_FRICTION_SCENE, 3.0)]
    if "ppo" in controllers():
        cases.append(("ppo", LAG_FRICTION_SCENE, 3.0))
    fig, axes = plt.subplots(3, len(cases), figsize=(5.0 * len(cases), 7), squeeze=False)
    for j, (kind, kwargs, seconds) in enumerate(cases):
        tr = _trace(kind, SEEDS[0], seconds, kwargs)
        x0 = tr["x_tail"][0]
        axes[0, j].plot(tr["t"], tr["kappa"], drawstyle="steps-post")
        axes[0, j].set_ylabel("realised kappa# (1/m)")
        scene = "pdms_sma" if not kwargs else "lag_friction"
        axes[0, j].set_title(f"{scene} {kind}: S = 0, L/2, L")
        axes[1, j].plot(tr["t"], tr["grip"][:, 0], label="tail grip")
        axes[1, j].plot(tr["t"], tr["grip"][:, 1], label="head grip")
        axes[1, j].set_ylabel("grip engagement (-)")
        axes[1, j].legend(loc="upper right")
        axes[2, j].plot(tr["t"], tr["x_tail"] - x0, label="tail")
        axes[2, j].plot(tr["t"], tr["x_head"] - x0, label="head")
        axes[2, j].set_ylabel("x - x_tail(0) (m)")
        axes[2, j].set_xlabel("time after warm-up (s)")
        axes[2, j].legend(loc="upper left")
    fig.tight_layout()
    path = Path(out) / "inchworm_gaits.png"
    save_figure(fig, path, dpi=100)
    return [path]
