"""Simple solids in their own body frame: box, disk/cylinder, gimbal ring, ship hull, wave sheet.

Every builder returns a `Mesh` in body coordinates (m); place it with `Mesh.transformed(R, x)`.
Closed solids list their faces counter-clockwise seen from outside (outward normals).
"""

from __future__ import annotations

import numpy as np

from mf_envs.render.projection import RGB, Mesh

# muted axis colours: faces normal to e1 / e2 / e3 (like an axis triad: red, green, blue)
AXIS_COLORS: tuple[RGB, RGB, RGB] = ((214, 96, 77), (110, 170, 90), (80, 130, 200))

_BOX_FACES = (  # vertex indices (of the 8 corners below), outward, counter-clockwise
    ((1, 3, 7, 5), 0),  # +x
    ((0, 4, 6, 2), 0),  # -x
    ((2, 6, 7, 3), 1),  # +y
    ((0, 1, 5, 4), 1),  # -y
    ((4, 5, 7, 6), 2),  # +z
    ((0, 2, 3, 1), 2),  # -z
)


def box_corners(half_extents: np.ndarray) -> np.ndarray:
    """The 8 corners (8, 3) of an axis-aligned box; corner i has sign bits (x, y, z) = i."""
    a = np.asarray(half_extents, float)
    s = np.array([[(i >> 0) & 1, (i >> 1) & 1, (i >> 2) & 1] for i in range(8)]) * 2 - 1
    return s * a


def box(
    half_extents: np.ndarray,
    color: RGB | tuple[RGB, RGB, RGB],
    center: np.ndarray = (0.0, 0.0, 0.0),
) -> Mesh:
    """Axis-aligned box; `color` one RGB or one per axis (faces normal to e1, e2, e3)."""
    colors = color if isinstance(color[0], (tuple, list)) else (color, color, color)
    c = box_corners(half_extents) + np.asarray(center, float)
    mesh = Mesh()
    for idx, axis in _BOX_FACES:
        mesh.add(c[list(idx)], colors[axis])
    return mesh


def cylinder(
    radius: float,
    half_height: float,
    color: RGB,
    *,
    segments: int = 24,
    marker: RGB | None = None,
    angle: float = 0.0,
) -> Mesh:
    """Cylinder about the body e3 axis, centred at the origin.

    With `marker`, two opposite quarter sectors of each cap get that colour and turn with
    `angle` (rad, about e3): this is what makes a spinning rotor's angle visible.
    """
    th = angle + np.linspace(0.0, 2 * np.pi, segments, endpoint=False)
    ring = np.stack([radius * np.cos(th), radius * np.sin(th), np.zeros(segments)], axis=1)
    top, bot = ring + [0, 0, half_height], ring - [0, 0, half_height]
    mesh = Mesh()
    for i in range(segments):
        j = (i + 1) % segments
        mesh.add(np.array([bot[i], bot[j], top[j], top[i]]), color, outline=False)
    if marker is None:
        mesh.add(top, color)
        mesh.add(bot[::-1], color)
        return mesh
    q = segments // 4
    for k in range(4):  # quarter sectors, alternating colours
        idx = [(k * q + m) % segments for m in range(q + 1)]
        col = marker if k % 2 == 0 else color
        for cap, zc, flip in ((top, half_height, False), (bot, -half_height, True)):
            sector = np.vstack([[0.0, 0.0, zc], cap[idx]])
            mesh.add(sector[::-1] if flip else sector, col, outline=False)
    return mesh


def gimbal_ring(half_width: float, half_height: float, bar: float, color: RGB) -> Mesh:
    """Rectangular gimbal frame in the body e2-e3 plane around the origin (4 bars of square
    cross-section `bar`), plus the two pivot stubs on the e2 axis."""
    mesh = Mesh()
    w, h, b = half_width, half_height, bar / 2
    mesh.extend(box((b, w + b, b), color, center=(0, 0, h)))
    mesh.extend(box((b, w + b, b), color, center=(0, 0, -h)))
    mesh.extend(box((b, b, h - b), color, center=(0, w, 0)))
    mesh.extend(box((b, b, h - b), color, center=(0, -w, 0)))
    for s in (1, -1):
        mesh.extend(box((0.7 * b, 1.2 * b, 0.7 * b), color, center=(0, s * (w + 2.2 * b), 0)))
    return mesh


def ship_hull(
    length: float, beam: float, depth: float, freeboard: float, color: RGB, deck: RGB
) -> Mesh:
    """A schematic hull: pointed bow on +e1, transom at -e1, deck at z = freeboard, keel
    narrower than the deck at z = -depth (body frame: e1 forward, e2 port, e3 up)."""
    L, B = length / 2, beam / 2
    deck_xy = np.array([[-L, -B], [0.45 * L, -B], [L, 0.0], [0.45 * L, B], [-L, B]])
    keel_xy = deck_xy * [0.92, 0.45]
    top = np.column_stack([deck_xy, np.full(5, freeboard)])
    bot = np.column_stack([keel_xy, np.full(5, -depth)])
    mesh = Mesh()
    for i in range(5):
        j = (i + 1) % 5
        mesh.add(np.array([bot[i], bot[j], top[j], top[i]]), color)
    mesh.add(top, deck)
    mesh.add(bot[::-1], color)
    return mesh


def pedestal(center: np.ndarray, half_width: float, height: float, bar: float, color: RGB) -> Mesh:
    """Two uprights at +-half_width along e2 that carry a gimbal's pivots at `center`."""
    mesh = Mesh()
    cx, cy, cz = center
    b = bar / 2
    for s in (1, -1):
        mesh.extend(
            box((b, b, height / 2), color, center=(cx, cy + s * half_width, cz - height / 2))
        )
    return mesh


def wave_sheet(
    s: np.ndarray, z: np.ndarray, direction: float, half_width: float, color: RGB, depth: float
) -> tuple[Mesh, Mesh]:
    """The sea surface z(s) along the horizontal direction `direction` (rad from x1), extruded
    +-half_width sideways; returns (surface strips, the vertical cut on the +side face)."""
    d = np.array([np.cos(direction), np.sin(direction), 0.0])
    side = np.array([np.sin(direction), -np.cos(direction), 0.0])  # camera side
    p = s[:, None] * d + z[:, None] * [0, 0, 1]
    near, far = p + half_width * side, p - half_width * side
    surface = Mesh()
    for i in range(len(s) - 1):
        surface.add(
            np.array([near[i], near[i + 1], far[i + 1], far[i]]), color, closed=False, outline=False
        )
    bottom = z.min() - depth
    cut_pts = np.vstack(
        [near, near[-1] * [1, 1, 0] + [0, 0, bottom], near[0] * [1, 1, 0] + [0, 0, bottom]]
    )
    cut = Mesh()
    cut.add(cut_pts, tuple(int(c * 0.62) for c in color), closed=False, outline=False)
    return surface, cut
