"""Serpenoid gaits for Serpentine-v0, driven through the env's action interface.

* `serpenoid`: Hirose's serpenoid curve kappa#(S, t) = a sin(2 pi (L - S) / lambda
  - w t) at the control points (the wave runs head to tail, the body crawls head first, as
  `physics.serpentine.gait.serpenoid(direction=-1)`), PyElastica's snake's numbers (a = 20 1/m,
  lambda = L, T = 2 s); the command of step k is the curve at the step's end, t = (k + 1) dt;
* `tuned`: the same curve with (a, lambda, T) optimised by scipy (Nelder-Mead, bounded) for
  the speed of the centre of mass on a short horizon (`tune`; the numbers are `TUNED`);
* `heading` (default, the strongest): the tuned serpenoid plus a curvature bias -gain x heading
  error, the error being the head's heading relative to the target direction (observed as sin,
  cos) low-pass filtered over one gait period (the head swings with the wave), so the snake
  arcs toward the target.

The open-loop gaits ignore the observation; `heading` reads only its heading slots.
"""

from __future__ import annotations

import argparse
import math
from typing import Any

import numpy as np
from scipy.optimize import minimize

from mf_envs._validate import check_range, positive_scalar
from mf_envs.controllers import register
from mf_envs.envs.serpentine.task import DECLARATION

ENV_ID = DECLARATION.env_id
ELASTICA = (20.0, 1.0, 2.0)  # a [1/m], lambda / L, T [s]: PyElastica's snake (~ its muscles)
# `python -m mf_envs.controllers.serpentine --tune` (default env, 8 s horizon, speed 2-8 s,
# Nelder-Mead from ELASTICA, 40 evaluations); stored at full precision: the speed is not smooth
# in the parameters (Newton's step splitting and stick-slip switch discretely), so rounding
# the optimum to 4 digits once cost 6 % (0.0469 -> 0.0440 m/s on the old env, measured).
# gait_speed 0.0598 m/s re-evaluated 2026-11-28 (ELASTICA: 0.0235); a and T sit on their bounds.
TUNED = (25.0, 1.0387002743484175, 1.0)
BOUNDS = ((5.0, 25.0), (0.5, 2.0), (1.0, 4.0))  # a [1/m], lambda / L, T [s]
# the gait PPO found (docs/serpentine.md, "What PPO found": every control point at 1.6 Hz,
# nearly in phase, at the action bounds a third of the time) as a serpenoid: a [1/m] (1.2
# max_curvature: saturated), wavenumber L / lambda (the wave head to tail), T [s]
PPO_LIKE = (30.0, 0.2, 0.625)
# PyElastica's example's muscle-torque spline coefficients [N m] (`ElasticaMuscles`)
ELASTICA_COEFFICIENTS = np.array([3.4e-3, 3.3e-3, 4.2e-3, 2.6e-3, 3.6e-3, 3.5e-3])


class Serpenoid:
    """kappa#(S_j, t) = a e(S_j) sin(2 pi q (L - S_j) / L - 2 pi t / T) + bias (module
    docstring), clipped to the action bounds; q = L / lambda the wavenumber (`wavenumber`, or
    1 / `wavelength` in body lengths): q > 0 the wave runs head to tail, q = 0 a standing wave
    (every point in phase), q < 0 tail to head. The envelope e(S) = r + (1 - r) (L - S) / L
    grows from r at the head to 1 at the tail (head_ratio r = 1: the uniform serpenoid); an
    amplitude above max_curvature saturates into a square-topped wave."""

    def __init__(self, env: Any, amplitude: float = ELASTICA[0], wavelength: float = ELASTICA[1],
                 period: float = ELASTICA[2], head_ratio: float = 1.0,
                 wavenumber: float | None = None) -> None:  # fmt: skip
        base = env.unwrapped
        self.base = base
        self.amplitude = check_range("amplitude", amplitude, 0.0, 1e3)
        self.period = positive_scalar("period", period)
        self.dt = float(base.control_dt)
        self.scale = 1.0 / float(base.max_curvature)
        s = np.linspace(0.0, 1.0, base.n_ctrl)  # S / L
        if wavenumber is None:  # divided by the wavelength: the baselines' bits as before
            self.phase = 2.0 * math.pi * (1.0 - s) / positive_scalar("wavelength", wavelength)
        else:
            q = check_range("wavenumber", wavenumber, -1e3, 1e3)  # L / lambda
            self.phase = 2.0 * math.pi * (1.0 - s) * q
        r = check_range("head_ratio", head_ratio, 0.0, 1.0)
        self.envelope = r + (1.0 - r) * (1.0 - s)  # exactly 1 for r = 1
        self.reset()

    def reset(self) -> None:
        self.k = 0

    def bias(self, obs: np.ndarray) -> float:
        """Curvature bias [1/m] (0: straight-line gait)."""
        del obs
        return 0.0

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        del deterministic
        self.k += 1
        t = self.k * self.dt
        wave = np.sin(self.phase - 2.0 * math.pi * t / self.period)
        kappa = self.amplitude * self.envelope * wave
        a = np.clip((kappa + self.bias(obs)) * self.scale, -1.0, 1.0)
        return a.astype(np.float32), None


