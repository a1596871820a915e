"""`HumanWindow`: shows frames for render_mode="human".

pygame when installed (`pip install mf-envs[render]`), else a matplotlib window. Neither is
imported until the first `show`, so the headless rgb_array path never touches a display.
"""

from __future__ import annotations

import importlib.util
from typing import Any

import numpy as np


def _check_frame(frame: Any) -> np.ndarray:
    a = np.asarray(frame)
    if a.ndim != 3 or a.shape[2] != 3 or a.dtype != np.uint8:
        raise ValueError(f"frame: expected uint8 (H, W, 3), got {a.dtype} {a.shape}")
    return a


class HumanWindow:
    """A window titled `title`; `show(frame)` displays a uint8 (H, W, 3) frame, `close()` ends.

    `backend`: "pygame", "matplotlib" or None (pygame if importable, else matplotlib).
    """

    def __init__(self, title: str = "mf_envs", backend: str | None = None) -> None:
        if backend is None:
            backend = "pygame" if importlib.util.find_spec("pygame") else "matplotlib"
        if backend not in ("pygame", "matplotlib"):
            raise ValueError(f"backend: must be 'pygame' or 'matplotlib', got {backend!r}")
        self.title = str(title)
        self.backend = backend
        self._screen: Any = None
        self._fig: Any = None
        self._im: Any = None

    def show(self, frame: np.ndarray) -> None:
        frame = _check_frame(frame)
        if self.backend == "pygame":
            self._show_pygame(frame)
        else:
            self._show_matplotlib(frame)

    def _show_pygame(self, frame: np.ndarray) -> None:
        import pygame

        h, w, _ = frame.shape
        if self._screen is None or self._screen.get_size() != (w, h):
            pygame.display.init()  # video only (no audio device needed)
            self._screen = pygame.display.set_mode((w, h))
            pygame.display.set_caption(self.title)
        pygame.event.pump()
        surf = pygame.surfarray.make_surface(np.ascontiguousarray(frame.swapaxes(0, 1)))
        self._screen.blit(surf, (0, 0))
        pygame.display.flip()

    def _show_matplotlib(self, frame: np.ndarray) -> None:
        import matplotlib.pyplot as plt

        if self._fig is None or not plt.fignum_exists(self._fig.number):
            plt.ion()
            h, w, _ = frame.shape
            self._fig = plt.figure(self.title, figsize=(w / 100, h / 100), dpi=100)
            ax = self._fig.add_axes((0, 0, 1, 1))
            ax.set_axis_off()
            self._im = ax.imshow(frame)
            self._fig.show()
        else:
            self._im.set_data(frame)
        self._fig.canvas.draw_idle()
        self._fig.canvas.flush_events()

    def close(self) -> None:
        """Close the window (safe to call twice or before any `show`)."""
        if self._screen is not None:
            import pygame

            pygame.display.quit()
            self._screen = None
        if self._fig is not None:
            import matplotlib.pyplot as plt

            plt.close(self._fig)
            self._fig = self._im = None
