"""Frames of GOWEC-v1: the floating buoy pitching in the wave with its gimbal and rotor."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mf_envs.physics import waves


def draw_frame(env: Any) -> np.ndarray:
    """The current frame (H, W, 3) uint8 of a GOWECV1Env (`mf_envs.render.draw_gowec`)."""
    from mf_envs.render import draw_gowec

    lam = float(waves.wavelength(env.wave_period))
    x = np.linspace(-lam, lam, 121)
    c, s = math.cos(env.wave_direction), math.sin(env.wave_direction)
    z = env.wave.elevation(env._t, x * c, x * s)
    R = waves.buoy_rotation(float(env.state[0]), 0, 0, float(env.state[1]), 0, 0)[0]
    psi = math.fmod(env.model.psid * env._t, 2 * math.pi)
    phi = math.remainder(float(env.state[2]), 2 * math.pi)
    return draw_gowec(
        buoy_R=R,
        gimbal_angle=float(env.state[2]),
        rotor_angle=psi,
        wave_x=x,
        wave_z=z,
        wave_direction=env.wave_direction,
        buoy_radius=env.buoy_radius or None,
        text=f"t = {env._t:5.1f} s  pitch = {env.state[0]:+.2f} rad  phi = {phi:+.2f} rad"
        f"  P = {env._last_power / 1e3:.2f} kW",
    )
