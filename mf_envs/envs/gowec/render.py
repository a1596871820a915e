"""Frames of the GOWEC envs (v0 and v1): buoy, gimbal and rotor riding the wave profile."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from mf_envs.physics import waves


def wave_frame(
    wave: waves.WaveField,
    t: float,
    wave_period: float,
    wave_direction: float,
    buoy_R: ArrayLike,
    gimbal_angle: float,
    spin: float,
    buoy_radius: float,
    text: str,
    half_width: float | None = None,
    buoy_plan: tuple[float, float] | None = None,
) -> np.ndarray:
    """One frame (H, W, 3) uint8 of `mf_envs.render.draw_gowec`: the elevation profile of `wave`
    at time t (s) over +-`half_width` m (default: one wavelength of `wave_period`) along
    `wave_direction` (rad), the buoy at attitude buoy_R (3, 3), gimbal angle (rad), rotor angle
    spin t (spin rad/s), buoy radius (m, 0 = the renderer's default), a box hull's plan
    (`draw_gowec`'s `buoy_plan`)."""
    from mf_envs.render import draw_gowec

    lam = float(waves.wavelength(wave_period)) if half_width is None else half_width
    x = np.linspace(-lam, lam, 121)
    c, s = math.cos(wave_direction), math.sin(wave_direction)
    return draw_gowec(
        buoy_R=buoy_R,
        gimbal_angle=float(gimbal_angle),
        rotor_angle=math.fmod(spin * t, 2 * math.pi),
        wave_x=x,
        wave_z=wave.elevation(t, x * c, x * s),
        wave_direction=wave_direction,
        buoy_radius=buoy_radius if buoy_radius > 0 else None,
        buoy_plan=buoy_plan,
        text=text,
    )
