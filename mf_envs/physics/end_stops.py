"""Cushioned end stops of a gimbal (physics only): one law for every gyro machine.

A cushion (spring-damper) engages at +-a_s and pushes only, never pulling the gimbal back into
the stop (the ship stabilizer's precession brake, `ship.brake`, and drives, `ship.drive`; the
floating GOWEC's gimbal, `gowec.hydro.floating`):

    tau_s = -sign(a) max(0, k_s d + c_s d'),  d = |a| - a_s > 0 (the penetration).

`size_cushion` sizes k_s so that a gimbal of inertia J_g reaching the stop at rate v, driven
over the penetration by a gyroscopic torque of at most H p, stops within d_max:
k_s d_max^2 / 2 = J_g v^2 / 2 + H p d_max (damping only helps), c_s = 2 zeta sqrt(k_s J_g).
"""

from __future__ import annotations

import math

from mf_envs._jit import kernel


@kernel(forceinline=True)
def cushion_torque(a: float, ad: float, a_s: float, k_s: float, c_s: float) -> float:
    """tau_s (N m) of the cushioned stops at gimbal angle a (rad) and rate ad (rad/s), engaging
    at +-a_s (rad) with stiffness k_s (N m/rad) and damping c_s (N m s/rad) (module doc)."""
    d = abs(a) - a_s
    if d <= 0.0:
        return 0.0
    s = 1.0 if a > 0.0 else -1.0
    return -s * max(0.0, k_s * d + c_s * s * ad)


@kernel(forceinline=True)
def cushion_spring_energy(a: float, a_s: float, k_s: float) -> float:
    """Energy (J) held in the cushion's spring at gimbal angle a (rad): k_s d^2 / 2, d > 0."""
    d = abs(a) - a_s
    return 0.5 * k_s * d * d if d > 0.0 else 0.0


def size_cushion(
    gimbal_inertia: float,
    contact_rate: float,
    angular_momentum: float,
    hull_rate: float,
    max_penetration: float,
    damping_ratio: float,
) -> tuple[float, float]:
    """(k_s N m/rad, c_s N m s/rad) of a cushion that stops a gimbal of inertia J_g (kg m^2)
    meeting it at rate v (rad/s) within d_max (rad) against a gyroscopic torque of at most
    H p (rotor H in N m s, hull rate p in rad/s) (module doc)."""
    jg, v, h, p, d = gimbal_inertia, contact_rate, angular_momentum, hull_rate, max_penetration
    ks = (jg * v * v + 2.0 * h * p * d) / (d * d)
    return ks, 2.0 * damping_ratio * math.sqrt(ks * jg)
