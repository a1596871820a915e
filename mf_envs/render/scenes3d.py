"""3-D scenes in perspective: the free rigid body (ch.2), the GOWEC buoy (ch.3 §3.2) and the
ship with gyro stabilizers (ch.3 §3.3). Pure functions: state in, uint8 (H, W, 3) frame out.

Frames follow the seed: the gimbal turns about the body e2 axis, R^(2/1) = R_2(phi)
(ch.3 Eq. 30/98), the rotor spins about the gimbal e3 axis, R^(3/2) = R_3(psi) (Eq. 40);
the second gyro of the ship sits at -h2 on e2 (Eqs. 100-101). Sizes are schematic.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from mf_envs._validate import (
    check_finite,
    check_positive,
    check_shape,
    finite_scalar,
    positive_scalar,
)
from mf_envs.frames import rot_y
from mf_envs.render import meshes
from mf_envs.render.canvas import Canvas, axis_triad, check_size
from mf_envs.render.projection import Camera, Mesh, orbit_camera, paint, shade

ROTOR = (176, 182, 192)
ROTOR_MARK = (226, 150, 60)
GIMBAL = (96, 104, 120)
HULL = (190, 70, 60)
DECK = (214, 200, 170)
BUOY = (235, 190, 60)
SEA = (66, 132, 190)
SKY = ((178, 206, 232), (236, 242, 248))


def _attitude(name: str, R: ArrayLike) -> np.ndarray:
    return check_shape(name, R, (3, 3))


def _cross2(a: np.ndarray, b: np.ndarray) -> float:
    return float(a[0] * b[1] - a[1] * b[0])


def _shadow(mesh: Mesh, z: float) -> Mesh:
    """Convex hull of the mesh dropped vertically onto the plane x3 = z, as one dark face."""
    pts = np.unique(np.concatenate(mesh.polys)[:, :2].round(9), axis=0)
    pts = pts[np.lexsort((pts[:, 1], pts[:, 0]))]

    def half(points):
        h: list[np.ndarray] = []
        for p in points:
            while len(h) >= 2 and _cross2(h[-1] - h[-2], p - h[-2]) <= 0:
                h.pop()
            h.append(p)
        return h

    hull = half(pts)[:-1] + half(pts[::-1])[:-1]
    out = Mesh()
    if len(hull) >= 3:
        out.add(
            np.column_stack([np.array(hull), np.full(len(hull), z)]),
            (150, 156, 166),
            closed=False,
            outline=False,
        )
    return out


def gyro_mesh(phi: float, psi: float, scale: float) -> Mesh:
    """One gyro (gimbal ring + rotor disk) in its carrier's frame, pivot at the origin:
    gimbal R_2(phi), rotor R_2(phi) R_3(psi) (ch.3 Eqs. 30, 40)."""
    r = 0.5 * scale
    rotor = meshes.cylinder(r, 0.16 * r, ROTOR, marker=ROTOR_MARK, angle=psi)
    ring = meshes.gimbal_ring(1.28 * r, 0.72 * r, 0.18 * r, GIMBAL)
    axle = meshes.cylinder(0.07 * r, 0.72 * r, GIMBAL, segments=8)
    g = Mesh()
    g.extend(rotor)
    g.extend(ring)
    g.extend(axle)
    return g.transformed(rot_y(phi), np.zeros(3))


def draw_rigid_body(
    *, R: ArrayLike, half_extents: ArrayLike, text: str = "", size: tuple[int, int] = (360, 480)
) -> np.ndarray:
    """A box body of `half_extents` (3,) (m, along body e1, e2, e3) at attitude `R` (3, 3),
    body -> inertial (ch.2 Eq. 29), in perspective, faces coloured by body axis
    (e1 red, e2 green, e3 blue), with its shadow and the inertial axes.

    Returns uint8 (H, W, 3) for `size` = (H, W).
    """
    R = _attitude("R", R)
    a = check_positive("half_extents", half_extents)
    if a.shape != (3,):
        raise ValueError(f"half_extents: expected shape (3,), got {a.shape}")
    size = check_size(size)
    radius = float(np.linalg.norm(a))
    body = meshes.box(a, meshes.AXIS_COLORS).transformed(R, np.zeros(3))
    cam = orbit_camera(
        np.array([0, 0, -0.35 * radius]), 5.6 * radius, -35.0, 26.0, size, fov_deg=32.0
    )
    canvas = Canvas(size)
    paint(canvas.draw, cam, _shadow(body, -1.05 * radius), canvas.ss)
    paint(canvas.draw, cam, body, canvas.ss, edge_width=canvas.ss)
    h, w = size
    return canvas.finish(
        text,
        overlay=lambda d: axis_triad(d, cam, (0.1 * w, 0.86 * h), 0.07 * h),
    )


def ship_meshes(phis: np.ndarray, psis: np.ndarray) -> tuple[Mesh, Mesh]:
    """(hull, deck gear) meshes in the ship's body frame for gimbal angles `phis` and rotor
    angles `psis` (rad, 1 or 2 each); gyro k pivots at (0.8, +-1.0, 1.55) m (Eqs. 100-101)."""
    freeboard = 0.8
    hull = meshes.ship_hull(10.0, 4.0, 1.4, freeboard, HULL, DECK)
    items = meshes.box((0.9, 1.2, 0.6), (235, 235, 230), center=(-3.6, 0, freeboard + 0.6))
    y_pos = [0.0] if len(phis) == 1 else [1.0, -1.0]
    pivot_z = freeboard + 0.75
    for y, phi, psi in zip(y_pos, phis, psis):
        center = np.array([0.8, y, pivot_z])
        items.extend(gyro_mesh(float(phi), float(psi), 1.15).transformed(np.eye(3), center))
        items.extend(meshes.pedestal(center, 0.86, pivot_z - freeboard + 0.05, 0.12, GIMBAL))
    return hull, items


def draw_ship(
    *,
    ship_R: ArrayLike,
    gimbal_angles: ArrayLike,
    rotor_angles: ArrayLike | None = None,
    text: str = "",
    size: tuple[int, int] = (360, 480),
) -> np.ndarray:
    """A schematic ship (bow on body +e1) at attitude `ship_R` (3, 3, body -> inertial) on a
    calm sea plane, with one gyro on the centreline or two at +-e2 (ch.3 Fig. 6, Eqs. 98-113).

    gimbal_angles: (n_gyros,) rad, each about the ship's e2 axis (pass (phi, -phi) for the
    counter-rotating pair); rotor_angles: (n_gyros,) rad about each gimbal's e3 (default 0).
    Returns uint8 (H, W, 3) for `size` = (H, W). The hull is clipped at the waterline x3 = 0.
    """
    R = _attitude("ship_R", ship_R)
    phis = np.atleast_1d(check_finite("gimbal_angles", gimbal_angles)).ravel()
    if not 1 <= len(phis) <= 2:
        raise ValueError(f"gimbal_angles: expected 1 or 2 angles, got {len(phis)}")
    psis = (
        np.zeros_like(phis)
        if rotor_angles is None
        else np.atleast_1d(check_finite("rotor_angles", rotor_angles)).ravel()
    )
    if psis.shape != phis.shape:
        raise ValueError(f"rotor_angles: expected {len(phis)} angles, got {len(psis)}")
    size = check_size(size)
    hull, items = ship_meshes(phis, psis)
    up = np.array([0.0, 0.0, 1.0])
    az = np.radians(-40.0)  # eye 5.4 m up, 14.6 m out; look at a point above the ship so the
    # horizon sits in the upper quarter of the frame (camera pitched 12 deg down)
    eye = np.array([14.6 * np.cos(az), 14.6 * np.sin(az), 5.4])
    cam = Camera(eye=eye, target=np.array([0.0, 0.0, 2.3]), size=size, fov_deg=36.0)
    canvas = Canvas(size, *SKY)
    # the sea plane x3 = 0 seen to infinity: everything below the horizon row (the camera has
    # no roll, so the horizon is the image row of the horizontal view direction)
    _, _, f = cam.basis()
    pitch = -np.arcsin(f[2])
    focal = 0.5 * size[0] / np.tan(np.radians(cam.fov_deg) / 2)
    horizon = (0.5 * size[0] - focal * np.tan(pitch)) * canvas.ss
    canvas.draw.rectangle(
        (0, horizon, size[1] * canvas.ss, size[0] * canvas.ss), fill=shade(SEA, np.eye(3)[2])
    )
    # hull first: everything else stands on its deck (painter's order by layer, then depth)
    for layer in (hull, items):
        world = layer.transformed(R, np.zeros(3)).clipped_above(up, 0.0)
        paint(canvas.draw, cam, world, canvas.ss, edge_width=canvas.ss)
    h, w = size
    return canvas.finish(text, overlay=lambda d: axis_triad(d, cam, (0.1 * w, 0.86 * h), 0.07 * h))


def _wave_profile(wave_x: ArrayLike, wave_z: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """The (n,) profile arrays, checked: equal lengths >= 2, wave_x strictly increasing."""
    s = np.ravel(check_finite("wave_x", wave_x))
    z = np.ravel(check_finite("wave_z", wave_z))
    if s.shape != z.shape or len(s) < 2:
        raise ValueError(f"wave_x, wave_z: need equal lengths >= 2, got {len(s)} and {len(z)}")
    if np.any(np.diff(s) <= 0):
        raise ValueError("wave_x: must be strictly increasing")
    return s, z


def draw_gowec(
    *,
    buoy_R: ArrayLike,
    gimbal_angle: float,
    rotor_angle: float = 0.0,
    wave_x: ArrayLike,
    wave_z: ArrayLike,
    text: str = "",
    size: tuple[int, int] = (360, 480),
    wave_direction: float = np.pi / 2,
    buoy_radius: float | None = None,
    buoy_plan: tuple[float, float] | None = None,
) -> np.ndarray:
    """The GOWEC buoy (ch.3 Fig. 2) riding a wave profile, gyro on its deck.

    buoy_R: (3, 3) buoy attitude, body -> inertial; gimbal_angle phi (rad, about buoy e2,
    Eq. 30); rotor_angle psi (rad, about gimbal e3, Eq. 40); wave_x, wave_z: (n,) elevation
    profile (m) along the travel direction `wave_direction` (theta of Eq. 89, pi/2 = along x2,
    head-on), with the buoy at wave_x = 0. `buoy_radius` (m) defaults to 1/10 of the profile
    span; `buoy_plan` (length along e2, beam along e1; m) draws a box hull of that plan instead
    of the cylinder (its gear sized on the half beam). The buoy is cut at the plane tangent to
    the wave under it; the view is from the side of the wave so the profile reads as in a wave
    flume. Returns uint8 (H, W, 3).
    """
    R = _attitude("buoy_R", buoy_R)
    phi = finite_scalar("gimbal_angle", gimbal_angle)
    psi = finite_scalar("rotor_angle", rotor_angle)
    theta = finite_scalar("wave_direction", wave_direction)
    s, z = _wave_profile(wave_x, wave_z)
    size = check_size(size)
    span = float(s[-1] - s[0])
    rb = span / 10 if buoy_radius is None else positive_scalar("buoy_radius", buoy_radius)
    if buoy_plan is not None:
        length = positive_scalar("buoy_plan", buoy_plan[0])
        rb = 0.5 * positive_scalar("buoy_plan", buoy_plan[1])
    eta0 = float(np.interp(0.0, s, z))
    slope = float(np.interp(0.0, s, np.gradient(z, s)))
    d = np.array([np.cos(theta), np.sin(theta), 0.0])

    deck = 0.32 * rb
    buoy = (meshes.cylinder(rb, deck, BUOY, segments=28) if buoy_plan is None
            else meshes.box(np.array([rb, 0.5 * length, deck]), BUOY))  # fmt: skip
    pivot = np.array([0.0, 0.0, deck + 0.62 * rb])
    gyro = gyro_mesh(phi, psi, 1.05 * rb).transformed(np.eye(3), pivot)
    gyro.extend(meshes.pedestal(pivot, 0.86 * rb, 0.66 * rb, 0.1 * rb, GIMBAL))
    center = np.array([0.0, 0.0, eta0])
    normal = np.array([0.0, 0.0, 1.0]) - slope * d
    normal /= np.linalg.norm(normal)
    layers = [
        m.transformed(R, center).clipped_above(normal, float(normal @ center)) for m in (buoy, gyro)
    ]

    amp = max(float(np.ptp(z)) / 2, 1e-9)
    surface, cut = meshes.wave_sheet(s, z, theta, 2.0 * rb, SEA, 0.8 * rb + amp)
    az = np.degrees(theta) - 90.0 - 24.0
    dist = 0.42 * span / np.tan(np.radians(17.0)) + 2 * rb
    target = np.array([0.0, 0.0, float(np.mean(z)) - 0.2 * rb])
    cam = orbit_camera(target, dist, az, 22.0, size, fov_deg=34.0)
    canvas = Canvas(size, *SKY)
    for mesh in (surface, *layers, cut):  # water, buoy, its deck gear, the near cut face
        paint(canvas.draw, cam, mesh, canvas.ss, edge_width=canvas.ss, sort=mesh is not cut)
    h, w = size
    return canvas.finish(
        text, overlay=lambda dr: axis_triad(dr, cam, (0.1 * w, 0.86 * h), 0.07 * h)
    )
