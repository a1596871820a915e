"""FloatingGOWEC-v0's env concerns, declared once: observation layout, reward terms, info keys,
options.

The first six slots are GOWEC-v0's (gimbal encoder and buoy IMU), so v0's controllers read the
same names; the inclinometer angles follow.
"""

from __future__ import annotations

from mf_envs.envs._spec import Field, ObsLayout

MAX_GIMBAL_RATE = 60.0  # rad/s, overspeed trip and observation bound
MAX_BUOY_RATE = 5.0  # rad/s, observation bound
MAX_BUOY_ANGLE = 1.0  # rad: observation bound (and of the device's survival tilt pitch_limit)
MAX_ELEVATION = 15.0  # m: observation bound of the wave elevation (and its preview)

# the env docstring's observation table, then its slots with little spread explained
_OBS_NOTE = (
    "In a sea along the pitch axis (the default `wave_direction` pi/2, and the headline JONSWAP "
    "id) the hull moves in one plane: w2, w3 and roll (slots 4, 5, 7) stay 0 and carry the "
    "motion of oblique seas and roll resets. With the gimbal swinging a few tens of degrees (a "
    "damping PTO), cos(phi) varies little (std 0.01) while sin(phi) carries the angle."
)
OBS = ObsLayout(
    Field("sin_gimbal_angle", "", 1.0, "sin(phi), gimbal angle phi (encoder)"),
    Field("cos_gimbal_angle", "", 1.0, "cos(phi)"),
    Field("gimbal_rate", "rad/s", "max_gimbal_rate", "phi', gimbal rate"),
    Field("buoy_rates", "rad/s", MAX_BUOY_RATE, "buoy body rates w1, w2, w3 (IMU)", size=3),
    Field(
        "buoy_angles", "rad", MAX_BUOY_ANGLE, "buoy pitch theta, roll rho (inclinometer)", size=2
    ),
    Field("wave_elevation", "m", MAX_ELEVATION, "incident wave elevation at the buoy (probe)"),
)
# opt-in (wave_preview > 0): N_PREVIEW more slots, the incident elevation at the buoy
# wave_preview * (j + 1) / N_PREVIEW s ahead (j = 0..N_PREVIEW-1), bounded by MAX_ELEVATION
N_PREVIEW = 8
I_SIN, I_COS = OBS.index("sin_gimbal_angle"), OBS.index("cos_gimbal_angle")
I_RATE = OBS.index("gimbal_rate")
OBS_DOC = OBS.table() + "\n\n" + _OBS_NOTE
S_BUOY = OBS.slice("buoy_rates")
S_ANGLES = OBS.slice("buoy_angles")
I_ELEVATION = OBS.index("wave_elevation")

REWARD_TERMS = ("net_electrical_energy", "shutdown_loss")
RESET_OPTIONS = ("buoy_pitch", "buoy_roll", "gimbal_angle", "gimbal_rate")
INFO_KEYS = (
    "power",  # W, net electrical power over the step (generator/motor efficiency, rotor loss)
    "power_mechanical",  # W, M_g phi' averaged over the step (positive = harvested)
    "buoy_pitch",  # rad, theta (about e1, the gyro's input axis)
    "buoy_roll",  # rad, rho (about e2, the gimbal axis)
    "buoy_rate",  # rad/s, (theta', rho') (2,)
    "excitation_moment",  # N m, wave excitation moment about e1 (pitch) at the end of the step
    "gyro_moment",  # N m, moment of the gyro unit on the hull about e1 at the end of the step
    "gimbal_angle",  # rad, phi (unwrapped)
    "gimbal_rate",  # rad/s, phi'
    "wave_elevation",  # m, eta at the buoy
    "time",  # s
    "reward_terms",  # {"net_electrical_energy": ...}, sums to the reward
    "numerical_failure",
    "overspeed",  # |phi'| > max_gimbal_rate: terminates (charged the shutdown_loss)
    "stroke_end",  # |phi| past the gimbal's stroke (its cushion bottomed out): terminates (same)
    "survival",  # the supervisor holds the device in survival (PTO unloaded, gimbal braked)
)
