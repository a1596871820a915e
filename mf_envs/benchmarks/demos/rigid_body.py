"""Chapter 2 showcase: the Dzhanibekov wing nut and the tennis racket (Rios 2017, §2.3).

Writes into `out`:
- rigid_body_polhodes.png   polhodes on the energy ellipsoid + projections, J1/J2 = 2, J3/J2 = 0.5,
                            with the seed scheme's trajectories on them (Fig. 2-5)
- rigid_body_momentum.png   H in the inertial frame (constant) and body frame (periodic), wing nut
                            and racket (Figs. 2-6b,c and 2-7b,c)
- rigid_body_racket_vs_exact.png  numerical vs Jacobi-elliptic omega for the racket (Fig. 2-8)
- rigid_body_racket.gif     the racket's flight (5 s, flips), drawn by mf_envs.render
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mf_envs._files import save_figure
from mf_envs.physics.rigid_body import (
    analytic_omega,
    elliptic_solution,
    flight_time,
    simulate,
)
from mf_envs.physics.rigid_body import polhode as polhode

ORDER = 10
TITLE = "Free rigid body (ch. 2): Dzhanibekov wing nut and tennis racket"

RACKET_J = np.array([0.0185, 0.0164, 0.00121])  # kg m^2 (§2.3.2)
RACKET_W0 = np.array([0.001, 5.0, 0.001])  # rad/s
RACKET_V0 = 24.5  # m/s vertical toss
RACKET_DT = 0.01  # s
RACKET_BOX = np.array([0.012, 0.14, 0.34])  # half extents (m) of the box drawn for the racket
NUT_J = np.array([3.036e-6, 2.741e-6, 0.699e-6])  # kg m^2 (§2.3.1)
NUT_H0 = np.array([1e-8, 2.1252e-5, 1e-8])  # kg m^2/s
FIG25_J = np.array([2.0, 1.0, 0.5])  # J1/J2 = 2, J3/J2 = 0.5 (Fig. 2-5)
FIG25_D = (0.65, 0.8, 0.95, 1.05, 1.2, 1.35, 1.5, 1.65, 1.8, 1.95)


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def polhode_figure(path: Path, dpi: int = 100) -> Path:
    """Fig. 2-5 with the numerical trajectories (dots) on the exact polhodes (lines)."""
    plt = _plt()
    J = FIG25_J  # K0 = 1/2, J2 = 1: H is already non-dimensional (Eq. 35a)
    fig = plt.figure(figsize=(10, 8.4))
    ax3 = fig.add_subplot(2, 2, 1, projection="3d")
    ax3.plot_wireframe(*polhode.energy_ellipsoid(J, 24), color="0.8", linewidth=0.4)
    planes = [fig.add_subplot(2, 2, k) for k in (2, 3, 4)]
    pairs = ((1, 2), (0, 2), (0, 1))  # Fig. 2-5 (b) h2-h3, (c) h1-h3, (d) h1-h2
    cmap = plt.get_cmap("viridis")
    for i, d in enumerate(FIG25_D):
        col = cmap(i / (len(FIG25_D) - 1))
        for curve in polhode.polhode(J, d, 240):
            ax3.plot(*curve.T, color=col, linewidth=1.0)
            for ax, (p, q) in zip(planes, pairs):
                ax.plot(curve[:, p], curve[:, q], color=col, linewidth=1.0)
        start = polhode.polhode(J, d, 240)[0][17]
        sol = elliptic_solution(J, start / J)
        tr = simulate(J, start / J, sol.period, sol.period / 400, save_every=8)
        ax3.plot(*tr.H.T, ".", color="k", markersize=1.5)
        for ax, (p, q) in zip(planes, pairs):
            ax.plot(tr.H[:, p], tr.H[:, q], ".", color="k", markersize=1.5)
    for curve in polhode.separatrices(J, 240):
        ax3.plot(*curve.T, "r--", linewidth=1.0)
        for ax, (p, q) in zip(planes, pairs):
            ax.plot(curve[:, p], curve[:, q], "r--", linewidth=1.0)
    names = ("h1 [-]", "h2 [-]", "h3 [-]")  # H / sqrt(2 K0 J2): dimensionless (Eq. 35a)
    ax3.set(xlabel=names[0], ylabel=names[1], zlabel=names[2])
    for ax, (p, q), tag in zip(planes, pairs, "bcd"):
        ax.set_xlabel(names[p])
        ax.set_ylabel(names[q])
        ax.set_aspect("equal")
        ax.set_title(f"({tag}) projection")
    ax3.set_title("(a) polhodes on the energy ellipsoid\n(lines exact, dots RK4 + Rodrigues)")
    ax3.set_box_aspect((np.sqrt(2), 1, np.sqrt(0.5)))
    fig.suptitle("Polhodes, J1/J2 = 2, J3/J2 = 0.5, d = 0.65 ... 1.95; separatrices red (Eq. 40b)")
    fig.tight_layout(w_pad=4.0)  # room between the 3D z label and panel (b)
    return save_figure(fig, path, dpi=dpi)


def momentum_figure(path: Path, nut, racket, dpi: int = 100) -> Path:
    """H components and |H| in the inertial and body frames for the wing nut and the racket."""
    plt = _plt()
    fig, axes = plt.subplots(2, 2, figsize=(11, 6.4), sharex="col")
    for col, (name, tr) in enumerate((("wing nut", nut), ("tennis racket", racket))):
        for row, (frame, H) in enumerate((("inertial", tr.H_inertial), ("body", tr.H))):
            ax = axes[row, col]
            for i in range(3):
                ax.plot(tr.t, H[:, i], label=f"H{i + 1}")
            ax.plot(tr.t, np.linalg.norm(H, axis=1), "k--", label="|H|")
            ax.set_title(f"{name}: H in the {frame} frame")
            ax.set_ylabel("angular momentum H [kg·m²/s]")
            ax.grid(alpha=0.3)
            ax.legend(fontsize=7, loc="lower left")
        axes[1, col].set_xlabel("t [s]")
    fig.tight_layout()
    return save_figure(fig, path, dpi=dpi)


def racket_vs_exact_figure(path: Path, tr, exact, dpi: int = 100) -> Path:
    """Fig. 2-8: numerical (dots) vs exact (lines) omega of the racket, and the error."""
    plt = _plt()
    fig, (ax, ax_err) = plt.subplots(2, 1, figsize=(8, 6.4), sharex=True,
                                     gridspec_kw={"height_ratios": (2, 1)})  # fmt: skip
    for i, c in enumerate(("C0", "C1", "C2")):
        ax.plot(tr.t, exact[:, i], color=c, label=f"omega{i + 1} exact")
        ax.plot(tr.t[::8], tr.omega[::8, i], ".", color=c, markersize=4, label=f"omega{i + 1} RK4")
    ax.set_ylabel("angular velocity ω [rad/s]")
    ax.legend(fontsize=7, ncol=3)
    ax.grid(alpha=0.3)
    rel = np.abs(tr.omega - exact) / np.max(np.abs(exact))
    ax_err.semilogy(tr.t, np.maximum(rel, 1e-17))
    ax_err.set_ylabel("|error| / max|ω| [-]")
    ax_err.set_xlabel("t [s]")
    ax_err.grid(alpha=0.3, which="both")
    ax.set_title(f"Tennis racket, seed scheme dt = {tr.dt:g} s: max rel. error {rel.max():.2e}")
    fig.tight_layout()
    return save_figure(fig, path, dpi=dpi)


def racket_gif(path: Path, tr, n_frames: int) -> Path:
    """The racket's attitude (box of RACKET_BOX) with time, height and flip count."""
    from mf_envs.render import draw_rigid_body, save_gif

    flips = elliptic_solution(RACKET_J, RACKET_W0).flip_times(tr.t[-1])
    idx = np.linspace(0, len(tr.t) - 1, n_frames).round().astype(int)
    frames = []
    for i in idx:
        n_flip = int(np.sum(flips <= tr.t[i]))
        text = f"t = {tr.t[i]:4.2f} s  height {tr.x[i, 2]:5.1f} m  flips {n_flip}"
        frames.append(draw_rigid_body(R=tr.R[i], half_extents=RACKET_BOX, text=text,
                                      size=(240, 320)))  # fmt: skip
    return save_gif(frames, path, fps=n_frames / tr.t[-1])


