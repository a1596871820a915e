"""GOWEC showcase (Rios 2017, Sec. 3.2): phase locking, the 4/pi square wave, Fig. 3-5 maps.

Writes into `out`:
- gowec_pll.png        one GOWEC-v0 episode (Seakeeper 26 rotor, a = 1 m, T = 6 s) under the PLL
                       and the square-wave controller: gimbal angle vs wave phase, power, running
                       mean power against Eq. 95 and the 4/pi ceiling
- gowec_power_map.png  Fig. 3-5: net electrical power of Seakeeper 26 and 35 (80% generator
                       efficiency minus spool-up power, Table 3-1) over wave height x period, with
                       the breaking limit of Eq. 97 (dashed; only the region below is attainable)
- gowec.gif            the buoy, gimbal and rotor over two wave periods (not with --quick)
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
from mf_envs.physics import gowec as gw
from mf_envs.physics.waves import BREAKING_STEEPNESS, G

ENV_ID = DECLARATION.env_id

ORDER = 20
TITLE = "GOWEC: gyroscopic wave energy converter (ch. 3.2)"


def _episode(kind: str, render: bool = False, n_frames: int = 0, **kw):
    env = gym.make(ENV_ID, render_mode="rgb_array" if render else None, **kw)
    ctrl = make_baseline(env, kind)
    obs, info = env.reset(seed=0, options=dict(wave_phase=0.0, gimbal_angle=0.0))
    ctrl.reset()
    rec = {k: [] for k in ("t", "phi", "power", "w1", "eta")}
    frames = []
    every = max(1, env.unwrapped.max_steps // (env.unwrapped.n_periods * 20))
    done = False
    while not done:
        a, _ = ctrl.predict(obs)
        obs, _, term, trunc, info = env.step(a)
        for k, key in (
            ("t", "time"),
            ("phi", "gimbal_angle"),
            ("power", "power"),
            ("w1", "buoy_rate"),
            ("eta", "wave_elevation"),
        ):
            rec[k].append(info[key])
        if render and len(frames) < n_frames and len(rec["t"]) % every == 0:
            frames.append(env.render())
        done = term or trunc
    ref = env.unwrapped.analytic_max_power()
    env.close()
    return {k: np.asarray(v) for k, v in rec.items()}, ref, frames


def _plot_episode(out: Path, runs: dict, ref: float) -> Path:
    """Gimbal angle and generator power over the first 5 wave periods (the PLL's lock-in
    transient included); running mean power / Eq. 95 over the whole episode. The square wave's
    power spikes (tens of kW at each flip) are clipped so that the other traces stay readable."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, figsize=(10, 8.5))
    T = 6.0
    win = runs["pll"]["t"] <= 5 * T
    wrap = lambda x: np.degrees(np.angle(np.exp(1j * x)))  # noqa: E731  (to (-180, 180] deg)
    r, b = runs["pll"], runs["bang_bang"]
    axes[0].plot(r["t"][win], wrap(r["phi"][win]), label="φ, PLL")
    axes[0].plot(
        r["t"][win], wrap(2 * math.pi / T * r["t"][win]), "k:", lw=1, label="wave phase ωt"
    )
    axes[0].plot(b["t"][win], wrap(b["phi"][win]), alpha=0.7, label="φ, square wave")
    axes[0].set(ylabel="gimbal angle φ [deg]", xlabel="t [s]", yticks=[-180, -90, 0, 90, 180])
    peak = 0.0
    for kind, rr in runs.items():
        w = rr["t"] <= 5 * T
        axes[1].plot(rr["t"][w], rr["power"][w] / 1e3, lw=0.9, label=kind)
        peak = max(peak, float(np.abs(rr["power"]).max()))
        cum = np.cumsum(rr["power"]) / np.arange(1, len(rr["power"]) + 1)
        axes[2].plot(rr["t"], cum / ref, label=f"{kind}: running mean")
    lim = 4 * ref / 1e3
    axes[1].set_ylim(-lim, lim)
    axes[1].set(ylabel="generator power [kW]", xlabel="t [s]")
    axes[1].set_title(
        f"square-wave flips reach ±{peak / 1e3:.0f} kW (clipped at ±{lim:.1f} kW)", fontsize=8
    )
    axes[2].axhline(1.0, color="k", lw=1, label="Eq. 95 (locked gimbal)")
    axes[2].axhline(4 / math.pi, color="r", ls="--", lw=1, label="4/π ceiling")
    axes[2].set(ylabel="running mean power / Eq. 95 [-]", xlabel="t [s]", ylim=(0, 1.5))
    axes[2].set_title("running mean from t = 0: includes the PLL's lock-in transient", fontsize=8)
    for ax in axes:
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0)
        ax.grid(alpha=0.3)
    fig.suptitle(f"GOWEC-v0, Seakeeper 26 rotor, a = 1 m, T = 6 s (Eq. 95 = {ref:.0f} W)")
    fig.tight_layout()
    return save_figure(fig, out / "gowec_pll.png", dpi=110)


