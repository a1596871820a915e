"""Frames of Eel-v0: the body seen from above in still water on a grid fixed to the water (so the
swimming is visible), in a window following the centre of mass, with arrows of Taylor's
resistive line force at the Gauss points (no wake: the model has none), the target direction
as an arrow. The drawing is the serpentine's (`envs.serpentine.render.draw`) in water colours."""

from __future__ import annotations

import numpy as np

from mf_envs.envs.serpentine.render import draw as draw_top_view

FORCE = (220, 60, 40)
WATER = {"back": (214, 232, 244), "border": (200, 222, 238), "grid": (170, 200, 222),
         "track": (120, 150, 190), "edge": (30, 52, 80), "body": (70, 110, 150),
         "force": FORCE, "width": 0.05, "edge_width": 0.07}  # fmt: skip


def draw(line: np.ndarray, track: list, target: float, text: str, forces: np.ndarray,
         force_scale: float, size=(400, 400)) -> np.ndarray:  # fmt: skip
    """Top view: centreline (N, 2) [m] tail to head, the past centre-of-mass track [(x, y)],
    the target direction [rad], a caption, forces (M, 4) rows (x, y, f_x, f_y) [m, N/m] drawn
    as arrows of force_scale [m per N/m]. Returns uint8 (H, W, 3)."""
    return draw_top_view(line, track, target, text, size, WATER, forces, force_scale)
