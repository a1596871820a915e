"""Checks of BEM coefficients against physics no solver run decides (used by the tests and docs).

- Haskind (Newman 1962): for an axisymmetric hull in deep water the pitch excitation pattern is
  |X(beta)| = |X| |cos beta|, and B55 = k / (8 pi rho g c_g) int |X(beta)|^2 dbeta
  = k |X|^2 / (8 rho g c_g), c_g = g / (2 w).
- Kramers-Kronig (causality of K(t)): A(w) - A_inf = (2/pi) PV int_0^inf B(s) / (s^2 - w^2) ds.
  The table stops at w_max, so the check uses differences A(w) - A(w_ref), whose kernel decays
  like s^-4 (the truncated tail then matters little at w << w_max).
- Haskind for surge/heave/pitch in finite depth (`haskind_matrix`) and the largest power the
  three modes absorb together (`max_absorbed_power`; for an axisymmetric hull 3 lambda J / 2 pi:
  lambda J / 2 pi in heave, lambda J / pi in surge and pitch together; Newman 1976, Evans 1976).
- Hydrostatics: C55 = rho g (I_wp + V z_B) - m g z_G from the geometry (`CylinderHull`,
  `BoxHull`).
- Haskind for any hull with the xOz and yOz mirror planes (`haskind_headings`, the box): the
  angular integral of X_i(beta) conj(X_j(beta)) over the whole circle, from the excitation at
  headings over 0..pi/2 and the modes' mirror parities.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray
from scipy.integrate import quad
from scipy.interpolate import CubicSpline

from mf_envs.physics.gowec.hydro import HullCoefficients
from mf_envs.physics.gowec.hydro.three_dof import ThreeDofCoefficients


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


# Far-field patterns of an axisymmetric hull's modes (surge, heave, pitch): X_i(beta) =
# X_i p_i(beta) with p = cos, 1, cos, so int_0^2pi p_i p_j dbeta is pi, 2 pi, pi on the diagonal,
# pi between surge and pitch, 0 between heave and the others.
PATTERN_INTEGRALS = np.array([[np.pi, 0.0, np.pi], [0.0, 2.0 * np.pi, 0.0], [np.pi, 0.0, np.pi]])


def haskind_matrix(h: ThreeDofCoefficients) -> NDArray[np.float64]:
    """B_ij (n, 3, 3) from the excitation by the Haskind relation in finite depth (Newman 1962;
    Falnes 2002 ch. 5): B_ij = k / (8 pi rho g c_g) Re int X_i(beta) conj(X_j(beta)) dbeta,
    c_g the finite-depth group velocity."""
    X = h.excitation
    c = h.wavenumber / (8.0 * np.pi * h.rho * h.g * h.group_velocity)
    return c[:, None, None] * PATTERN_INTEGRALS * np.real(X[:, :, None] * np.conj(X[:, None, :]))


def max_absorbed_power(h: ThreeDofCoefficients, rcond: float = 0.05) -> NDArray[np.float64]:
    """Largest mean power (W per m^2 of wave amplitude) the three modes together can absorb from
    a regular head wave, 1/8 X^H B^+ X (Falnes 2002 ch. 6, optimal velocities u = B^+ X / 2),
    at each frequency. Surge and pitch radiate the same cos(beta) pattern, so by Haskind their
    2 x 2 damping block has rank one (the combination that moves a non-radiating point). B is
    scaled to unit diagonal, D^-1/2 B D^-1/2, whose eigenvalues are then ~1 (heave), ~2 and ~0
    (surge-pitch); the pseudo-inverse drops those below rcond, the ~0 one's mesh error."""
    out = np.empty(h.omega.size)
    for n in range(h.omega.size):
        Bn = 0.5 * (h.damping[n] + h.damping[n].T)
        s = 1.0 / np.sqrt(np.diag(Bn))
        Bp = np.linalg.pinv(Bn * np.outer(s, s), rcond=rcond, hermitian=True)
        X = h.excitation[n] * s
        out[n] = 0.125 * float(np.real(np.conj(X) @ Bp @ X))
    return out


# Mirror parities of modes 1..5 (surge, sway, heave, roll, pitch): the sign a mode's motion takes
# under y -> -y (the xOz plane) and under x -> -x (yOz). A body with both planes then has
# X_i(-beta) = s_y X_i(beta) and X_i(pi - beta) = s_x X_i(beta) (Newman 1977 ch. 6 for the
# reflection argument).
MIRROR_PARITY_Y = np.array([1.0, -1.0, 1.0, -1.0, 1.0])
MIRROR_PARITY_X = np.array([-1.0, 1.0, 1.0, 1.0, -1.0])


def full_circle(headings: NDArray, X: NDArray) -> tuple[NDArray, NDArray]:
    """Headings (m,) evenly spaced over 0..pi/2 and X (n, m, 5) of modes 1..5 -> the 4(m - 1)
    headings k pi / (2 (m - 1)) over [0, 2 pi) and X (n, 4(m - 1), 5) there, by the mirror
    parities (`MIRROR_PARITY_Y`, `MIRROR_PARITY_X`). ValueError unless 0..pi/2 evenly."""
    b = np.asarray(headings, dtype=float)
    m = b.size
    if m < 2 or not np.allclose(b, np.linspace(0.0, 0.5 * np.pi, m), rtol=0, atol=1e-12):
        raise ValueError("headings: expected evenly spaced 0..pi/2")
    upper = np.concatenate((X, MIRROR_PARITY_X * X[:, -2::-1]), axis=1)  # 0..pi, 2m - 1
    full = np.concatenate((upper, MIRROR_PARITY_Y * upper[:, -2:0:-1]), axis=1)
    return np.arange(full.shape[1]) * (b[1] - b[0]), full


def haskind_headings(h: ThreeDofCoefficients) -> NDArray[np.float64]:
    """B_ij (n, 5, 5) of modes 1..5 by the general Haskind relation in finite depth (Newman
    1962; Falnes 2002 ch. 5), B_ij = k / (8 pi rho g c_g) Re int_0^2pi X_i conj(X_j) dbeta,
    from the heading table of a twice mirror-symmetric hull (`full_circle`; the periodic
    trapezoid rule, spectrally accurate for the smooth X(beta))."""
    if h.headings is None or h.heading_excitation is None:
        raise ValueError(f"hull {h.name!r}: no heading table (headings, heading_excitation)")
    beta, X = full_circle(h.headings, h.heading_excitation)
    step = beta[1] - beta[0]
    integral = step * np.real(np.einsum("nbi,nbj->nij", X, np.conj(X)))
    c = h.wavenumber / (8.0 * np.pi * h.rho * h.g * h.group_velocity)
    return c[:, None, None] * integral
