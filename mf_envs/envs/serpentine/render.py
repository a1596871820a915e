"""Frames of Serpentine-v0: the body seen from above on a ground grid that stays fixed (so the
crawl is visible), in a window following the centre of mass, the target direction as an arrow.
`draw` also serves Eel-v0 (`envs.eel.render`: the water's palette and its force arrows)."""

from __future__ import annotations

import math

import numpy as np

from mf_envs.render.canvas import Canvas

# colours of the ground scene: background, its border, grid, track, body edge, body, head, target,
# force arrows; the body's width and its edge's as fractions of its length
GROUND = {"back": (238, 240, 236), "border": (226, 230, 222), "grid": (200, 206, 214),
          "track": (150, 160, 190), "edge": (50, 92, 44), "body": (104, 168, 84),
          "head": (200, 70, 60), "target": (200, 120, 40), "force": (220, 60, 40),
          "width": 0.04, "edge_width": 0.06}  # fmt: skip


def draw(
    line: np.ndarray,
    track: list,
    target: float,
    text: str,
    size=(400, 400),
    style: dict | None = None,
    forces: np.ndarray | None = None,
    force_scale: float = 0.0,
) -> np.ndarray:
    """Top view: centreline (N, 2) [m] tail to head, the past centre-of-mass track [(x, y)],
    the target direction [rad] and a caption; `style` overrides `GROUND`'s colours and widths;
    `forces` (M, 4) rows (x, y, f_x, f_y) [m, N/m] drawn as arrows of `force_scale` [m per N/m].
    Returns uint8 (H, W, 3)."""
    c = {**GROUND, **(style or {})}
    h, w = size
    canvas = Canvas((h, w), c["back"], c["border"])
    ss, dr = canvas.ss, canvas.draw
    length = float(np.sum(np.hypot(*np.diff(line, axis=0).T))) or 1.0
    span = 2.4 * length
    ppm = w * ss / span
    mid = line.mean(axis=0)

    def px(p):
        p = np.asarray(p, float)
        u = (p[..., 0] - mid[0]) * ppm + 0.5 * w * ss
        return u, (mid[1] - p[..., 1]) * ppm + 0.5 * h * ss

    step = length / 2  # grid every half body length, fixed to the ground (the water)
    for k in range(int(2 * span / step) + 2):
        x = math.floor((mid[0] - span) / step) * step + k * step
        y = math.floor((mid[1] - span) / step) * step + k * step
        lo, hi = mid - span, mid + span
        for seg in ([[x, lo[1]], [x, hi[1]]], [[lo[0], y], [hi[0], y]]):
            u, v = px(seg)
            dr.line((u[0], v[0], u[1], v[1]), fill=c["grid"], width=ss)
    if len(track) > 1:
        u, v = px(np.array(track))
        dr.line(list(zip(u.tolist(), v.tolist())), fill=c["track"], width=ss)
    u, v = px(line)
    pts = list(zip(u.tolist(), v.tolist()))
    dr.line(pts, fill=c["edge"], width=int(max(6, c["edge_width"] * length * ppm)))
    dr.line(pts, fill=c["body"], width=int(max(4, c["width"] * length * ppm)))
    r = 0.03 * length * ppm
    dr.ellipse((u[-1] - r, v[-1] - r, u[-1] + r, v[-1] + r), fill=c["head"])
    if forces is not None and np.isfinite(forces).all():
        for x, y, fx, fy in forces:
            a, b = px([x, y]), px([x + force_scale * fx, y + force_scale * fy])
            dr.line((a[0], a[1], b[0], b[1]), fill=c["force"], width=ss)
    cx, cy, arm = 0.12 * w * ss, 0.88 * h * ss, 0.08 * w * ss
    tip = (cx + arm * math.cos(target), cy - arm * math.sin(target))
    dr.line((cx, cy, *tip), fill=c["target"], width=3 * ss)
    dot = 3 * ss
    dr.ellipse((tip[0] - dot, tip[1] - dot, tip[0] + dot, tip[1] + dot), fill=c["target"])
    return canvas.finish(text)
