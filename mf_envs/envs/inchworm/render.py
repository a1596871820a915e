"""Frames of Inchworm-v0: the body's centreline on the ground, with the gripping foot."""

from __future__ import annotations

from typing import Any

import numpy as np

FRAME_KEYS = ("centerline", "x_head", "x_tail", "anchor")


def frame_state(info: dict[str, Any], step: int) -> dict[str, Any] | None:
    """The drawable state of `info` if it is finite, else None (after a numerical failure the
    physics state may be NaN; render() then shows the last finite one)."""
    if np.isfinite(info["x_head"] + info["x_tail"]) and np.isfinite(info["centerline"]).all():
        return {**{k: info[k] for k in FRAME_KEYS}, "step": step}
    return None


def sim_state(sim: Any) -> dict[str, Any]:
    """The drawable state of the constructed robot (before the first reset)."""
    return {"centerline": sim.centerline(), "x_head": sim.x_head, "x_tail": sim.x_tail,
            "anchor": sim.anchor}  # fmt: skip


def draw(fs: dict[str, Any], step: int) -> np.ndarray:
    """The frame of the remembered state `fs` at control step `step`."""
    from mf_envs.render import draw_inchworm

    note = "" if fs["step"] == step else "  (last finite state)"
    return draw_inchworm(
        centerline=fs["centerline"],
        x_head=fs["x_head"],
        x_tail=fs["x_tail"],
        text=f"step {fs['step']}  tail x = {fs['x_tail']:+.3f} m  grip: {fs['anchor']}{note}",
    )
