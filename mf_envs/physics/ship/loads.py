"""Numba kernels of the ship's loads and gimbal drives (Rios 2017 ch. 3 Eqs. 118-119, 123):
prescribed / servo gimbal motion, the torque drive (`ship.drive`), hydrostatic and damping
moments, wave moment and heave force (regular or a table). Units SI; P is the packed vector of
`layout.KernelParams`."""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.frames.kernels import sincos_near
from mf_envs.physics.ship.drive import drive_torque, stop_envelope
from mf_envs.physics.ship.layout import (
    DRV0,
    GIMBAL_CONTINUOUS,
    GIMBAL_SINUSOIDAL,
    WAVE_REGULAR,
    WAVE_TABLE,
)
from mf_envs.physics.ship.layout import Slot as S


@numba.njit(cache=True)
def gimbal_motion(t: float, phi: float, phid: float, u: float, P: np.ndarray):
    """(phi, phi', phi'') of gyro 1 at time t: Eq. 119 / Eq. 118 or the rate servo.

    Servo: phi'' = (u_eff - phi') / tau with u_eff the command u (rad/s) clipped to the
    precession-rate limit and to the end-stop envelope (|phi| <= phi_max approached at
    rate <= (phi_max - |phi|) / t_stop) when `gimbal_limits` is on.
    """
    mode = int(P[S.GMODE])
    if mode == GIMBAL_SINUSOIDAL:
        om = 2.0 * math.pi * P[S.GFREQ]
        arg = om * t - P[S.GPHASE]
        a = P[S.GAMP]
        return a * math.sin(arg), a * om * math.cos(arg), -a * om * om * math.sin(arg)
    if mode == GIMBAL_CONTINUOUS:
        rate = 4.0 * P[S.GAMP] * P[S.GFREQ]
        return rate * t, rate, 0.0
    ue = u
    if P[S.LIMITS] > 0.5:
        rmax = P[S.RATEMAX]
        ue = min(max(ue, -rmax), rmax)
        ue = stop_envelope(ue, phi, P[S.PHIMAX], P[S.TSTOP])
    return phi, phid, (ue - phid) / P[S.TAU]


@kernel(forceinline=True)
def gyro_gimbal_torque(w1, w3, phi, P, c, s):
    """H w_g1 (N m): the gyroscopic torque on gyro 1's gimbal, H (cos phi w1 - sin phi w3) for
    one gyro, H cos(phi) w1 on the common coordinate of the mirrored pair. c, s: cos(phi),
    sin(phi) if the caller has them (NaN: computed here)."""
    if c != c:  # NaN: not given
        c, s = math.cos(phi), math.sin(phi)
    return gyro_torque_cs(w1, w3, c, s, P)


@kernel(forceinline=True)
def gyro_torque_cs(w1, w3, c, s, P):
    """`gyro_gimbal_torque` from c = cos(phi), s = sin(phi) (no libm)."""
    h = P[S.JR3] * P[S.PSID]
    return h * (c * w1 - s * w3) if int(P[S.NGYRO]) == 1 else h * c * w1


@kernel(forceinline=True)
def gimbal_drive(w1, w3, phi, phid, z, u, r20, r22, P, c, s):
    """(tau in N m, z' in rad/s) of the torque drive (`ship.drive.drive_torque`) on gyro 1's
    gimbal; the gyroscopic torque it feeds forward is H w_g1 (one gyro) or H cos(phi) w1 (pair).
    c, s: cos(phi), sin(phi) if the caller has them (`gyro_gimbal_torque`)."""
    g = gyro_gimbal_torque(w1, w3, phi, P, c, s)
    return drive_torque(phi, phid, z, u, g, r20, r22, int(P[S.NGYRO]), P, DRV0)


_TAN14_SQ = math.tan(1.4) ** 2  # the wall-sided GZ's tan(r) is clipped to |r| <= 1.4 rad


ASIN_SERIES = 0.05  # |x| below which `_asin` uses its series


@kernel(forceinline=True)
def _asin(x: float) -> float:
    """asin(x); for |x| < ASIN_SERIES (pitch below 2.9 deg) its Taylor series to x^11
    (truncation < 2e-19 |x|, as accurate as libm asin, and a few times cheaper)."""
    if abs(x) < ASIN_SERIES:
        return asin_series(x)
    return math.asin(x)


@kernel(forceinline=True)
def asin_series(x: float) -> float:
    """The series of `_asin` (|x| < ASIN_SERIES)."""
    x2 = x * x
    return x + x * x2 * (
        1.0 / 6.0
        + x2 * (3.0 / 40.0 + x2 * (5.0 / 112.0 + x2 * (35.0 / 1152.0 + x2 * (63.0 / 2816.0))))
    )


@kernel(forceinline=True)
def pitch_sine(r20: float) -> float:
    """-R31 clipped to [-1, 1]: the sine of the pitch, the argument of its asin."""
    return max(min(-r20, 1.0), -1.0)


