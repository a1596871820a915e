"""GyroStabilizer-v0's env concerns, declared once: observation layout, reward terms, info keys,
failure contract. Used by `GyroStabilizerEnv` (env.py) and the native vector env (vector.py);
the observation and the finiteness check are one numba function, `observe`, which the vector env
calls row by row (`observe_rows`), so the two agree bit for bit.
"""

from __future__ import annotations

import math
from typing import Any

import numba

from mf_envs.envs._spec import Field, ObsLayout

OBS = ObsLayout(
    Field("roll", "rad", math.pi, "roll angle (z-y-x Euler angle, `physics.ship.roll_angle`)"),
    Field("roll_rate", "rad/s", 10.0, "roll rate omega_1 (body)"),
    Field("pitch_rate", "rad/s", 10.0, "pitch rate omega_2 (body)"),
    Field("yaw_rate", "rad/s", 10.0, "yaw rate omega_3 (body)"),
    Field("gimbal_angle", "rad", math.pi, "gimbal angle phi of gyro 1, wrapped to [-pi, pi)"),
    Field("gimbal_rate", "rad/s", 20.0, "gimbal rate phi'"),
)
REWARD_TERMS = ("roll", "effort")
RESET_OPTIONS = ("roll", "roll_rate", "gimbal_angle", "wave_phase")
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
    "time",  # s, steps x control_dt
    "reward_terms",  # {"roll", "effort"}, sums to the reward
    "numerical_failure",  # the failure contract (docs/api.md), terminates
)
PHYSICS_DT_NOTE = """
The default physics step is one RK4-Munthe-Kaas step per 0.05 s control step for the servo
(physics_dt = 0.025 s, two steps, before the kernel was sped up; pass it to get that back):
against a reference at 0.05/32 s over a 30 s episode of the default scene (seeds 0-2) the
roll differs by 4.6e-6 rad RMS (7.3e-6 max; 0.03 % of the 1.8e-2 rad RMS roll) under the
`pid` baseline and 3.4e-7...7.5e-7 rad RMS under `lqr` (returns within 5e-4 of about -7 and
-2), and by 6.8e-5 rad RMS (0.04 % of the 0.18 rad RMS roll) with uniform random actions
that drive the gimbal into its end stops; physics_dt = 0.025 cuts these 20-25 fold (4th
order). The torque drive keeps 0.025 s: its end-stop spring (k_stop = 1e5 N m/rad on the
14.3 kg m^2 gimbal, 84 rad/s) is beyond RK4's stability limit at 0.05 s.
"""
_HIGH = tuple(float(v) for v in OBS.high())


@numba.njit(cache=True)
def observe(roll, y, R, out):
    """The observation (OBS order) of ship state y (N_STATE,), attitude R (3, 3) and its roll
    angle (rad) into the float32 row `out`, clipped to the bounds; returns False (out untouched)
    if the state is not finite (the failure contract)."""
    for i in range(y.shape[0]):
        if not math.isfinite(y[i]):
            return False
    for i in range(3):
        for j in range(3):
            if not math.isfinite(R[i, j]):
                return False
    phi = (y[3] + math.pi) % (2.0 * math.pi) - math.pi
    vals = (roll, y[0], y[1], y[2], phi, y[4])
    for i in range(6):
        out[i] = min(max(vals[i], -_HIGH[i]), _HIGH[i])
    return True


@numba.njit(cache=True)
def observe_rows(active, roll, y, R, out, ok):
    """`observe` for every active row i: roll (N,), y (N, N_STATE), R (N, 3, 3), out (N, 6)."""
    for i in range(y.shape[0]):
        if active[i]:
            ok[i] = observe(roll[i], y[i], R[i], out[i])


def reward_terms(roll_obs, action, roll_scale: float, effort_weight: float) -> dict[str, Any]:
    """roll = -(roll / roll_scale)^2 on the observed (float32) roll, effort = -w action^2;
    scalars or (N,) arrays. q * q, not q ** 2: libm pow, which numpy would not match."""
    q = roll_obs / roll_scale
    return {"roll": -(q * q), "effort": -effort_weight * action * action}


def step_info(roll, y, out, time, terms) -> dict[str, Any]:
    """The info of a state: y (N_STATE,) ship state and out (2,) (gyro, wave moment N m), or
    batched (N, N_STATE), (N, 2) with roll (N,), time (N,) (columns copied)."""
    if y.ndim == 1:
        cols = [float(y[j]) for j in range(5)] + [float(out[0]), float(out[1])]
    else:
        cols = [y[:, j].copy() for j in range(5)] + [out[:, 0].copy(), out[:, 1].copy()]
    info = {"roll": roll, **dict(zip(INFO_KEYS[1:8], cols))}
    info["time"] = time
    info["reward_terms"] = terms
    return info
