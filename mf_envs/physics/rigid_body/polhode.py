"""Poinsot geometry of torque-free rotation (Rios 2017, ch. 2 §2.2.4, Eqs. 32-40).

In body components H the motion lies on the energy ellipsoid (Eq. 32a) and on the momentum sphere
(Eq. 33a); their intersections are the polhodes. Non-dimensionalised by sqrt(2 K0 J2) (Eq. 35a):

    (J2/J1) h1^2 + h2^2 + (J2/J3) h3^2 = 1        energy ellipsoid      (Eq. 36)
    h1^2 + h2^2 + h3^2 = d,  d = D/J2              momentum sphere       (Eq. 37a)
    J3/J2 <= d <= J1/J2                                                  (Eq. 37b)

d < 1: the polhode circles the h3 axis; d > 1: it circles h1; d = 1: the separatrices, the planes
h3 = +-k h1, k = sqrt(J3 (J1 - J2) / (J1 (J2 - J3))) (Eq. 40b; the source prints h2 on the right,
a slip - setting d = 1 in Eq. 40a gives h1). These helpers need J1 > J2 > J3 > 0 (the seed's
labelling) and raise ValueError naming `J` otherwise; `sort_axes` gives that order and its
permutation for any inertia triple.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import check_positive, check_shape, positive_scalar


def sort_axes(J: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.int64]]:
    """(J sorted decreasing, perm) with J_sorted = J[perm]; relabel H as H[..., perm]."""
    Jv = check_shape("J", check_positive("J", J), (3,))
    perm = np.argsort(-Jv, kind="stable")
    return Jv[perm], perm


def _decreasing(J: ArrayLike) -> NDArray[np.float64]:
    Jv = check_shape("J", check_positive("J", J), (3,))
    if not (Jv[0] > Jv[1] > Jv[2]):
        raise ValueError(f"J: polhode geometry needs J1 > J2 > J3 (use sort_axes), got {Jv}")
    return Jv


def energy(J: ArrayLike, H: ArrayLike) -> NDArray[np.float64]:
    """K = 0.5 sum H_i^2 / J_i (J) for body momenta H (..., 3) kg m^2/s (Eq. 16b, 32b)."""
    H = np.asarray(H, dtype=np.float64)
    return 0.5 * np.sum(H * H / np.asarray(J, dtype=np.float64), axis=-1)


def d_bar(J: ArrayLike, H: ArrayLike) -> NDArray[np.float64]:
    """d = D / J2 = |H|^2 / (2 K J2) (Eqs. 33b, 35b) for H (..., 3); J decreasing."""
    Jv = _decreasing(J)
    H = np.asarray(H, dtype=np.float64)
    return np.sum(H * H, axis=-1) / (2.0 * energy(Jv, H) * Jv[1])


def separatrix_side(J: ArrayLike, H: ArrayLike) -> NDArray[np.float64]:
    """sign(2K (D - J2)) for H (..., 3), computed without cancellation (the H2 term drops):
    2K (D - J2) = H1^2 (J1 - J2)/J1 - H3^2 (J2 - J3)/J3. +1: circles e1, -1: circles e3."""
    Jv = _decreasing(J)
    H = np.asarray(H, dtype=np.float64)
    s = H[..., 0] ** 2 * (Jv[0] - Jv[1]) / Jv[0] - H[..., 2] ** 2 * (Jv[1] - Jv[2]) / Jv[2]
    return np.sign(s)


def nondimensional(J: ArrayLike, H: ArrayLike, K0: float) -> NDArray[np.float64]:
    """h = H / sqrt(2 K0 J2) (Eq. 35a); H (..., 3) kg m^2/s, K0 in J."""
    Jv = _decreasing(J)
    return np.asarray(H, dtype=np.float64) / np.sqrt(2.0 * K0 * Jv[1])


def energy_ellipsoid(
    J: ArrayLike, n: int = 40
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Mesh (X, Y, Z), each (n, n), of the non-dimensional energy ellipsoid (Eq. 36): semi-axes
    sqrt(J1/J2), 1, sqrt(J3/J2)."""
    Jv = _decreasing(J)
    u, v = np.meshgrid(np.linspace(0.0, 2.0 * np.pi, n), np.linspace(0.0, np.pi, n))
    ax = np.sqrt(Jv / Jv[1])
    return ax[0] * np.cos(u) * np.sin(v), ax[1] * np.sin(u) * np.sin(v), ax[2] * np.cos(v)


