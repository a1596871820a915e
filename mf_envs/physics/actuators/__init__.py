"""Actuators of the active beam (Rios 2017 §4.4.3): shared by every robot built on it.

curvature   the curvature actuator: rate-limited first-order lag (A1) of the commanded
            kappa# at control points, actuation power and work (A2), energy meter
kernels     their compiled forms (lag solution, increment work, substep count)
"""

from mf_envs.physics.actuators.curvature import (
    SMA_RATE_LIMIT,
    SMA_TIME_CONSTANT,
    ActuatorParams,
    EnergyMeter,
    RateLimitedLag,
    actuation_power,
    bending_moment,
    increment_work,
    integrate_along,
    kappa_at_gauss,
    rate_limited_lag,
)

__all__ = [
    "SMA_RATE_LIMIT",
    "SMA_TIME_CONSTANT",
    "ActuatorParams",
    "EnergyMeter",
    "RateLimitedLag",
    "actuation_power",
    "bending_moment",
    "increment_work",
    "integrate_along",
    "kappa_at_gauss",
    "rate_limited_lag",
]
