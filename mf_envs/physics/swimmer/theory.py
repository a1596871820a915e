"""Closed-form results the swimmer is checked against (tests/test_swimmer.py, docs/eel.md).

* `coasting_speed`: a rigid straight body of mass M per length moving along one of its axes in
  water at rest under the quadratic law g(V) = k |V| V only: M dV/dt = -k |V| V, so
  V(t) = V0 / (1 + k |V0| t / M) (M = m_A + m_a across the body with the added mass).
* `coasting_distance`: the distance a body of mass M coasts along its axis while it slows from
  V0 to V1 under a linear and a quadratic drag, M dV/dt = -a V - b V^2: with dx = V dt,
  x = (M / b) ln((a + b V0) / (a + b V1)) (b > 0), (M / a)(V0 - V1) (b = 0); with a = 0,
  (M / b) ln(V0 / V1), which grows without bound as V1 -> 0 (quadratic drag alone never stops
  a body), and with a > 0 the whole glide is (M / b) ln(1 + b V0 / a).
* `taylor_small_amplitude_speed`: the linear (resistive-force) law's swimming speed of a small
  travelling curvature wave on a finite, inertia-free body with its recoil, U = (c_n / c_t - 1)
  < int Y' Y_dot ds > / L (Taylor 1952 for waving cylinders; the derivation and its quadrature
  are `serpentine.theory.viscous_wave_speed`, whose ground law is the same linear law).
* `lighthill_thrust`: Lighthill's (1960) mean thrust of a prescribed small-amplitude lateral
  motion h(x, t) of a body swimming at U, m_a / 2 < h_t^2 - U^2 h_x^2 > at the trailing edge.
"""

from __future__ import annotations

import numpy as np

from mf_envs._validate import check_positive
from mf_envs.physics.serpentine.theory import viscous_wave_speed


def coasting_speed(v0: float, t: np.ndarray, k: float, mass_per_length: float) -> np.ndarray:
    """V(t) [m/s] of M dV/dt = -k |V| V from V0 (module docstring); k [kg/m^2], M [kg/m]."""
    check_positive("mass_per_length", mass_per_length)
    return v0 / (1.0 + k * abs(v0) * np.asarray(t, float) / mass_per_length)


def coasting_distance(v0: float, v1: float, mass: float, linear: float, quadratic: float) -> float:
    """Distance [m] a body of mass M [kg] coasts while slowing from V0 to V1 (0 <= V1 < V0)
    [m/s] under M dV/dt = -a V - b V^2, a = `linear` [kg/s], b = `quadratic` [kg/m] (module
    docstring)."""
    check_positive("mass", mass)
    if not 0.0 <= v1 < v0:
        raise ValueError(f"v1: must be in [0, v0), got {v1!r} with v0 = {v0!r}")
    a, b = float(linear), float(quadratic)
    if a < 0.0 or b < 0.0 or a + b == 0.0:
        raise ValueError("linear, quadratic: must be >= 0 and not both 0")
    if b == 0.0:
        return mass * (v0 - v1) / a
    if a == 0.0 and v1 == 0.0:
        return float("inf")
    return mass / b * float(np.log((a + b * v0) / (a + b * v1)))


def taylor_small_amplitude_speed(length: float, wavenumber: float, omega: float,
                                 amplitude: float, c_t: float, c_n: float) -> float:  # fmt: skip
    """Mean speed along +s [m/s] of kappa = a sin(k s - w t) under the linear law (c_t, c_n
    [N s/m^2]) on a body of length L [m] (module docstring)."""
    return viscous_wave_speed(length, wavenumber, omega, amplitude, c_t, c_n)


def lighthill_thrust(added_mass: float, h_t: np.ndarray, h_x: np.ndarray, speed: float) -> float:
    """Lighthill's mean thrust [N]: m_a / 2 mean(h_t^2 - U^2 h_x^2) of samples over whole
    periods of the lateral velocity h_t [m/s] and slope h_x at the tail; m_a [kg/m], U [m/s]."""
    return 0.5 * added_mass * float(np.mean(np.asarray(h_t) ** 2 - speed**2 * np.asarray(h_x) ** 2))
