"""Panel meshes for the BEM front end (`bem.py`); needs the `hydro` extra.

A body of revolution about z is described by its meridian profile (r, z) from the waterline
down to the axis; Capytaine's `RotationSymmetricMesh` repeats one wedge of panels `n_theta`
times, and its solver then works on one wedge's block-circulant system (cost ~ n_theta x
(panels per wedge)^2 instead of (all panels)^2), which makes fine meshes affordable.

`cylinder_mesh` grades the panels towards the keel edge (r = R, z = -d): the velocity potential
of a rotating or translating cylinder is singular there (a 270-degree corner, flow ~ rho^(-1/3)),
and the pitch moment about G of a shallow-draft cylinder is a small difference of large
contributions from the side and the bottom, so the panel error at the corner controls
B55 and |X5|. Grading: panel sizes grow geometrically away from the corner by `ratio`.

`box_mesh` is a rectangular barge (ISWEC's 15 x 8 m hull) with its two mirror planes (xOz, yOz):
one quarter of the panels is stored and Capytaine's nested `ReflectionSymmetricMesh` makes the
influence matrices four quarter-size blocks (Green function evaluated N x N/4 times, four
(N/4)^3 factorisations instead of one N^3). Panels can be graded towards the keel edges, the
vertical corners and the waterline (`ratio`).

    quarter stored (x <= 0, y <= 0), seen from above:     and from the side (y = -B/2):

      y=0  +----------------+ x=0                        z=0  +-------------------+ x=0
           |    bottom      |                                 |   side  (graded   |
           |  (graded to    |                                 |   to x=-L/2, the  |
           |   x=-L/2 and   |                                 |   keel and the    |
           |   y=-B/2)      |                                 |   waterline)      |
     y=-B/2+----------------+                            z=-d +-------------------+
         x=-L/2                                             x=-L/2
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


def wall_stations(draft: float, n: int, ratio: float) -> NDArray[np.float64]:
    """Depths 0 .. -draft down a vertical wall in n panels (n // 2 above mid-draft), graded by
    `ratio` towards both ends: the waterline, where the free surface meets the wall, and the keel
    edge (`graded`)."""
    half = n // 2
    upper = graded(0.5 * draft, max(half, 1), ratio)  # from the waterline down to mid-draft
    lower = graded(0.5 * draft, max(n - half, 1), ratio)  # from the keel up to mid-draft
    return np.concatenate((-upper, -draft + lower[::-1][1:]))


def cylinder_profile(
    radius: float, draft: float, n_side: int, n_bottom: int, ratio: float = 1.1
) -> NDArray[np.float64]:
    """Meridian points (m, 3) of a vertical cylinder's wetted surface, axis -> keel edge ->
    waterline (the order `revolve` needs), graded towards the keel edge (`graded`); the
    waterline end of the side is graded too (smallest panels at both ends of the side, the
    free-surface intersection being the other place where the potential varies fast)."""
    z_side = wall_stations(draft, n_side, ratio)
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


def _grid(a: NDArray, b: NDArray, point) -> tuple[NDArray, NDArray]:
    """Vertices and quads of the structured grid point(a_i, b_j) (i along a, j along b);
    quads (a_i, b_j) -> (a_i+1, b_j) -> (a_i+1, b_j+1) -> (a_i, b_j+1)."""
    A, Bm = np.meshgrid(a, b, indexing="ij")
    v = np.stack(point(A.ravel(), Bm.ravel()), axis=1)
    nb = b.size
    i, j = np.meshgrid(np.arange(a.size - 1), np.arange(nb - 1), indexing="ij")
    q = (i * nb + j).ravel()
    return v, np.stack((q, q + nb, q + nb + 1, q + 1), axis=1)


def _quarter(parts: list[tuple[NDArray, NDArray]], outward: NDArray, name: str):
    """Capytaine Mesh of the quarter's faces, each face's quads oriented so that its normal
    has a positive component along its `outward` row (into the fluid)."""
    from capytaine.meshes.meshes import Mesh

    verts, faces, off = [], [], 0
    for (v, f), out in zip(parts, outward):
        n = np.cross(v[f[0, 1]] - v[f[0, 0]], v[f[0, 3]] - v[f[0, 0]])
        verts.append(v)
        faces.append((f if n @ out > 0 else f[:, ::-1]) + off)
        off += len(v)
    return Mesh(np.concatenate(verts), np.concatenate(faces), name=name)


def _mirrored_twice(quarter, name: str):
    """The full mesh from its x <= 0, y <= 0 quarter: nested `ReflectionSymmetricMesh`, yOz
    inside xOz (the nesting Capytaine's solver recognises; as `mesh_parallelepiped`)."""
    from capytaine.meshes.symmetric_meshes import ReflectionSymmetricMesh

    half = ReflectionSymmetricMesh(quarter, plane="yOz", name=f"half_of_{name}")
    return ReflectionSymmetricMesh(half, plane="xOz", name=name)


def box_mesh(
    length: float,
    beam: float,
    draft: float,
    n_length: int = 24,
    n_beam: int = 12,
    n_draft: int = 10,
    ratio: float = 1.0,
    lid_panels: tuple[int, int] | None = None,
):
    """(hull, lid) of a floating rectangular box, x along `length`, y along `beam` (m), keel at
    z = -`draft`, both nested mirror-symmetric (`_mirrored_twice`). Per quarter: n_length panels
    along x over L/2 and n_beam along y over B/2, graded by `ratio` towards the box's edge (the
    smallest panels at x = -L/2, y = -B/2); n_draft panels down the walls, graded towards both
    the waterline and the keel (`wall_stations`, as the cylinder's side). Hull panels:
    4 (n_length n_draft + n_beam n_draft + n_length n_beam). The lid (the waterplane at
    z = -0.01 d, for the irregular frequencies) has lid_panels = (along x, along y) uniform panels
    per quarter (default half the hull's counts). Default ratio 1: on this hull grading made
    the Haskind check worse, not better (docs/gowec_v1.md, "ISWEC's box hull")."""
    for k, v in (("length", length), ("beam", beam), ("draft", draft)):
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"{k}: must be > 0, got {v!r}")
    for k, v in (("n_length", n_length), ("n_beam", n_beam), ("n_draft", n_draft)):
        if not (isinstance(v, int) and v >= 2):
            raise ValueError(f"{k}: must be an integer >= 2, got {v!r}")
    hl, hb = 0.5 * length, 0.5 * beam
    x = -hl + graded(hl, n_length, ratio)  # -L/2 (fine) .. 0
    y = -hb + graded(hb, n_beam, ratio)
    z = wall_stations(draft, n_draft, ratio)

    parts = [
        _grid(x, z, lambda a, b: (a, np.full_like(a, -hb), b)),  # side wall y = -B/2
        _grid(y, z, lambda a, b: (np.full_like(a, -hl), a, b)),  # end wall x = -L/2
        _grid(x, y, lambda a, b: (a, b, np.full_like(a, -draft))),  # bottom
    ]
    out = np.array([[0.0, -1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
    hull = _mirrored_twice(_quarter(parts, out, "box_quarter"), "box")
    nlx, nly = lid_panels or (max(2, n_length // 2), max(2, n_beam // 2))
    zl = -0.01 * draft
    lid_q = _grid(np.linspace(-hl, 0.0, nlx + 1), np.linspace(-hb, 0.0, nly + 1),
                  lambda a, b: (a, b, np.full_like(a, zl)))  # fmt: skip
    lid = _mirrored_twice(_quarter([lid_q], np.array([[0.0, 0.0, -1.0]]), "lid_quarter"), "lid")
    return hull, lid
