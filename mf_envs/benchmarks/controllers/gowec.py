"""GOWEC-v0 baselines: mean power / Eq. 95 on regular and irregular seas, and Fig. 3-4.

Rows: every controller on every scene, metric `power_ratio` = mean generator power after a
start-up of a quarter of the episode divided by `analytic_max_power()` (Eq. 95; for irregular
seas the Eq. 95 of the equivalent regular wave, a = Hs/(2 sqrt 2), T = Tp), with the 4/pi ceiling
of a square-wave sin(phi) (regular waves) in the `ceiling` column. Scenes `detune_*` are the
Fig. 3-4 sweep: the sea period is T (1 + d) while the controllers are told the nominal T.
`plot` draws the bar chart and the sweep with Eq. 96 (`detuned_mean_power`).
"""

from __future__ import annotations

import math
from pathlib import Path

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401
from mf_envs._files import save_figure
from mf_envs.controllers import make_baseline
from mf_envs.envs.gowec.task import DECLARATION
from mf_envs.physics.gowec import SEAKEEPER, detuned_mean_power
from mf_envs.physics.waves import G

ENV_ID = DECLARATION.env_id
KINDS = ("pll", "fixed_rate", "bang_bang")
T0 = 6.0
HA = SEAKEEPER["26"][1] * (2 * math.pi / T0) ** 3 / G  # peak gyroscopic moment, a = 1 m
SCENES: dict[str, dict] = {
    "regular": {},
    "regular_oblique": dict(wave_direction=1.0, wave_amplitude=0.6, wave_period=5.0),
    "regular_torque_1.2HA": dict(max_generator_torque=1.2 * HA),
    "irregular_jonswap": dict(effects=("gyroscopic", "buoy_rocking", "wave_2d", "irregular_waves")),
}


def episode_ratio(kind: str, seed: int, ctrl: dict | None = None, **kw) -> float:
    """Mean power / Eq. 95 over the last three quarters of one episode."""
    env = gym.make(ENV_ID, **kw)
    c = make_baseline(env, kind, **(ctrl or {}))
    obs, _ = env.reset(seed=seed)
    c.reset()
    P = []
    done = False
    while not done:
        a, _ = c.predict(obs)
        obs, _, term, trunc, info = env.step(a)
        P.append(info["power"])
        done = term or trunc
    ref = env.unwrapped.analytic_max_power()
    env.close()
    return float(np.mean(P[len(P) // 4 :]) / ref)


def _row(scene: str, kind: str, vals: list[float], **extra) -> dict:
    return dict(
        env_id=ENV_ID,
        scene=scene,
        controller=kind,
        metric="power_ratio",
        mean=float(np.mean(vals)),
        std=float(np.std(vals)),
        n_seeds=len(vals),
        **extra,
    )


def rows(quick: bool) -> list[dict]:
    seeds = [0] if quick else [0, 1, 2]
    out = []
    for scene, kw in SCENES.items():
        ceiling = 4 / math.pi if "irregular" not in scene else math.nan
        for kind in KINDS:
            vals = [episode_ratio(kind, s, **kw) for s in seeds]
            out.append(_row(scene, kind, vals, ceiling=ceiling))
    detunes = [-0.02, -0.01, 0.0, 0.01, 0.02] if quick else list(np.linspace(-0.05, 0.05, 11))
    for d in detunes:
        for kind in ("pll", "fixed_rate"):
            vals = [
                episode_ratio(kind, s, ctrl=dict(period=T0), wave_period=T0 * (1 + d))
                for s in seeds[:1]
            ]
            out.append(_row(f"detune_{d:+.3f}", kind, vals, detune=float(d), ceiling=4 / math.pi))
    return out


def plot(out: Path, rows: list[dict]) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 4.3))
    scenes = [s for s in SCENES if any(r["scene"] == s for r in rows)]
    width = 0.25
    for i, kind in enumerate(KINDS):
        ys = [
            next((r["mean"] for r in rows if r["scene"] == s and r["controller"] == kind), np.nan)
            for s in scenes
        ]
        es = [
            next((r["std"] for r in rows if r["scene"] == s and r["controller"] == kind), 0.0)
            for s in scenes
        ]
        ax1.bar(np.arange(len(scenes)) + (i - 1) * width, ys, width, yerr=es, label=kind)
    ax1.axhline(1.0, color="k", lw=1, label="Eq. 95 (locked gimbal)")
    ax1.axhline(4 / math.pi, color="r", ls="--", lw=1, label="4/pi ceiling (regular)")
    ax1.set_xticks(np.arange(len(scenes)), scenes, rotation=15, fontsize=8)
    ax1.set_ylabel("mean power / Eq. 95")
    ax1.legend(fontsize=7)
    ax1.set_title("GOWEC-v0 baselines")
    det = [r for r in rows if r["scene"].startswith("detune_")]
    for kind, style in (("pll", "o-"), ("fixed_rate", "s-")):
        pts = sorted((r["detune"], r["mean"]) for r in det if r["controller"] == kind)
        if pts:
            d, m = zip(*pts)
            ax2.plot(100 * np.array(d), m, style, label=f"{kind} (env, steady 3/4 episode)")
    d = np.linspace(-0.05, 0.05, 201)
    ax2.plot(
        100 * d, detuned_mean_power(d * T0, T0), "k:", label="Eq. 96 mean over 20 T (Fig. 3-4)"
    )
    ax2.set_xlabel("period detuning (T - T_nominal) / T_nominal [%]")
    ax2.set_ylabel("mean power / Eq. 95 [-]")
    ax2.set_title("Fig. 3-4: fixed rate vs phase-locked loop")
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=7)
    fig.tight_layout()
    path = out / "controllers_gowec.png"
    save_figure(fig, path, dpi=110)
    return [path]
