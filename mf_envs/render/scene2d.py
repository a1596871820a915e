"""The inchworm (ch.4 §4.10) seen from the side: its centreline on the ground, in a window that
follows it, with fixed ground ticks (so forward progress is visible) and head/tail markers."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from mf_envs._validate import check_finite, finite_scalar
from mf_envs.render.canvas import Canvas, check_size, font

BODY = (104, 168, 84)
BODY_EDGE = (50, 92, 44)
GROUND = (196, 170, 128)
GROUND_EDGE = (120, 96, 64)
HEAD = (200, 70, 60)
TAIL = (70, 110, 190)


def _nice_step(span: float) -> float:
    """A 1-2-5 x 10^k tick spacing giving about 8 ticks over `span`."""
    raw = span / 8
    k = 10 ** math.floor(math.log10(raw))
    return min((m * k for m in (1, 2, 5, 10)), key=lambda v: abs(v - raw))


def _label(x: float, step: float) -> str:
    if step < 0.1:
        return f"{100 * x:.0f} cm" if step >= 0.01 else f"{1000 * x:.0f} mm"
    return f"{x:g} m"


def draw_inchworm(
    *,
    centerline: ArrayLike,
    x_head: float,
    x_tail: float,
    ground_z: float = 0.0,
    text: str = "",
    size: tuple[int, int] = (360, 480),
) -> np.ndarray:
    """Side view of a planar beam robot. centerline: (N, 2) points (x along the ground, z up)
    in m from tail (S = 0) to head (S = L); x_head, x_tail: ground positions (m) of the two
    end nodes, marked on the ground; ground_z: ground height (m). The window is 2.4 body
    lengths wide and centred on the body. Returns uint8 (H, W, 3) for `size` = (H, W).
    """
    c = check_finite("centerline", centerline)
    if c.ndim != 2 or c.shape[1] != 2 or c.shape[0] < 2:
        raise ValueError(f"centerline: expected shape (N, 2) with N >= 2, got {c.shape}")
    xh = finite_scalar("x_head", x_head)
    xt = finite_scalar("x_tail", x_tail)
    gz = finite_scalar("ground_z", ground_z)
    h, w = check_size(size)
    length = float(np.sum(np.hypot(*np.diff(c, axis=0).T))) or 1.0
    canvas = Canvas((h, w), (234, 240, 246), (214, 224, 234))
    ss, draw = canvas.ss, canvas.draw
    span = 2.4 * length
    ppm = w * ss / span  # supersampled pixels per metre
    x_mid = 0.5 * (c[:, 0].min() + c[:, 0].max())
    ground_row = 0.74 * h * ss

    def px(x, z):
        return (
            (np.asarray(x) - x_mid) * ppm + 0.5 * w * ss,
            ground_row - (np.asarray(z) - gz) * ppm,
        )

    _ground(draw, px, x_mid, span, gz, ground_row, (h, w), ss)
    # head / tail ground markers (triangles pointing up at the node's ground position)
    tri = 6 * ss
    for x, col in ((xt, TAIL), (xh, HEAD)):
        u, v = px(x, gz)
        draw.polygon([(u, v), (u - tri, v + 1.6 * tri), (u + tri, v + 1.6 * tri)], fill=col)

    _body(draw, np.column_stack(px(c[:, 0], c[:, 1])), max(4.0 * ss, 0.05 * length * ppm), ss)
    return canvas.finish(text)


def _ground(draw, px, x_mid: float, span: float, gz: float, ground_row: float, hw, ss: int):
    """The ground band, its ticks and labels (fixed in x), and the dashed start line x = 0."""
    h, w = hw
    draw.rectangle((0, ground_row, w * ss, h * ss), fill=GROUND)
    draw.line((0, ground_row, w * ss, ground_row), fill=GROUND_EDGE, width=2 * ss)
    step = _nice_step(span)
    f = font(max(9, round(h / 34)) * ss)
    x0 = math.floor((x_mid - span / 2) / step) * step
    for k in range(int(span / step) + 3):
        x = x0 + k * step
        u, _ = px(x, gz)
        major = abs(round(x / step) % 2) == 0
        draw.line(
            (u, ground_row, u, ground_row + (9 if major else 5) * ss), fill=GROUND_EDGE, width=ss
        )
        label = _label(round(x, 9), step)
        half = 0.5 * f.getlength(label)
        if major and half < u < w * ss - half:  # whole labels only
            draw.text((u, ground_row + 11 * ss), label, font=f, fill=GROUND_EDGE, anchor="mt")
    u0, _ = px(0.0, gz)
    for v in np.arange(0.15 * h * ss, ground_row, 8 * ss):  # dashed start line at x = 0
        draw.line((u0, v, u0, v + 4 * ss), fill=(150, 150, 160), width=ss)


def _body(draw, pts: np.ndarray, thick: float, ss: int) -> None:
    """The body: a ribbon of width `thick` around the centreline points `pts` (offset along the
    normals), the tail and head as discs."""
    tangent = np.gradient(pts, axis=0)
    normal = np.column_stack([-tangent[:, 1], tangent[:, 0]])
    normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-12)
    ribbon = np.vstack([pts + 0.5 * thick * normal, (pts - 0.5 * thick * normal)[::-1]])
    draw.polygon([tuple(p) for p in ribbon.tolist()], fill=BODY, outline=BODY_EDGE, width=ss)
    ends = [tuple(p) for p in pts.tolist()]
    for (u, v), col, rad in ((ends[0], TAIL, 0.55 * thick), (ends[-1], HEAD, 0.8 * thick)):
        draw.ellipse((u - rad, v - rad, u + rad, v + rad), fill=col, outline=BODY_EDGE, width=ss)
