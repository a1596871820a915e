"""Closed-form results the swimmer is checked against (tests/test_swimmer.py, docs/eel.md).

* `coasting_speed`: a rigid straight body of mass M per length moving along one of its axes in
  water at rest under the quadratic law g(V) = k |V| V only: M dV/dt = -k |V| V, so
  V(t) = V0 / (1 + k |V0| t / M) (M = m_A + m_a across the body with the added mass).
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


def taylor_small_amplitude_speed(length: float, wavenumber: float, omega: float,
                                 amplitude: float, c_t: float, c_n: float) -> float:  # fmt: skip
    """Mean speed along +s [m/s] of kappa = a sin(k s - w t) under the linear law (c_t, c_n
    [N s/m^2]) on a body of length L [m] (module docstring)."""
    return viscous_wave_speed(length, wavenumber, omega, amplitude, c_t, c_n)


def lighthill_thrust(added_mass: float, h_t: np.ndarray, h_x: np.ndarray, speed: float) -> float:
    """Lighthill's mean thrust [N]: m_a / 2 mean(h_t^2 - U^2 h_x^2) of samples over whole
    periods of the lateral velocity h_t [m/s] and slope h_x at the tail; m_a [kg/m], U [m/s]."""
    return 0.5 * added_mass * float(np.mean(np.asarray(h_t) ** 2 - speed**2 * np.asarray(h_x) ** 2))
