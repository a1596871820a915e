"""FloatingGOWEC-v0 baselines: capture width and share of the radiation bound, regular and
irregular seas.

Rows: every controller on every scene, metrics `capture_width` (m) = mean mechanical PTO power
over the last half of the episode / wave power flux J, `bound_ratio` = that power /
`power_bound()` (radiation-limited, |X|^2 a^2 / (8 B) summed over components) and
`net_power` (W, electrical, after efficiency and rotor loss). Controllers: the classical
baselines and, when the `train` extra is installed, the shipped PPO policy (trained with domain
randomisation on regular and JONSWAP seas, `train/configs/ppo_randomized.yml`), all on the same
unseen seeds 2000-2004 (training used 0.., its evaluation 1000..). `figures(out)` draws the
docs' free decay, RAO against the frequency domain and the two-way coupling plot
(`python -m mf_envs.benchmarks.controllers.gowec_v1 docs/img`).
"""

from __future__ import annotations

import math
from pathlib import Path

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401
from mf_envs._files import save_figure
from mf_envs.benchmarks.controllers.ppo import make_controller, with_ppo
from mf_envs.controllers import make_baseline
from mf_envs.envs.gowec_v1.task import DECLARATION

ENV_ID = DECLARATION.env_id
SCORES_PPO = True  # PPO rows beside the baselines here, not in ppo.py
KINDS = ("pll", "bang_bang", "linear_pto", "passive_damper", "efficient_pto")
SEEDS = tuple(range(2000, 2005))  # unseen by training (0..) and its evaluation (1000..)
SCENES: dict[str, dict] = {
    "regular_a0.5_T6": dict(wave_amplitude=0.5, wave_period=6.0),
    "regular_a0.5_T7": dict(wave_amplitude=0.5, wave_period=7.0),
    "irregular_hs1.5_tp6": dict(significant_wave_height=1.5, peak_period=6.0),
}


def controllers() -> tuple[str, ...]:
    """The baselines, plus "ppo" when the shipped policy and the train extra are there."""
    return with_ppo(ENV_ID, KINDS)


def _controller(env: gym.Env, kind: str):
    return make_controller(env, ENV_ID, kind)


def episode(kind: str, seed: int, seconds: float, **kw) -> dict[str, float]:
    """Mean mechanical and net electrical power (W) over the last half, J (W/m), bound (W)."""
    env = gym.make(ENV_ID, episode_seconds=seconds, max_episode_steps=-1, **kw)  # no TimeLimit
    c = _controller(env, kind)
    obs, _ = env.reset(seed=seed)
    c.reset()
    Pm, Pe, done = [], [], False
    while not done:
        a, _ = c.predict(obs)
        obs, _, term, trunc, info = env.step(a)
        Pm.append(info["power_mechanical"])
        Pe.append(info["power"])
        done = term or trunc
    u = env.unwrapped
    n = len(Pm) // 2
    out = dict(
        P=float(np.mean(Pm[n:])),
        Pe=float(np.mean(Pe[n:])),
        J=u.wave_power_flux(),
        bound=u.power_bound(),
        terminated=float(term),
    )
    env.close()
    return out


def rows(quick: bool) -> list[dict]:
    seeds = SEEDS[:1] if quick else SEEDS
    seconds = 60.0 if quick else 200.0
    out = []
    for scene, kw in SCENES.items():
        for kind in controllers():
            runs = [episode(kind, s, seconds, **kw) for s in seeds]
            for metric, f in (
                ("capture_width", lambda r: r["P"] / r["J"]),
                ("bound_ratio", lambda r: r["P"] / r["bound"]),
                ("net_power", lambda r: r["Pe"]),
                ("mech_power", lambda r: r["P"]),
            ):
                v = [f(r) for r in runs]
                out.append(
                    dict(
                        env_id=ENV_ID,
                        scene=scene,
                        controller=kind,
                        metric=metric,
                        mean=float(np.mean(v)),
                        std=float(np.std(v)),
                        n_seeds=len(v),
                    )
                )
    return out


