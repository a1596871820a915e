"""Eel-v0's env concerns, declared once: observation layout (sized by the number of control
points), reward terms, reset options and info keys, shared by the single and the vector env."""

from __future__ import annotations

from mf_envs.envs._spec import Field, ObsLayout

# the serpentine's reward terms, reset options, info keys and step info: the same beam robot
from mf_envs.envs.serpentine.spec import (  # noqa: F401
    INFO_KEYS,
    RESET_OPTIONS,
    REWARD_TERMS,
    step_info,
)

CURVATURE_OBS_LIMIT = 20.0  # |kappa L| bound of the observation (also caps max_curvature * L)
VELOCITY_OBS_LIMIT = 20.0  # |v_com| / L bound [1/s] (eels cruise at 0.5-2 L/s)
TAIL_RATE_OBS_LIMIT = 200.0  # |d psi_tail / dt| bound [rad/s]


def observation_layout(n: int) -> ObsLayout:
    """The observation of an eel with n control points (2 n + 6 slots)."""
    return ObsLayout(
        Field("curvature", "", CURVATURE_OBS_LIMIT, "measured kappa L at the control points", n),
        Field("sin_heading", "", 1.0, "sin(mean frame angle - target direction)"),
        Field("cos_heading", "", 1.0, "cos(mean frame angle - target direction)"),
        Field("velocity", "1/s", VELOCITY_OBS_LIMIT, "v_com / L along, across the mean axis", 2),
        Field("tail_angle", "rad", 3.5, "tail frame angle - mean frame angle (wrapped)"),
        Field("tail_rate", "rad/s", TAIL_RATE_OBS_LIMIT, "rate of the tail's frame angle"),
        Field("curvature_command", "", 1.0, "kappa# / max_curvature at the step's end", n),
    )
