"""Frames of FloatingGOWEC-v0: the floating buoy pitching in the wave with its gimbal and rotor."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mf_envs.envs.gowec.render import wave_frame
from mf_envs.physics import waves
from mf_envs.physics.gowec.hydro import axes


def draw_frame(env: Any) -> np.ndarray:
    """The current frame (H, W, 3) uint8 of a GOWECV1Env (`wave_frame`)."""
    y = env.state
    R = waves.buoy_rotation(float(y[0]), 0, 0, float(y[1]), 0, 0)[0]
    phi = math.remainder(float(y[2]), 2 * math.pi)
    text = f"t = {env._t:5.1f} s  pitch = {y[0]:+.2f} rad  phi = {phi:+.2f} rad"
    text += f"  P = {env._last_power / 1e3:.2f} kW"
    # the real hull to scale: a window of a quarter wavelength (at least 5 radii) each side,
    # so the 5 m buoy is not a few pixels on a 110 m strip of a 6 s wave
    plan = axes.plan(env.model.three)  # a box: (length, beam), its length along e2
    r = env.buoy_radius or (0.5 * plan[0] if plan else 0.0)
    half = max(0.25 * float(waves.wavelength(env.wave_period)), 5.0 * r) if r > 0 else None
    return wave_frame(
        env.wave, env._t, env.wave_period, env.wave_direction, R, float(y[2]), env.model.psid,
        r, text, half_width=half, buoy_plan=plan,
    )  # fmt: skip
