"""A supersampled PIL canvas: background gradient, HUD text, final uint8 (H, W, 3) frame.

Polygons are drawn at `SUPERSAMPLE` times the output size and box-filtered down (PIL's
`Image.reduce`), which gives anti-aliased edges at a measured cost (benchmarks/speed/render.py).
Text is drawn after the reduction at the output resolution with a TrueType font (DejaVu Sans,
shipped with matplotlib; PIL's built-in font otherwise).
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import numpy as np
from PIL import Image, ImageDraw, ImageFont

from mf_envs._validate import check_int

SUPERSAMPLE = 2
TEXT_COLOR = (30, 34, 40)


def check_size(size: tuple[int, int]) -> tuple[int, int]:
    """Validated (H, W) in pixels (each 32 ... 4096)."""
    try:
        h, w = size
    except (TypeError, ValueError) as exc:
        raise ValueError(f"size: expected (H, W), got {size!r}") from exc
    return check_int("size[0]", h, 32, 4096), check_int("size[1]", w, 32, 4096)


@lru_cache(maxsize=8)
def font(px: int) -> ImageFont.ImageFont:
    """DejaVu Sans at `px` pixels (matplotlib's copy), PIL's default font as a fallback."""
    try:
        import matplotlib

        path = Path(matplotlib.get_data_path()) / "fonts" / "ttf" / "DejaVuSans.ttf"
        return ImageFont.truetype(str(path), px)
    except (ImportError, OSError):  # pragma: no cover - matplotlib is a dependency
        return ImageFont.load_default(size=px)


@lru_cache(maxsize=16)
def _gradient(
    h: int, w: int, top: tuple[int, int, int], bottom: tuple[int, int, int]
) -> Image.Image:
    t = np.linspace(0.0, 1.0, h)[:, None, None]
    img = (1 - t) * np.array(top) + t * np.array(bottom)
    return Image.fromarray(np.broadcast_to(img, (h, w, 3)).astype(np.uint8))


class Canvas:
    """Output size (H, W); `draw` works in supersampled pixels, `ss` is the factor."""

    def __init__(
        self,
        size: tuple[int, int],
        top: tuple[int, int, int] = (236, 240, 245),
        bottom: tuple[int, int, int] = (200, 208, 218),
        ss: int = SUPERSAMPLE,
    ) -> None:
        self.size = check_size(size)
        self.ss = ss
        h, w = self.size
        self.image = _gradient(h * ss, w * ss, top, bottom).copy()
        self.draw = ImageDraw.Draw(self.image)

    def finish(self, text: str = "", overlay=None) -> np.ndarray:
        """Reduce to the output size, draw the HUD text (top left) and return uint8 (H, W, 3).

        `overlay(draw)` draws extra items at the output resolution before the text.
        """
        img = self.image.reduce(self.ss) if self.ss > 1 else self.image
        draw = ImageDraw.Draw(img)
        if overlay is not None:
            overlay(draw)
        if text:
            hud_text(draw, str(text), self.size)
        return np.asarray(img, dtype=np.uint8)


def hud_text(draw: ImageDraw.ImageDraw, text: str, size: tuple[int, int]) -> None:
    """Multi-line text in a light rounded box at the top left, scaled with the frame height."""
    px = max(10, round(size[0] / 28))
    f = font(px)
    x0, y0, pad = round(px * 0.6), round(px * 0.6), round(px * 0.4)
    box = draw.multiline_textbbox((x0, y0), text, font=f, spacing=round(px * 0.25))
    draw.rounded_rectangle(
        (box[0] - pad, box[1] - pad, box[2] + pad, box[3] + pad),
        radius=pad,
        fill=(255, 255, 255),
        outline=(170, 176, 186),
    )
    draw.multiline_text((x0, y0), text, font=f, fill=TEXT_COLOR, spacing=round(px * 0.25))


def axis_triad(
    draw: ImageDraw.ImageDraw,
    camera,
    origin_px: tuple[float, float],
    length_px: float,
    labels=("x1", "x2", "x3"),
) -> None:
    """The inertial axes e1, e2, e3 as seen by `camera`, drawn at `origin_px` (output pixels)."""
    from mf_envs.render.meshes import AXIS_COLORS

    r, u, _ = camera.basis()
    f = font(max(9, round(length_px / 2.6)))
    pad = 1.45 * length_px
    draw.rounded_rectangle(
        (origin_px[0] - pad, origin_px[1] - pad, origin_px[0] + pad, origin_px[1] + 0.6 * pad),
        radius=round(0.3 * length_px),
        fill=(250, 250, 250),
        outline=(170, 176, 186),
    )
    for k in range(3):
        e = np.eye(3)[k]
        v = np.array([e @ r, -(e @ u)])
        end = (origin_px[0] + length_px * v[0], origin_px[1] + length_px * v[1])
        color = tuple(int(c * 0.8) for c in AXIS_COLORS[k])
        draw.line([origin_px, end], fill=color, width=2)
        draw.text(
            (end[0] + 2 * v[0], end[1] + 2 * v[1]), labels[k], font=f, fill=color, anchor="mm"
        )