def run(out: Path, quick: bool) -> tuple[list[Path], list[str]]:
    """Simulate both seed cases with the seed's scheme, plot, animate; return files and lines."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    t_air = 5.0  # s, the seed's air time (2 v0 / g = 4.995 s for v0 = 24.5 m/s)
    racket = simulate(RACKET_J, RACKET_W0, t_air, RACKET_DT, effects=("ballistic",),
                      v0=(0.0, 0.0, RACKET_V0))  # fmt: skip
    exact = analytic_omega(RACKET_J, RACKET_W0, racket.t)
    rel = float(np.max(np.abs(racket.omega - exact)) / np.max(np.abs(exact)))
    nut = simulate(NUT_J, NUT_H0 / NUT_J, 10.0, 1e-3, save_every=10)
    sol_r = elliptic_solution(RACKET_J, RACKET_W0)
    sol_n = elliptic_solution(NUT_J, NUT_H0 / NUT_J)
    files = [
        polhode_figure(out / "rigid_body_polhodes.png"),
        momentum_figure(out / "rigid_body_momentum.png", nut, racket),
        racket_vs_exact_figure(out / "rigid_body_racket_vs_exact.png", racket, exact),
        racket_gif(out / "rigid_body_racket.gif", racket, 30 if quick else 60),
    ]
    drift = np.max(np.abs(racket.H_inertial - racket.H_inertial[0])) / racket.momentum_norm[0]
    flips = ", ".join(f"{t:.3f}" for t in sol_r.flip_times(t_air))
    lines = [
        f"racket: max relative error of omega vs exact {rel:.2e} ({100 * rel:.5f}%) at dt = "
        f"{racket.dt:g} s, seed scheme (the seed reports 0.19%)",
        f"racket: |H| = {racket.momentum_norm[0]:.4f} kg m^2/s, inertial H drift {drift:.1e}; "
        f"flips at t = {flips} s (flight 2 v0/g = {flight_time(RACKET_V0):.3f} s, Eq. 3); "
        f"period {sol_r.period:.6f} s",
        f"wing nut: flips at t = {', '.join(f'{t:.3f}' for t in sol_n.flip_times(10.0))} s, period "
        f"{sol_n.period:.4f} s, d - 1 = {polhode.d_bar(NUT_J, NUT_H0) - 1:.2e}",
        f"wrote {len(files)} files into {out}",
    ]
    return files, lines
