"""Inchworm-v0's kwargs -> typed physics parameters, never the env (errors name the kwarg).

`build(kw)`: the `Scene` (body, actuation range, reward weight, start noise, control points,
soil, actuator and feet); `drive_kwargs`: `make_driven`'s arguments once the effects and the
physics step are known; `episode_steps`: the episode length.

`beam_params`: the body (length, section, material, mesh). `robot_params` (issue 16): the
actuator and feet kwargs `actuator_time_constant` [s], `actuator_rate_limit` [1/(m s)],
`grip_time_constant` [s] and `friction_coefficients` become the physics' `ActuatorParams` and
`FrictionParams` (`mf_envs.physics.actuators.curvature`,
`mf_envs.physics.beam.contact.friction`).
"""

from __future__ import annotations

import dataclasses
from typing import Any

from mf_envs._validate import check_choice, check_int, check_range
from mf_envs.envs.inchworm.spec import CURVATURE_OBS_LIMIT
from mf_envs.physics.actuators.curvature import SMA_RATE_LIMIT, SMA_TIME_CONSTANT, ActuatorParams
from mf_envs.physics.beam.contact.friction import FrictionParams
from mf_envs.physics.inchworm import InchwormParams
from mf_envs.physics.terrain import SOILS

MAX_INCREMENTS = 200  # increments (or Newmark steps) of a full-range step: a step stays fast
FRICTION_KEYS = ("grip_forward", "grip_backward", "slide_forward", "slide_backward")
GRIP_TIME_CONSTANT = 0.2  # s, FrictionParams' default engage/release time
DEFAULT_EPISODE_STEPS = 400
__all__ = [
    "GRIP_TIME_CONSTANT",
    "SMA_RATE_LIMIT",
    "SMA_TIME_CONSTANT",
    "Scene",
    "beam_params",
    "build",
    "drive_kwargs",
    "episode_steps",
    "robot_params",
    "step_budget",
]


@dataclasses.dataclass(frozen=True)
class Scene:
    """What the env's kwargs become (SI units), validated; the env reads its parameters here."""

    params: InchwormParams
    max_curvature: float  # 1/m, the actuation range kappa0#
    effort_weight: float  # 1 / (J) per step: default 1 / (body weight x length)
    reset_noise_scale: float
    increment_factor: float  # quasi-static increments of increment_factor x 2 h / L^2
    n_ctrl: int  # control points
    soil: str
    actuator_rate_limit: float  # 1/(m s), with `actuator_dynamics`
    actuator_params: ActuatorParams
    feet: FrictionParams

    @property
    def weight(self) -> float:
        """Body weight m_A g L (N)."""
        p = self.params
        return p.mass_per_length * p.gravity * p.length


def build(kw: dict[str, Any], effects: frozenset, n_substeps: int) -> Scene:
    """The `Scene` of the env's kwargs `kw` under these effects and physics substeps per control
    step; ValueError names the kwarg."""
    params = beam_params(kw["length"], kw["width"], kw["height"], kw["youngs_modulus"],
                         kw["shear_modulus"], kw["mass_per_length"], kw["n_elements"])  # fmt: skip
    L = params.length
    max_curvature = check_range("max_curvature", kw["max_curvature"], 1e-9)
    if max_curvature * L > CURVATURE_OBS_LIMIT:
        raise ValueError(
            f"max_curvature: max_curvature * length must be <= {CURVATURE_OBS_LIMIT:g} (the "
            f"curvature observation bound), got {max_curvature:g} 1/m x {L:g} m"
        )
    effort = kw["effort_weight"]
    if effort is None:
        effort = 1.0 / (params.mass_per_length * params.gravity * L * L)
    head = dict(
        params=params,
        max_curvature=max_curvature,
        effort_weight=check_range("effort_weight", effort, 0.0, 1e6),
        reset_noise_scale=check_range("reset_noise_scale", kw["reset_noise_scale"], 0.0, 1.0),
        increment_factor=step_budget(
            kw["increment_factor"], max_curvature, params, n_substeps, effects
        ),  # fmt: skip
        n_ctrl=check_int("n_control_points", kw["n_control_points"], low=2, high=64),
        soil=check_choice("soil", kw["soil"], tuple(SOILS)),
    )
    act, feet = robot_params(kw["actuator_time_constant"], kw["actuator_rate_limit"],
                             kw["grip_time_constant"], kw["friction_coefficients"])  # fmt: skip
    return Scene(**head, actuator_rate_limit=act.rate_limit, actuator_params=act, feet=feet)


