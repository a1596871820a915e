"""FloatingGOWEC-v0 showcase: the floating buoy pitching in the wave with its gimbal and rotor.

Writes into `out`:
- gowec_v1_episode.png  the default sea (regular, a = 1 m, T = 6 s) with the efficient_pto
                        and with the rotor off: buoy pitch, gimbal angle, mechanical PTO power,
                        against the wave elevation (two-way coupling: the loaded gyro changes
                        the buoy's motion). An episode that ends early (the rotor-off hull
                        pitching past its limit) is plotted over what it ran, its end marked.
- gowec_v1.gif          the buoy, gimbal and rotor over two wave periods (not with --quick)

`--quick` runs the same 60 s episodes and only skips the GIF: a shorter run would show nothing
but the wave's ramp.
"""

from __future__ import annotations

from pathlib import Path

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401
from mf_envs._files import save_figure
from mf_envs.controllers import make_baseline
from mf_envs.envs.gowec_v1.task import DECLARATION

ENV_ID = DECLARATION.env_id

ORDER = 25
TITLE = "FloatingGOWEC-v0: the floating buoy, Cummins equation + BEM coefficients"
SECONDS = 60.0


def _episode(kind: str, rotor: bool, seconds: float, frames: int = 0):
    """Time series of one episode on the default sea; `frames` rgb frames of the first two
    wave periods (every ~0.2 s)."""
    kw = {} if rotor else {"rotor_speed": 0.0}
    env = gym.make(
        ENV_ID,
        episode_seconds=seconds,
        max_episode_steps=-1,  # no TimeLimit: episode_seconds ends the episode
        render_mode="rgb_array" if frames else None,
        **kw,
    )
    ctrl = make_baseline(env, kind)
    obs, info = env.reset(seed=0)
    ctrl.reset()
    keys = (
        "time", "buoy_pitch", "gimbal_angle", "gimbal_rate", "power_mechanical", "power",
        "wave_elevation",
    )  # fmt: skip
    rec: dict[str, list] = {k: [] for k in keys}
    shots, every, done = [], max(1, int(round(0.2 / env.unwrapped.control_dt))), False
    while not done:
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        for k in keys:
            rec[k].append(info[k])
        if len(shots) < frames and len(rec["time"]) % every == 0:
            shots.append(env.render())
        done = term or trunc
    u = env.unwrapped
    end = ""
    if term:
        end = "pitch or roll limit" if info.get("out_of_range") else "gimbal overspeed"
        end = "numerical failure" if info.get("numerical_failure") else end
    extra = {
        "end": end,
        "ramp": float(u.wave_ramp),
        "J": u.wave_power_flux(),
        "Tn": u.natural_period(),
        "units": u.model.p.gyro[5],
    }
    # the linear PTO's torque c phi' + k phi against the generator's torque and power limits
    rec_rate, rec_phi = np.asarray(rec["gimbal_rate"]), np.asarray(rec["gimbal_angle"])
    m = ctrl.c * rec_rate + ctrl.k * rec_phi if hasattr(ctrl, "c") else np.zeros_like(rec_rate)
    lim = np.minimum(
        u.max_generator_torque, u.max_generator_power / np.maximum(np.abs(rec_rate), 1e-12)
    )
    extra["saturated"] = np.abs(m) >= lim
    extra["torque_limit"] = u.max_generator_torque
    env.close()
    return {k: np.asarray(v) for k, v in rec.items()}, extra, shots


def run(out: Path, quick: bool) -> tuple[list[Path], list[str]]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    seconds = SECONDS
    n_frames = 0 if quick else 60
    pto, ex, shots = _episode("efficient_pto", True, seconds, n_frames)
    off, ex_off, _ = _episode("efficient_pto", False, seconds)
    fig, ax = plt.subplots(4, 1, figsize=(8, 8), sharex=True)
    ax[0].plot(pto["time"], pto["wave_elevation"], "k", lw=0.8)
    ax[0].set_ylabel("wave elevation (m)")
    off_label = "rotor off" + (
        f" (episode ends at {off['time'][-1]:.0f} s: {ex_off['end']})" if ex_off["end"] else ""
    )
    ax[1].plot(off["time"], np.degrees(off["buoy_pitch"]), label=off_label)
    if ex_off["end"]:
        ax[1].plot(off["time"][-1], np.degrees(off["buoy_pitch"][-1]), "x", color="tab:blue")
    ax[1].plot(pto["time"], np.degrees(pto["buoy_pitch"]), label="rotor on, linear PTO")
    ax[1].set_ylabel("buoy pitch (deg)")
    lo, hi = ax[1].get_ylim()
    ax[1].set_ylim(lo, hi + 0.6 * (hi - lo))  # room for the legend above the traces
    ax[1].legend(loc="upper left", ncol=2, fontsize=8)
    ax[2].plot(pto["time"], np.degrees(pto["gimbal_angle"]))
    ax[2].set_ylabel("gimbal angle (deg)")
    ax[3].plot(pto["time"], pto["power_mechanical"] / 1e3)
    ax[3].set_ylabel(f"PTO power, {ex['units']:.0f} units (kW)")
    ax[3].set_xlabel("time (s)")
    sat = ex["saturated"]
    if sat.any():  # where the PTO's c phi' + k phi asks for more than the generator's rating
        t = pto["time"]
        for a in ax[2:]:
            a.fill_between(t, 0, 1, where=sat, color="tab:red", alpha=0.15, lw=0,
                           transform=a.get_xaxis_transform(), step="mid")  # fmt: skip
        ax[3].plot([], [], color="tab:red", alpha=0.3, lw=6, label=(
            f"shaded: the PTO's c phi' + k phi asks for more than the generator's "
            f"{ex['torque_limit'] / 1e3:.0f} kN m (per unit); the torque clips and power peaks"
        ))  # fmt: skip
        ax[3].legend(loc="upper left", fontsize=8)
    fig.suptitle(
        "FloatingGOWEC-v0, regular wave a = 1 m, T = 6 s: the loaded gyros (efficient_pto)\n"
        "hold the hull's pitch that, with the rotor off, grows past its limit"
    )
    fig.tight_layout()
    files = [out / "gowec_v1_episode.png"]
    save_figure(fig, files[0], dpi=100)
    if shots:
        from mf_envs.render import save_gif

        files.append(save_gif(shots, out / "gowec_v1.gif", fps=5))
    steady = pto["time"] > max(ex["ramp"], pto["time"][-1] / 2)  # after the wave's ramp
    p = float(np.mean(pto["power_mechanical"][steady]))
    lines = [
        f"natural pitch period (rotor off) {ex['Tn']:.2f} s; wave power flux {ex['J']:.0f} W/m",
        f"efficiency-aware linear PTO, t > {pto['time'][steady][0]:.0f} s: {p:.0f} W mechanical,"
        f" capture width {p / ex['J']:.3f} m (net electrical after the rotor's running loss: "
        f"{np.mean(pto['power'][steady]):.0f} W)",
        f"largest pitch, rotor on: {np.degrees(np.abs(pto['buoy_pitch'][steady]).max()):.2f} deg;"
        f" rotor off: {np.degrees(np.abs(off['buoy_pitch']).max()):.2f} deg"
        + (
            f" (its episode ends at {off['time'][-1]:.1f} s: {ex_off['end']})"
            if ex_off["end"]
            else ""
        ),
    ]
    return files, lines
