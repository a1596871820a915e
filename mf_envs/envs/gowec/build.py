"""GOWEC-v0's kwargs -> typed physics parameters, never the env: `build(kw)` validates the wave,
the gyroscope and the generator limits into a `Scene`; `own_length` turns `n_periods` or
`episode_seconds` into control steps. The grouped kwargs `sea=` (`Sea`) and `gyro=`
(`GOWECParams`) and their flat aliases: `GROUPS` (`envs._groups`)."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from mf_envs._validate import check_int, check_nonnegative, check_range, check_shape
from mf_envs.envs._groups import Group
from mf_envs.envs.base import MAX_EPISODE_STEPS, MIN_DT
from mf_envs.physics import gowec as gw

DEFAULT_N_PERIODS = 20


@dataclasses.dataclass(frozen=True)
class Sea:
    """GOWEC-v0's wave (the `sea=` kwarg): a regular wave of amplitude a (m), period T (s) and
    direction theta (rad, Eq. 89: pi/2 head-on); with the `irregular_waves` effect a JONSWAP sea
    of Hs = 2 sqrt(2) a and Tp = T, peak enhancement `gamma`, `n_components` components.
    Validated by `build` (the ValueError names the field's flat alias, `SEA`)."""

    amplitude: float = 1.0
    period: float = 6.0
    direction: float = math.pi / 2
    n_components: int = 64
    gamma: float = 3.3


SEA = Group(
    "sea",
    Sea,
    {"wave_amplitude": "amplitude", "wave_period": "period", "wave_direction": "direction",
     "n_components": "n_components", "gamma": "gamma"},
)  # fmt: skip
GYRO_FIELDS = ("rotor_inertia", "rotor_speed", "rotor_transverse_inertia", "gimbal_inertia")
GYRO = Group("gyro", gw.GOWECParams, {name: name for name in GYRO_FIELDS})
GROUPS = (SEA, GYRO)


@dataclasses.dataclass(frozen=True)
class Scene:
    """What the env's kwargs become (SI units), validated; the env reads its parameters here."""

    wave_amplitude: float  # m
    wave_period: float  # s
    wave_direction: float  # rad
    max_generator_torque: float  # N m
    max_gimbal_rate: float  # rad/s
    steps_per_period: int
    n_components: int
    gamma: float
    params: gw.GOWECParams


def build(kw: dict[str, Any]) -> Scene:
    """The `Scene` of the env's kwargs `kw`; ValueError names the kwarg."""
    amplitude = check_range("wave_amplitude", kw["wave_amplitude"], 1e-6, 30.0)
    period = check_range("wave_period", kw["wave_period"], 0.5, 60.0)
    direction = check_range("wave_direction", kw["wave_direction"], -2 * math.pi, 2 * math.pi)
    torque = check_range("max_generator_torque", kw["max_generator_torque"], 0.0)
    if torque == 0.0:
        raise ValueError("max_generator_torque: must be > 0, got 0")
    rate = check_range("max_gimbal_rate", kw["max_gimbal_rate"], 1e-6)
    spp = check_int("steps_per_period", kw["steps_per_period"], low=4, high=10**6)
    n_components = check_int("n_components", kw["n_components"], low=1, high=4096)
    gamma = check_range("gamma", kw["gamma"], 1.0, 20.0)
    jt = kw["rotor_transverse_inertia"]
    if jt is not None:
        jt = check_range("rotor_transverse_inertia", jt, 1e-9, 1e6)
    gimbal = check_nonnegative(
        "gimbal_inertia", check_shape("gimbal_inertia", kw["gimbal_inertia"], (3,))
    )
    params = gw.GOWECParams(
        check_range("rotor_inertia", kw["rotor_inertia"], 1e-9, 1e6),
        check_range("rotor_speed", kw["rotor_speed"], -1e4, 1e4),
        jt,
        tuple(float(v) for v in gimbal),
    )
    if period / spp < MIN_DT:
        raise ValueError(f"steps_per_period: wave_period / steps_per_period < {MIN_DT:g} s")
    return Scene(amplitude, period, direction, torque, rate, spp, n_components, gamma, params)


def own_length(
    n_periods: Any, episode_seconds: Any, spp: int, seconds_to_steps
) -> tuple[str, Any, int] | None:
    """The episode length given in GOWEC-v0's own terms, as (argument, value, control steps):
    `n_periods` wave periods x `spp`, or `seconds_to_steps(episode_seconds)`
    (`MFEnv._episode_steps`); None if neither (the default: DEFAULT_N_PERIODS periods, or
    `max_episode_steps`: `MFEnv._episode_length`)."""
    if episode_seconds is not None and n_periods is not None:
        raise ValueError("episode_seconds: give either episode_seconds or n_periods, not both")
    if episode_seconds is not None:
        return ("episode_seconds", episode_seconds, seconds_to_steps(episode_seconds))
    if n_periods is None:
        return None
    n = check_int("n_periods", n_periods, 1, 10**6)
    if n * spp > MAX_EPISODE_STEPS:
        raise ValueError(
            f"n_periods: n_periods * steps_per_period = {n * spp} control steps "
            f"exceeds {MAX_EPISODE_STEPS}"
        )
    return ("n_periods", n_periods, n * spp)
