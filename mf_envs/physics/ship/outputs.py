"""What one step of the ship + gyro reports (`kernels.advance`'s out, layout in `layout`):
the gyro roll moment, the drive's torque and power, the mount moment per unit, and the roll
angle read from an attitude."""

from __future__ import annotations

import math

import numba

from mf_envs._jit import kernel
from mf_envs.frames.kernels import sincos_near
from mf_envs.physics.ship.drive import DKS, cushion_torque
from mf_envs.physics.ship.layout import DRV0, GIMBAL_SERVO, GIMBAL_TORQUE, Z_STATE
from mf_envs.physics.ship.layout import Slot as S
from mf_envs.physics.ship.loads import gimbal_drive, gimbal_motion, gyro_gimbal_torque


@kernel
def roll_of(R) -> float:
    """Roll r = atan2(R32, R33) (rad, z-y-x Euler angles) of one attitude R (3, 3) with libm's
    scalar atan2: the single env (through numba's dispatch) and the vector kernel call this one
    function, so they agree bit for bit (numpy's SIMD `arctan2`, `ship.roll_angle`, can differ
    from it by an ulp on AVX-512 machines)."""
    return math.atan2(R[2, 1], R[2, 2])


@numba.njit(cache=True)
def gyro_roll_moment(phi: float, phi_rate: float, angular_momentum: float, n_gyros: int) -> float:
    """Gyroscopic roll moment on the hull, -n H phi' cos(phi) (N m; Eq. 123 right-hand side):
    gimbal angle phi (rad) and rate phi' (rad/s) of gyro 1, H = J3^(3) psi' (N m s) per gyro."""
    return -n_gyros * angular_momentum * phi_rate * math.cos(phi)


@kernel
def gyro_moment(y, P, c):
    """Gyro roll moment (N m, Eq. 123) of state y: `gyro_roll_moment` with the packed P;
    c = cos(phi) if the caller has it (NaN: libm)."""
    if c != c:
        return gyro_roll_moment(y[3], y[4], P[S.JR3] * P[S.PSID], P[S.NGYRO])
    return -P[S.NGYRO] * (P[S.JR3] * P[S.PSID]) * y[4] * c


@kernel(forceinline=True)
def step_outputs(t, y, R, u, P, out, mw, near0):
    """out (`advance`'s doc) at the end of a control step at time t: mw the wave moment (N m)
    at t, near0 the step's start values (`start_values`)."""
    c, s = math.nan, math.nan  # cos, sin of the final gimbal angle (NaN: libm in the callees)
    mode = int(P[S.GMODE])
    if mode == GIMBAL_SERVO or mode == GIMBAL_TORQUE:
        c, s = sincos_near(y[3], near0[0], near0[1], near0[2])
    out[0] = gyro_moment(y, P, c)
    out[1] = mw
    out[2], out[3] = drive_output(t, y, R, u, P, c, s)
    out[4] = mount_moment(y, out[2], P)
    out[5] = P[S.PROTOR]


@kernel
def mount_moment(y, tau, P):
    """Moment (N m) one unit's foundation takes (`N_OUT` doc): |(H phi', tau_g)| / units, the
    precession moment H phi' (roll and yaw of the unit's frame) and the gimbal-axis torque
    tau_g = drive torque tau (N m, of the lumped gyro) + cushion torque."""
    hp = P[S.JR3] * P[S.PSID] * y[4]
    tg = tau
    if P[DRV0 + DKS] > 0.0:
        tg = tau + cushion_torque(y[3], y[4], P, DRV0)
    return math.sqrt(hp * hp + tg * tg) / P[S.UNITS]


@kernel
def drive_output(t, y, R, u, P, c, s):
    """(torque on gyro 1's gimbal in N m, power n tau phi' in W) of the drive at state y.

    Torque drives: the machine's torque (`gimbal_drive`). The kinematic servo (and prescribed
    gimbals) report the torque they impose, J_g phi'' - H w_g1 (the gimbal's own equation with
    the hull's pitch acceleration neglected), without any limit. c, s: cos, sin of the gimbal
    angle if the caller has them (NaN: libm).
    """
    phi, phid = y[3], y[4]
    if int(P[S.GMODE]) == GIMBAL_TORQUE:
        tau = gimbal_drive(y[0], y[2], phi, phid, y[Z_STATE], u, R[2, 0], R[2, 2], P, c, s)[0]
    else:
        phidd = gimbal_motion(t, phi, phid, u, P)[2]
        tau = P[S.D2] * phidd - gyro_gimbal_torque(y[0], y[2], phi, P, c, s)
    return tau, P[S.NGYRO] * tau * phid
