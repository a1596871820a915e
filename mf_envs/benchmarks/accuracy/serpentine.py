"""Work-precision of the serpentine beam: elements x time step against a converged run.

Scenes (`dt` = the physics step [s], `method` = the number of elements):
- `serpentine_elastica`: PyElastica's continuum snake in our model (`speed.snake_elastica.snake`:
  its rod, muscles, anisotropic Coulomb friction and damper equivalents), error = relative
  difference of the mean forward speed over periods 5-11 from the converged run
  (`speed.snake_elastica.CONVERGED`: 40 elements, dt = 2.5 ms); quick: a 3 x 2 grid against
  20 elements, 5 ms.
- `serpentine_env`: Serpentine-v0's physics at its defaults (Kelvin-Voigt body, lagged muscles,
  slip speed 1 mm/s) driven by the `serpenoid` baseline from rest, error = relative difference
  of the centre-of-mass speed over 4-10 s from 24 elements at dt = 2.5 ms (quick: 12 elements,
  5 ms); `seconds` = the 10 s episode's CPU time.
- `serpentine_saturated`: the same with the fast, saturated, nearly in-phase gait PPO found
  (`controllers.serpentine.PPO_LIKE` as an open-loop serpenoid) against 48 elements at
  1.5625 ms (quick: 24 elements, 1.5625 ms). With the first, the table behind the env's
  n_elements = 12, physics_dt = 3.125 ms (docs/serpentine.md, "What accuracy costs in time").
"""

from __future__ import annotations

import math
import time

from mf_envs.benchmarks._io import accuracy_row
from mf_envs.benchmarks.speed import snake_elastica as se

ORDER = 45


def _elastica(quick: bool) -> list[dict]:
    ref_n, ref_dt = (20, 0.005) if quick else se.CONVERGED
    grid = [(n, dt) for n in ((4, 6, 10) if quick else (4, 6, 10, 20)) for dt in
            ((0.02, 0.01) if quick else (0.04, 0.02, 0.01, 0.005))]  # fmt: skip
    t, com, _, _ = se.run_ours(ref_n, ref_dt)
    v_ref = se.forward_speed(t, com)
    out = []
    for n, dt in grid:
        try:
            t, com, wall, its = se.run_ours(n, dt)
        except Exception as exc:  # noqa: BLE001  (a failed setting is a row, not a crash)
            out.append(accuracy_row("serpentine_elastica", f"n_el={n}", dt, math.nan, math.nan,
                                    "dt [s]", failed=str(exc)[:60]))  # fmt: skip
            continue
        v = se.forward_speed(t, com)
        out.append(accuracy_row("serpentine_elastica", f"n_el={n}", dt, abs(v - v_ref) / v_ref,
                                wall, "dt [s]", speed_mm_s=1e3 * v,
                                reference_speed_mm_s=1e3 * v_ref,
                                reference=f"n_el={ref_n} dt={ref_dt:g}",
                                newton_per_step=its / (se.N_PERIODS * se.PERIOD / dt)))  # fmt: skip
    return out


def env_speed(n_elements: int, physics_dt: float, gait: str = "serpenoid") -> tuple[float, float]:
    """(speed over 4-10 s [m/s], CPU seconds) of Serpentine-v0 (defaults otherwise) from rest
    under the `serpenoid` baseline (`gait="serpenoid"`) or the open-loop `PPO_LIKE` serpenoid
    (`gait="saturated"`), 10 s at control_dt = 50 ms (physics_dt rounded to divide it)."""
    import gymnasium as gym
    import numpy as np

    import mf_envs  # noqa: F401
    from mf_envs.controllers import make_baseline
    from mf_envs.controllers.serpentine import PPO_LIKE, Serpenoid

    env = gym.make("Serpentine-v0", n_elements=n_elements, physics_dt=physics_dt,
                   episode_seconds=10.0)  # fmt: skip
    u = env.unwrapped
    obs, _ = env.reset(seed=0, options={"heading": 0.0, "kappa": np.zeros(u.n_ctrl)})
    if gait == "saturated":
        a, q, period = PPO_LIKE
        ctrl = Serpenoid(env, amplitude=a, wavenumber=q, period=period)
    else:
        ctrl = make_baseline(env, gait)
    start, t0 = None, time.process_time()
    for k in range(1, u.max_steps + 1):
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        if term:
            raise RuntimeError(f"numerical failure at step {k}")
        if k == round(4.0 / u.control_dt):
            start = (info["x"], info["y"])
    cpu = time.process_time() - t0
    return math.hypot(info["x"] - start[0], info["y"] - start[1]) / 6.0, cpu


def _env(quick: bool, gait: str = "serpenoid") -> list[dict]:
    scene = "serpentine_env" if gait == "serpenoid" else "serpentine_" + gait
    if gait == "serpenoid":
        ref_n, ref_dt = (12, 0.005) if quick else (24, 0.0025)
    else:
        ref_n, ref_dt = (24, 0.0015625) if quick else (48, 0.0015625)
    grid = [(n, dt) for n in ((6, 12) if quick else (4, 6, 8, 12, 24)) for dt in
            ((0.025, 0.003125) if quick else (0.05, 0.025, 0.0125, 0.00625, 0.003125))]  # fmt: skip
    env_speed(4, 0.05)  # compile / warm
    v_ref, _ = env_speed(ref_n, ref_dt, gait)
    out = []
    for n, dt in grid:
        v, cpu = env_speed(n, dt, gait)
        out.append(accuracy_row(scene, f"n_el={n}", dt, abs(v - v_ref) / v_ref, cpu,
                                "physics_dt [s]", speed_mm_s=1e3 * v,
                                reference_speed_mm_s=1e3 * v_ref,
                                reference=f"n_el={ref_n} dt={ref_dt:g}"))  # fmt: skip
    return out


def rows(quick: bool) -> list[dict]:
    return _elastica(quick) + _env(quick) + _env(quick, "saturated")