def episode_steps(max_episode_steps: Any, episode_seconds: Any, seconds_to_steps) -> int:
    """Control steps per episode: `seconds_to_steps(episode_seconds)` (`MFEnv._episode_steps`)
    or `max_episode_steps` (default 400); not both."""
    if episode_seconds is not None and max_episode_steps is not None:
        raise ValueError("episode_seconds: give episode_seconds or max_episode_steps, not both")
    if episode_seconds is not None:
        return seconds_to_steps(episode_seconds)
    steps = DEFAULT_EPISODE_STEPS if max_episode_steps is None else max_episode_steps
    return check_int("max_episode_steps", steps, 1, 10**7)


def drive_kwargs(scene: Scene, effects: frozenset) -> dict[str, Any]:
    """`make_driven`'s arguments: the scene's robot with these effects."""
    return dict(params=scene.params, effects=effects, n_control_points=scene.n_ctrl,
                actuator=scene.actuator_params, friction=scene.feet,
                increment_factor=scene.increment_factor, soil=scene.soil)  # fmt: skip


def step_budget(
    increment_factor: Any, max_curvature: float, params: InchwormParams, n_substeps: int, effects
) -> float:
    """The validated increment_factor; a full-range step must take <= MAX_INCREMENTS quasi-static
    increments of increment_factor * 2h/L^2 (or Newmark steps with `inertia`)."""
    increment_factor = check_range("increment_factor", increment_factor, 1e-3, 1e6)
    if max_curvature / (increment_factor * params.max_dkappa) > MAX_INCREMENTS:
        raise ValueError(
            f"increment_factor: a full-range step (max_curvature {max_curvature:g} 1/m) "
            f"would take more than {MAX_INCREMENTS} increments of "
            f"increment_factor * 2 height / length^2; raise increment_factor"
        )
    if "inertia" in effects and n_substeps > MAX_INCREMENTS:
        raise ValueError(
            f"physics_dt: with `inertia` a step takes control_dt / physics_dt Newmark steps, "
            f"at most {MAX_INCREMENTS}; got {n_substeps}"
        )
    return increment_factor


def beam_params(length, width, height, youngs, shear, mass, n_elements) -> InchwormParams:
    """The beam parameters from the public arguments (errors name them)."""
    L = check_range("length", length, 0.01, 10.0)
    h = check_range("height", height, 1e-4, 1.0)
    if h > L / 5:
        raise ValueError(f"height: must be <= length / 5 (a slender beam), got {height!r}")
    m = check_range("mass_per_length", mass, 1e-6, 1e4)
    return dataclasses.replace(
        InchwormParams(),
        length=L,
        width=check_range("width", width, 1e-4, 1.0),
        height=h,
        youngs_modulus=check_range("youngs_modulus", youngs, 1e3, 1e13),
        shear_modulus=check_range("shear_modulus", shear, 1e3, 1e13),
        mass_per_length=m,
        rotary_inertia=m * h**2 / 12.0,
        n_elements=check_int("n_elements", n_elements, low=1, high=64),
    )


def _friction(coefficients: Any, grip_time: float) -> FrictionParams:
    """FrictionParams from a mapping of FRICTION_KEYS (missing keys keep their defaults) or a
    4-sequence in that order."""
    if coefficients is None:
        coefficients = {}
    elif not isinstance(coefficients, dict):
        try:
            values = tuple(coefficients)
        except TypeError:
            values = ()
        if len(values) != 4:
            raise ValueError(
                f"friction_coefficients: expected a dict of {FRICTION_KEYS} or 4 numbers, "
                f"got {coefficients!r}"
            )
        coefficients = dict(zip(FRICTION_KEYS, values))
    bad = sorted(set(coefficients) - set(FRICTION_KEYS))
    if bad:
        raise ValueError(f"friction_coefficients: unknown {bad}; known {FRICTION_KEYS}")
    mu = {
        k: check_range(f"friction_coefficients[{k!r}]", v, 0.0, 10.0)
        for k, v in coefficients.items()
    }
    return dataclasses.replace(
        FrictionParams(), **mu, engage_time=grip_time, release_time=grip_time
    )


def robot_params(
    actuator_time_constant: Any,
    actuator_rate_limit: Any,
    grip_time_constant: Any,
    friction_coefficients: Any,
) -> tuple[ActuatorParams, FrictionParams]:
    """(ActuatorParams, FrictionParams) from the env's kwargs; ValueError names the kwarg."""
    tau = check_range("actuator_time_constant", actuator_time_constant, 1e-4, 1e3)
    rate = check_range("actuator_rate_limit", actuator_rate_limit, 1e-6, 1e6)
    grip = check_range("grip_time_constant", grip_time_constant, 1e-4, 1e3)
    return ActuatorParams(tau, rate), _friction(friction_coefficients, grip)
