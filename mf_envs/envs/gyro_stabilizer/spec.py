"""GyroStabilizer-v0's env concerns, declared once: observation layout, reward terms, info keys,
failure contract, the grouped kwarg `drive=` (`Drive`, its flat aliases `DRIVE`). The step
itself (physics, observation, reward terms, info columns) is one compiled function,
`rows.step_rows`, and the reset one more, `rows.reset_row`: the single env (`GyroStabilizerEnv`,
env.py) is row 0 of a batch of one, the native vector env (vector.py) runs the same functions on
N rows.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from mf_envs.envs._groups import Group
from mf_envs.envs._spec import Field, ObsLayout

# the observation's fixed units of roll and roll rate (`_spec.Field.scale`): a stabilised hull
# rolls by a few hundredths of a radian (RMS roll 0.015 rad under LQR, 0.047 under random
# actions on GyroStabilizer-JONSWAP-v0), so in radians the two slots sat near 0.02-0.05
ROLL_UNIT, ROLL_RATE_UNIT = 0.05, 0.05  # rad, rad/s
OBS = ObsLayout(
    Field(
        "roll",
        "rad",
        math.pi,
        "roll angle (z-y-x Euler angle, `physics.ship.roll_angle`)",
        scale=ROLL_UNIT,
    ),
    Field("roll_rate", "rad/s", 10.0, "roll rate omega_1 (body)", scale=ROLL_RATE_UNIT),
    Field("pitch_rate", "rad/s", 10.0, "pitch rate omega_2 (body)"),
    Field("yaw_rate", "rad/s", 10.0, "yaw rate omega_3 (body)"),
    Field("gimbal_angle", "rad", math.pi, "gimbal angle phi of gyro 1, wrapped to [-pi, pi)"),
    Field("gimbal_rate", "rad/s", 20.0, "gimbal rate phi'"),
)
REWARD_TERMS = ("roll", "effort")
N_OUT = 6  # the ship kernel's out vector (`physics.ship.kernels.N_OUT`), reported in the info
RESET_OPTIONS = ("roll", "roll_rate", "gimbal_angle", "wave_phase", "spool_up")
# `sensor_noise` (opt-in effect): white noise per observation, standard deviation per sample at
# the control rate f_s = 1 / control_dt over the Nyquist band f_s / 2 (docs/stabilizer_physics.md
# §6): rate gyro 0.007 deg/s/sqrt(Hz) (Bosch BMI270, typical, performance mode), roll from the
# accelerometer 0.16 mg/sqrt(Hz) / g rad/sqrt(Hz) (same sensor), gimbal angle from a 12-bit
# absolute encoder (quantisation 2 pi / 4096 / sqrt(12) rad), gimbal rate its difference over
# one control step (sqrt(2) x that / control_dt). Densities in SI: rad/s/sqrt(Hz), rad/sqrt(Hz).
GYRO_NOISE_DENSITY = math.radians(0.007)
TILT_NOISE_DENSITY = 0.16e-3
ENCODER_NOISE = 2.0 * math.pi / 4096.0 / math.sqrt(12.0)


def sensor_sigma(control_dt: float, scale: float = 1.0) -> np.ndarray:
    """Per-sample noise standard deviations (OBS order, SI) at control step control_dt (s);
    / `OBS.scales()` in the observation's units."""
    band = math.sqrt(0.5 / control_dt)  # sqrt(Nyquist bandwidth), sqrt(Hz)
    rate = GYRO_NOISE_DENSITY * band
    return scale * np.array([TILT_NOISE_DENSITY * band, rate, rate, rate, ENCODER_NOISE,
                             math.sqrt(2.0) * ENCODER_NOISE / control_dt])  # fmt: skip


