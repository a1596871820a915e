"""Distributed (line) loads on the n-link chain: Gauss points and virtual-work lumping.

A line load f(S) (N/m, inertial frame) on link b does the virtual work
integral f . (dx_c + s e_perp dpsi) ds, so it lumps exactly into a link-centre force
F_b = integral f ds and moment M_b = integral s (e_perp . f) ds, then into B^T F_ex (Eq. 28d).
Use: evaluate the load (gravity, terrain contact, fluid drag ...) at `gauss_points`, lump with
`lump_line_load`, pass the result to `generalized_loads` / the `loads` callback of `simulate`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import check_finite, check_int
from mf_envs.physics.multilink.model import _e, _split, b_matrix, link_centers
from mf_envs.physics.multilink.params import ChainParams


def gauss_points(
    params: ChainParams, q: ArrayLike, qdot: ArrayLike | None = None, n_gauss: int = 3
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Gauss points on every link: positions (n, g, 2) m, velocities (n, g, 2) m/s, weights (g,) m.

    Evaluate a line load (N/m) at these points, then `lump_line_load` gives link forces/moments.
    """
    s, w = np.polynomial.legendre.leggauss(check_int("n_gauss", n_gauss, low=1))
    s, w = 0.5 * params.link_length * s, 0.5 * params.link_length * w
    _, psi = _split(params, q)
    e = np.stack(_e(psi), axis=1)
    pos = link_centers(params, q)[:, None, :] + s[None, :, None] * e[:, None, :]
    vel = np.zeros_like(pos)
    if qdot is not None:
        qdot = np.asarray(qdot, dtype=np.float64)
        V = (b_matrix(params, q) @ qdot).reshape(params.n_links, 3)
        e_perp = np.stack([-e[:, 1], e[:, 0]], axis=1)
        vel = V[:, None, :2] + (s[None, :] * V[:, 2:3])[..., None] * e_perp[:, None, :]
    return pos, vel, w


def lump_line_load(
    params: ChainParams, q: ArrayLike, line_load: ArrayLike, weights: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Virtual-work lumping of a line load f (n, g, 2) N/m at `gauss_points` into link-centre
    forces (n, 2) N and moments (n,) N m: F = sum w f, M = sum w s (e_perp . f)."""
    f = check_finite("line_load", line_load)
    w = np.asarray(weights, dtype=np.float64)
    _, psi = _split(params, q)
    s = np.polynomial.legendre.leggauss(w.size)[0] * 0.5 * params.link_length
    c, sn = _e(psi)
    e_perp_f = -sn[:, None] * f[..., 0] + c[:, None] * f[..., 1]
    return np.einsum("g,ngk->nk", w, f), e_perp_f @ (w * s)
