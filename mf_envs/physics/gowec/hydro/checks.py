"""Checks of BEM coefficients against physics no solver run decides (used by the tests and docs).

- Haskind (Newman 1962): for an axisymmetric hull in deep water the pitch excitation pattern is
  |X(beta)| = |X| |cos beta|, and B55 = k / (8 pi rho g c_g) int |X(beta)|^2 dbeta
  = k |X|^2 / (8 rho g c_g), c_g = g / (2 w).
- Kramers-Kronig (causality of K(t)): A(w) - A_inf = (2/pi) PV int_0^inf B(s) / (s^2 - w^2) ds.
  The table stops at w_max, so the check uses differences A(w) - A(w_ref), whose kernel decays
  like s^-4 (the truncated tail then matters little at w << w_max).
- Hydrostatics: C55 = rho g (I_wp + V z_B) - m g z_G from the geometry (`CylinderHull`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import quad
from scipy.interpolate import CubicSpline

from mf_envs.physics.gowec.hydro import HullCoefficients


def haskind_damping(h: HullCoefficients) -> NDArray[np.float64]:
    """B55 (n,) N m s/rad predicted from |X| by the Haskind relation (deep water)."""
    k = h.omega**2 / h.g
    cg = h.g / (2.0 * h.omega)
    return k * np.abs(h.excitation) ** 2 / (8.0 * h.rho * h.g * cg)


def kramers_kronig_added_mass(h: HullCoefficients, w: NDArray, w_ref: float) -> NDArray:
    """A(w) - A(w_ref) (kg m^2) from the damping table by the Kramers-Kronig relation."""
    Bs = CubicSpline(h.omega, h.damping)
    top = float(h.omega[-1])

    def pv(x: float) -> float:  # PV int_0^top B(s) / ((s - x)(s + x)) ds
        return quad(lambda s: Bs(s) / (s + x), 0.0, top, weight="cauchy", wvar=x, limit=400)[0]

    ref = pv(w_ref)
    return np.array([2.0 / np.pi * (pv(float(x)) - ref) for x in w])