def plot(out: Path, rows: list[dict]) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    out.mkdir(parents=True, exist_ok=True)
    fig, ax = plt.subplots(figsize=(8, 4))
    scenes = list(SCENES)
    kinds = [k for k in (*KINDS, "ppo") if any(r["controller"] == k for r in rows)]
    width = 0.8 / len(kinds)
    for i, kind in enumerate(kinds):
        ys = [
            next(
                (
                    r["mean"]
                    for r in rows
                    if r["scene"] == s
                    and r["controller"] == kind
                    and r["metric"] == "capture_width"
                ),
                np.nan,
            )
            for s in scenes
        ]
        ax.bar(np.arange(len(scenes)) + (i - (len(kinds) - 1) / 2) * width, ys, width, label=kind)
    ax.axhline(0.0, color="k", lw=0.8)
    ax.set_xticks(np.arange(len(scenes)), scenes)
    ax.set_ylabel("capture width P_mech / J (m)")
    ax.set_title("FloatingGOWEC-v0 controllers (mean mechanical PTO power / wave power flux)")
    ax.legend()
    fig.tight_layout()
    p = out / "gowec_v1_capture_width.png"
    save_figure(fig, p, dpi=110)
    return [p]


def figures(out: Path) -> list[Path]:
    """Free decay, RAO vs frequency domain, two-way coupling (docs/img), of the seed buoy
    (`device="seed_buoy"`, whose figures these are)."""
    import matplotlib

    matplotlib.use("Agg")

    from mf_envs.physics.gowec import GOWECParams
    from mf_envs.physics.gowec.hydro import load_hull
    from mf_envs.physics.gowec.hydro.model import FloatingModel

    out.mkdir(parents=True, exist_ok=True)
    hull = load_hull()
    pto = dict(
        damping=0.0, stiffness=0.0, max_torque=1e9, max_power=1e12, eta_generator=1.0, eta_motor=1.0
    )
    m = FloatingModel(hull, GOWECParams(), pto, gyroscopic=False)
    return [_free_decay(m, hull, out), _rao(m, hull, out), _coupling(out)]


def _free_decay(m, hull, out: Path) -> Path:
    """gowec_v1_free_decay.png: rotor-off pitch decay against the envelope from B(w_n)."""
    import matplotlib.pyplot as plt

    dt, n = 0.01, 6000
    y, th = m.initial_state(pitch=0.05), [0.05]
    for i in range(n):
        y = m.step(i * dt, y, 0.0, dt, 1)
        th.append(y[0])
    t = np.arange(n + 1) * dt
    wn = hull.natural_frequency()
    A, B, _ = hull.at(wn)
    zeta = B / (2 * math.sqrt(hull.stiffness * (m.pitch_inertia() + A)))
    fig, ax = plt.subplots(figsize=(8, 3.5))
    ax.plot(t, th, label="Cummins + state-space radiation (rotor off)")
    ax.plot(t, 0.05 * np.exp(-zeta * wn * t), "k--", lw=1, label="envelope from B(w_n)")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("pitch (rad)")
    ax.set_title(f"Free decay: T = {2 * math.pi / wn:.3f} s, zeta = {zeta:.1e}")
    ax.set_ylim(-0.085, 0.06)
    ax.legend(loc="lower right", fontsize=8, ncol=2)
    fig.tight_layout()
    return save_figure(fig, out / "gowec_v1_free_decay.png", dpi=110)


