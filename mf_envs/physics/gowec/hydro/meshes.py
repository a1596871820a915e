"""Axisymmetric panel meshes for the BEM front end (`bem.py`); needs the `hydro` extra.

A body of revolution about z is described by its meridian profile (r, z) from the waterline
down to the axis; Capytaine's `RotationSymmetricMesh` repeats one wedge of panels `n_theta`
times, and its solver then works on one wedge's block-circulant system (cost ~ n_theta x
(panels per wedge)^2 instead of (all panels)^2), which makes fine meshes affordable.

`cylinder_mesh` grades the panels towards the keel edge (r = R, z = -d): the velocity potential
of a rotating or translating cylinder is singular there (a 270-degree corner, flow ~ rho^(-1/3)),
and the pitch moment about G of a shallow-draft cylinder is a small difference of large
contributions from the side and the bottom, so the panel error at the corner controls
B55 and |X5|. Grading: panel sizes grow geometrically away from the corner by `ratio`.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray


def graded(length: float, n: int, ratio: float) -> NDArray[np.float64]:
    """n + 1 stations 0..length with panel sizes h_0, h_0 q, ..., h_0 q^(n-1) (q = `ratio`):
    the smallest panel at 0. ratio 1 gives uniform panels."""
    if not (isinstance(n, int) and n >= 1):
        raise ValueError(f"n: must be an integer >= 1, got {n!r}")
    if not (math.isfinite(ratio) and 1.0 <= ratio <= 2.0):
        raise ValueError(f"ratio: must be in [1, 2], got {ratio!r}")
    if not (math.isfinite(length) and length > 0):
        raise ValueError(f"length: must be > 0, got {length!r}")
    h = ratio ** np.arange(n, dtype=float)
    return length * np.concatenate(([0.0], np.cumsum(h))) / h.sum()


def cylinder_profile(
    radius: float, draft: float, n_side: int, n_bottom: int, ratio: float = 1.1
) -> NDArray[np.float64]:
    """Meridian points (m, 3) of a vertical cylinder's wetted surface, axis -> keel edge ->
    waterline (the order `revolve` needs), graded towards the keel edge (`graded`); the
    waterline end of the side is graded too (smallest panels at both ends of the side, the
    free-surface intersection being the other place where the potential varies fast)."""
    half = n_side // 2
    upper = graded(0.5 * draft, max(half, 1), ratio)  # from the waterline down to mid-draft
    lower = graded(0.5 * draft, max(n_side - half, 1), ratio)  # from the keel up to mid-draft
    z_side = np.concatenate((-upper, -draft + lower[::-1][1:]))
    r_bot = radius - graded(radius, n_bottom, ratio)[1:]  # keel edge -> axis
    r = np.concatenate((np.full_like(z_side, radius), r_bot))
    z = np.concatenate((z_side, np.full_like(r_bot, -draft)))
    return np.stack((r, np.zeros_like(r), z), axis=1)[::-1]


def revolve(profile: NDArray, n_theta: int, name: str | None = None):
    """`RotationSymmetricMesh` of the profile (points (m, 3) in the xz plane) repeated n_theta
    times about z. Capytaine sorts the points by increasing z (stable sort) and joins neighbours,
    so a profile must already run upwards, and along a horizontal part (a flat bottom) from the
    axis outwards; the normals then point out of the body."""
    from capytaine.meshes.symmetric_meshes import RotationSymmetricMesh

    if not (isinstance(n_theta, int) and n_theta >= 3):
        raise ValueError(f"n_theta: must be an integer >= 3, got {n_theta!r}")
    return RotationSymmetricMesh.from_profile_points(np.asarray(profile, float), n_theta, name=name)


def lid_mesh(radius: float, z: float, n_radial: int, n_theta: int):
    """Axisymmetric disk at height z (the interior free-surface lid that removes the irregular
    frequencies), uniform radial rings."""
    r = np.linspace(radius, 0.0, n_radial + 1)
    pts = np.stack((r, np.zeros_like(r), np.full_like(r, z)), axis=1)
    return revolve(pts, n_theta, name="lid")


def cylinder_mesh(
    radius: float,
    draft: float,
    n_theta: int = 64,
    n_side: int = 16,
    n_bottom: int = 16,
    ratio: float = 1.1,
):
    """(hull, lid) axisymmetric meshes of a floating vertical cylinder, graded at the keel.
    Panels: n_theta x (n_side + n_bottom) on the hull."""
    for k, v in (("radius", radius), ("draft", draft)):
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"{k}: must be > 0, got {v!r}")
    hull = revolve(cylinder_profile(radius, draft, n_side, n_bottom, ratio), n_theta, "cylinder")
    n_lid = max(2, n_bottom // 2)
    return hull, lid_mesh(radius, -0.01 * draft, n_lid, n_theta)


def hemisphere_mesh(radius: float, n_theta: int = 64, n_meridian: int = 24):
    """(hull, lid) of a floating sphere's wetted half (centre on the waterline), uniform in
    polar angle: the WAMIT verification case of Capytaine's repository."""
    if not (math.isfinite(radius) and radius > 0):
        raise ValueError(f"radius: must be > 0, got {radius!r}")
    t = np.linspace(0.5 * math.pi, math.pi, n_meridian + 1)  # equator -> south pole
    pts = radius * np.stack((np.sin(t), np.zeros_like(t), np.cos(t)), axis=1)
    hull = revolve(pts, n_theta, "hemisphere")
    return hull, lid_mesh(radius, -0.01 * radius, max(2, n_meridian // 2), n_theta)