def _plot_maps(out: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import LogNorm
    from matplotlib.patches import Patch

    heights = np.linspace(0.25, 10.0, 160)
    periods = np.linspace(2.0, 8.0, 200)  # beyond ~7 s no height nets power
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for ax, model in zip(axes, ("26", "35")):
        P, _ = gw.power_map(model, heights, periods)
        kw = np.ma.masked_less_equal(P / 1e3, 0.0)  # no net power: left light gray
        ax.set_facecolor("0.85")
        im = ax.pcolormesh(periods, heights, kw, cmap="magma",
                           norm=LogNorm(vmin=0.1, vmax=1e3), shading="auto")  # fmt: skip
        ax.plot(periods, 2 * BREAKING_STEEPNESS * G * periods**2, "w--", lw=2,
                label="breaking limit, Eq. 97 (steeper waves break)")  # fmt: skip
        ax.set_ylim(heights[0], heights[-1])
        ax.set_xlim(periods[0], periods[-1])
        ax.set_xlabel("wave period T (s)")
        ax.set_ylabel("wave height H = 2a (m)")
        ax.set_title(f"Seakeeper {model}: net electrical power")
        gray = Patch(color="0.85", label="no net power (losses exceed the harvest)")
        handles = [*ax.get_legend_handles_labels()[0], gray]
        ax.legend(handles=handles, loc="upper left", fontsize=8)
        fig.colorbar(im, ax=ax, label="net power (kW)")
    fig.suptitle("Fig. 3-5: the GOWEC nets power only in short, steep waves "
                 "(80 % generator efficiency, spool-up subtracted)")  # fmt: skip
    fig.tight_layout()
    return save_figure(fig, out / "gowec_power_map.png", dpi=110)


def run(out: Path, quick: bool) -> tuple[list[Path], list[str]]:
    out.mkdir(parents=True, exist_ok=True)
    n = 8 if quick else 20
    runs, frames = {}, []
    for kind in ("pll", "bang_bang", "fixed_rate"):
        rec, ref, fr = _episode(
            kind, render=(kind == "pll" and not quick), n_frames=40, n_periods=n
        )
        runs[kind] = rec
        frames = frames or fr
    files = [_plot_episode(out, runs, ref), _plot_maps(out)]
    if frames:
        from mf_envs.render import save_gif

        files.append(save_gif(frames, out / "gowec.gif", fps=10))
    lines = [f"Eq. 95 for Seakeeper 26, a = 1 m, T = 6 s: {ref:.0f} W per gyroscope"]
    lines.append("mean power over the last 3/4 of the episode (after the PLL's lock-in):")
    for kind, rec in runs.items():
        m = rec["power"][len(rec["power"]) // 4 :].mean()
        lines.append(
            f"{kind:10s}: mean power {m:7.0f} W = {m / ref:.3f} x Eq. 95 "
            f"(ceiling 4/pi = {4 / math.pi:.3f})"
        )
    best = gw.seakeeper_net_power("35", 1.0, 4.0)
    lines.append(
        f"Seakeeper 35, a = 1 m, T = 4 s: net {best / 1e3:.1f} kW (80% eff., spool-up "
        "subtracted; Fig. 3-5)"
    )
    return files, lines