class HeadingSerpenoid(Serpenoid):
    """The tuned serpenoid plus bias = -gain x filtered heading error, |bias| <= max_bias."""

    def __init__(self, env: Any, gain: float = 8.0, max_bias: float = 8.0,
                 amplitude: float = TUNED[0], wavelength: float = TUNED[1],
                 period: float = TUNED[2], head_ratio: float = 1.0,
                 wavenumber: float | None = None) -> None:  # fmt: skip
        self.gain = check_range("gain", gain, 0.0, 1e3)  # 1/m per rad
        self.max_bias = check_range("max_bias", max_bias, 0.0, 1e3)  # 1/m
        layout = env.unwrapped.obs_layout
        self.i_sin, self.i_cos = layout.index("sin_heading"), layout.index("cos_heading")
        super().__init__(env, amplitude, wavelength, period, head_ratio, wavenumber)

    def reset(self) -> None:
        super().reset()
        self.filt: np.ndarray | None = None

    def bias(self, obs: np.ndarray) -> float:
        sc = np.array([obs[self.i_sin], obs[self.i_cos]], float)
        if self.filt is None:
            self.filt = sc
        self.filt = self.filt + min(1.0, self.dt / self.period) * (sc - self.filt)
        err = math.atan2(self.filt[0], self.filt[1])
        return float(np.clip(-self.gain * err, -self.max_bias, self.max_bias))


class ElasticaMuscles:
    """PyElastica's continuum snake's muscle torques as the command (`preset="pyelastica"`):
    kappa#(S_j, t) = beta(s) sin(K s - w t) / EI at the control points (s = 1 - S / L, beta the
    spline of the example's coefficients, K = 2 pi / (wavelength L), w = 2 pi / period, ramped
    over one period: `physics.serpentine.gait.elastica_muscles`), the command of step k the
    muscles at the step's end, t = (k + 1) dt. Open loop; for the preset's scene."""

    def __init__(self, env: Any, wavelength: float = 1.0, period: float = 2.0) -> None:
        from mf_envs.physics.serpentine.gait import elastica_muscles

        base = env.unwrapped
        self.base, self.dt = base, float(base.control_dt)
        s_ctrl = np.linspace(0.0, base.scene.length, base.n_ctrl)[None, :]  # (1, n)
        wavelength = positive_scalar("wavelength", wavelength)
        period = positive_scalar("period", period)
        self.gait = elastica_muscles(s_ctrl, base.scene.length, base.model.params.EI,
                                     ELASTICA_COEFFICIENTS, wavelength, period, period)  # fmt: skip
        self.scale = 1.0 / float(base.max_curvature)
        self.reset()

    def reset(self) -> None:
        self.k = 0

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        del obs, deterministic
        self.k += 1
        a = np.clip(self.gait.kappa(self.k * self.dt)[0] * self.scale, -1.0, 1.0)
        return a.astype(np.float32), None


def gait_speed(env: Any, params: tuple[float, float, float], seconds: float = 8.0,
               warmup: float = 2.0, seed: int = 0) -> float:  # fmt: skip
    """Speed [m/s] of the centre of mass (|displacement| from `warmup` to `seconds`) of the
    serpenoid (a, lambda / L, T) in `env` (reset with seed, heading 0, no start noise)."""
    ctrl = Serpenoid(env, *params)
    obs, info = env.reset(seed=seed, options={"heading": 0.0, "kappa": np.zeros(ctrl.base.n_ctrl)})
    n_warm, n = round(warmup / ctrl.dt), round(seconds / ctrl.dt)
    start = None
    for k in range(n):
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        if term or trunc:
            return 0.0
        if k + 1 == n_warm:
            start = (info["x"], info["y"])
    return math.hypot(info["x"] - start[0], info["y"] - start[1]) / (seconds - warmup)


def tune(env: Any, x0: tuple = ELASTICA, max_evals: int = 40) -> tuple[tuple, float]:
    """(a, lambda / L, T) maximising `gait_speed` within BOUNDS (Nelder-Mead), and the speed."""
    res = minimize(lambda x: -gait_speed(env, tuple(x)), np.array(x0, float),
                   method="Nelder-Mead", bounds=BOUNDS,
                   options={"maxfev": max_evals, "xatol": 1e-2, "fatol": 1e-5})  # fmt: skip
    return tuple(float(v) for v in res.x), float(-res.fun)


# the default is the strongest on the default scene (the start heading is
# random, so the open-loop gaits crawl off target): `mf-envs evaluate`, seeds 1000-1004, speed
# heading 0.0581, tuned 0.0137, serpenoid 0.0051 m/s
register(ENV_ID, "heading", HeadingSerpenoid, default=True)
register(ENV_ID, "serpenoid", Serpenoid)
register(ENV_ID, "tuned", lambda env, **kw: Serpenoid(env, *TUNED, **kw))
register(ENV_ID, "elastica_muscles", ElasticaMuscles)


def tuning_cli(env_id: str, doc: str, max_evals: int, argv: list[str] | None) -> tuple:
    """A gait module's command line: `--tune` (run its tuner), `--max-evals` (default
    `max_evals`); returns the default env of `env_id` and the parsed arguments."""
    import gymnasium as gym

    import mf_envs  # noqa: F401  (registers the envs)

    parser = argparse.ArgumentParser(description=doc.split("\n")[0])
    parser.add_argument("--tune", action="store_true")
    parser.add_argument("--max-evals", type=int, default=max_evals)
    args = parser.parse_args(argv)
    return gym.make(env_id), args


def main(argv: list[str] | None = None) -> None:
    """`--tune`: run `tune` on the default env and print the constants."""
    env, args = tuning_cli(ENV_ID, __doc__, 40, argv)
    print("elastica", ELASTICA, "speed", gait_speed(env, ELASTICA))
    print("stored TUNED", TUNED, "speed", gait_speed(env, TUNED))
    if args.tune:
        x, v = tune(env, max_evals=args.max_evals)
        print("TUNED =", tuple(x), "speed", v)  # full precision (see TUNED)


if __name__ == "__main__":
    main()
