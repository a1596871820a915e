"""Inchworm-v0's robot parameters from the public kwargs, validated (errors name the kwarg).

`beam_params`: the body (length, section, material, mesh). `robot_params` (issue 16): the
actuator and feet kwargs `actuator_time_constant` [s], `actuator_rate_limit` [1/(m s)],
`grip_time_constant` [s] and `friction_coefficients` become the physics' `ActuatorParams` and
`FrictionParams` (`mf_envs.physics.actuators.curvature`,
`mf_envs.physics.beam.contact.friction`).
"""

from __future__ import annotations

import dataclasses
from typing import Any

from mf_envs._validate import check_int, check_range
from mf_envs.physics.actuators.curvature import SMA_RATE_LIMIT, SMA_TIME_CONSTANT, ActuatorParams
from mf_envs.physics.beam.contact.friction import FrictionParams
from mf_envs.physics.inchworm import InchwormParams

MAX_INCREMENTS = 200  # increments (or Newmark steps) of a full-range step: a step stays fast
FRICTION_KEYS = ("grip_forward", "grip_backward", "slide_forward", "slide_backward")
GRIP_TIME_CONSTANT = 0.2  # s, FrictionParams' default engage/release time
__all__ = [
    "GRIP_TIME_CONSTANT",
    "SMA_RATE_LIMIT",
    "SMA_TIME_CONSTANT",
    "beam_params",
    "robot_params",
    "step_budget",
]


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