def momentum_sphere(
    d: float, n: int = 40
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Mesh (X, Y, Z), each (n, n), of the non-dimensional momentum sphere of radius sqrt(d)
    (Eq. 37a)."""
    r = float(np.sqrt(check_positive("d", d)))
    u, v = np.meshgrid(np.linspace(0.0, 2.0 * np.pi, n), np.linspace(0.0, np.pi, n))
    return r * np.cos(u) * np.sin(v), r * np.sin(u) * np.sin(v), r * np.cos(v)


def polhode(J: ArrayLike, d: float, n: int = 200) -> list[NDArray[np.float64]]:
    """The two closed polhodes (each (n, 3), non-dimensional h) for sphere parameter d (Eq. 37a).

    d > 1: the projection on (h2, h3) is the ellipse of Eq. 38 and h1 = +-sqrt(d - h2^2 - h3^2);
    d < 1: the projection on (h1, h2) is the ellipse of Eq. 39 and h3 = +-(...). d = 1 returns
    the separatrices (`separatrices`). Raises ValueError if d is outside Eq. 37b.
    """
    Jv = _decreasing(J)
    r1, r3 = Jv[0] / Jv[1], Jv[2] / Jv[1]
    d = positive_scalar("d", d)
    if not (r3 * (1 - 1e-12) <= d <= r1 * (1 + 1e-12)):
        raise ValueError(f"d: must lie in [J3/J2, J1/J2] = [{r3:.6g}, {r1:.6g}] (Eq. 37b), got {d}")
    if d == 1.0:
        return separatrices(J, n)
    s = np.linspace(0.0, 2.0 * np.pi, n)
    if d > 1.0:  # Eq. 38: (1 - 1/r1) h2^2 + (1/r3 - 1/r1) h3^2 = 1 - d/r1
        rhs = max(1.0 - d / r1, 0.0)
        h2 = np.sqrt(rhs / (1.0 - 1.0 / r1)) * np.cos(s)
        h3 = np.sqrt(rhs / (1.0 / r3 - 1.0 / r1)) * np.sin(s)
        h1 = np.sqrt(np.maximum(d - h2 * h2 - h3 * h3, 0.0))
        return [np.stack([sg * h1, h2, h3], axis=1) for sg in (1.0, -1.0)]
    # Eq. 39: (1/r3 - 1/r1) h1^2 + (1/r3 - 1) h2^2 = d/r3 - 1
    rhs = max(d / r3 - 1.0, 0.0)
    h1 = np.sqrt(rhs / (1.0 / r3 - 1.0 / r1)) * np.cos(s)
    h2 = np.sqrt(rhs / (1.0 / r3 - 1.0)) * np.sin(s)
    h3 = np.sqrt(np.maximum(d - h1 * h1 - h2 * h2, 0.0))
    return [np.stack([h1, h2, sg * h3], axis=1) for sg in (1.0, -1.0)]


def separatrix_slope(J: ArrayLike) -> float:
    """k of the separatrix planes h3 = +-k h1: sqrt(J3 (J1 - J2) / (J1 (J2 - J3))) (Eq. 40b)."""
    Jv = _decreasing(J)
    return float(np.sqrt(Jv[2] * (Jv[0] - Jv[1]) / (Jv[0] * (Jv[1] - Jv[2]))))


def separatrices(J: ArrayLike, n: int = 200) -> list[NDArray[np.float64]]:
    """The two separatrix ellipses (each (n, 3), non-dimensional h): the energy ellipsoid cut by
    the planes h3 = +-k h1 (Eq. 40b); each passes through the saddles h = (0, +-1, 0)."""
    Jv = _decreasing(J)
    k = separatrix_slope(Jv)
    # on h3 = k h1 with d = 1: h1^2 (1 + k^2) + h2^2 = 1 (sphere), also on the ellipsoid
    s = np.linspace(0.0, 2.0 * np.pi, n)
    h1 = np.cos(s) / np.sqrt(1.0 + k * k)
    h2 = np.sin(s)
    return [np.stack([h1, h2, sg * k * h1], axis=1) for sg in (1.0, -1.0)]
