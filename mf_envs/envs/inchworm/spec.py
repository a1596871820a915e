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
    "electrical_energy",  # J, electrical energy of the wires in the step (sma_wires; else 0)
    "mechanical_work",  # J, positive mechanical work of the actuator in the step
    "wire_temperature",  # (n,) degC, each wire group's (sma_wires; else the ambient)
    "duty",  # (n,) duty cycles of the wire groups in [0, 1] (the action's, any scene)
    "quasi_static_error",  # inertia / friction of the feet (0 without friction feet)
    "reward_terms",  # {"progress", "effort"}, sums to the reward
    "numerical_failure",  # Newton failed after step halving: terminates (docs/api.md)
)


# quasi_static_error above this: the neglected inertia exceeds half the feet's friction (our
# choice; measured: the lag-friction robot's 5 Hz gait 0.71 every step, the SMA robot's gaits
# median 0.003-0.012, 0.25-0.31 for one step per cycle at the slip onset; docs/inchworm.md)
QUASI_STATIC_LIMIT = 0.5
WIRE_TEMPERATURE_OBS_LIMIT = 4.0  # bound of (T - T_amb) / (Af - T_amb)


def observation_layout(n: int, sma: bool = False) -> ObsLayout:
    """The observation of an inchworm with n control points (2 n + 6 slots); with the SMA
    wires (`sma`) the command slots hold the wire groups' temperatures instead (what the
    robot knows of its actuators: the realised curvature is measured by the strain gauges)."""
    second = (
        Field("wire_temperature", "", WIRE_TEMPERATURE_OBS_LIMIT,
              "(T - T_amb) / (Af - T_amb) of each control point's wire group", n)
        if sma
        else Field("curvature_command", "", 1.0, "commanded kappa# / max_curvature", n)
    )  # fmt: skip
    return ObsLayout(
        Field("curvature", "", CURVATURE_OBS_LIMIT, "measured kappa L at the control points", n),
        second,
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


def wire_temperature_obs(temperature: np.ndarray, wires: Any) -> np.ndarray:
    """(T - T_amb) / (Af - T_amb) of the wire groups, clipped to the observation bound."""
    p = wires.params
    scale = p.alloy.austenite_finish - p.ambient
    lim = WIRE_TEMPERATURE_OBS_LIMIT
    return np.clip((np.asarray(temperature, float) - p.ambient) / scale, -lim, lim)


def grip_capacity(law: Any, grip: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """The largest friction force [N] each gripping foot (`grip.GripLaw`) can exert,
    N (mu_s + phi(g) (min(mu_grip) - mu_s)) (the smaller gripping coefficient: conservative);
    grip, normal (..., 2) -> (..., 2)."""
    mu_g = np.minimum(law.grip_forward, law.grip_backward)  # (law's fields: numbers or columns)
    x = np.clip((np.asarray(grip, float) - law.threshold) / law.width, 0.0, 1.0)
    phi = x * x * (3.0 - 2.0 * x)
    return np.maximum(np.asarray(normal, float), 0.0) * (law.mu_slide + phi * (mu_g - law.mu_slide))


def holding_capacity(mu4: np.ndarray, grip: np.ndarray, ground_x: np.ndarray, normal) -> np.ndarray:
    """Coulomb feet (`friction.holding_limit`): mu(g, s) max(N, 0) for the direction s each foot
    is pulled in (s = -sign R_x); arrays (..., 2) -> (..., 2)."""
    grip, rx = np.asarray(grip, float), np.asarray(ground_x, float)
    backward = rx > 0.0
    mu_grip = np.where(backward, mu4[1], mu4[0])
    mu_slide = np.where(backward, mu4[3], mu4[2])
    return (mu_slide + grip * (mu_grip - mu_slide)) * np.maximum(np.asarray(normal, float), 0.0)


def quasi_static_error(
    dx: np.ndarray, dx_prev: np.ndarray, dt: float, params: Any, limit: np.ndarray
) -> np.ndarray:
    """Inertia over friction, the quasi-static model's error estimate: for each foot the
    acceleration |dx - dx_prev| / dt^2 of its step-mean velocities (m/s over one control step)
    times half the body's mass, over the friction force the foot can exert (`limit`, N);
    the larger of the two feet. dx, dx_prev, limit (..., 2) -> (...). Above
    QUASI_STATIC_LIMIT the neglected inertia is not small (`info["quasi_static_error"]`)."""
    half_mass = 0.5 * params.mass_per_length * params.length
    accel = np.abs(np.asarray(dx, float) - np.asarray(dx_prev, float)) / dt**2
    return np.max(half_mass * accel / np.maximum(limit, 1e-12), axis=-1)


def step_quasi_static_error(
    driven: Any, scene: Any, report: Any, dx: np.ndarray, dx_prev: np.ndarray, dt: float
) -> float:
    """`quasi_static_error` of a control step of the single env from the feet's displacements
    of this and the last step [m] and the friction the feet can exert at the step's end
    (`holding_capacity` on Coulomb feet, `grip_capacity` on gripping feet); 0 when the drive
    has neither (kinematic anchors, terrain, inertia) or the step failed (report None)."""
    if report is None or (driven.feet is None and driven.grip_feet is None):
        return 0.0
    if driven.feet is not None:
        f = report.feet
        limit = holding_capacity(driven.feet.params.coefficients, driven.grip, f.ground_x, f.normal)
    else:
        limit = grip_capacity(scene.grip_feet.law, driven.grip, report.normal)
    return float(quasi_static_error(dx, dx_prev, dt, scene.params, limit))
