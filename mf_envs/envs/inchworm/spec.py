"""Inchworm-v0's env concerns, declared once: observation layout (sized by the number of control
points), reward terms, info keys and the failure contract."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mf_envs.envs._spec import Field, ObsLayout
from mf_envs.envs.inchworm.rows import observe_row, sample_points

CURVATURE_OBS_LIMIT = 20.0  # |kappa L| bound of the observation (also caps max_curvature * L)
REACTION_OBS_LIMIT = 20.0  # |ground reaction| / body weight bound
REWARD_TERMS = ("progress", "effort")
RESET_OPTIONS = ("kappa", "x_tail")
MAX_X_TAIL = 1e6  # m, |x_tail| of a reset: x carries ~1e-10 m resolution there
INFO_KEYS = (
    "x_head",  # m
    "x_tail",  # m
    "centerline",  # (N, 2) m, (x, z) of the centroid line
    "anchor",  # "head" or "tail", the gripping foot
    "kappa_sharp",  # (n,) 1/m, realised actuation curvature at the control points
    "kappa_command",  # (n,) 1/m, commanded actuation curvature at the control points
    "actuation_power",  # W, mean mechanical actuation power of the step (A2, signed)
    "actuation_energy",  # J, energy drawn by the actuators in the step (no regeneration)
    "grip",  # (2,) engagement of the tail, head foot in [0, 1] (1: gripping)
    "foot_slip",  # (2,) m, x-slip of the tail, head foot in the step (friction)
    "elastic_energy",  # J
    "newton_iterations",  # of the step
    "increments",  # load increments of the step
    "time",  # s, steps x control_dt
    "reward_terms",  # {"progress", "effort"}, sums to the reward
    "numerical_failure",  # Newton failed after step halving: terminates (docs/api.md)
)


def observation_layout(n: int) -> ObsLayout:
    """The observation of an inchworm with n control points (2 n + 6 slots)."""
    return ObsLayout(
        Field("curvature", "", CURVATURE_OBS_LIMIT, "measured kappa L at the control points", n),
        Field("curvature_command", "", 1.0, "commanded kappa# / max_curvature", n),
        Field("tail_angle", "rad", 2 * math.pi, "frame angle psi at the tail (foot IMU)"),
        Field("head_angle", "rad", 2 * math.pi, "frame angle psi at the head (foot IMU)"),
        Field("head_tail_distance", "", 1.5, "(x_head - x_tail) / L"),
        Field("grip", "", 1.0, "gripping foot: +1 head, -1 tail"),
        Field("tail_reaction", "", REACTION_OBS_LIMIT, "ground reaction at the tail / weight"),
        Field("head_reaction", "", REACTION_OBS_LIMIT, "ground reaction at the head / weight"),
    )


def observe_geometry(sim: Any, s_ctrl: np.ndarray) -> tuple:
    """The constant geometry `observe.observe_row` needs for the inchworm `sim`."""
    xis, s_samples = sample_points(sim.model)
    return (sim.model.le, *sim.model.quad, xis, s_samples, np.asarray(s_ctrl, float))


def observe(
    sim: Any, geometry: tuple, kappa_ctrl: np.ndarray, max_curvature: float, weight: float
) -> np.ndarray:
    """The observation (layout order, float32) of the inchworm simulation `sim`
    (`observe.observe_row`; `geometry` from `observe_geometry`)."""
    n = len(kappa_ctrl)
    out = np.empty(2 * n + 6, np.float32)
    own = sim.terrain is None
    reactions = np.zeros(2) if own else np.array(sim.support_reactions())
    observe_row(
        sim.state.d, sim.x_origin, sim.kappa, np.asarray(kappa_ctrl, float),
        sim.anchor == "head", reactions, own, geometry, sim.f_ext,
        (sim.params.length, max_curvature, weight), out,
    )  # fmt: skip
    return out


def tail_position(sim: Any) -> tuple[float, float]:
    """(x_origin, local x) of the tail (m): their sum is x_tail; differences of the local part
    stay exact at any distance crawled (reward without cancellation at large x)."""
    return sim.x_origin, float(sim.state.d[sim.model.dof(sim.tail, "z1")])


def reward_terms(
    before: tuple[float, float],
    after: tuple[float, float],
    length: float,
    energy: float,
    effort_weight: float,
) -> dict[str, float]:
    """progress = tail advance / L from `tail_position` before and after the step (origin
    shifts added separately); effort = -w x actuation energy of the step [J]."""
    advance = (after[1] - before[1]) + (after[0] - before[0])
    return {"progress": float(advance / length), "effort": -effort_weight * float(energy)}