# step and reset info, SI; the state is reported as is, also after a numerical failure
INFO_KEYS = (
    "roll",  # rad, roll angle (unclipped)
    "roll_rate",  # rad/s, body rates
    "pitch_rate",
    "yaw_rate",
    "gimbal_angle",  # rad, gyro 1, unwrapped
    "gimbal_rate",  # rad/s
    "gyro_moment",  # N m, -n H phi' cos(phi) (Eq. 123)
    "wave_moment",  # N m, wave roll moment
    "drive_torque",  # N m, the drive's torque on gyro 1's gimbal
    "drive_power",  # W, n tau phi' (negative: braking)
    "mount_moment",  # N m, per unit: |(H phi', drive + cushion torque)| (kernels.mount_moment)
    "rotor_power",  # W, the rotors' running power (all units; spool-up power when spooling)
    "drive_energy",  # J, int n |tau phi'| dt over the step
    "time",  # s, steps x control_dt
    "reward_terms",  # {"roll", "effort"}, sums to the reward (effort: drive energy, J)
    "numerical_failure",  # the failure contract (docs/api.md), terminates
)
PHYSICS_DT_NOTE = """
The kinematic servo (gimbal_drive="kinematic") runs one RK4-Munthe-Kaas step per 0.05 s control
step (physics_dt = min(0.05, servo_time_constant)): against a reference at 0.05/32 s over a 30 s
episode of the default scene (seeds 0-2) the roll differs by 4.6e-6 rad RMS (0.03 % of the
1.8e-2 rad RMS roll) under `pid`, 3.4e-7...7.5e-7 under `lqr` and 6.8e-5 rad RMS (0.04 %) with
uniform random actions. The torque drives run two steps per control step by default
(physics_dt = min(control_dt, RK4 limit) / 2, the limit from
`physics.ship.step_bound.stable_physics_dt`, 0.139 s for the electric drive on the default
yacht): against 0.05/32 s (seeds 0-2, 30 s) the roll differs by 6.0e-7 rad RMS under `pid`
(0.003 % of its RMS roll),
3.1e-5 under `lqr` (0.35 %) and 3.1e-4 with uniform random actions (0.7 %; 1.9e-3 at one 0.05 s
step): saturations and the inelastic end stops are not smooth, so RK4 loses its order there.
A physics_dt beyond the RK4 limit is refused (ValueError naming physics_dt).
"""


def precession_command(action, max_precession_rate: float):
    """The precession-rate command (rad/s) of an action in [-1, 1] (scalar or (N,) array): the
    one scaling, for the single and the vector env."""
    return action * max_precession_rate


@dataclasses.dataclass(frozen=True)
class Drive:
    """The gimbal drive (the `drive=` kwarg, or a dict of its fields; `build` doc); None: the
    preset's. kind "servo" and "torque" are the v0 names of "kinematic" and "electric"."""

    kind: str | None = None  # brake (Seakeeper), electric (seed), damper, pendulous, spring, ...
    servo_time_constant: float = 0.05  # s, of the kinematic servo
    loop_gain: float | None = None  # K_p of the rate loop, N m s/rad (sets bandwidth)
    max_torque: float | None = None  # N m (seed 0.1 H; Seakeeper brake relief, electric H p_d)
    max_power: float | None = None  # W, motoring (seed 1000; Seakeeper H p_d r_cap)
    bandwidth: float = 20.0  # rad/s, of the rate loop
    damping: float | None = None  # brake c, N m s/rad (passive default n H^2 / sqrt(C44 J))
    stiffness: float | None = None  # m g l (pendulous) or spring k, N m/rad (default J_g w_n^2)


DRIVE = Group(
    "drive",
    Drive,
    {"gimbal_drive": "kind", "servo_time_constant": "servo_time_constant",
     "gimbal_loop_gain": "loop_gain", "max_gimbal_torque": "max_torque",
     "max_drive_power": "max_power", "drive_bandwidth": "bandwidth", "gimbal_damping": "damping",
     "gimbal_stiffness": "stiffness"},
)  # fmt: skip