def _rao(m, hull, out: Path) -> Path:
    """gowec_v1_rao.png: the time-domain pitch RAO (steady part, least squares) at six periods
    against the frequency-domain |X| / |-w^2 (I + A) + i w B + C|."""
    import matplotlib.pyplot as plt

    from mf_envs.physics.waves import regular_wave

    dt, wn, I = 0.01, hull.natural_frequency(), m.pitch_inertia()
    periods = [4.5, 5.0, 5.3, 5.8, 6.5, 7.5]
    sim = []
    for T in periods:
        w = 2 * math.pi / T
        m.set_sea(regular_wave(0.05, T))
        y, ths = m.initial_state(), []
        for i in range(40000):
            y = m.step(i * dt, y, 0.0, dt, 1)
            ths.append(y[0])
        tt = np.arange(1, 40001) * dt
        sel = tt > 50
        basis = np.stack([np.cos(w * tt[sel]), np.sin(w * tt[sel]), np.cos(wn * tt[sel]),
                          np.sin(wn * tt[sel]), np.ones(sel.sum())], 1)  # fmt: skip
        c = np.linalg.lstsq(basis, np.asarray(ths)[sel], rcond=None)[0]
        sim.append(math.hypot(c[0], c[1]) / 0.05)
    wf = np.linspace(0.6, 2.0, 400)
    rao = [
        abs(hull.at(w)[2])
        / abs(complex(hull.stiffness - w * w * (I + hull.at(w)[0]), w * hull.at(w)[1]))
        for w in wf
    ]
    fig, ax = plt.subplots(figsize=(8, 3.5))
    ax.semilogy(wf, rao, label="frequency domain |X| / |-w^2 (I + A) + i w B + C|")
    ax.semilogy([2 * math.pi / T for T in periods], sim, "o", label="time domain (steady part)")
    ax.set_xlabel("wave frequency (rad/s)")
    ax.set_ylabel("pitch RAO (rad/m)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save_figure(fig, out / "gowec_v1_rao.png", dpi=110)


def _coupling(out: Path) -> Path:
    import matplotlib.pyplot as plt

    res = {}
    for label, kw, kind in (
        ("rotor off", dict(effects=("radiation", "viscous_damping")), None),
        ("rotor on, matched linear PTO", {}, "linear_pto"),
        ("rotor on, PLL", {}, "pll"),
    ):
        env = gym.make(ENV_ID, wave_amplitude=0.5, wave_period=6.0, episode_seconds=120.0,
                       device="seed_buoy", **kw)  # fmt: skip
        c = make_baseline(env, kind) if kind else None
        obs, _ = env.reset(seed=0)
        if c:
            c.reset()
        th, M, t, done = [], [], [], False
        while not done:
            a = c.predict(obs)[0] if c else np.zeros(1, np.float32)
            obs, _, term, trunc, info = env.step(a)
            th.append(info["buoy_pitch"])
            M.append(info["gyro_moment"])
            t.append(info["time"])
            done = term or trunc
        res[label] = (np.array(t), np.array(th), np.array(M))
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(8, 5.5), sharex=True)
    style = {"rotor on, PLL": dict(color="tab:green", alpha=0.5, lw=2.5, zorder=1),
             "rotor off": dict(color="tab:blue", lw=1.2, zorder=3),
             "rotor on, matched linear PTO": dict(color="tab:orange", lw=1.2,
                                                  zorder=2)}  # fmt: skip
    for label in ("rotor on, PLL", "rotor off", "rotor on, matched linear PTO"):  # PLL behind
        t, th, M = res[label]
        a1.plot(t, np.degrees(th), label=label, **style[label])
        a2.plot(t, M / 1e3, label=label, **style[label])
    a1.set_ylabel("buoy pitch (deg)")
    a2.set_yscale("symlog", linthresh=10.0)
    a2.set_ylabel("gyro moment on hull (kN m, symlog)")
    a2.set_xlabel("time (s)")
    a1.set_title(
        "Two-way coupling on the seed buoy, a = 0.5 m, T = 6 s (dual Seakeeper 26):\n"
        "the loaded gyro changes how the buoy pitches"
    )
    lo, hi = a1.get_ylim()
    a1.set_ylim(lo, hi + 0.3 * (hi - lo))  # room for the legend
    a1.legend(fontsize=8, loc="upper left", ncol=3)
    fig.tight_layout()
    return save_figure(fig, out / "gowec_v1_coupling.png", dpi=110)


if __name__ == "__main__":  # python -m mf_envs.benchmarks.controllers.gowec_v1 OUT_FOLDER
    import sys

    if len(sys.argv) != 2:
        raise SystemExit("usage: python -m mf_envs.benchmarks.controllers.gowec_v1 OUT_FOLDER")
    folder = Path(sys.argv[1])
    folder.mkdir(parents=True, exist_ok=True)
    for written in figures(folder):
        print(f"wrote {written}")
