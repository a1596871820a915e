"""`save_gif`: frames -> animated GIF (pillow)."""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

import numpy as np
from PIL import Image

from mf_envs._files import atomic_path
from mf_envs._validate import positive_scalar


def save_gif(frames: Iterable[np.ndarray], path: str | Path, fps: float = 30) -> Path:
    """Write uint8 (H, W, 3) `frames` (all the same shape) to `path` as a looping GIF.

    `fps` frames per second (GIF delays are whole centiseconds, so the rate is rounded).
    One median-cut palette serves all frames (no dithering). Parent folders are created.
    Returns the path written.
    """
    fps = positive_scalar("fps", fps)
    arrays = []
    for i, frame in enumerate(frames):
        a = np.asarray(frame)
        if a.ndim != 3 or a.shape[2] != 3 or a.dtype != np.uint8:
            raise ValueError(f"frames[{i}]: expected uint8 (H, W, 3), got {a.dtype} {a.shape}")
        if arrays and a.shape != arrays[0].shape:
            raise ValueError(
                f"frames[{i}]: shape {a.shape} differs from frames[0] {arrays[0].shape}"
            )
        arrays.append(a)
    if not arrays:
        raise ValueError("frames: need at least one frame")
    # one palette for the whole animation (median cut over the first, middle and last frame),
    # no dithering: no flicker between frames and unchanged regions compress to nothing
    picks = sorted({0, len(arrays) // 2, len(arrays) - 1})
    mosaic = Image.fromarray(np.concatenate([arrays[i] for i in picks], axis=0))
    palette = mosaic.quantize(colors=255, method=Image.Quantize.MEDIANCUT)
    images = [
        Image.fromarray(a).quantize(palette=palette, dither=Image.Dither.NONE) for a in arrays
    ]
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    duration = max(20, round(100 / fps) * 10)  # ms, a multiple of 10 (GIF centiseconds)
    with atomic_path(path) as tmp:  # no link followed at `path`; the old GIF or the new one
        images[0].save(
            tmp,
            format="GIF",
            save_all=True,
            append_images=images[1:],
            duration=duration,
            loop=0,
            optimize=False,
        )
    return path
