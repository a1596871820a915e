"""Frames of Eel-v0: the body seen from above in still water on a grid fixed to the water (so the
swimming is visible), in a window following the centre of mass, with arrows of Taylor's
resistive line force at the Gauss points (no wake: the model has none), the target direction
as an arrow."""

from __future__ import annotations

import math

import numpy as np

from mf_envs.render.canvas import Canvas

BODY, EDGE, HEAD = (70, 110, 150), (30, 52, 80), (200, 70, 60)
GRID, TARGET, TRACK, FORCE = (170, 200, 222), (200, 120, 40), (120, 150, 190), (220, 60, 40)


def draw(line: np.ndarray, track: list, target: float, text: str, forces: np.ndarray,
         force_scale: float, size=(400, 400)) -> np.ndarray:  # fmt: skip
    """Top view: centreline (N, 2) [m] tail to head, the past centre-of-mass track [(x, y)],
    the target direction [rad], a caption, forces (M, 4) rows (x, y, f_x, f_y) [m, N/m] drawn
    as arrows of force_scale [m per N/m]. Returns uint8 (H, W, 3)."""
    h, w = size
    canvas = Canvas((h, w), (214, 232, 244), (200, 222, 238))
    ss, dr = canvas.ss, canvas.draw
    length = float(np.sum(np.hypot(*np.diff(line, axis=0).T))) or 1.0
    span = 2.4 * length
    ppm = w * ss / span
    mid = line.mean(axis=0)

    def px(p):
        p = np.asarray(p, float)
        u = (p[..., 0] - mid[0]) * ppm + 0.5 * w * ss
        return u, (mid[1] - p[..., 1]) * ppm + 0.5 * h * ss

    step = length / 2  # grid every half body length, fixed to the water
    for k in range(int(2 * span / step) + 2):
        x = math.floor((mid[0] - span) / step) * step + k * step
        y = math.floor((mid[1] - span) / step) * step + k * step
        lo, hi = mid - span, mid + span
        for seg in ([[x, lo[1]], [x, hi[1]]], [[lo[0], y], [hi[0], y]]):
            u, v = px(seg)
            dr.line((u[0], v[0], u[1], v[1]), fill=GRID, width=ss)
    if len(track) > 1:
        u, v = px(np.array(track))
        dr.line(list(zip(u.tolist(), v.tolist())), fill=TRACK, width=ss)
    u, v = px(line)
    dr.line(list(zip(u.tolist(), v.tolist())), fill=EDGE, width=int(max(6, 0.07 * length * ppm)))
    dr.line(list(zip(u.tolist(), v.tolist())), fill=BODY, width=int(max(4, 0.05 * length * ppm)))
    r = 0.03 * length * ppm
    dr.ellipse((u[-1] - r, v[-1] - r, u[-1] + r, v[-1] + r), fill=HEAD)
    if np.isfinite(forces).all():
        for x, y, fx, fy in forces:
            a = px([x, y])
            b = px([x + force_scale * fx, y + force_scale * fy])
            dr.line((a[0], a[1], b[0], b[1]), fill=FORCE, width=ss)
    cx, cy, arm = 0.12 * w * ss, 0.88 * h * ss, 0.08 * w * ss
    tip = (cx + arm * math.cos(target), cy - arm * math.sin(target))
    dr.line((cx, cy, *tip), fill=TARGET, width=3 * ss)
    dr.ellipse((tip[0] - 3 * ss, tip[1] - 3 * ss, tip[0] + 3 * ss, tip[1] + 3 * ss), fill=TARGET)
    return canvas.finish(text)
