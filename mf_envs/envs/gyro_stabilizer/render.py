"""Frames of GyroStabilizer-v0: the hull rolling with its gyro(s), gimbal and rotor."""

from __future__ import annotations

import math

import numpy as np

from mf_envs.physics.ship import kernels as K


def draw(R: np.ndarray, phi: float, t: float, rotor_speed: float, n_gyros: int, note: str = ""):
    """The frame (H, W, 3) uint8 of attitude R, gimbal angle phi (rad) at time t (s); a pair of
    gyros counter-rotates (gimbal and rotor angles mirrored)."""
    from mf_envs.render import draw_ship

    psi = math.fmod(rotor_speed * t, 2.0 * math.pi)
    angles = (phi,) if n_gyros == 1 else (phi, -phi)
    rotors = (psi,) if n_gyros == 1 else (psi, -psi)
    roll = math.degrees(K.roll_of(R))
    return draw_ship(
        ship_R=R.copy(),
        gimbal_angles=angles,
        rotor_angles=rotors,
        text=f"t = {t:5.2f} s  roll = {roll:+5.1f} deg  "
        f"gimbal = {math.degrees(phi):+5.1f} deg{note}",
    )
