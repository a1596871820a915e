"""GyroStabilizer-v0 baselines: RMS roll reduction RR = 1 - RMS_on / RMS_off on several seas.

Scenes (the default 18 t yacht + one Seakeeper Model 7000 on its hydraulic brake,
before it a Seakeeper 9 on an electric drive; the irregular-sea grid: `stabilizer_grid`; natural
roll period T_n = 3.70 s, M0 = 8 kN m):
- `resonance`: regular beam wave at T_n (capacity M0 / (H w sin(phi_max)) = 0.88; 0.60 for
  the Seakeeper 9);
- `below_resonance` / `above_resonance`: regular waves at 0.6 T_n and 1.6 T_n;
- `resonance_overload`: regular wave at T_n with 2 M0 (capacity 1.75; 1.21 for the Seakeeper 9;
  see the bounds below);
- `jonswap_beam`: long-crested JONSWAP beam sea, Hs = 0.6 m, Tp = T_n;
- `jonswap_quartering`: bow-quartering JONSWAP sea (beta = 135 deg) at 5 m/s, Hs = 1 m,
  Tp = 5.3 s, met at the encounter frequency near the roll resonance (`physics.ship.seas`).
Rows per (scene, controller), over 5 seeds not used in any tuning (100-104; 0-1 with --quick):
`rr` (vs the rotor off, same seeds), `rms_roll` and `peak_roll` (rad, after 10 s),
`energy_per_hour` (drive energy int n |tau phi'| dt per hour, J/h), `peak_torque` (N m),
`peak_power` (motoring, W) and `gimbal_peak` (rad). Per scene the `capacity` (irregular seas:
M0 = sqrt(2) x the RMS wave moment met by the ship, w the peak frequency) and two bounds of a
linear roll model: `rr_bound_sinusoidal` = min(1, 1/capacity) -- a sinusoidal sin(phi) of
amplitude sin(phi_max) supplies at most n H w sin(phi_max) of the wave moment -- and
`rr_bound_any` = min(1, 4/(pi capacity)) for any gimbal motion within the stops (a square-wave
sin(phi) has a fundamental 4/pi larger; the docs/design.md GOWEC bound). Quadratic roll damping
makes both approximate. Controllers: `pid`, `lqr`, the classic `rate` law phi' = k w1, and the
seed's open-loop excitations (Eqs. 118-119, amplitude asin(min(1, capacity)) for `sinusoidal`)
both phase-locked to the wave moment (`_locked`, wave_phase = 0, their best case) and at the
env's random wave phase (`_random`); in irregular seas the two are the same runs; and
`ppo_shipped`, the shipped PPO policy (`train/policies/GyroStabilizer-v0`, if the train extra is
installed) on the same seeds with the same metrics (drive energy included; `ppo.py`'s `ppo` rows
score it on seeds 2000-2004 without the drive metrics).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from mf_envs._files import save_figure
from mf_envs.envs.gyro_stabilizer.task import DECLARATION, SETTLE

ENV_ID = DECLARATION.env_id
FLOOR = -2.0  # lowest RR drawn: a controller that doubles the roll is off the chart
# (name, baseline kind, open-loop phase): the seed's open-loop excitations are scored
# phase-locked to the wave moment (their best case) and at the env's random wave phase
CONTROLLERS = (
    ("pid", "pid", None),
    ("lqr", "lqr", None),
    ("rate", "rate", None),
    ("sinusoidal_locked", "sinusoidal", "locked"),
    ("sinusoidal_random", "sinusoidal", "random"),
    ("continuous_locked", "continuous", "locked"),
    ("continuous_random", "continuous", "random"),
)
PPO = ("ppo_shipped", "ppo", None)  # appended to CONTROLLERS when a policy is shipped
METRICS = ("rms_roll", "peak_roll", "energy_per_hour", "peak_torque", "peak_power", "gimbal_peak")


def _scenes() -> dict[str, dict]:
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS
    from mf_envs.physics.ship.hulls import Hull

    tn = Hull.yacht().natural_roll_period()
    irr = tuple(e for e in DEFAULT_EFFECTS if e != "wave_moment") + ("irregular_waves",)
    return {
        "resonance": {"wave_period": tn},
        "below_resonance": {"wave_period": 0.6 * tn},
        "above_resonance": {"wave_period": 1.6 * tn},
        "resonance_overload": {"wave_period": tn, "wave_moment_amplitude": 16000.0},
        "jonswap_beam": {"wave_period": tn, "effects": irr},
        # bow-quartering sea (beta = 135 deg) at 5 m/s: Tp = 5.3 s is met at w_e = 1.70 rad/s,
        # the roll resonance (a stern-quartering sea at 5 m/s cannot reach it: w_e <= 0.69)
        "jonswap_quartering": {
            "wave_period": 5.3,
            "effects": irr,
            "heading": 0.75 * math.pi,
            "ship_speed": 5.0,
            "significant_wave_height": 1.0,
        },
    }


def _episode(kwargs: dict, kind: str | None, seed: int, phase: str | None = None) -> dict:
    import gymnasium as gym

    import mf_envs  # noqa: F401
    from mf_envs.controllers import make_baseline

    env = gym.make(ENV_ID, **kwargs)
    opts = {"wave_phase": 0.0} if phase == "locked" else None
    obs, info = env.reset(seed=seed, options=opts)
    params = {}
    if kind == "sinusoidal":
        params = {"amplitude": math.asin(min(1.0, _capacity(env.unwrapped)))}
    if kind == "ppo":
        from mf_envs.train.policy import load_policy

        ctrl = load_policy(ENV_ID)
    else:
        ctrl = make_baseline(env, kind, **params) if kind else None
    roll, gim, tau, pw = [], [], [], []
    energy = 0.0
    done = False
    while not done:
        a = ctrl.predict(obs)[0] if ctrl else np.zeros(1, np.float32)
        obs, _, term, trunc, info = env.step(a)
        done = term or trunc
        if info["time"] > SETTLE:
            roll.append(info["roll"])
            gim.append(info["gimbal_angle"])
            tau.append(info["drive_torque"])
            pw.append(info["drive_power"])
            energy += info["drive_energy"]
    roll = np.array(roll)
    hours = len(roll) * env.unwrapped.control_dt / 3600.0
    return {
        "rms_roll": float(np.sqrt(np.mean(roll**2))),
        "peak_roll": float(np.abs(roll).max()),
        "energy_per_hour": energy / hours,
        "peak_torque": float(np.abs(tau).max()),
        "peak_power": float(np.max(pw)),
        "gimbal_peak": float(np.abs(gim).max()),
    }


def _capacity(env) -> float:
    """M0 / (n H w sin(phi_max)) (regular); for an irregular sea the same with M0 = sqrt(2) x the
    RMS wave moment met by the ship and w the peak frequency (after a reset)."""
    if "irregular_waves" not in env.effects:
        return env.capacity()
    from mf_envs.physics.ship.params import capacity_ratio

    m0 = math.sqrt(2.0) * float(np.std(env._tab[:, 0]))
    w = 2.0 * math.pi / env.wave_period
    return capacity_ratio(m0, env.gyro.angular_momentum, w, env.n_gyros, env.max_gimbal_angle)


def _rotor_off(kwargs: dict) -> dict:
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS

    eff = kwargs.get("effects", DEFAULT_EFFECTS)
    return {**kwargs, "effects": tuple(e for e in eff if e != "gyroscopic")}


def _controllers() -> tuple[tuple[str, str, str | None], ...]:
    """CONTROLLERS, plus PPO if a policy is shipped and the train extra is installed."""
    import importlib.util

    from mf_envs.train.policy import POLICY_FILE, policy_dir

    extra = all(importlib.util.find_spec(m) for m in ("stable_baselines3", "torch", "safetensors"))
    shipped = (policy_dir(ENV_ID) / POLICY_FILE).is_file()
    return CONTROLLERS + ((PPO,) if extra and shipped else ())


def _row(base: dict, controller: str, metric: str, v: np.ndarray | float) -> dict:
    v = np.atleast_1d(np.asarray(v, dtype=float))
    return {**base, "controller": controller, "metric": metric, "mean": float(v.mean()),
            "std": float(v.std())}  # fmt: skip


def rows(quick: bool) -> list[dict]:
    import gymnasium as gym

    seeds = (0, 1) if quick else (100, 101, 102, 103, 104)  # unseen by the tuning (seeds 0-2)
    out: list[dict] = []
    for scene, kwargs in _scenes().items():
        env = gym.make(ENV_ID, **kwargs).unwrapped
        env.reset(seed=seeds[0])
        cap = _capacity(env)
        base = dict(env_id=ENV_ID, scene=scene, n_seeds=len(seeds))
        out.append(_row(base, "-", "capacity", cap))
        out.append(_row(base, "-", "rr_bound_sinusoidal", min(1.0, 1.0 / cap)))
        out.append(_row(base, "-", "rr_bound_any", min(1.0, 4.0 / (math.pi * cap))))
        off = np.array([_episode(_rotor_off(kwargs), None, s)["rms_roll"] for s in seeds])
        out.append(_row(base, "rotor_off", "rms_roll", off))
        for name, kind, phase in _controllers():
            res = [_episode(kwargs, kind, s, phase) for s in seeds]
            out.append(_row(base, name, "rr", [1.0 - r["rms_roll"] / o for r, o in zip(res, off)]))
            for m in METRICS:
                out.append(_row(base, name, m, [r[m] for r in res]))
    return out


def ppo_extra_rows(
    scene: str, kwargs: dict, per_seed: list[dict[str, float]], seeds: tuple[int, ...]
) -> list[dict]:
    """For `ppo.py`'s rows: RR = 1 - RMS_ppo / RMS_rotor_off per seed (this module's `rr`, the
    rotor-off episodes from `_episode`)."""
    on = np.array([m["rms_roll"] for m in per_seed])
    off = np.array([_episode(_rotor_off(kwargs), None, s)["rms_roll"] for s in seeds])
    rr = 1.0 - on / off
    base = {"env_id": ENV_ID, "scene": scene, "n_seeds": len(seeds)}
    return [
        {**base, "seeds": f"{seeds[0]}-{seeds[-1]}", "controller": "ppo", "metric": "rr",
         "mean": float(rr.mean()), "std": float(rr.std(ddof=1))}
    ]  # fmt: skip


def plot(out: Path, rows: list[dict]) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    fig, ax = plt.subplots(figsize=(10, 4))
    names = list(dict.fromkeys(r["controller"] for r in rows if r["metric"] == "rr"))
    width = 0.8 / max(len(names), 1)
    for i, kind in enumerate(names):
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
        x = np.arange(len(scenes)) + i * width
        ax.bar(x, np.maximum(vals, FLOOR), width, label=kind)
        for xi, v in zip(x, vals):  # a bar below the axis floor is cut there and labelled
            if v < FLOOR:
                ax.annotate(f"{v:.2f}", (xi, FLOOR), xytext=(0, 3), textcoords="offset points",
                            ha="center", fontsize=7, rotation=90)  # fmt: skip
    ceil = [
        next(
            (r["mean"] for r in rows if r["scene"] == s and r["metric"] == "rr_bound_sinusoidal"),
            math.nan,
        )
        for s in scenes
    ]
    left = np.arange(len(scenes)) - width / 2  # each scene's bound spans its group of bars
    ax.hlines(ceil, left, left + 0.8, colors="k", lw=2,
              label="bound min(1, 1/capacity), sinusoidal gimbal")  # fmt: skip
    ax.set_xticks(np.arange(len(scenes)) + 0.4 - width / 2, scenes, fontsize=8, rotation=15)
    ax.set_ylabel("RMS roll reduction RR")
    low = min([0.0, *[r["mean"] for r in rows if r["metric"] == "rr"]])
    ax.set_ylim(max(FLOOR, low - 0.05), 1.05)
    ax.axhline(0, color="0.5", lw=0.8)
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.set_title("GyroStabilizer-v0 baselines (18 t yacht, Seakeeper Model 7000): RMS roll "
                 "reduction on six seas (higher is better)", fontsize=10)  # fmt: skip
    if low < FLOOR:
        ax.set_xlabel(f"bars below {FLOOR:g} are cut at the axis and labelled with their value",
                      fontsize=7)  # fmt: skip
    fig.tight_layout()
    p = out / "controllers_stabilizer.png"
    save_figure(fig, p, dpi=100)
    return [p]
