"""Serpentine-v0's env concerns, declared once: observation layout (sized by the number of control
points), reward terms, reset options and info keys, shared by the single and the vector env."""

from __future__ import annotations

from mf_envs.envs._spec import Field, ObsLayout

CURVATURE_OBS_LIMIT = 20.0  # |kappa L| bound of the observation (also caps max_curvature * L)
VELOCITY_OBS_LIMIT = 10.0  # |v_com| / L bound [1/s] (the snake crawls at ~0.1 L/s)
# the velocity slots' fixed unit (`_spec.Field.scale`), in L/s: the snake crawls at ~0.1 L/s,
# so in L/s the slots' spread was 0.02-0.04 (random actions, the heading baseline)
VELOCITY_UNIT = 0.1
REWARD_TERMS = ("progress", "effort")
RESET_OPTIONS = ("heading", "kappa")
INFO_KEYS = (
    "x",  # m, centre of mass
    "y",  # m, centre of mass
    "heading",  # rad, frame angle psi of the head segment (world, unwrapped)
    "speed",  # m/s, centre-of-mass displacement along the target direction / control_dt
    "kappa_command",  # (n,) 1/m, commanded actuation curvature at the control points
    "actuation_energy",  # J, positive work of the muscles in the step (no regeneration)
    "actuation_power",  # W, actuation_energy / control_dt
    "actuation_net_work",  # J, the muscles' signed work in the step (dKE + dU - ground work)
    "newton_iterations",  # of the step (all substeps)
    "time",  # s, steps x control_dt
    "reward_terms",  # {"progress", "effort"}, sums to the reward
    "numerical_failure",  # Newton failed after step halving, or a non-finite state
)


def observation_layout(n: int) -> ObsLayout:
    """The observation of a serpentine with n control points (2 n + 4 slots)."""
    return beam_layout(n, "psi_head", VELOCITY_OBS_LIMIT, velocity_unit=VELOCITY_UNIT)


def beam_layout(
    n: int, heading: str, velocity_limit: float, extra: tuple = (), velocity_unit: float = 1.0
) -> ObsLayout:
    """A beam robot's observation with n control points: the curvatures, the heading (`heading`:
    the angle it reads) against the target, the centre of mass's velocity (bound
    `velocity_limit` L/s, in units of `velocity_unit` L/s), the robot's `extra` fields and the
    commanded curvatures."""
    return ObsLayout(
        Field("curvature", "", CURVATURE_OBS_LIMIT, "measured kappa L at the control points", n),
        Field("sin_heading", "", 1.0, f"sin({heading} - target direction)"),
        Field("cos_heading", "", 1.0, f"cos({heading} - target direction)"),
        Field(
            "velocity",
            "1/s",
            velocity_limit,
            "v_com / L along, across the mean axis",
            2,
            scale=velocity_unit,
        ),
        *extra,
        Field("curvature_command", "", 1.0, "kappa# / max_curvature at the step's end", n),
    )


def step_info(x, y, heading, speed, cmd, energy, net, dt, iterations, time, terms) -> dict:
    """The info of a step (scalars, or (N,) arrays in the vector env)."""
    return {
        "x": x,
        "y": y,
        "heading": heading,
        "speed": speed,
        "kappa_command": cmd,
        "actuation_energy": energy,
        "actuation_power": energy / dt,
        "actuation_net_work": net,
        "newton_iterations": iterations,
        "time": time,
        "reward_terms": terms,
    }
