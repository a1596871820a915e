"""The moving-frame kernel: SO(3)/SE(3) frame connection matrices (Rios 2017, ch. 2-3).

`so3`, `se3`: numpy faces (batched, validated). `kernels`: the numba kernels every model calls
(hat/vee, Rodrigues exp, log, dexp and dexp^-1 left and right, the RK4 and RKMK4 steppers).
No Gymnasium imports.
"""

from mf_envs.frames.se3 import (
    compose,
    frame_connection,
    frame_inverse,
    relative_connection,
    time_rate_connection,
    twist_from_time_rate,
)
from mf_envs.frames.so3 import (
    exp_so3,
    hat,
    log_so3,
    orthonormality_error,
    project_to_so3,
    rot_x,
    rot_y,
    rot_z,
    vee,
)

__all__ = [
    "hat",
    "vee",
    "exp_so3",
    "log_so3",
    "rot_x",
    "rot_y",
    "rot_z",
    "project_to_so3",
    "orthonormality_error",
    "frame_connection",
    "frame_inverse",
    "relative_connection",
    "compose",
    "time_rate_connection",
    "twist_from_time_rate",
]
