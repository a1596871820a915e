"""Perspective projection, flat shading and the painter's algorithm (numpy + PIL, headless).

World frame: the inertial frame e^I of the seed with x3 up (ch.3 Eq. 20), lengths in m (or any
consistent unit: a picture is scale-free). A `Mesh` is a list of planar polygons in world
coordinates; `paint` projects them with a pinhole `Camera`, culls back faces of closed solids,
shades each face by the angle between its normal and a fixed light, and draws far-to-near.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
from PIL import ImageDraw

RGB = tuple[int, int, int]

# direction towards the light in the world frame (upper left, in front of the usual cameras)
LIGHT_DIR = np.array([0.45, -0.55, 0.70]) / np.linalg.norm([0.45, -0.55, 0.70])
AMBIENT = 0.42


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Cross product of two 3-vectors (cheaper than np.cross for single vectors)."""
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


@dataclass(frozen=True)
class Camera:
    """Pinhole camera looking from `eye` at `target` (world, m), `up` the world vertical.

    `size` = (H, W) in pixels of the image it projects into; `fov_deg` the vertical field of view.
    """

    eye: np.ndarray
    target: np.ndarray
    size: tuple[int, int]
    fov_deg: float = 30.0
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)

    def basis(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(right, up, forward) unit vectors (3,) of the camera in the world frame."""
        return self._basis

    @cached_property
    def _basis(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        f = np.asarray(self.target, float) - np.asarray(self.eye, float)
        f = f / np.linalg.norm(f)
        r = _cross(f, np.asarray(self.up, float))
        r = r / np.linalg.norm(r)
        return r, _cross(r, f), f

    def project(self, P: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pixel coordinates (..., 2) (column, row) and depth (...) of world points P (..., 3)."""
        r, u, f = self.basis()
        d = np.asarray(P, float) - np.asarray(self.eye, float)
        xc, yc, zc = d @ r, d @ u, d @ f
        h, w = self.size
        focal = 0.5 * h / np.tan(np.radians(self.fov_deg) / 2)
        z = np.maximum(zc, 1e-9)
        uv = np.stack([0.5 * w + focal * xc / z, 0.5 * h - focal * yc / z], axis=-1)
        return uv, zc


def orbit_camera(
    target: np.ndarray,
    distance: float,
    azimuth_deg: float,
    elevation_deg: float,
    size: tuple[int, int],
    fov_deg: float = 30.0,
) -> Camera:
    """Camera on a sphere around `target`; azimuth from +x1 towards +x2, elevation above the
    horizontal plane (degrees)."""
    az, el = np.radians(azimuth_deg), np.radians(elevation_deg)
    direction = np.array([np.cos(el) * np.cos(az), np.cos(el) * np.sin(az), np.sin(el)])
    target = np.asarray(target, float)
    return Camera(eye=target + distance * direction, target=target, size=size, fov_deg=fov_deg)


@dataclass
class Mesh:
    """Planar polygons in world coordinates with a base colour each.

    `closed=True` faces belong to a closed solid with outward normals (vertex order
    counter-clockwise seen from outside) and are culled when they face away from the camera;
    open faces (sheets) are shaded on whichever side the camera sees.
    """

    polys: list[np.ndarray] = field(default_factory=list)
    colors: list[RGB] = field(default_factory=list)
    closed: list[bool] = field(default_factory=list)
    outline: list[bool] = field(default_factory=list)

    def add(
        self, verts: np.ndarray, color: RGB, *, closed: bool = True, outline: bool = True
    ) -> None:
        self.polys.append(np.asarray(verts, float))
        self.colors.append(tuple(int(c) for c in color))
        self.closed.append(closed)
        self.outline.append(outline)

    def extend(self, other: Mesh) -> None:
        self.polys += other.polys
        self.colors += other.colors
        self.closed += other.closed
        self.outline += other.outline

    def _flat(self) -> tuple[np.ndarray, np.ndarray]:
        """All vertices (m, 3) and the split indices between polygons."""
        return np.concatenate(self.polys), np.cumsum([len(p) for p in self.polys])[:-1]

    def transformed(self, R: np.ndarray, x: np.ndarray) -> Mesh:
        """The mesh moved by the frame connection (R, x): p -> R p + x (ch.3 Eq. 21)."""
        if not self.polys:
            return Mesh()
        allv, cuts = self._flat()
        moved = allv @ np.asarray(R, float).T + np.asarray(x, float)
        return Mesh(np.split(moved, cuts), self.colors[:], self.closed[:], self.outline[:])

    def clipped_above(self, normal: np.ndarray, offset: float) -> Mesh:
        """Keep the parts of every polygon with normal . p >= offset (waterline clipping)."""
        if not self.polys:
            return Mesh()
        n = np.asarray(normal, float)
        allv, cuts = self._flat()
        lows = np.minimum.reduceat(allv @ n, np.concatenate([[0], cuts]))
        if np.all(lows >= offset):
            return self
        out = Mesh()
        for p, c, cl, ol, lo in zip(self.polys, self.colors, self.closed, self.outline, lows):
            q = p if lo >= offset else clip_polygon(p, n, offset)
            if q is not None:
                out.add(q, c, closed=cl, outline=ol)
        return out


def clip_polygon(poly: np.ndarray, normal: np.ndarray, offset: float) -> np.ndarray | None:
    """Sutherland-Hodgman clip of a convex polygon (k, 3) to the half-space n.p >= offset."""
    s = poly @ normal - offset
    if np.all(s >= 0):
        return poly
    if np.all(s < 0):
        return None
    out = []
    k = len(poly)
    for i in range(k):
        j = (i + 1) % k
        if s[i] >= 0:
            out.append(poly[i])
        if (s[i] >= 0) != (s[j] >= 0):
            t = s[i] / (s[i] - s[j])
            out.append(poly[i] + t * (poly[j] - poly[i]))
    return np.array(out) if len(out) >= 3 else None


def shade(color: RGB, normal: np.ndarray) -> RGB:
    """Lambert shading of a base colour for a unit face normal (3,) (world frame)."""
    k = AMBIENT + (1.0 - AMBIENT) * max(0.0, float(normal @ LIGHT_DIR))
    return tuple(int(min(255, c * k + 12)) for c in color)


def _normals(polys: list[np.ndarray]) -> np.ndarray:
    """Unit normals (n, 3) by Newell's method (robust for any planar polygon), vectorised:
    polygons are padded to the longest by repeating their last vertex (a zero-length edge)."""
    counts = np.array([len(p) for p in polys])
    kmax = int(counts.max())
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    idx = starts[:, None] + np.minimum(np.arange(kmax)[None, :], counts[:, None] - 1)
    P = np.concatenate(polys)[idx]  # (n, kmax, 3)
    Q = np.roll(P, -1, axis=1)
    D, S = P - Q, P + Q
    n = np.stack(
        [
            np.sum(D[..., 1] * S[..., 2], axis=1),
            np.sum(D[..., 2] * S[..., 0], axis=1),
            np.sum(D[..., 0] * S[..., 1], axis=1),
        ],
        axis=1,
    )
    return n / np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)


