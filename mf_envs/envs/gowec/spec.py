"""GOWEC-v0's env concerns, declared once: observation layout, reward, info keys, failure contract.

Used by both `GOWECEnv` (env.py) and the native `GOWECVectorEnv` (vector.py); the step itself
(physics, observation, flags, reward) is one compiled function, `rows.step_rows`, whose row 0
is the single env, so the two agree bit for bit.
"""

from __future__ import annotations

import math
from typing import Any

from mf_envs.envs._spec import Field, ObsLayout
from mf_envs.physics import gowec as gw
from mf_envs.physics.constants import G

MAX_GIMBAL_RATE = 60.0  # rad/s, default overspeed trip (and observation bound)
MAX_BUOY_RATE = 5.0  # rad/s, observation bound (breaking waves stay below ~1.6 rad/s)
# share of the head-on point-buoy Eq. 86 below which the reward reference is floored
REFERENCE_FLOOR = 0.1

OBS = ObsLayout(
    Field("sin_gimbal_angle", "", 1.0, "sin(phi), gimbal angle phi (encoder)"),
    Field("cos_gimbal_angle", "", 1.0, "cos(phi)"),
    Field("gimbal_rate", "rad/s", "max_gimbal_rate", "phi', gimbal rate"),
    Field("buoy_rates", "rad/s", MAX_BUOY_RATE, "buoy body rates w1, w2, w3 (IMU)", size=3),
)
I_SIN, I_COS = OBS.index("sin_gimbal_angle"), OBS.index("cos_gimbal_angle")
I_RATE = OBS.index("gimbal_rate")
S_BUOY = OBS.slice("buoy_rates")

REWARD_TERMS = ("energy",)
RESET_OPTIONS = ("gimbal_angle", "gimbal_rate", "wave_phase")
# step info: the keys and what they hold (SI); after a numerical failure only FAILURE_KEYS
INFO_KEYS = (
    "power",  # W, generator power M_g phi' averaged over the step (energy / control_dt)
    "gimbal_angle",  # rad, phi (unwrapped)
    "gimbal_rate",  # rad/s, phi'
    "buoy_rate",  # rad/s, w1
    "wave_elevation",  # m, eta at the buoy
    "time",  # s, steps x control_dt
    "reward_terms",  # {"energy": ...}, sums to the reward
    "numerical_failure",  # the failure contract (docs/api.md)
    "overspeed",  # |phi'| > max_gimbal_rate: the gimbal trip, terminates
)
FAILURE_KEYS = ("power", "reward_terms", "numerical_failure", "overspeed")


def reference_power(
    rotor_inertia: float,
    rotor_speed: float,
    wave_amplitude: float,
    wave_period: float,
    wave_direction: float,
    buoy_radius: float,
) -> float:
    """The reward's reference power P_ref (W), > 0 for every valid scene.

    P_ref = max(|Eq. 95|, REFERENCE_FLOOR * P_86'), where Eq. 95 is the locked-gimbal mean power
    of this wave, rotor and buoy (`physics.gowec.analytic_max_power`, sign of sin(theta) dropped)
    and P_86' = 1/2 J3 max(|psi'|, 10 w) a k w^2 is the head-on point-buoy Eq. 86 with the spin
    floored at 10 w (w = 2 pi / T, k = w^2 / g). The floor only acts where Eq. 95 is below 10 %
    of head-on: waves within ~6 deg of the gimbal axis (theta near 0 or pi, where Eq. 95 -> 0),
    a rotor off or slow (psi' = 0), or a buoy radius at a zero of J1. The default scenes are far
    from it (P_ref = Eq. 95 exactly).
    """
    eq95 = gw.analytic_max_power(
        rotor_inertia,
        rotor_speed,
        wave_amplitude,
        wave_period,
        wave_direction,
        buoy_radius=buoy_radius,
    )
    w = 2.0 * math.pi / wave_period
    spin = max(abs(rotor_speed), 10.0 * w)
    floor = REFERENCE_FLOOR * 0.5 * rotor_inertia * spin * wave_amplitude * w**4 / G
    return max(abs(eq95), floor)


def step_info(power, phi, phid, w1, eta, time, reward) -> dict[str, Any]:
    """The step info of a finite state (scalars, or (N,) arrays in the vector env)."""
    return {
        "power": power,
        "gimbal_angle": phi,
        "gimbal_rate": phid,
        "buoy_rate": w1,
        "wave_elevation": eta,
        "time": time,
        "reward_terms": {"energy": reward},
    }


assert OBS.size == 6 and S_BUOY == slice(3, 6) and (I_SIN, I_COS, I_RATE) == (0, 1, 2)
