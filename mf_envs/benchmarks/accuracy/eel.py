"""Work-precision of Eel-v0's swimmer (`physics.swimmer`): error vs wall seconds of the env
itself (its compiled step, the `wave` baseline's commands, 4 s from rest, heading 0).

Scenes (the `dt` column is the refinement parameter named in `param`):
- `eel_physics_dt`: physics_dt = control_dt / 1, 2, 4, 8, 16 at the default control_dt = 0.02 s
  and 6 elements, for numerical_damping 0.1 (the default) and 0 (the energy-conserving
  scheme); error = |mean speed from 1.5 to 4 s - reference| / reference, the reference being
  the same damping at control_dt / REFERENCE_SUBSTEPS (256; the commands are the same for every
  row: the error is the time integration's; the end point's distance to the reference's, / L,
  is the column `position_error`). The reference's own error is estimated by the run at half
  its substeps (control_dt / 128): columns `reference_speed_change` and
  `reference_position_change` (relative speed change and end-point gap / L between the two).
  The speed scatters by ~1 % at every step: the rate-limited commands' corners excite the shear
  and axial modes (periods below 1 ms, resolved by no step here), whose aliasing differs from
  step to step.
- `eel_elements`: n_elements = 3, 4, 6, 8, 12 at the default steps; error = |mean speed from
  1.5 to 4 s - the 24-element speed| / that speed; param h = L / n_el.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mf_envs.benchmarks._io import accuracy_row, timed

ORDER = 60
REFERENCE_SUBSTEPS = 256  # physics steps per control step of the physics_dt scene's reference
SECONDS, WARMUP = 4.0, 1.5


def _swim(**kw: Any) -> tuple[np.ndarray, float]:
    """(centre of mass at SECONDS [m], mean speed over [WARMUP, SECONDS] [m/s]) of the `wave`
    baseline in Eel-v0(**kw)."""
    import gymnasium as gym

    import mf_envs  # noqa: F401  (registers the envs)
    from mf_envs.controllers.eel import TravellingWave

    env = gym.make("Eel-v0", **kw)
    ctrl = TravellingWave(env)
    base = env.unwrapped
    obs, info = env.reset(seed=0, options={"heading": 0.0, "kappa": np.zeros(base.n_ctrl)})
    start = None
    for k in range(round(SECONDS / base.control_dt)):
        obs, _, term, _, info = env.step(ctrl.predict(obs)[0])
        if term:
            raise RuntimeError(f"Eel-v0 {kw}: numerical failure at step {k}")
        if abs((k + 1) * base.control_dt - WARMUP) < 1e-9:
            start = info["x"], info["y"]
    end = np.array([info["x"], info["y"]])
    return end, float(np.hypot(*(end - start)) / (SECONDS - WARMUP))


def _physics_dt(quick: bool) -> list[dict]:
    rows = []
    control = 0.02
    for damping in (0.1, 0.0):
        ref, ref_speed = _swim(physics_dt=control / REFERENCE_SUBSTEPS, numerical_damping=damping)
        half, half_speed = _swim(physics_dt=2 * control / REFERENCE_SUBSTEPS,
                                 numerical_damping=damping)  # fmt: skip
        ref_check = {
            "reference_speed_change": abs(half_speed - ref_speed) / ref_speed,
            "reference_position_change": float(np.linalg.norm(half - ref) / 0.2),
        }
        for n_sub in (1, 2, 4) if quick else (1, 2, 4, 8, 16):
            (end, speed), sec = timed(_swim, physics_dt=control / n_sub, numerical_damping=damping)
            err = abs(speed - ref_speed) / ref_speed
            gap = float(np.linalg.norm(end - ref) / 0.2)
            rows.append(accuracy_row("eel_physics_dt", f"numerical_damping {damping:g}",
                                     control / n_sub, err, sec, "physics_dt [s]", speed=speed,
                                     reference_speed=ref_speed, position_error=gap,
                                     **ref_check))  # fmt: skip
    return rows


def _elements(quick: bool) -> list[dict]:
    _, ref = _swim(n_elements=24)
    rows = []
    for n_el in (3, 4, 6) if quick else (3, 4, 6, 8, 12):
        (_, speed), sec = timed(_swim, n_elements=n_el)
        rows.append(accuracy_row("eel_elements", "energy-momentum", 0.2 / n_el,
                                 abs(speed - ref) / ref, sec, "h = L / n_el [m]",
                                 speed=speed, reference_speed=ref))  # fmt: skip
    return rows


def rows(quick: bool) -> list[dict]:
    return _physics_dt(quick) + _elements(quick)
