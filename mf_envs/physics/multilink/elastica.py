"""Reference: the inextensible, unshearable elastica cantilever by `scipy.integrate.solve_bvp`.

An independent check of the n-link chain (and of the beam FE): a beam clamped at the origin along
+x, bending stiffness EI, under a dead tip force P (2,) N, tip moment M_tip N m and a uniform dead
distributed load q (2,) N/m. With the internal force n(S) = P + q (L - S) carried across the
section at S (Eq. 40 with inertia off), the moment balance (Eq. 41, with M_3 = EI psi') reads

    x' = cos psi,   z' = sin psi,   psi' = M / EI,   M' = -(cos psi n_z - sin psi n_x),
    x(0) = z(0) = psi(0) = 0,       M(L) = M_tip.

The load is applied in `n_continuation` equal steps, each solve starting from the previous one.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_bvp

from mf_envs._validate import (
    check_int,
    check_shape,
    finite_scalar,
    positive_scalar,
)


@dataclass(frozen=True, eq=False)
class ElasticaSolution:
    """tip_position (2,) m; tip_angle rad; centerline (N, 2) m; s (N,) m; psi (N,) rad."""

    tip_position: NDArray[np.float64]
    tip_angle: float
    centerline: NDArray[np.float64]
    s: NDArray[np.float64]
    psi: NDArray[np.float64]


def elastica_cantilever(
    length: float,
    EI: float,
    tip_force: ArrayLike = (0.0, 0.0),
    tip_moment: float = 0.0,
    distributed_load: ArrayLike = (0.0, 0.0),
    tol: float = 1e-10,
    n_continuation: int = 8,
) -> ElasticaSolution:
    """Solve the elastica cantilever (module docstring); raises RuntimeError if solve_bvp fails."""
    L = positive_scalar("length", length)
    EI = positive_scalar("EI", EI)
    P = check_shape("tip_force", tip_force, (2,))
    M0 = finite_scalar("tip_moment", tip_moment)
    q = check_shape("distributed_load", distributed_load, (2,))
    steps = check_int("n_continuation", n_continuation, low=1)
    s = np.linspace(0.0, L, 201)
    y = np.zeros((4, s.size))
    y[0] = s
    sol = None
    for lam in np.linspace(1.0 / steps, 1.0, steps):

        def f(S: NDArray[np.float64], Y: NDArray[np.float64], lam: float = lam) -> NDArray:
            nx = lam * (P[0] + q[0] * (L - S))
            nz = lam * (P[1] + q[1] * (L - S))
            c, sn = np.cos(Y[2]), np.sin(Y[2])
            return np.vstack([c, sn, Y[3] / EI, -(c * nz - sn * nx)])

        def bc(ya: NDArray, yb: NDArray, lam: float = lam) -> NDArray:
            return np.array([ya[0], ya[1], ya[2], yb[3] - lam * M0])

        sol = solve_bvp(f, bc, s, y, tol=tol, max_nodes=200_000)
        if not sol.success:
            raise RuntimeError(f"elastica_cantilever: solve_bvp failed: {sol.message}")
        s, y = sol.x, sol.y
    assert sol is not None
    return ElasticaSolution(
        y[:2, -1].copy(), float(y[2, -1]), y[:2].T.copy(), s.copy(), y[2].copy()
    )
