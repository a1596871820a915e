"""Baselines for FloatingGOWEC-v0: PLL and square wave on the measured (floating) buoy motion,
and the matched linear PTO.

- `pll`, `bang_bang`: GOWEC-v0's controllers (`controllers.gowec`) unchanged: they read the same
  observation slots (gimbal encoder, buoy IMU rate w1) and the device's own rotor and gimbal
  (`env.unwrapped.model.inert`, `.psid`). On the floating buoy the rate they lock to is the
  buoy's actual motion, which the gyro's reaction changes.
- `linear_pto`: the classical impedance match (issue 14). With the gimbal as a linear load
  Z_g = c + i (w I_g - k / w) the gyro presents H^2 / Z_g to the hull; matching it to the
  conjugate of the hull's pitch impedance Z_h = R + i X_h, R = B(w) + b_v (radiation + viscous),
  X_h = w (I + A(w)) - C / w, gives (n = gyro_units in parallel: load n H^2 / Z_g)

      c* = n H^2 R / |Z_h|^2,     k* = w^2 I_g - w n H^2 X_h / |Z_h|^2

  and the absorbed power |M_ex|^2 / (8 R). The gains are set once on the drive's inner loop
  (`env.unwrapped.set_pto`, evaluated every physics substep); the torque command is 0.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mf_envs.controllers import register
from mf_envs.controllers.gowec import PLLController, SquareWaveController
from mf_envs.envs.gowec_v1.task import DECLARATION

ENV_ID = DECLARATION.env_id


def matched_pto(env: Any, period: float | None = None) -> tuple[float, float]:
    """(c*, k*) (N m s/rad, N m/rad) for the env's hull and gyro at `period` (default: the
    env's wave/peak period); module docstring."""
    raw = env.unwrapped
    w = 2.0 * math.pi / float(raw.wave_period if period is None else period)
    hull, p = raw.hull, raw.model.p
    A, B, _ = hull.at(w)
    R = B + p.viscous
    Xh = w * (raw.model.pitch_inertia() + A) - hull.stiffness / w
    H2 = raw.model.units * (p.gyro[0] * p.psid) ** 2  # n units in parallel: n H^2 / Z_g
    Ig = p.gyro[1] + p.gyro[3]
    Z2 = R * R + Xh * Xh
    return H2 * R / Z2, w * w * Ig - w * H2 * Xh / Z2


class LinearPTOController:
    """Sets the matched (c*, k*) on the drive at reset; commands zero extra torque."""

    def __init__(self, env: Any, period: float | None = None) -> None:
        self.env = env
        self.c, self.k = matched_pto(env, period)
        self.reset()

    def reset(self) -> None:
        self.env.unwrapped.set_pto(self.c, self.k)

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return np.zeros(1, dtype=np.float32), None


register(ENV_ID, "pll", PLLController, default=True)
register(ENV_ID, "bang_bang", SquareWaveController)
register(ENV_ID, "linear_pto", LinearPTOController)
