"""Gyro roll stabilizer showcase (Rios 2017, §3.3): the seed's Figs. 3-9 to 3-15, then the env.

Writes into `out`:
- stabilizer_fig3_9.png    continuous (Eq. 118) vs sinusoidal (Eq. 119) at a = pi/2, seed hull,
                           fast path (lines) and the multibody engine (dots)
- stabilizer_fig3_10_11.png  M_e = 1e5 cos(2 pi t / T): rotor off, then a = pi/10 ... pi/3.6;
                           the residual equals the capacity bound 1 - 2 H w sin(a) / M0
- stabilizer_fig3_12_13.png  peak roll rate / psi' vs J_rotor / J_ship (slope 2 sin a) and the fit
                           A sin(B a) (seed: 2.003 sin(1.002 a))
- stabilizer_fig3_14_15.png  roll angle and roll acceleration amplitudes vs excitation period
- stabilizer_yacht.png     GyroStabilizer-v0 defaults: rotor off vs PID vs LQR at roll resonance
- stabilizer_yacht.gif     the yacht with PID, drawn by mf_envs.render
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from mf_envs._files import save_figure
from mf_envs.envs.gyro_stabilizer.task import DECLARATION
from mf_envs.physics.ship import (
    SEED_EFFECTS,
    GimbalDrive,
    GyroParams,
    WaveLoad,
    pack_params,
    seed_test_hull,
    simulate,
    simulate_engine,
)

ENV_ID = DECLARATION.env_id

ORDER = 30
TITLE = "Gyro roll stabilizer (ch. 3.3): seed Figs. 3-9..3-15 and GyroStabilizer-v0 with PID/LQR"

T_SEED = 10.0  # s, gimbal / moment period of the seed's demonstrations
M_E = 1.0e5  # N m, the seed's external moment amplitude (Figs. 3-10/3-11)


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _run(
    mode: str,
    a: float,
    n: int = 2,
    T: float = T_SEED,
    gyro: GyroParams | None = None,
    moment: float = 0.0,
    t_end: float = 2 * T_SEED,
    dt: float = 0.01,
):
    ship, g0 = seed_test_hull()
    gyro = g0 if gyro is None else gyro
    eff = SEED_EFFECTS + (("wave_moment",) if moment else ())
    drive = GimbalDrive(mode, amplitude=a, frequency=1.0 / T)
    wave = WaveLoad(moment, T)
    return simulate(pack_params(ship, gyro, n, eff, drive, wave), t_end, dt), ship, gyro


def fig_3_9(out: Path, quick: bool) -> tuple[Path, str]:
    plt = _plt()
    fig, ax = plt.subplots(1, 3, figsize=(13, 4.6))
    peaks = {}
    for mode, style in (("continuous", "-"), ("sinusoidal", "--")):
        r, ship, gyro = _run(mode, math.pi / 2)
        peaks[mode] = np.abs(r.omega[:, 0]).max()
        ax[0].plot(r.t, r.phi, style, label=mode)
        ax[1].plot(r.t, r.phi_rate, style, label=mode)
        ax[2].plot(r.t, r.omega[:, 0], style, label=f"{mode}: ω1")
        drive = GimbalDrive(mode, amplitude=math.pi / 2, frequency=1.0 / T_SEED)
        e = simulate_engine(ship, gyro, 2, SEED_EFFECTS, drive, 2 * T_SEED, 0.05)
        ax[2].plot(e.t[::4], e.omega[::4, 0], "o", ms=3, mfc="none", label=f"{mode}: engine")
    for a_, t_ in zip(
        ax, ("gimbal angle φ [rad]", "gimbal rate φ' [rad/s]", "ship roll rate ω1 [rad/s]")
    ):
        a_.set_xlabel("t [s]")
        a_.set_ylabel(t_)
        a_.grid(alpha=0.3)
        a_.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.18), ncol=2)
    fig.suptitle("Fig. 3-9: continuous vs sinusoidal gimbal excitation, a = π/2 (two gyros)")
    fig.tight_layout()
    p = out / "stabilizer_fig3_9.png"
    save_figure(fig, p, dpi=100)
    return p, (
        f"Fig 3-9: peak roll rate continuous {peaks['continuous']:.5f}, sinusoidal "
        f"{peaks['sinusoidal']:.5f} rad/s (same response)"
    )


def fig_3_10_11(out: Path, quick: bool) -> tuple[Path, str]:
    plt = _plt()
    fig, ax = plt.subplots(1, 2, figsize=(13, 5.2))
    ship, gyro = seed_test_hull()
    w = 2 * math.pi / T_SEED
    H = gyro.angular_momentum
    off, _, _ = _run("sinusoidal", 0.0, moment=M_E, gyro=GyroParams(50.0, 10.0, 0.0))
    # with the rotor off pitch and yaw stay at rest: w2 and w3 lie on top of each other at 0,
    # so they get their own line styles and their peak in the legend
    styles = (("-", 1.5), ("--", 3.0), (":", 1.5))
    for k, lab in enumerate(("ω1 (roll)", "ω2 (pitch)", "ω3 (yaw)")):
        peak = np.abs(off.omega[:, k]).max()
        ls, lw = styles[k]
        ax[0].plot(off.t, off.omega[:, k], ls, lw=lw, label=f"{lab}, peak {peak:.3g} rad/s")
    base = np.abs(off.omega[:, 0]).max()
    ax[1].plot(off.t, off.omega[:, 0], "k", label="rotor off")
    lines = []
    for a in (math.pi / 10, math.pi / 6, math.pi / 4, math.pi / 3.6):
        r, _, _ = _run("sinusoidal", a, moment=M_E)
        pk = np.abs(r.omega[:, 0]).max()
        bound = 1.0 - 2 * H * w * math.sin(a) / M_E  # residual fraction of the peak roll rate
        ax[1].plot(
            r.t,
            r.omega[:, 0],
            label=f"a = π/{math.pi / a:.1f}: residual {pk / base:.3f} (bound {bound:.3f})",
        )
        lines.append(f"a=pi/{math.pi / a:.1f}: residual {pk / base:.3f}, bound {bound:.3f}")
    ax[0].set_title("Fig. 3-10: M_e = 1e5 N·m cos(2πt/T), rotor off")
    ax[1].set_title(f"Fig. 3-11: rotor on; M0/(2Hω) = {M_E / (2 * H * w):.2f} > 1 (over capacity)")
    ax[0].set_ylabel("body angular velocity [rad/s]")
    ax[1].set_ylabel("roll rate ω1 [rad/s]")
    for a_ in ax:
        a_.set_xlabel("t [s]")
        a_.grid(alpha=0.3)
        a_.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    fig.tight_layout()
    p = out / "stabilizer_fig3_10_11.png"
    save_figure(fig, p, dpi=100)
    return p, "Figs 3-10/11 peak roll-rate residual vs capacity bound: " + "; ".join(lines)


def slope_law(quick: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Amplitudes a, rotor/ship inertia ratios x, and peak (omega_1 / psi') (len(a), len(x))."""
    ship, g0 = seed_test_hull()
    amps = np.linspace(0.1, math.pi / 2, 5 if quick else 9)
    j_rotor = np.array([10.0, 50.0, 100.0, 200.0])
    y = np.zeros((amps.size, j_rotor.size))
    for i, a in enumerate(amps):
        for j, jr in enumerate(j_rotor):
            gyro = GyroParams(jr, g0.gimbal_inertia, g0.rotor_speed)
            r, _, _ = _run("sinusoidal", a, gyro=gyro, t_end=T_SEED, dt=0.02)
            y[i, j] = np.abs(r.omega[:, 0]).max() / gyro.rotor_speed
    return amps, j_rotor / ship.inertia[0], y


