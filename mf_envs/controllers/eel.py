"""Anguilliform gaits for Eel-v0, driven through the env's action interface.

* `wave`: a travelling curvature wave whose amplitude grows linearly from the head to
  the tail (anguilliform: Gray 1933; Tytell & Lauder 2004 measured a body wave whose amplitude
  grows along the whole body),
      kappa#(S, t) = a (r + (1 - r) (L - S) / L) sin(2 pi (L - S) / lambda - 2 pi t / T),
  the wave running from the head S = L to the tail, head ratio r = HEAD_RATIO; the command of
  step k is the curve at the step's end, t = (k + 1) dt. Default (a, lambda / L, T) = WAVE;
* `fast`: the wave with (a, lambda / L, T) optimised by scipy (Nelder-Mead, bounded) for the
  centre-of-mass speed on a short horizon (`tune`, the numbers are `FAST`);
* `efficient`: the same for the Froude efficiency `froude_efficiency` (`EFFICIENT`);
* `eel`: the wave set by hand to an American eel's measured kinematics at 1.4 L/s (`EEL`: a tail
  amplitude near 0.08 L, Gillis 1998, at the 2.8 Hz that Strouhal number 0.32, Tytell 2004,
  implies there; docs/eel.md, "Kinematics against eels");
* `heading` (default, the strongest: the start heading is random): the fast wave plus a
  curvature bias -gain x heading error (the mean axis's heading relative to the target
  direction, observed as sin, cos, low-pass filtered over one period), so the eel turns
  towards the target.

The open-loop gaits ignore the observation; `heading` reads only its heading slots.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from scipy.optimize import minimize

from mf_envs._validate import check_range
from mf_envs.controllers import register
from mf_envs.controllers.serpentine import HeadingSerpenoid, Serpenoid, tuning_cli
from mf_envs.envs.eel.build import HEAD_RATIO  # curvature amplitude at the head / at the tail
from mf_envs.envs.eel.task import DECLARATION

ENV_ID = DECLARATION.env_id
WAVE = (40.0, 0.8, 0.4)  # a [1/m], lambda / L, T [s]: a hand-picked anguilliform start
# `python -m mf_envs.controllers.eel --tune` (default env, 4 s horizon, speed and power over
# 1.5-4 s, Nelder-Mead from WAVE, 60 evaluations each); the fast gait sits on the period bound
# and saturates the muscles' rate limit (a 2 pi / T > max_curvature_rate)
# (the stats as tuned, before the form drag and power limit; now: fast 0.789 m/s, slip 0.81;
# efficient 0.192 m/s, slip 0.60; `gait_stats`, seed 0)
FAST = (44.3981, 0.9791, 0.2)  # 0.834 m/s, slip 0.85, Froude efficiency 0.11
EFFICIENT = (30.532, 0.7501, 0.465)  # 0.208 m/s, slip 0.65, Froude efficiency 0.26
# by hand (five trials, seed 0): 1.33 L/s, tail amplitude 0.083 L, St 0.35 (docs/eel.md)
EEL = (30.5, 0.75, 1.0 / 2.8)
BOUNDS = ((5.0, 50.0), (0.4, 2.0), (0.2, 1.5))  # a [1/m], lambda / L, T [s]


class TravellingWave(Serpenoid):
    """kappa#(S_j, t) (module docstring) plus a bias [1/m]: the serpentine's serpenoid
    (`controllers.serpentine.Serpenoid`, the wave running head to tail) with the anguilliform
    envelope, head_ratio r = HEAD_RATIO by default."""

    def __init__(self, env: Any, amplitude: float = WAVE[0], wavelength: float = WAVE[1],
                 period: float = WAVE[2], head_ratio: float = HEAD_RATIO) -> None:  # fmt: skip
        super().__init__(env, amplitude, wavelength, period, head_ratio)


class HeadingWave(TravellingWave):
    """The fast wave plus bias = -gain x filtered heading error, |bias| <= max_bias (the
    serpentine's `HeadingSerpenoid` filter and bias)."""

    bias = HeadingSerpenoid.bias

    def __init__(self, env: Any, gain: float = 10.0, max_bias: float = 10.0,
                 amplitude: float | None = None, wavelength: float | None = None,
                 period: float | None = None, head_ratio: float = HEAD_RATIO) -> None:  # fmt: skip
        self.gain = check_range("gain", gain, 0.0, 1e3)  # 1/m per rad
        self.max_bias = check_range("max_bias", max_bias, 0.0, 1e3)  # 1/m
        layout = env.unwrapped.obs_layout
        self.i_sin, self.i_cos = layout.index("sin_heading"), layout.index("cos_heading")
        given = (amplitude, wavelength, period)
        a, lam, per = (x if x is not None else y for x, y in zip(given, FAST))
        super().__init__(env, a, lam, per, head_ratio)

    def reset(self) -> None:
        super().reset()
        self.filt: np.ndarray | None = None  # the filtered (sin, cos) of the heading error


def gait_stats(env: Any, params: tuple[float, float, float], seconds: float = 4.0,
               warmup: float = 1.5, seed: int = 0) -> dict[str, float]:  # fmt: skip
    """Speed [m/s] (centre-of-mass displacement from `warmup` to `seconds` / time), mean net
    muscle power [W] over the same window, slip U / c (c = lambda / T the commanded wave's
    speed), the Froude efficiency in the towed-body convention (`froude_efficiency`) and in
    Lighthill's elongated-body one, (1 + U / c) / 2 (`froude_lighthill`), of the wave
    (a, lambda / L, T) in `env` (reset with seed, heading 0, straight)."""
    ctrl = TravellingWave(env, *params)
    base = ctrl.base
    obs, info = env.reset(seed=seed, options={"heading": 0.0, "kappa": np.zeros(base.n_ctrl)})
    n_warm, n = round(warmup / ctrl.dt), round(seconds / ctrl.dt)
    start, net = None, 0.0
    for k in range(n):
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        if term or trunc:
            return {"speed": 0.0, "power": float("inf"), "slip": 0.0, "froude": 0.0,
                    "froude_lighthill": 0.0}  # fmt: skip
        if k + 1 == n_warm:
            start = (info["x"], info["y"])
        elif k + 1 > n_warm:
            net += info["actuation_net_work"]
    span = seconds - warmup
    speed = math.hypot(info["x"] - start[0], info["y"] - start[1]) / span
    power = net / span
    wave_speed = params[1] * base.scene.length / params[2]
    return {
        "speed": speed,
        "power": power,
        "slip": speed / wave_speed,
        "froude": froude_efficiency(base.scene, speed, power),
        "froude_lighthill": 0.5 * (1.0 + speed / wave_speed),
    }


def froude_efficiency(scene: Any, speed: float, power: float) -> float:
    """Useful power / power into the water in the towed-body convention: D(U) U / P, D(U) =
    (1/2 rho pi d C_T L + k_f) U^2 the drag of the straight body towed along its axis at the
    swimming speed U (Taylor's tangential law and the form drag, if on), P the mean net muscle
    power [W] (all of it goes to the water at a steady gait). Not comparable with Lighthill's
    elongated-body efficiency (1 + U / V) / 2, which counts only the reactive wake's loss
    (`gait_stats`' froude_lighthill, `gait_kinematics`)."""
    if power <= 0.0:
        return 0.0
    drag = (scene.water.k_tangential * scene.length + scene.water.k_form) * speed**2
    return drag * speed / power


def gait_kinematics(env: Any, kind: str | tuple = "wave", seconds: float = 6.0,
                    warmup: float = 3.0, seed: int = 0) -> dict[str, float]:  # fmt: skip
    """The swimming kinematics (`physics.swimmer.kinematics.body_kinematics`: tail-beat
    frequency and amplitude, wavelength, wave speed, slip, Strouhal number, Lighthill's
    efficiencies) of the baseline `kind` (or the wave (a, lambda / L, T)) in `env`, measured on
    its centreline nodes from `warmup` to `seconds` [s] after a reset with seed, heading 0 and
    a straight body."""
    from mf_envs.controllers import make_baseline
    from mf_envs.physics.swimmer.kinematics import body_kinematics

    base = env.unwrapped
    ctrl = make_baseline(env, kind) if isinstance(kind, str) else TravellingWave(env, *kind)
    ctrl.reset()
    obs, _ = env.reset(seed=seed, options={"heading": 0.0, "kappa": np.zeros(base.n_ctrl)})
    n_warm, n = round(warmup / base.control_dt), round(seconds / base.control_dt)
    rec: dict[str, list] = {"t": [], "p": [], "c": [], "a": [], "v": []}
    for k in range(n):
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        if term or trunc:
            raise ValueError("seconds: the run ended (failure or truncation) before it")
        if k + 1 >= n_warm:
            d, v = base.state
            rec["t"].append((k + 1) * base.control_dt)
            rec["p"].append(np.stack([d[0::6], d[2::6]], axis=1))
            rec["c"].append((info["x"], info["y"]))
            rec["a"].append(d[4])
            rec["v"].append((v[0], v[2]))
    arr = {key: np.array(val) for key, val in rec.items()}
    return body_kinematics(arr["t"], arr["p"], base.model.node_S, arr["c"], arr["a"], arr["v"])


def tune(env: Any, objective: str = "speed", x0: tuple = WAVE,
         max_evals: int = 60) -> tuple[tuple, dict]:  # fmt: skip
    """(a, lambda / L, T) maximising `gait_stats`' `objective` ("speed" or "froude") within
    BOUNDS (Nelder-Mead), and its stats."""
    res = minimize(lambda x: -gait_stats(env, tuple(x))[objective], np.array(x0, float),
                   method="Nelder-Mead", bounds=BOUNDS,
                   options={"maxfev": max_evals, "xatol": 1e-2, "fatol": 1e-6})  # fmt: skip
    x = tuple(float(v) for v in res.x)
    return x, gait_stats(env, x)


# the default is the strongest (closed loop: the start heading is random)
register(ENV_ID, "heading", HeadingWave, default=True)
register(ENV_ID, "wave", TravellingWave)
register(ENV_ID, "fast", lambda env, **kw: TravellingWave(env, *FAST, **kw))
register(ENV_ID, "efficient", lambda env, **kw: TravellingWave(env, *EFFICIENT, **kw))
register(ENV_ID, "eel", lambda env, **kw: TravellingWave(env, *EEL, **kw))


def main(argv: list[str] | None = None) -> None:
    """`--tune`: run `tune` for speed and for Froude efficiency on the default env."""
    env, args = tuning_cli(ENV_ID, __doc__, 60, argv)
    for name, x in (("WAVE", WAVE), ("FAST", FAST), ("EFFICIENT", EFFICIENT)):
        print(name, x, gait_stats(env, x))
    if args.tune:
        for objective in ("speed", "froude"):
            x, stats = tune(env, objective, max_evals=args.max_evals)
            print(objective, "->", tuple(round(c, 4) for c in x), stats)


if __name__ == "__main__":
    main()
