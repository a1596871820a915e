"""Numba kernels of the reduced ship + gyro model (the fast paths, Rios 2017 ch. 3 Eqs. 123-128).

Sketch (one gyro; a second one mirrors it with -phi, -psi, Eqs. 98-99, 106-107)::

        e3 (yaw)          ship e^(1), attitude R(t) in SO(3)
         |   gimbal e^(2) = e^(1) R_2(phi)       precession axis e_2 (athwartships)
         |   rotor  e^(3) = e^(2) R_3(psi)       spin axis: the gimbal's e_3
         +----- e1 (roll)

With the gimbal and rotor motions known (prescribed, or a servo state), the ship's rotational
equations are the balance of the total angular momentum about the centre of mass, in the ship frame:

    H = J(phi) w + h(phi, phi', psi'),     dH/dt|_ship + w x H = M_ext,
    J(phi) = J^(1) + sum_k R_2(s_k phi) diag(J_g + J_r) R_2(s_k phi)^T,   s_k = +1, -1
    h = sum_k [ s_k (J_g2 + J_r1) phi' e_2 + J3^(3) psi' (sin phi, 0, s_k cos phi) ].

This is exactly what the B-matrix route (Eqs. 74-75 with delta phi = delta psi = 0, Eq. 115)
gives for fixed gyro positions and no translation (Eq. 116); with the seed's Eq. 117 it reproduces
Eqs. 123-128 term by term except (i) Eq. 123's roll inertia, which the seed freezes at its
phi = 0 value J1 + 2 J2^(2) + J3^(3) (exact: J1 + 2 J2^(2) + J3^(3) (3 - cos 2 phi) / 2), and
(ii) Eqs. 126/128, which print 2 J2^(2) where the gimbal contributes J2^(2) phi' (w x e_2) once,
and J3/4 cos 2phi in the yaw w1 phi' term (exact J3/2). `FORM_SEED` steps the seed's equations as
printed (legible terms; the garbled pitch Eq. 127 is the exact one), `FORM_EXACT` the balance above.

Gimbal drives: prescribed phi(t) (Eqs. 118-119), a rate servo (phi'' = (u - phi') / tau, a
kinematic actuator: the gyroscopic torque on the gimbal is absorbed by it), or a torque drive in
which phi is a degree of freedom (the phi-row of Eq. 74, see `ship_accel`).

State y (float64): [w1, w2, w3, phi, phi', x1, x2, x3, v1, v2, v3] (body rates in rad/s, gimbal
angle/rate of gyro 1 in rad, rad/s; hull CM position/velocity in the inertial frame, m, m/s).
The attitude R (3x3, inertial <- ship) is rebuilt each step with Rodrigues' formula (ch. 2 Eq. 29)
inside a Runge-Kutta-Munthe-Kaas step (4th order also in R; the seed's midpoint-Rodrigues update
is 2nd order, which limits the hydrostatic moment's accuracy, see docs/design.md ch. 2 notes).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs.physics.ship.coupling import N_COUPLING, solve_sway_roll_yaw
from mf_envs.physics.ship.drive import N_DRIVE, drive_torque, end_stop

# ---- packed parameter vector P (built by ship_model.pack_params) ----
J1, J2, J3 = 0, 1, 2  # hull inertia (+ A44 in J1 when added_inertia is on)
D1, D2, D3 = 3, 4, 5  # gimbal + rotor transverse inertias in the gimbal frame
JR3, PSID, NGYRO, FORM = 6, 7, 8, 9  # rotor polar inertia, spin rate, 1 or 2, form
K44, GZR, K55 = 10, 11, 12  # roll / pitch stiffness, BM/GM of the wall-sided GZ
B44, B44Q, B55, B66 = 13, 14, 15, 16  # damping
GMODE, GAMP, GFREQ, GPHASE = 17, 18, 19, 20  # gimbal mode, Eq. 118/119 amplitude, freq, phase
TAU, RATEMAX, PHIMAX, LIMITS, TSTOP = 21, 22, 23, 24, 25  # servo lag, limits, end-stop time
WMODE, WM0, WOMEGA, WPHASE, WF0 = 26, 27, 28, 29, 30  # wave moment mode, M0, omega, phase, heave
TABDT, JG2, TRANS, MASS, KH, CH, CSS = 31, 32, 33, 34, 35, 36, 37
GZ3 = 38  # cubic GZ term over GM (1/rad^2), `ship.hulls.Hull.gz_cubic`
DRV0 = 39  # the packed gimbal drive `ship.drive.DriveParams.pack` occupies P[DRV0:DRV0 + N_DRIVE]
SPEED = DRV0 + N_DRIVE  # ship speed U, m/s (sway-roll-yaw coupling)
CPLON = SPEED + 1  # 1: sway-roll-yaw coupling on (`ship.coupling`)
CPL0 = CPLON + 1  # `ship.coupling.SwayRollYaw.pack` at P[CPL0:CPL0 + N_COUPLING]
N_PARAMS = CPL0 + N_COUPLING

FORM_EXACT, FORM_SEED = 0, 1
GIMBAL_SERVO, GIMBAL_SINUSOIDAL, GIMBAL_CONTINUOUS, GIMBAL_TORQUE = 0, 1, 2, 3
WAVE_NONE, WAVE_REGULAR, WAVE_TABLE = 0, 1, 2
N_STATE = 14  # + drive loop integral z (rad), drive energy int n |tau phi'| dt (J), sway v (m/s)
Z_STATE, E_STATE, V_STATE = 11, 12, 13


@numba.njit(cache=True)
def gimbal_motion(t: float, phi: float, phid: float, u: float, P: np.ndarray):
    """(phi, phi', phi'') of gyro 1 at time t: Eq. 119 / Eq. 118 or the rate servo.

    Servo: phi'' = (u_eff - phi') / tau with u_eff the command u (rad/s) clipped to the
    precession-rate limit and to the end-stop envelope (|phi| <= phi_max approached at
    rate <= (phi_max - |phi|) / t_stop) when `gimbal_limits` is on.
    """
    mode = int(P[GMODE])
    if mode == GIMBAL_SINUSOIDAL:
        om = 2.0 * math.pi * P[GFREQ]
        arg = om * t - P[GPHASE]
        a = P[GAMP]
        return a * math.sin(arg), a * om * math.cos(arg), -a * om * om * math.sin(arg)
    if mode == GIMBAL_CONTINUOUS:
        rate = 4.0 * P[GAMP] * P[GFREQ]
        return rate * t, rate, 0.0
    ue = u
    if P[LIMITS] > 0.5:
        rmax = P[RATEMAX]
        ue = min(max(ue, -rmax), rmax)
        hi = (P[PHIMAX] - phi) / P[TSTOP]
        lo = (-P[PHIMAX] - phi) / P[TSTOP]
        ue = min(max(ue, lo), hi)
    return phi, phid, (ue - phid) / P[TAU]


@numba.njit(cache=True)
def gimbal_drive(w1, w3, phi, phid, z, u, r20, r22, P):
    """(tau in N m, z' in rad/s) of the torque drive (`ship.drive.drive_torque`) on gyro 1's
    gimbal; the gyroscopic torque it feeds forward is H w_g1 (one gyro) or H cos(phi) w1 (pair)."""
    g = _gyro_torque(w1, w3, phi, P)
    return drive_torque(phi, phid, z, u, g, r20, r22, int(P[NGYRO]), P[DRV0 : DRV0 + N_DRIVE])


_TAN14_SQ = math.tan(1.4) ** 2  # the wall-sided GZ's tan(r) is clipped to |r| <= 1.4 rad


@numba.njit(cache=True)
def _asin(x: float) -> float:
    """asin(x); for |x| < 0.05 (pitch below 2.9 deg) its Taylor series to x^11 (truncation
    < 2e-19 |x|, as accurate as libm asin, and a few times cheaper)."""
    if abs(x) < 0.05:
        x2 = x * x
        return x + x * x2 * (
            1.0 / 6.0
            + x2 * (3.0 / 40.0 + x2 * (5.0 / 112.0 + x2 * (35.0 / 1152.0 + x2 * 63.0 / 2816.0)))
        )
    return math.asin(x)


@numba.njit(cache=True)
def hull_moment(w1, w2, w3, r20, r21, r22, P):
    """Hydrostatic and damping moments (N m, ship frame) from the body rates (rad/s) and the
    third row (r20, r21, r22) of the attitude R; see `external_moment`.

    Roll r = atan2(R32, R33) enters the wall-sided GZ only through sin(r) = R32 / |(R32, R33)|
    and tan(r)^2 = (R32 / R33)^2 (clipped at |r| = 1.4), the same numbers without atan2/sin/tan.
    """
    m1 = 0.0
    m2 = 0.0
    if P[K44] > 0.0:
        if P[GZR] > 0.0:
            hyp = math.sqrt(r21 * r21 + r22 * r22)
            sr = r21 / hyp if hyp > 0.0 else 0.0
            t2 = _TAN14_SQ
            if r22 > 0.0:
                t2 = min((r21 / r22) * (r21 / r22), _TAN14_SQ)
            m1 -= P[K44] * sr * (1.0 + 0.5 * P[GZR] * t2)
        else:
            m1 -= P[K44] * math.atan2(r21, r22)
        if P[GZ3] > 0.0:  # cubic GZ (MSS's K_phiphiphi phi^3)
            r = math.atan2(r21, r22)
            m1 -= P[K44] * P[GZ3] * r * r * r
    if P[K55] > 0.0:
        m2 -= P[K55] * _asin(max(min(-r20, 1.0), -1.0))
    m1 -= P[B44] * w1 + P[B44Q] * abs(w1) * w1
    m2 -= P[B55] * w2
    return m1, m2, -P[B66] * w3


@numba.njit(cache=True)
def wave_loads(t: float, P: np.ndarray, tab: np.ndarray):
    """(wave roll moment M_e in N m, heave force in N; the force only with `translation`) at t."""
    mode = int(P[WMODE])
    trans = P[TRANS] > 0.5
    mw = 0.0
    fw = 0.0
    if mode == WAVE_REGULAR:
        mw = P[WM0] * math.cos(P[WOMEGA] * t + P[WPHASE])
        if trans:
            fw = P[WF0] * math.sin(P[WOMEGA] * t + P[WPHASE])
    elif mode == WAVE_TABLE:
        mw = table_value(t, tab, 0, P[TABDT])
        if trans:
            fw = table_value(t, tab, 1, P[TABDT])
    return mw, fw


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


@numba.njit(cache=True)
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


@numba.njit(cache=True)
def ship_accel(w1, w2, w3, phi, phid, phidd, m1, m2, m3, P, free_gimbal, tau, v=0.0, roll=0.0):
    """Body angular acceleration w' (rad/s^2) from the angular-momentum balance (module doc)
    at body rates (w1, w2, w3) (rad/s) and moments (m1, m2, m3) (N m, ship frame).

    With `free_gimbal` the gimbal is a degree of freedom driven by the torque tau (N m, per
    gimbal) and phi'' is solved with the hull (the phi-equation of Eq. 74):
    one gyro:  d2 (w2' + phi'') = tau + H w_g1 - (d1 - d3) w_g1 w_g3,
               w_g = (c w1 - s w3, w2, s w1 + c w3) the gimbal's body rates;
    the pair:  d2 phi'' = tau + H c w1 - (d1 - d3) s c (w1^2 - w3^2).
    With the coupling on (P[CPLON]) the roll and yaw rows are solved together with the sway
    equation of `ship.coupling` at sway velocity v (m/s) and roll angle `roll` (rad).
    Returns (w1', w2', w3', gyro roll moment -n H phi' cos(phi) in N m, phi'', v' in m/s^2).
    """
    n = int(P[NGYRO])
    c = math.cos(phi)
    s = math.sin(phi)
    s2 = 2.0 * s * c
    c2 = c * c - s * s
    d1, d2, d3 = P[D1], P[D2], P[D3]
    dd = d3 - d1
    H = P[JR3] * P[PSID]
    # inertia J(phi): xx, yy, zz and xz (xz cancels for two mirrored gyros)
    jxx = P[J1] + n * (c * c * d1 + s * s * d3)
    jyy = P[J2] + n * d2
    jzz = P[J3] + n * (s * s * d1 + c * c * d3)
    jxz = s * c * dd if n == 1 else 0.0
    # dJ/dt
    dxx = n * phid * s2 * dd
    dzz = -dxx
    dxz = phid * c2 * dd if n == 1 else 0.0
    # internal angular momentum h and its rate hd (ship frame)
    hx = n * H * s
    hy = d2 * phid if n == 1 else 0.0
    hz = H * c if n == 1 else 0.0
    hdx = n * H * phid * c
    hdz = -H * phid * s if n == 1 else 0.0
    # total momentum L = J w + h
    lx = jxx * w1 + jxz * w3 + hx
    ly = jyy * w2 + hy
    lz = jxz * w1 + jzz * w3 + hz
    r1 = m1 - (dxx * w1 + dxz * w3) - hdx - (w2 * lz - w3 * ly)
    r2 = m2 - (w3 * lx - w1 * lz)
    r3 = m3 - (dxz * w1 + dzz * w3) - hdz - (w1 * ly - w2 * lx)
    if int(P[FORM]) == FORM_SEED:
        if n == 2:
            jxx = P[J1] + 2.0 * d1  # Eq. 123: roll inertia frozen at phi = 0
        else:
            jg = P[JG2]  # Eqs. 126 and 128 as printed
            r1 += jg * phid * w3
            r3 -= (jg - 0.25 * P[JR3] * c2) * phid * w1
    dv = 0.0
    if P[CPLON] > 0.5:
        C = P[CPL0 : CPL0 + N_COUPLING]
        dv, a1, a3 = solve_sway_roll_yaw(jxx, jzz, jxz, r1, r3, P[SPEED], v, w1, w3, roll, C)
    else:
        det = jxx * jzz - jxz * jxz
        a1 = (jzz * r1 - jxz * r3) / det
        a3 = (jxx * r3 - jxz * r1) / det
    if free_gimbal:
        if n == 1:
            wg1 = c * w1 - s * w3
            g = tau + H * wg1 - (d1 - d3) * wg1 * (s * w1 + c * w3)
            a2 = (r2 - g) / (jyy - d2)  # [jyy d2; d2 d2] [w2'; phi''] = [r2; g]
            phidd = g / d2 - a2
        else:
            phidd = (tau + H * c * w1 - (d1 - d3) * s * c * (w1 * w1 - w3 * w3)) / d2
            a2 = r2 / jyy
    else:
        a2 = (r2 - d2 * phidd) / jyy if n == 1 else r2 / jyy
    return a1, a2, a3, -n * H * phid * c, phidd, dv


@numba.njit(cache=True)
def ang_rates(w1, w2, w3, phi, phid, z, v, r20, r21, r22, u, mw, pg, P):
    """(w1', w2', w3', phi', phi'', z', drive power n |tau phi'|, v') of the rotational state, the
    drive-loop integral z and the sway velocity v (`ship.coupling`) at attitude third row
    (r20, r21, r22).

    mw: wave roll moment (N m) at the stage time; pg: (phi, phi', phi'') of a prescribed gimbal
    at that time (`gimbal_motion`, ignored for the servo and torque drives).
    """
    mode = int(P[GMODE])
    free = mode == GIMBAL_TORQUE
    tau = 0.0
    dz = 0.0
    phidd = 0.0
    if free:
        tau, dz = gimbal_drive(w1, w3, phi, phid, z, u, r20, r22, P)
    elif mode == GIMBAL_SERVO:
        phi, phid, phidd = gimbal_motion(0.0, phi, phid, u, P)
        tau = P[D2] * phidd - _gyro_torque(w1, w3, phi, P)  # what the kinematic servo applies
    else:
        phi, phid, phidd = pg
    m1, m2, m3 = hull_moment(w1, w2, w3, r20, r21, r22, P)
    roll = math.atan2(r21, r22) if P[CPLON] > 0.5 else 0.0
    a1, a2, a3, _, phidd, dv = ship_accel(
        w1, w2, w3, phi, phid, phidd, m1 + mw, m2, m3, P, free, tau, v, roll
    )
    return a1, a2, a3, phid, phidd, dz, P[NGYRO] * abs(tau * phid), dv


@numba.njit(cache=True)
def _gyro_torque(w1, w3, phi, P):
    """H w_g1 (N m): the gyroscopic torque on gyro 1's gimbal, H (cos phi w1 - sin phi w3) for
    one gyro, H cos(phi) w1 on the common coordinate of the mirrored pair."""
    c = math.cos(phi)
    h = P[JR3] * P[PSID]
    return h * (c * w1 - math.sin(phi) * w3) if int(P[NGYRO]) == 1 else h * c * w1


@numba.njit(cache=True)
def deriv(t, y, u, R, P, tab, dy):
    """dy/dt for state y (module doc) at attitude R, written into dy; returns the wave moment.
    (Reference form of the right-hand side that `rk4_step` evaluates stage by stage.)"""
    mw, fw = wave_loads(t, P, tab)
    pg = gimbal_motion(t, y[3], y[4], u, P)
    a = ang_rates(
        y[0], y[1], y[2], y[3], y[4], y[11], y[13], R[2, 0], R[2, 1], R[2, 2], u, mw, pg, P
    )
    for i in range(dy.shape[0]):
        dy[i] = 0.0
    for i in range(5):
        dy[i] = a[i]
    dy[Z_STATE], dy[E_STATE], dy[V_STATE] = a[5], a[6], a[7]
    if P[TRANS] > 0.5:
        # hull CM (= system CM: gyro CMs are fixed in the hull) in the inertial frame
        v1, v2, v3 = _trans_rates(y[7], y[8], y[9], y[10], fw, P)
        dy[5], dy[6], dy[7], dy[8], dy[9], dy[10] = y[8], y[9], y[10], v1, v2, v3
    return mw


@numba.njit(cache=True)
def _trans_rates(x3, v1, v2, v3, fw, P):
    """Hull CM acceleration (m/s^2, inertial): surge/sway damping, heave spring-damper + force."""
    m = P[MASS]
    return -P[CSS] * v1 / m, -P[CSS] * v2 / m, (fw - P[KH] * x3 - P[CH] * v3) / m


@numba.njit(cache=True)
def _trans_rk4(y, dt, f0, fh, f1, P):
    """Classical RK4 of the (decoupled, linear) translation y[5:11] with heave forces f0, fh, f1
    at t, t + dt/2, t + dt; the same arithmetic as RK4 on the whole state."""
    h = 0.5 * dt
    x1, x2, x3, v1, v2, v3 = y[5], y[6], y[7], y[8], y[9], y[10]
    a1, b1, c1 = _trans_rates(x3, v1, v2, v3, f0, P)
    p1, q1, s1 = v1 + h * a1, v2 + h * b1, v3 + h * c1
    a2, b2, c2 = _trans_rates(x3 + h * v3, p1, q1, s1, fh, P)
    p2, q2, s2 = v1 + h * a2, v2 + h * b2, v3 + h * c2
    a3, b3, c3 = _trans_rates(x3 + h * s1, p2, q2, s2, fh, P)
    p3, q3, s3 = v1 + dt * a3, v2 + dt * b3, v3 + dt * c3
    a4, b4, c4 = _trans_rates(x3 + dt * s2, p3, q3, s3, f1, P)
    y[5] = x1 + dt * (v1 + 2.0 * p1 + 2.0 * p2 + p3) / 6.0
    y[6] = x2 + dt * (v2 + 2.0 * q1 + 2.0 * q2 + q3) / 6.0
    y[7] = x3 + dt * (v3 + 2.0 * s1 + 2.0 * s2 + s3) / 6.0
    y[8] = v1 + dt * (a1 + 2.0 * a2 + 2.0 * a3 + a4) / 6.0
    y[9] = v2 + dt * (b1 + 2.0 * b2 + 2.0 * b3 + b4) / 6.0
    y[10] = v3 + dt * (c1 + 2.0 * c2 + 2.0 * c3 + c4) / 6.0


@numba.njit(cache=True)
def _rodrigues_ab(x2):
    """a = sin(x)/x, b = (1 - cos x)/x^2 of the angle x = sqrt(x2) (ch. 2 Eq. 29); for x < 0.1
    their Taylor series to x^8 (truncation < 3e-18, as accurate as libm sin/cos)."""
    if x2 < 0.01:
        a = 1.0 - x2 * (1.0 / 6.0 - x2 * (1.0 / 120.0 - x2 * (1.0 / 5040.0 - x2 / 362880.0)))
        b = 0.5 - x2 * (1.0 / 24.0 - x2 * (1.0 / 720.0 - x2 * (1.0 / 40320.0 - x2 / 3628800.0)))
        return a, b
    x = math.sqrt(x2)
    s = math.sin(0.5 * x)
    return math.sin(x) / x, 2.0 * s * s / x2


@numba.njit(cache=True)
def _rot_row(r0, r1, r2, x, y, z, a, b, x2):
    """Row (r0, r1, r2) of R times exp(hat(x, y, z)) = I + a W + b W^2 (Rodrigues, Eq. 29)."""
    e00, e11, e22 = 1.0 + b * (x * x - x2), 1.0 + b * (y * y - x2), 1.0 + b * (z * z - x2)
    e01, e10 = -a * z + b * x * y, a * z + b * x * y
    e02, e20 = a * y + b * x * z, -a * y + b * x * z
    e12, e21 = -a * x + b * y * z, a * x + b * y * z
    return (
        r0 * e00 + r1 * e10 + r2 * e20,
        r0 * e01 + r1 * e11 + r2 * e21,
        r0 * e02 + r1 * e12 + r2 * e22,
    )


@numba.njit(cache=True)
def _row3_step(R, x, y, z):
    """Third row of R exp(hat(x, y, z)): all the stage attitudes enter the moments through."""
    x2 = x * x + y * y + z * z
    a, b = _rodrigues_ab(x2)
    return _rot_row(R[2, 0], R[2, 1], R[2, 2], x, y, z, a, b, x2)


@numba.njit(cache=True)
def _rot_update(R, x, y, z):
    """R <- R exp(hat(x, y, z)) in place, row by row (no allocation)."""
    x2 = x * x + y * y + z * z
    a, b = _rodrigues_ab(x2)
    for i in range(3):
        R[i, 0], R[i, 1], R[i, 2] = _rot_row(R[i, 0], R[i, 1], R[i, 2], x, y, z, a, b, x2)


@numba.njit(cache=True)
def _dexpinv(t0, t1, t2, w0, w1, w2):
    """dexp^-1_th(w) = w - th x w / 2 + c(|th|) th x (th x w) (right trivialisation),
    c = (1 - (x/2) cot(x/2)) / x^2 (its series 1/12 + x^2/720 + ... to x^8 for x < 0.1, which
    is accurate to round-off where the closed form cancels)."""
    x2 = t0 * t0 + t1 * t1 + t2 * t2
    if x2 < 0.01:
        c = 1.0 / 12.0 + x2 * (
            1.0 / 720.0 + x2 * (1.0 / 30240.0 + x2 * (1.0 / 1209600.0 + x2 / 47900160.0))
        )
    else:
        x = math.sqrt(x2)
        c = (1.0 - 0.5 * x / math.tan(0.5 * x)) / x2
    a0 = t1 * w2 - t2 * w1
    a1 = t2 * w0 - t0 * w2
    a2 = t0 * w1 - t1 * w0
    b0 = t1 * a2 - t2 * a1
    b1 = t2 * a0 - t0 * a2
    b2 = t0 * a1 - t1 * a0
    return w0 - 0.5 * a0 + c * b0, w1 - 0.5 * a1 + c * b1, w2 - 0.5 * a2 + c * b2


@numba.njit(cache=True)
def rk4_step(t, y, R, u, dt, P, tab, mw0, fw0):
    """One Runge-Kutta-Munthe-Kaas step (RK4 in the rates, the attitude in the Lie algebra):
    R_stage = R exp(theta_stage), theta' = dexp^-1_theta(w), R_new = R exp(theta_final) with
    the Rodrigues formula (ch. 2 Eq. 29): 4th order in R and w, R orthogonal to round-off.
    y and R are updated in place, without allocation. mw0, fw0: wave moment (N m) and heave
    force (N) at t (`wave_loads`); returns them at t + dt for the next step.
    """
    h = 0.5 * dt
    pres = int(P[GMODE]) == GIMBAL_SINUSOIDAL or int(P[GMODE]) == GIMBAL_CONTINUOUS
    mwh, fwh = wave_loads(t + h, P, tab)
    mw1, fw1 = wave_loads(t + dt, P, tab)
    w1, w2, w3, ph, pd, zz, vv = y[0], y[1], y[2], y[3], y[4], y[Z_STATE], y[V_STATE]
    pg0 = gimbal_motion(t, ph, pd, u, P)
    pgh = gimbal_motion(t + h, ph, pd, u, P) if pres else pg0
    pg1 = gimbal_motion(t + dt, ph, pd, u, P) if pres else pg0
    # stage 1 at R (dexpinv at theta = 0 is the identity)
    k1 = ang_rates(w1, w2, w3, ph, pd, zz, vv, R[2, 0], R[2, 1], R[2, 2], u, mw0, pg0, P)
    s0, s1, s2 = w1 + h * k1[0], w2 + h * k1[1], w3 + h * k1[2]
    r = _row3_step(R, h * w1, h * w2, h * w3)
    z2 = zz + h * k1[5]
    v2 = vv + h * k1[7]
    k2 = ang_rates(
        s0, s1, s2, ph + h * k1[3], pd + h * k1[4], z2, v2, r[0], r[1], r[2], u, mwh, pgh, P
    )
    q2 = _dexpinv(h * w1, h * w2, h * w3, s0, s1, s2)
    # stage 3
    s0, s1, s2 = w1 + h * k2[0], w2 + h * k2[1], w3 + h * k2[2]
    r = _row3_step(R, h * q2[0], h * q2[1], h * q2[2])
    z3 = zz + h * k2[5]
    v3 = vv + h * k2[7]
    k3 = ang_rates(
        s0, s1, s2, ph + h * k2[3], pd + h * k2[4], z3, v3, r[0], r[1], r[2], u, mwh, pgh, P
    )
    q3 = _dexpinv(h * q2[0], h * q2[1], h * q2[2], s0, s1, s2)
    # stage 4
    s0, s1, s2 = w1 + dt * k3[0], w2 + dt * k3[1], w3 + dt * k3[2]
    r = _row3_step(R, dt * q3[0], dt * q3[1], dt * q3[2])
    z4 = zz + dt * k3[5]
    v4 = vv + dt * k3[7]
    k4 = ang_rates(
        s0, s1, s2, ph + dt * k3[3], pd + dt * k3[4], z4, v4, r[0], r[1], r[2], u, mw1, pg1, P
    )
    q4 = _dexpinv(dt * q3[0], dt * q3[1], dt * q3[2], s0, s1, s2)
    th = (
        dt * (w1 + 2.0 * q2[0] + 2.0 * q3[0] + q4[0]) / 6.0,
        dt * (w2 + 2.0 * q2[1] + 2.0 * q3[1] + q4[1]) / 6.0,
        dt * (w3 + 2.0 * q2[2] + 2.0 * q3[2] + q4[2]) / 6.0,
    )
    for i in range(5):
        y[i] += dt * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]) / 6.0
    if not pres:
        y[Z_STATE] += dt * (k1[5] + 2.0 * k2[5] + 2.0 * k3[5] + k4[5]) / 6.0
        y[E_STATE] += dt * (k1[6] + 2.0 * k2[6] + 2.0 * k3[6] + k4[6]) / 6.0
        y[V_STATE] += dt * (k1[7] + 2.0 * k2[7] + 2.0 * k3[7] + k4[7]) / 6.0
        if int(P[GMODE]) == GIMBAL_TORQUE and P[LIMITS] > 0.5:
            _stop_gimbal(y, P)
    _rot_update(R, th[0], th[1], th[2])
    if pres:
        y[3] = pg1[0]
        y[4] = pg1[1]
    if P[TRANS] > 0.5:
        _trans_rk4(y, dt, fw0, fwh, fw1, P)
    return mw1, fw1


@numba.njit(cache=True)
def _stop_gimbal(y, P):
    """Inelastic end stop of the free gimbal (`ship.drive.end_stop`) at +-phi_max; one gyro's
    hull takes the reaction that keeps L_2 = J_yy w2 + J_g phi' (the pair's cancels)."""
    phi, phid, jump = end_stop(y[3], y[4], P[PHIMAX])
    y[3], y[4] = phi, phid
    if jump != 0.0 and int(P[NGYRO]) == 1:
        y[1] -= P[D2] * jump / (P[J2] + P[D2])


@numba.njit(cache=True)
def gyro_moment(y, P):
    """Gyro roll moment -n H phi' cos(phi) (N m, Eq. 123) of state y."""
    return -P[NGYRO] * P[JR3] * P[PSID] * y[4] * math.cos(y[3])


@numba.njit(cache=True)
def advance(t, y, R, u, dt, n_sub, P, tab, out):
    """n_sub RK4 steps of size dt with the command u held; returns the new time.
    out[0], out[1] <- gyro roll moment and wave moment (N m) at the end; out[2], out[3] <- gyro
    1's drive torque (N m) and the drive power n tau phi' (W) at the end (`drive_output`)."""
    mw, fw = wave_loads(t, P, tab)
    for _ in range(n_sub):
        mw, fw = rk4_step(t, y, R, u, dt, P, tab, mw, fw)
        t += dt
    out[0] = gyro_moment(y, P)
    out[1] = mw
    out[2], out[3] = drive_output(t, y, R, u, P)
    return t


@numba.njit(cache=True)
def drive_output(t, y, R, u, P):
    """(torque on gyro 1's gimbal in N m, power n tau phi' in W) of the drive at state y.

    Torque drives: the machine's torque (`gimbal_drive`). The kinematic servo (and prescribed
    gimbals) report the torque they impose, J_g phi'' - H w_g1 (the gimbal's own equation with
    the hull's pitch acceleration neglected), without any limit.
    """
    phi, phid = y[3], y[4]
    mode = int(P[GMODE])
    if mode == GIMBAL_TORQUE:
        tau = gimbal_drive(y[0], y[2], phi, phid, y[Z_STATE], u, R[2, 0], R[2, 2], P)[0]
    else:
        phidd = gimbal_motion(t, phi, phid, u, P)[2]
        tau = P[D2] * phidd - _gyro_torque(y[0], y[2], phi, P)
    return tau, P[NGYRO] * tau * phid


@numba.njit(cache=True)
def simulate_kernel(y0, R0, t_end, dt, P, tab):
    """Open-loop run (prescribed gimbal, or servo / torque drive with u = 0): t, y, R, moment."""
    n = int(round(t_end / dt))
    ts = np.empty(n + 1)
    ys = np.empty((n + 1, y0.shape[0]))
    Rs = np.empty((n + 1, 3, 3))
    mg = np.empty(n + 1)
    y = y0.copy()
    R = R0.copy()
    phi, phid, _ = gimbal_motion(0.0, y[3], y[4], 0.0, P)
    if int(P[GMODE]) == GIMBAL_SINUSOIDAL or int(P[GMODE]) == GIMBAL_CONTINUOUS:
        y[3] = phi
        y[4] = phid
    ts[0] = 0.0
    ys[0] = y
    Rs[0] = R
    mg[0] = gyro_moment(y, P)
    t = 0.0
    mw, fw = wave_loads(t, P, tab)
    for k in range(n):
        mw, fw = rk4_step(t, y, R, 0.0, dt, P, tab, mw, fw)
        t = (k + 1) * dt
        mw, fw = wave_loads(t, P, tab)  # t is k dt, not a running sum: recompute
        ts[k + 1] = t
        ys[k + 1] = y
        Rs[k + 1] = R
        mg[k + 1] = gyro_moment(y, P)
    return ts, ys, Rs, mg
