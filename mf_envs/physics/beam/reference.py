"""Independent references for verifying the beam: the inextensible, shear-rigid elastica by scipy
solve_bvp (a different model and method from the FE beam), and the seed's linear Timoshenko
cantilever data (Eqs. 65-67) converted to SI. Used by the tests and the accuracy benchmark."""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_bvp

IN, PSI, LBF = 0.0254, 6894.757293168361, 4.4482216152605
# seed §4.6: E = 30e6 psi, G = 12e6 psi, q0 = 200 lb/in, kappa0# = 0.0002 (1/in). The seed gives
# no geometry; we take L = 100 in, b = 1 in, h = 10 in (the tip then lifts ~ back to zero at
# alpha = 1, as in fig. 4-5b), A_s = 5bh/6.
SEED_CANTILEVER = {
    "E": 30e6 * PSI,
    "G": 12e6 * PSI,
    "q0": 200 * LBF / IN,
    "kappa0": 0.0002 / IN,
    "L": 100 * IN,
    "b": 1 * IN,
    "h": 10 * IN,
}


def seed_rigidities() -> tuple[float, float, float]:
    c = SEED_CANTILEVER
    area = c["b"] * c["h"]
    return c["E"] * area, c["G"] * 5 * area / 6, c["E"] * c["b"] * c["h"] ** 3 / 12


def elastica_tip(alpha: float) -> tuple[float, float, float]:
    """Inextensible, shear-rigid cantilever (L = 1, EI = 1) under a dead tip load alpha pointing
    -y: theta'' = alpha cos(theta), theta(0) = 0, theta'(1) = 0, x' = cos, y' = sin.
    Returns tip (x, y, theta)."""

    def rhs(s, u):
        return np.vstack([u[1], alpha * np.cos(u[0]), np.cos(u[0]), np.sin(u[0])])

    def bc(ua, ub):
        return np.array([ua[0], ub[1], ua[2], ua[3]])

    s = np.linspace(0, 1, 201)
    guess = np.vstack([-0.5 * alpha * s * (2 - s) / 2, -0.5 * alpha * (1 - s), s, 0 * s])
    sol = solve_bvp(rhs, bc, s, guess, tol=1e-10, max_nodes=100000)
    if not sol.success:
        raise RuntimeError(f"elastica reference: {sol.message}")
    tip = sol.sol(1.0)
    return float(tip[2]), float(tip[3]), float(tip[0])


def reissner_tip(alpha: float, ea: float, gas: float) -> tuple[float, float, float]:
    """Extensible, shearable (Reissner) cantilever, L = 1, EI = 1, dead tip load alpha along -y,
    by scipy solve_bvp: the same planar model as the FE beam (strains gamma = R^T z',
    kappa = psi') solved as a BVP, n = (0, -alpha) constant, (N1, N2) = R(psi)^T n,
    z' = R(psi) (1 + N1 / ea, N2 / gas), (EI psi')' = n1 z2' - n2 z1', psi'(1) = 0.
    ea, gas are EA L^2 / EI and GA_s L^2 / EI. Returns tip (x, y, psi)."""
    n1, n2 = 0.0, -float(alpha)

    def rhs(s, u):
        c, sn = np.cos(u[2]), np.sin(u[2])
        g1 = 1.0 + (c * n1 + sn * n2) / ea
        g2 = (-sn * n1 + c * n2) / gas
        dx, dy = c * g1 - sn * g2, sn * g1 + c * g2
        return np.vstack([dx, dy, u[3], n1 * dy - n2 * dx])

    def bc(ua, ub):
        return np.array([ua[0], ua[1], ua[2], ub[3]])

    s = np.linspace(0, 1, 401)
    guess = np.vstack([s, -alpha * s**2 / 2, -alpha * (s - s**2 / 2), -alpha * (1 - s)])
    sol = solve_bvp(rhs, bc, s, guess, tol=1e-10, max_nodes=100000)
    if not sol.success:
        raise RuntimeError(f"Reissner reference: {sol.message}")
    tip = sol.sol(1.0)
    return float(tip[0]), float(tip[1]), float(tip[2])


def timoshenko_cantilever_frequency(
    length: float, EI: float, GAs: float, mass_per_length: float, rotary_inertia: float
) -> float:
    """First bending angular frequency [rad/s] of a clamped-free Timoshenko beam (shear and
    rotary inertia) as an eigen-BVP by scipy solve_bvp, the eigenvalue an unknown parameter.
    Dimensionless (S = s/L, w/L, M L/EI, V L^2/EI, Om^2 = omega^2 m L^4 / EI):
    w' = e V + psi, psi' = M, M' = -V - r Om^2 psi, V' = -Om^2 w, e = EI/(GAs L^2),
    r = J/(m L^2); w(0) = psi(0) = 0, M(1) = V(1) = 0, w(1) = 1. Started from Euler-Bernoulli's
    first mode."""
    e = EI / (GAs * length**2)
    r = rotary_inertia / (mass_per_length * length**2)
    bl = 1.875104068711961

    def rhs(s, u, p):
        return np.vstack([e * u[3] + u[1], u[2], -u[3] - r * p[0] * u[1], -p[0] * u[0]])

    def bc(ua, ub, p):
        return np.array([ua[0], ua[1], ub[2], ub[3], ub[0] - 1.0])

    x = bl * np.linspace(0.0, 1.0, 201)
    sig = (np.cosh(bl) + np.cos(bl)) / (np.sinh(bl) + np.sin(bl))
    w = np.cosh(x) - np.cos(x) - sig * (np.sinh(x) - np.sin(x))
    dw = bl * (np.sinh(x) + np.sin(x) - sig * (np.cosh(x) - np.cos(x)))
    d2w = bl**2 * (np.cosh(x) + np.cos(x) - sig * (np.sinh(x) + np.sin(x)))
    d3w = bl**3 * (np.sinh(x) - np.sin(x) - sig * (np.cosh(x) + np.cos(x)))
    guess = np.vstack([w, dw, d2w, -d3w]) / w[-1]
    sol = solve_bvp(rhs, bc, x / bl, guess, p=[bl**4], tol=1e-10, max_nodes=100000)
    if not sol.success:
        raise RuntimeError(f"Timoshenko eigen-BVP: {sol.message}")
    return float(np.sqrt(sol.p[0] * EI / (mass_per_length * length**4)))
