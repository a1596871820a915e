"""Eel-v0's env concerns, declared once: observation layout (sized by the number of control
points), reward terms, reset options and info keys, shared by the single and the vector env."""

from __future__ import annotations

from mf_envs.envs._spec import Field, ObsLayout
from mf_envs.envs.serpentine.spec import step_info  # noqa: F401  (the same info of a step)

CURVATURE_OBS_LIMIT = 20.0  # |kappa L| bound of the observation (also caps max_curvature * L)
VELOCITY_OBS_LIMIT = 20.0  # |v_com| / L bound [1/s] (eels cruise at 0.5-2 L/s)
TAIL_RATE_OBS_LIMIT = 200.0  # |d psi_tail / dt| bound [rad/s]
REWARD_TERMS = ("progress", "effort")
RESET_OPTIONS = ("heading", "kappa")
INFO_KEYS = (
    "x",  # m, centre of mass
    "y",  # m, centre of mass
    "heading",  # rad, mean frame angle of the body (world, unwrapped)
    "speed",  # m/s, centre-of-mass displacement along the target direction / control_dt
    "kappa_command",  # (n,) 1/m, actuation curvature at the control points at the step's end
    "actuation_energy",  # J, positive work of the muscles in the step (no regeneration)
    "actuation_power",  # W, actuation_energy / control_dt
    "actuation_net_work",  # J, the muscles' signed work in the step
    "newton_iterations",  # of the step (all substeps)
    "time",  # s, steps x control_dt
    "reward_terms",  # {"progress", "effort"}, sums to the reward
    "numerical_failure",  # Newton failed after step halving, or a non-finite state
)


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