@kernel(forceinline=True)
def hull_moment(w1, w2, w3, r20, r21, r22, P):
    """Hydrostatic and damping moments (N m, ship frame) from the body rates (rad/s) and the
    third row (r20, r21, r22) of the attitude R; see `external_moment`.

    Roll r = atan2(R32, R33) enters the wall-sided GZ only through sin(r) = R32 / |(R32, R33)|
    and tan(r)^2 = (R32 / R33)^2 (clipped at |r| = 1.4), the same numbers without atan2/sin/tan.
    """
    roll = math.atan2(r21, r22) if roll_needed(P) else 0.0
    pitch = _asin(pitch_sine(r20)) if P[S.K55] > 0.0 else 0.0
    return hull_moment_with(w1, w2, w3, r21, r22, P, roll, pitch)


@kernel(forceinline=True)
def roll_needed(P) -> bool:
    """Whether `hull_moment` reads the roll angle itself: the linear GZ or the cubic term (the
    wall-sided GZ needs only R32 and R33)."""
    return P[S.K44] > 0.0 and (P[S.GZR] <= 0.0 or P[S.GZ3] > 0.0)


@kernel(forceinline=True, error_model="numpy")
def hull_moment_with(w1, w2, w3, r21, r22, P, roll, pitch):
    """`hull_moment` given the roll angle atan2(R32, R33) (rad; read only by the linear and
    the cubic GZ) and the pitch asin(-R31) (rad; read only with C55 > 0)."""
    m1 = 0.0
    m2 = 0.0
    if P[S.K44] > 0.0:
        if P[S.GZR] > 0.0:
            hyp = math.sqrt(r21 * r21 + r22 * r22)
            sr = r21 / hyp if hyp > 0.0 else 0.0
            t2 = _TAN14_SQ
            if r22 > 0.0:
                t2 = min((r21 / r22) * (r21 / r22), _TAN14_SQ)
            m1 -= P[S.K44] * sr * (1.0 + 0.5 * P[S.GZR] * t2)
        else:
            m1 -= P[S.K44] * roll
        if P[S.GZ3] > 0.0:  # cubic GZ (MSS's K_phiphiphi phi^3)
            m1 -= P[S.K44] * P[S.GZ3] * roll * roll * roll
    if P[S.K55] > 0.0:
        m2 -= P[S.K55] * pitch
    m1 -= P[S.B44] * w1 + P[S.B44Q] * abs(w1) * w1
    m2 -= P[S.B55] * w2
    return m1, m2, -P[S.B66] * w3


@kernel(forceinline=True)
def wave_loads(t: float, P: np.ndarray, tab: np.ndarray):
    """(wave roll moment M_e in N m, heave force in N; the force only with `translation`) at t."""
    mode = int(P[S.WMODE])
    trans = P[S.TRANS] > 0.5
    mw = 0.0
    fw = 0.0
    if mode == WAVE_REGULAR:
        mw = P[S.WM0] * math.cos(P[S.WOMEGA] * t + P[S.WPHASE])
        if trans:
            fw = P[S.WF0] * math.sin(P[S.WOMEGA] * t + P[S.WPHASE])
    elif mode == WAVE_TABLE:
        mw = table_value(t, tab, 0, P[S.TABDT])
        if trans:
            fw = table_value(t, tab, 1, P[S.TABDT])
    return mw, fw


@kernel(forceinline=True)
def wave_loads_near(t: float, P: np.ndarray, tab: np.ndarray, t0: float, c0: float, s0: float):
    """`wave_loads` at t from the regular wave's cos and sin at t0 (c0, s0) by
    `frames.kernels.sincos_near` (a Runge-Kutta step's stages: one libm sincos per step);
    equal to `wave_loads` to round-off, and bit for bit at t = t0."""
    if int(P[S.WMODE]) != WAVE_REGULAR:
        return wave_loads(t, P, tab)
    om, ph = P[S.WOMEGA], P[S.WPHASE]
    c, s = sincos_near(om * t + ph, om * t0 + ph, c0, s0)
    return P[S.WM0] * c, (P[S.WF0] * s if P[S.TRANS] > 0.5 else 0.0)


@numba.njit(cache=True)
def external_moment(t: float, w: np.ndarray, R: np.ndarray, P: np.ndarray, tab: np.ndarray):
    """Hydrostatic, damping and wave moments in the ship frame (N m) and the wave roll moment.

    Roll r = atan2(R32, R33), pitch p = -asin(R31) (z-y-x Euler angles of R).
    Restoring: -C44 r (linear) or -C44 sin(r) (1 + BM/(2 GM) tan^2 r) (wall-sided GZ);
    -C55 p in pitch. Damping: -B44 w1 - B44q |w1| w1, -B55 w2, -B66 w3.
    """
    m1, m2, m3 = hull_moment(w[0], w[1], w[2], R[2, 0], R[2, 1], R[2, 2], P)
    mw = wave_loads(t, P, tab)[0]
    return m1 + mw, m2, m3, mw


@kernel(forceinline=True)
def table_value(t: float, tab: np.ndarray, col: int, h: float) -> float:
    """Linear interpolation of column `col` of a table sampled every h seconds from t = 0."""
    s = t / h
    i = int(math.floor(s))
    n = tab.shape[0]
    if i < 0:
        return tab[0, col]
    if i >= n - 1:
        return tab[n - 1, col]
    f = s - i
    return (1.0 - f) * tab[i, col] + f * tab[i + 1, col]