def fig_3_12_13(out: Path, quick: bool) -> tuple[Path, str]:
    from scipy.optimize import curve_fit

    plt = _plt()
    amps, x, y = slope_law(quick)
    slopes = np.array([np.polyfit(x, yi, 1)[0] for yi in y])
    (A, B), _ = curve_fit(lambda a, A, B: A * np.sin(B * a), amps, slopes, p0=(2.0, 1.0))
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.2))
    for a, yi in zip(amps, y):
        ax[0].plot(x * 1e4, yi * 1e4, "o-", ms=3, label=f"a = {a:.2f} rad")
    ax[0].set_xlabel("inertia ratio J_rotor / J_ship [×10⁻⁴]")
    ax[0].set_ylabel("peak roll rate / rotor speed ω1/ψ' [×10⁻⁴]")
    ax[0].set_title("Fig. 3-12: peak roll rate vs inertia ratio")
    ax[0].legend(fontsize=6, title="gimbal amplitude", title_fontsize=6, loc="upper left")
    aa = np.linspace(0, math.pi / 2, 100)
    ax[1].plot(amps, slopes, "o", label="slope of Fig. 3-12")
    ax[1].plot(aa, 2 * np.sin(aa), "k-", label="2 sin(a)")
    ax[1].plot(aa, A * np.sin(B * aa), "r--", label=f"fit {A:.3f} sin({B:.3f} a)")
    ax[1].set_xlabel("gimbal amplitude a [rad]")
    ax[1].set_ylabel("slope d(ω1/ψ')/d(J_rotor/J_ship) [-]")
    ax[1].set_title("Fig. 3-13: slope vs amplitude (seed fit 2.003 sin(1.002 a))")
    ax[1].legend(fontsize=7)
    for a_ in ax:
        a_.grid(alpha=0.3)
    fig.tight_layout()
    p = out / "stabilizer_fig3_12_13.png"
    save_figure(fig, p, dpi=100)
    err = np.abs(slopes / (2 * np.sin(amps)) - 1).max()
    return p, f"Figs 3-12/13: fit {A:.4f} sin({B:.4f} a); max |slope/(2 sin a) - 1| = {err:.2e}"


