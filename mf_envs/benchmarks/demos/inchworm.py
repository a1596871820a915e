"""Inchworm showcase (Rios 2017 §4.6-4.10): the active beam, the seed gaits, Inchworm-v0.

ENV_ID = DECLARATION.env_id

Writes into `out`:
- beam_fig4_5.png          linear active cantilever (seed numbers, Eqs. 65-67, in m and mm; the
                           seed's inches on the second axes): Eq. 65/67 lines
                           vs the nonlinear C1 beam (dots) for alpha = 0, 0.25, ..., 1
- beam_rollup.png          roll-up under end moments up to 2 pi EI / L (16 elements)
- inchworm_fig4_8.png      curling with the head held (no switching), kappa# 0 .. -13 1/m
- inchworm_fig4_9.png      uniform gait (Eq. 101): snapshots over one cycle, anchors marked
- inchworm_fig4_10.png     linear gait (Eq. 103, c1 = 0.2, c2 = 0.8): snapshots over one cycle
- inchworm_progress.png    x_head, x_tail over 3 cycles for both gaits
- inchworm_seed_uniform.gif  Inchworm-v0 driven by the seed_uniform baseline (mf_envs.render)
Section: b = 0.02 m, h = 0.01 m, E = 2.4 GPa, G = 0.96 GPa, m_A = 0.278 kg/m, J3C = 0.232e-5 kg m,
A_s = 5bh/6, L = 0.3 m (our choice), kappa0# = 13 1/m, increments |d kappa#| <= 2h/L^2.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mf_envs._files import save_figure
from mf_envs.envs.inchworm.task import DECLARATION
from mf_envs.physics.beam import solve_cantilever, timoshenko_cantilever_uniform
from mf_envs.physics.inchworm import (
    Inchworm,
    InchwormParams,
    run_gait,
    seed_linear_kappa,
    seed_uniform_kappa,
)

ENV_ID = DECLARATION.env_id
ORDER = 40
TITLE = f"Inchworm (ch. 4): active C1 beam, seed Figs. 4-5, 4-8..4-10, {ENV_ID}"
KAPPA0 = 13.0
P = InchwormParams()
GAITS = {
    "uniform": lambda S, t: np.full(S.shape, seed_uniform_kappa(t, KAPPA0)),
    "linear": lambda S, t: seed_linear_kappa(S, t, KAPPA0, P.length),
}
FULL = frozenset({"gravity", "shear_deformation", "anchor_switching"})


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _fig4_5(out: Path) -> Path:
    from mf_envs.physics.beam.reference import SEED_CANTILEVER as C
    from mf_envs.physics.beam.reference import seed_rigidities

    ea, gas, ei = seed_rigidities()
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.5, 4))
    s = np.linspace(0, C["L"], 200)
    for alpha in np.linspace(0, 1, 5):
        v, _ = timoshenko_cantilever_uniform(s, C["L"], ei, gas, C["q0"], alpha * C["kappa0"])
        sol = solve_cantilever(
            C["L"], ea, gas, ei, 4, distributed_load=(0, -C["q0"]), kappa_sharp=alpha * C["kappa0"]
        )
        line = ax.plot(s, v * 1e3, label=f"α = {alpha:.2f}")[0]
        pts = sol.centerline[::4]
        ax.plot(pts[:, 0], pts[:, 1] * 1e3, "o", ms=3, color=line.get_color())
    ax.set(
        xlabel="arc length S [m]",
        ylabel="deflection v [mm]",
        title="Active cantilever: Eqs. 65-67 (lines) vs C1 beam, 4 elements (dots)",
    )
    inch = 0.0254  # the seed's Fig. 4-5 is in inches: a second axis only
    top = ax.secondary_xaxis("top", functions=(lambda x: x / inch, lambda x: x * inch))
    top.set_xlabel("S [in] (seed's unit)", fontsize=8)
    right = ax.secondary_yaxis(
        "right", functions=(lambda y: y / 1e3 / inch, lambda y: y * 1e3 * inch)
    )
    right.set_ylabel("v [in]", fontsize=8)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return save_figure(fig, out / "beam_fig4_5.png", dpi=110)


def _rollup(out: Path) -> Path:
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5, 4.5))
    for frac in (0.25, 0.5, 0.75, 1.0):
        sol = solve_cantilever(1.0, 1e4, 1e4, 1.0, 16, tip_moment=frac * 2 * np.pi)
        ax.plot(*sol.centerline.T, label=f"M = {frac:.2f} × 2πEI/L")
    ax.set_aspect("equal")
    ax.set(
        title="Roll-up of a cantilever (16 C1 elements, L = 1 m)", xlabel="x [m]", ylabel="z [m]"
    )
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    return save_figure(fig, out / "beam_rollup.png", dpi=110)


def _snapshots(out: Path, name: str, hist, title: str, every: int = 5) -> Path:
    """Centre lines at every `every`-th increment, coloured by time (colour bar = fraction of
    the shown sequence, 0 = first); black triangles mark the gripping foot."""
    plt = _plt()
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize

    n = len(hist.centerlines)
    pts = np.concatenate([hist.centerlines[i] for i in range(0, n, every)])
    (x0, z0), (x1, z1) = pts.min(axis=0), pts.max(axis=0)
    pad = 0.03 * (x1 - x0)
    width = 8.0
    height = max(1.6, width * (z1 - z0 + 2 * pad) / (x1 - x0 + 2 * pad)) + 1.1
    fig, ax = plt.subplots(figsize=(width, height))
    cmap = plt.get_cmap("viridis")
    for i in range(0, n, every):
        c = hist.centerlines[i]
        ax.plot(c[:, 0], c[:, 1], color=cmap(i / (n - 1)), lw=1.5)
        grip = c[-1] if hist.anchors[i] == "head" else c[0]
        ax.plot(*grip, "k^", ms=5)
    ax.axhline(0, color="0.4", lw=1)
    ax.set_xlim(x0 - pad, x1 + pad)
    ax.set_ylim(min(z0, 0.0) - pad, z1 + pad)
    ax.set_aspect("equal")
    ax.set(title=title, xlabel="x [m]", ylabel="z [m]")
    sm = ScalarMappable(norm=Normalize(0.0, 1.0), cmap=cmap)
    bar = fig.colorbar(sm, ax=ax, orientation="vertical", fraction=0.03, pad=0.02)
    bar.set_label("time order\n(0 = first, 1 = last)", fontsize=8)
    return save_figure(fig, out / name, dpi=110, bbox_inches="tight")


def _gif(out: Path, quick: bool) -> Path | None:
    try:
        from mf_envs.render import save_gif
    except ImportError:  # the renderer is optional for the physics demo
        return None
    import gymnasium as gym

    import mf_envs  # noqa: F401
    from mf_envs.controllers import make_baseline

    env = gym.make(ENV_ID, render_mode="rgb_array")
    ctrl = make_baseline(env, "seed_uniform")
    obs, _ = env.reset(seed=0, options={"kappa": np.zeros(3)})
    frames = [env.render()]
    for _ in range(40 if quick else 120):
        obs, *_ = env.step(ctrl.predict(obs)[0])
        frames.append(env.render())
    env.close()
    return save_gif(frames, out / "inchworm_seed_uniform.gif", fps=15)


def _head(hist, n: int):
    """The first n samples of a gait history."""
    return type(hist)(hist.t[:n], hist.x_head[:n], hist.x_tail[:n], hist.anchors[:n],
                      hist.centerlines[:n], hist.kappa_sharp[:n], 0)  # fmt: skip


def run(out: Path, quick: bool) -> tuple[list[Path], list[str]]:
    out.mkdir(parents=True, exist_ok=True)
    files = [_fig4_5(out), _rollup(out)]
    curl = run_gait(
        Inchworm(P, frozenset({"gravity", "shear_deformation"})), GAITS["uniform"], 1, 40
    )
    title = "Head held: curling, Eq. 101 (fig. 4-8)"
    files.append(_snapshots(out, "inchworm_fig4_8.png", _head(curl, 21), title))
    gait_files, lines = _gaits(out, 2 if quick else 3)
    files += gait_files
    gif = _gif(out, quick)
    if gif is not None:
        files.append(gif)
    return files, lines


def _gaits(out: Path, n_cyc: int) -> tuple[list[Path], list[str]]:
    """Figs. 4-9 and 4-10 (one cycle of each seed gait), their advance per cycle, and
    inchworm_progress.png (head and tail over n_cyc cycles)."""
    files, lines = [], []
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 3.5))
    for name, fn in GAITS.items():
        hist = run_gait(Inchworm(P, FULL), fn, n_cyc, 40)
        fig_name = "inchworm_fig4_9.png" if name == "uniform" else "inchworm_fig4_10.png"
        title = f"{name} gait, one cycle (grip = black triangle)"
        files.append(_snapshots(out, fig_name, _head(hist, 41), title))
        per = np.diff(hist.x_tail[::40])
        lines.append(
            f"{name} gait: tail advance per cycle {per.mean():.5f} m = "
            f"{per.mean() / P.length:.4f} L; head {np.diff(hist.x_head[::40]).mean():.5f}"
            f" m; {hist.iterations} Newton iterations for {n_cyc} cycles"
        )
        ax.plot(hist.t / (2 * np.pi), hist.x_tail, label=f"{name}: tail")
        ax.plot(hist.t / (2 * np.pi), hist.x_head, "--", label=f"{name}: head")
    ax.set(
        xlabel="time [gait cycles]",
        ylabel="position x [m]",
        title="Seed gaits, κ0# = 13 1/m, L = 0.3 m",
    )
    ax.legend(fontsize=7, loc="upper left")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, out / "inchworm_progress.png", dpi=110)
    files.append(out / "inchworm_progress.png")
    return files, lines