def paint(
    draw: ImageDraw.ImageDraw,
    camera: Camera,
    mesh: Mesh,
    scale: float = 1.0,
    edge_width: int = 1,
    sort: bool = True,
) -> None:
    """Draw `mesh` far-to-near (painter's algorithm) into `draw`.

    `scale` multiplies pixel coordinates (supersampling factor of the canvas vs `camera.size`).
    Faces crossing the camera's near plane are clipped to it; `sort=False` keeps the given order.
    """
    if not mesh.polys:
        return
    mesh = _clip_near(camera, mesh)
    if not mesh.polys:
        return
    counts = np.array([len(p) for p in mesh.polys])
    allv = np.concatenate(mesh.polys)
    uv, depth = camera.project(allv)
    uv = uv * scale
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    centroids = np.add.reduceat(allv, starts) / counts[:, None]
    normals = _normals(mesh.polys)
    to_eye = np.asarray(camera.eye, float) - centroids
    facing = np.einsum("ij,ij->i", normals, to_eye)
    mean_depth = np.linalg.norm(to_eye, axis=1)
    order = np.argsort(-mean_depth, kind="stable") if sort else np.arange(len(counts))
    for i in order:
        n = normals[i]
        if facing[i] < 0:
            if mesh.closed[i]:
                continue
            n = -n
        fill = shade(mesh.colors[i], n)
        pts = [tuple(xy) for xy in uv[starts[i] : starts[i] + counts[i]].tolist()]
        if mesh.outline[i]:
            edge = tuple(int(c * 0.55) for c in fill)
            draw.polygon(pts, fill=fill, outline=edge, width=edge_width)
        else:
            draw.polygon(pts, fill=fill)


def _clip_near(camera: Camera, mesh: Mesh, near: float = 1e-3) -> Mesh:
    """`mesh` with every polygon clipped to the half-space in front of the camera's near plane
    (at `near` times the eye-target distance)."""
    _, _, f = camera.basis()
    eye = np.asarray(camera.eye, float)
    limit = float(f @ eye) + near * float(np.linalg.norm(np.asarray(camera.target) - eye))
    return mesh.clipped_above(f, limit)