def fig_3_14_15(out: Path, quick: bool) -> tuple[Path, str]:
    plt = _plt()
    periods = np.array([2.0, 4.0, 6.0, 8.0, 10.0, 15.0, 20.0])
    a = math.pi / 4
    roll_amp, acc_amp = [], []
    for T in periods:
        r, _, _ = _run("sinusoidal", a, T=T, t_end=T, dt=T / 1000)
        roll_amp.append(np.ptp(r.roll) / 2)
        acc_amp.append(np.abs(np.gradient(r.omega[:, 0], r.t)).max())
    fig, ax = plt.subplots(1, 2, figsize=(11, 3.6))
    ax[0].plot(periods, roll_amp, "o-")
    ax[0].set_title("Fig. 3-14: roll angle amplitude vs period (linear, no restoring)")
    ax[0].set_ylabel("roll angle amplitude [rad]")
    ax[1].plot(periods, acc_amp, "o-")
    ax[1].set_title("Fig. 3-15: peak roll acceleration vs period (~1/T)")
    ax[1].set_ylabel("peak roll acceleration [rad/s²]")
    for a_ in ax:
        a_.set_xlabel("excitation period T [s]")
        a_.grid(alpha=0.3)
    fig.tight_layout()
    p = out / "stabilizer_fig3_14_15.png"
    save_figure(fig, p, dpi=100)
    lin = np.polyfit(periods, roll_amp, 1)
    resid = np.abs(np.polyval(lin, periods) - roll_amp).max() / max(roll_amp)
    inv = np.array(acc_amp) * periods
    return p, (
        f"Figs 3-14/15: roll amplitude linear in T (max residual {resid:.1e}); "
        f"accel x T constant to {np.ptp(inv) / inv.mean():.1e}"
    )


