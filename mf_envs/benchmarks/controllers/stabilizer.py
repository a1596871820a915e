"""GyroStabilizer-v0 baselines: RMS roll reduction RR = 1 - RMS_on / RMS_off on several seas.

Scenes (the default 18 t yacht + one Seakeeper 9, natural roll period T_n = 3.70 s, M0 = 8 kN m):
- `resonance`: regular wave at T_n (capacity M0 / (H w sin(phi_max)) = 0.60);
- `below_resonance` / `above_resonance`: regular waves at 0.6 T_n and 1.6 T_n;
- `resonance_overload`: regular wave at T_n with 2 M0 (capacity 1.21 > 1, see the bounds below);
- `irregular`: JONSWAP sea, Hs = 0.6 m, Tp = T_n (`physics.ship_waves` roll-moment model).
Rows per (scene, controller): `rms_roll` (rad, after 10 s), `rr` (vs the rotor off, same seeds),
`gimbal_rms` and `gimbal_peak` (rad), `rate_rms` (precession rate, rad/s); per scene the
`capacity` and two bounds of a linear roll model (regular seas; NaN for irregular):
`rr_bound_sinusoidal` = min(1, 1/capacity) -- a sinusoidal sin(phi) of amplitude sin(phi_max)
supplies at most n H w sin(phi_max) of the wave moment -- and `rr_bound_any` =
min(1, 4/(pi capacity)) for any gimbal motion within the stops (a square-wave sin(phi) has a
fundamental 4/pi larger; the docs/design.md GOWEC bound). Quadratic roll damping makes both
approximate: a controller that rides the end stops can beat the first one slightly.
The open-loop seed excitations use the wave period and are phase-locked to the wave moment
(wave_phase = 0, amplitude asin(min(1, capacity)) for `sinusoidal`), i.e. their best case.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

ENV_ID = "GyroStabilizer-v0"
SETTLE = 10.0
CONTROLLERS = ("pid", "lqr", "sinusoidal", "continuous")


def _scenes() -> dict[str, dict]:
    from mf_envs.physics.ship.params import small_yacht

    tn = small_yacht().natural_roll_period(True)
    irr = (
        "gyroscopic",
        "gimbal_inertia",
        "added_inertia",
        "hydrostatic_restoring",
        "roll_damping",
        "irregular_waves",
        "gimbal_limits",
    )
    return {
        "resonance": {"wave_period": tn},
        "below_resonance": {"wave_period": 0.6 * tn},
        "above_resonance": {"wave_period": 1.6 * tn},
        "resonance_overload": {"wave_period": tn, "wave_moment_amplitude": 16000.0},
        "irregular": {"wave_period": tn, "effects": irr},
    }


def _episode(kwargs: dict, kind: str | None, seed: int) -> dict[str, float]:
    import gymnasium as gym

    import mf_envs  # noqa: F401
    from mf_envs.controllers import make_baseline

    env = gym.make(ENV_ID, **kwargs)
    open_loop = kind in ("sinusoidal", "continuous")
    opts = {"wave_phase": 0.0} if open_loop else None
    obs, info = env.reset(seed=seed, options=opts)
    params = {}
    if kind == "sinusoidal":
        params = {"amplitude": math.asin(min(1.0, env.unwrapped.capacity()))}
    ctrl = make_baseline(env, kind, **params) if kind else None
    roll, gim, rate = [], [], []
    done = False
    while not done:
        a = ctrl.predict(obs)[0] if ctrl else np.zeros(1, np.float32)
        obs, _, term, trunc, info = env.step(a)
        done = term or trunc
        if info["time"] > SETTLE:
            roll.append(info["roll"])
            gim.append(info["gimbal_angle"])
            rate.append(info["gimbal_rate"])
    roll, gim, rate = np.array(roll), np.array(gim), np.array(rate)
    return {
        "rms_roll": float(np.sqrt(np.mean(roll**2))),
        "gimbal_rms": float(np.sqrt(np.mean(gim**2))),
        "gimbal_peak": float(np.abs(gim).max()),
        "rate_rms": float(np.sqrt(np.mean(rate**2))),
    }


def _rotor_off(kwargs: dict) -> dict:
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS

    eff = kwargs.get("effects", DEFAULT_EFFECTS)
    return {**kwargs, "effects": tuple(e for e in eff if e != "gyroscopic")}


def rows(quick: bool) -> list[dict]:
    import gymnasium as gym

    seeds = (0, 1) if quick else (0, 1, 2, 3, 4)
    out: list[dict] = []
    for scene, kwargs in _scenes().items():
        env = gym.make(ENV_ID, **kwargs).unwrapped
        irregular = "irregular_waves" in env.effects
        cap = math.nan if irregular else env.capacity()
        base = dict(env_id=ENV_ID, scene=scene, n_seeds=len(seeds))
        out.append({**base, "controller": "-", "metric": "capacity", "mean": cap, "std": 0.0})
        for name, factor in (("rr_bound_sinusoidal", 1.0), ("rr_bound_any", 4.0 / math.pi)):
            out.append(
                {
                    **base,
                    "controller": "-",
                    "metric": name,
                    "mean": math.nan if irregular else min(1.0, factor / cap),
                    "std": 0.0,
                }
            )
        off = np.array([_episode(_rotor_off(kwargs), None, s)["rms_roll"] for s in seeds])
        out.append(
            {
                **base,
                "controller": "rotor_off",
                "metric": "rms_roll",
                "mean": float(off.mean()),
                "std": float(off.std()),
            }
        )
        for kind in CONTROLLERS:
            res = [_episode(kwargs, kind, s) for s in seeds]
            rr = np.array([1.0 - r["rms_roll"] / o for r, o in zip(res, off)])
            out.append(
                {
                    **base,
                    "controller": kind,
                    "metric": "rr",
                    "mean": float(rr.mean()),
                    "std": float(rr.std()),
                }
            )
            for m in ("rms_roll", "gimbal_rms", "gimbal_peak", "rate_rms"):
                v = np.array([r[m] for r in res])
                out.append(
                    {
                        **base,
                        "controller": kind,
                        "metric": m,
                        "mean": float(v.mean()),
                        "std": float(v.std()),
                    }
                )
    return out


def plot(out: Path, rows: list[dict]) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, ax = plt.subplots(figsize=(10, 4))
    width = 0.8 / len(CONTROLLERS)
    for i, kind in enumerate(CONTROLLERS):
        vals = [
            next(
                (
                    r["mean"]
                    for r in rows
                    if r["scene"] == s and r["controller"] == kind and r["metric"] == "rr"
                ),
                math.nan,
            )
            for s in scenes
        ]
        ax.bar(np.arange(len(scenes)) + i * width, vals, width, label=kind)
    ceil = [
        next(
            (r["mean"] for r in rows if r["scene"] == s and r["metric"] == "rr_bound_sinusoidal"),
            math.nan,
        )
        for s in scenes
    ]
    ax.plot(
        np.arange(len(scenes)) + 0.4 - width / 2,
        ceil,
        "k_",
        ms=30,
        mew=2,
        label="bound min(1, 1/capacity), sinusoidal gimbal",
    )
    ax.set_xticks(np.arange(len(scenes)) + 0.4 - width / 2, scenes, fontsize=8)
    ax.set_ylabel("RMS roll reduction RR")
    ax.set_ylim(-1.0, 1.05)
    ax.axhline(0, color="0.5", lw=0.8)
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=7)
    ax.set_title("GyroStabilizer-v0 baselines (18 t yacht, Seakeeper 9)")
    fig.tight_layout()
    p = out / "controllers_stabilizer.png"
    fig.savefig(p, dpi=100)
    plt.close(fig)
    return [p]
