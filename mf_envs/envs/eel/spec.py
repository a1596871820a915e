"""Eel-v0's env concerns, declared once: observation layout (sized by the number of control
points), reward terms, reset options and info keys, shared by the single and the vector env."""

from __future__ import annotations

from mf_envs.envs._spec import Field, ObsLayout

# the serpentine's reward terms, reset options, info keys, step info and observation bounds:
# the same beam robot
from mf_envs.envs.serpentine.spec import (  # noqa: F401
    CURVATURE_OBS_LIMIT,
    INFO_KEYS,
    RESET_OPTIONS,
    REWARD_TERMS,
    beam_layout,
    step_info,
)

VELOCITY_OBS_LIMIT = 20.0  # |v_com| / L bound [1/s] (eels cruise at 0.5-2 L/s)
TAIL_RATE_OBS_LIMIT = 200.0  # |d psi_tail / dt| bound [rad/s]
# the tail rate's fixed unit (`_spec.Field.scale`): a beating tail turns at tens of rad/s (std 26
# under the heading baseline, 43 under random actions), so in rad/s the slot was far above O(1)
TAIL_RATE_UNIT = 10.0  # rad/s


def observation_layout(n: int) -> ObsLayout:
    """The observation of an eel with n control points (2 n + 6 slots)."""
    tail = (
        Field("tail_angle", "rad", 3.5, "tail frame angle - mean frame angle (wrapped)"),
        Field(
            "tail_rate",
            "rad/s",
            TAIL_RATE_OBS_LIMIT,
            "rate of the tail's frame angle",
            scale=TAIL_RATE_UNIT,
        ),
    )
    return beam_layout(n, "mean frame angle", VELOCITY_OBS_LIMIT, tail)