def env_episode(kind: str | None, frames: bool = False, seed: int = 0, seconds: float = 30.0):
    """(t, roll, gimbal, frames, title) of GyroStabilizer-v0 defaults with a baseline (None:
    rotor off); `title` names the unit and its capacity as the env reports them."""
    import gymnasium as gym

    import mf_envs  # noqa: F401
    from mf_envs.controllers import make_baseline
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS

    eff = DEFAULT_EFFECTS if kind else tuple(e for e in DEFAULT_EFFECTS if e != "gyroscopic")
    env = gym.make(
        ENV_ID,
        effects=eff,
        episode_seconds=seconds,
        max_episode_steps=-1,  # no TimeLimit: episode_seconds ends the episode
        render_mode="rgb_array" if frames else None,
    )
    obs, info = env.reset(seed=seed)
    u = env.unwrapped  # the unit and its capacity (rotor off: H = 0, no capacity)
    title = f"{u.scene.unit_name or 'gyro'} (capacity {u.capacity():.2f})" if kind else ""
    ctrl = make_baseline(env, kind) if kind else None
    t, roll, gim, imgs = [0.0], [info["roll"]], [info["gimbal_angle"]], []
    done = False
    while not done:
        a = ctrl.predict(obs)[0] if ctrl else np.zeros(1, np.float32)
        obs, _, term, trunc, info = env.step(a)
        done = term or trunc
        t.append(info["time"])
        roll.append(info["roll"])
        gim.append(info["gimbal_angle"])
        if frames and len(t) % 4 == 0 and t[-1] <= 20.0:
            imgs.append(env.render())
    env.close()
    return np.array(t), np.array(roll), np.array(gim), imgs, title


def fig_yacht(out: Path, quick: bool) -> tuple[list[Path], str]:
    from mf_envs.render import save_gif

    plt = _plt()
    fig, ax = plt.subplots(2, 1, figsize=(10, 5.4), sharex=True)
    rms = {}
    frames, titles = [], []
    colors = {None: "tab:gray", "pid": "tab:blue", "lqr": "tab:green"}
    for kind in (None, "pid", "lqr"):
        t, roll, gim, imgs, title = env_episode(
            kind, frames=(kind == "pid"), seconds=15.0 if quick else 30.0
        )
        titles.append(title)
        if imgs:
            frames = imgs
        name = kind or "rotor off"
        rms[name] = float(np.sqrt(np.mean(roll[t > 10.0] ** 2)))
        lab = f"{name}: RMS {math.degrees(rms[name]):.2f} deg (t > 10 s)"
        ax[0].plot(t, np.degrees(roll), color=colors[kind], label=lab)
        if kind:
            ax[1].plot(t, np.degrees(gim), color=colors[kind], label=name)
    ax[0].set_ylabel("roll (deg)")
    ax[1].set_ylabel("gimbal angle (deg)")
    ax[1].set_xlabel("time (s)")
    for a_ in ax:
        a_.grid(alpha=0.3)
        lo, hi = a_.get_ylim()
        a_.set_ylim(lo, hi + 0.35 * (hi - lo))  # room for the legend above the traces
        a_.legend(fontsize=8, ncol=3, loc="upper left")
    off = rms["rotor off"]
    fig.suptitle(
        f"GyroStabilizer-v0: 18 t yacht + {titles[1]} at roll resonance:\n"
        f"LQR cuts the RMS roll by {100 * (1 - rms['lqr'] / off):.0f} %, PID by "
        f"{100 * (1 - rms['pid'] / off):.0f} %"
    )
    fig.tight_layout()
    p = out / "stabilizer_yacht.png"
    save_figure(fig, p, dpi=100)
    g = save_gif(frames, out / "stabilizer_yacht.gif", fps=5)
    return [p, g], (
        f"yacht RMS roll: off {math.degrees(off):.2f} deg, PID "
        f"{math.degrees(rms['pid']):.2f} (RR {1 - rms['pid'] / off:.3f}), LQR "
        f"{math.degrees(rms['lqr']):.2f} (RR {1 - rms['lqr'] / off:.3f})"
    )


def run(out: Path, quick: bool) -> tuple[list[Path], list[str]]:
    out.mkdir(parents=True, exist_ok=True)
    files, lines = [], []
    for fn in (fig_3_9, fig_3_10_11, fig_3_12_13, fig_3_14_15):
        p, line = fn(out, quick)
        files.append(p)
        lines.append(line)
    ps, line = fig_yacht(out, quick)
    files.extend(ps)
    lines.append(line)
    return files, lines
