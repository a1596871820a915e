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

State y (float64): [w1, w2, w3, phi, phi', x1, x2, x3, v1, v2, v3, z, E, v] (body rates in rad/s,
gimbal angle/rate of gyro 1 in rad, rad/s; hull CM position/velocity in the inertial frame, m,
m/s; the torque drive's loop integral z in rad, its energy E = int n |tau phi'| dt in J, the sway
velocity v of `ship.coupling` in m/s).
The attitude R (3x3, inertial <- ship) is rebuilt each step with Rodrigues' formula (ch. 2 Eq. 29)
inside a Runge-Kutta-Munthe-Kaas step (4th order also in R; the seed's midpoint-Rodrigues update
is 2nd order, which limits the hydrostatic moment's accuracy, see docs/design.md ch. 2 notes).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.frames.kernels import sincos_near
from mf_envs.frames.steppers import make_rkmk4, rk4_work, rkmk4_rwork
from mf_envs.physics.ship.coupling import N_COUPLING, solve_sway_roll_yaw
from mf_envs.physics.ship.drive import DKS, DRCAP, cap_rate, cushion_torque, end_stop
from mf_envs.physics.ship.layout import (  # noqa: F401 (re-exported)
    CPL0,
    DRV0,
    E_STATE,
    FORM_EXACT,
    FORM_SEED,
    GIMBAL_CONTINUOUS,
    GIMBAL_SERVO,
    GIMBAL_SINUSOIDAL,
    GIMBAL_TORQUE,
    N_OUT,
    N_PARAMS,
    N_STATE,
    V_STATE,
    WAVE_NONE,
    WAVE_REGULAR,
    WAVE_TABLE,
    Z_STATE,
)
from mf_envs.physics.ship.layout import Slot as S
from mf_envs.physics.ship.loads import (  # noqa: F401 (re-exported: the kernels' public face)
    external_moment,
    gimbal_drive,
    gimbal_motion,
    gyro_gimbal_torque,
    hull_moment,
    table_value,
    wave_loads,
    wave_loads_near,
)
from mf_envs.physics.ship.outputs import (  # noqa: F401 (re-exported: the kernels' public face)
    drive_output,
    gyro_moment,
    gyro_roll_moment,
    mount_moment,
    roll_of,
    step_outputs,
)

# P: the packed parameter vector of `layout.KernelParams`, indexed P[S.NAME]; the state y
# (N_STATE,) and the outputs out (N_OUT,) as `layout` lays them out


@kernel(forceinline=True, error_model="numpy")
def ship_accel(w1, w2, w3, c, s, phid, phidd, moments, P, free_gimbal, tau, v, roll):
    """Body angular acceleration w' (rad/s^2) from the angular-momentum balance (module doc)
    at body rates (w1, w2, w3) (rad/s) and moments = (m1, m2, m3) (N m, ship frame), gimbal
    angle phi given by c = cos(phi), s = sin(phi) (computed once per stage by the caller).

    With `free_gimbal` the gimbal is a degree of freedom driven by the torque tau (N m, per
    gimbal) and phi'' is solved with the hull (the phi-equation of Eq. 74):
    one gyro:  d2 (w2' + phi'') = tau + H w_g1 - (d1 - d3) w_g1 w_g3,
               w_g = (c w1 - s w3, w2, s w1 + c w3) the gimbal's body rates;
    the pair:  d2 phi'' = tau + H c w1 - (d1 - d3) s c (w1^2 - w3^2).
    With the coupling on (P[S.CPLON] > 0.5) the roll and yaw rows are solved together with the
    sway equation of `ship.coupling` at sway velocity v (m/s) and roll angle `roll` (rad).
    Division by zero gives inf/NaN (numpy's error model: no exception path to inline).
    Returns (w1', w2', w3', gyro roll moment -n H phi' cos(phi) in N m, phi'', v' in m/s^2).
    """
    m1, m2, m3 = moments
    n = int(P[S.NGYRO])
    s2 = 2.0 * s * c
    c2 = c * c - s * s
    d1, d2, d3 = P[S.D1], P[S.D2], P[S.D3]
    dd = d3 - d1
    H = P[S.JR3] * P[S.PSID]
    # inertia J(phi): xx, yy, zz and xz (xz cancels for two mirrored gyros)
    jxx = P[S.J1] + n * (c * c * d1 + s * s * d3)
    jyy = P[S.J2] + n * d2
    jzz = P[S.J3] + n * (s * s * d1 + c * c * d3)
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
    if int(P[S.FORM]) == FORM_SEED:
        if n == 2:
            jxx = P[S.J1] + 2.0 * d1  # Eq. 123: roll inertia frozen at phi = 0
        else:
            jg = P[S.JG2]  # Eqs. 126 and 128 as printed
            r1 += jg * phid * w3
            r3 -= (jg - 0.25 * P[S.JR3] * c2) * phid * w1
    dv = 0.0
    if P[S.CPLON] > 0.5:  # the sway-roll-yaw coupling
        C = P[CPL0 : CPL0 + N_COUPLING]
        dv, a1, a3 = solve_sway_roll_yaw(jxx, jzz, jxz, r1, r3, P[S.SPEED], v, w1, w3, roll, C)
    else:
        # 1/det from the gimbal angle alone, ready before the moments: a multiply, not a
        # division, on the roll chain (attitude -> moment -> w1')
        inv = 1.0 / (jxx * jzz - jxz * jxz)
        a1 = (jzz * r1 - jxz * r3) * inv
        a3 = (jxx * r3 - jxz * r1) * inv
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


@kernel(forceinline=True)
def ang_rates(y, r20, r21, r22, u, mw, pg, P, near):
    """(w1', w2', w3', phi', phi'', z', drive power n |tau phi'|, v') of the rotational state
    (w1, w2, w3, phi, phi') = y[:5], the drive-loop integral z = y[Z_STATE] and the sway
    velocity v = y[V_STATE] (`ship.coupling`) at attitude third row (r20, r21, r22).

    mw: wave roll moment (N m) at the stage time; pg: (phi, phi', phi'') of a prescribed gimbal
    at that time (`gimbal_motion`, ignored for the servo and torque drives); near = (phi0,
    cos phi0, sin phi0) at the step's start (`frames.kernels.sincos_near`).
    """
    w1, w2, w3, phi, phid = y[0], y[1], y[2], y[3], y[4]
    z, v = y[Z_STATE], y[V_STATE]
    mode = int(P[S.GMODE])
    free = mode == GIMBAL_TORQUE
    tau = 0.0
    dz = 0.0
    phidd = 0.0
    if not free and mode != GIMBAL_SERVO:
        phi, phid, phidd = pg
        c, s = math.cos(phi), math.sin(phi)
    else:  # once per stage (the drive and the balance share them), from the step's start
        c, s = sincos_near(phi, near[0], near[1], near[2])
    tg = 0.0  # the torque on the gimbal: drive, plus the cushioned stops if the unit has them
    if free:
        tau, dz = gimbal_drive(w1, w3, phi, phid, z, u, r20, r22, P, c, s)
        tg = tau
        if P[DRV0 + DKS] > 0.0:
            tg = tau + cushion_torque(phi, phid, P, DRV0)
    elif mode == GIMBAL_SERVO:
        phidd = gimbal_motion(0.0, phi, phid, u, P)[2]  # the servo keeps phi, phi'
        tau = P[S.D2] * phidd - gyro_gimbal_torque(w1, w3, phi, P, c, s)  # what it applies
    m1, m2, m3 = hull_moment(w1, w2, w3, r20, r21, r22, P)
    coupled = P[S.CPLON] > 0.5
    roll = math.atan2(r21, r22) if coupled else 0.0
    a1, a2, a3, _, phidd, dv = ship_accel(
        w1, w2, w3, c, s, phid, phidd, (m1 + mw, m2, m3), P, free, tg, v, roll
    )
    return a1, a2, a3, phid, phidd, dz, P[S.NGYRO] * abs(tau * phid), dv


@kernel(forceinline=True)
def _trans_rates(x3, v1, v2, v3, fw, P):
    """Hull CM acceleration (m/s^2, inertial): surge/sway damping, heave spring-damper + force."""
    m = P[S.MASS]
    return -P[S.CSS] * v1 / m, -P[S.CSS] * v2 / m, (fw - P[S.KH] * x3 - P[S.CH] * v3) / m


@kernel(forceinline=True)
def stage_inputs(t, args):
    """The state-free inputs at time t: (wave moment N m, heave force N, prescribed gimbal
    (phi, phi', phi'') of gyro 1; unused by the servo and torque drives). args = (u, P, tab,
    near), near the step's start values of `start_values`."""
    u, P, tab, near = args
    mw, fw = wave_loads_near(t, P, tab, near[3], near[4], near[5])
    mode = int(P[S.GMODE])
    if mode == GIMBAL_SINUSOIDAL or mode == GIMBAL_CONTINUOUS:
        return mw, fw, gimbal_motion(t, 0.0, 0.0, u, P)
    return mw, fw, (0.0, 0.0, 0.0)


@kernel(forceinline=True)
def stage_rhs(t, y, R, inp, args, dy):
    """y' (n,) of the state y at attitude R (module doc) into dy; returns the body rate omega
    (3-tuple, rad/s): the right-hand side of the RKMK4 step. The gimbal is prescribed by inp in
    the sinusoidal/continuous modes."""
    u, P, tab, near = args
    mw, fw, pg = inp
    r20, r21, r22 = R[2, 0], R[2, 1], R[2, 2]
    a = ang_rates(y, r20, r21, r22, u, mw, pg, P, near)
    for i in range(5):
        dy[i] = a[i]
    for i in range(5, y.shape[0]):
        dy[i] = 0.0
    # the sway v evolves with the coupling whatever drives the gimbal; a prescribed gimbal has
    # no drive loop and no drive energy (ang_rates gives z' = 0 and n |tau phi'| = 0 for it)
    dy[Z_STATE], dy[E_STATE], dy[V_STATE] = a[5], a[6], a[7]
    if P[S.TRANS] > 0.5:
        # hull CM (= system CM: gyro CMs are fixed in the hull) in the inertial frame
        v1, v2, v3 = _trans_rates(y[7], y[8], y[9], y[10], fw, P)
        dy[5], dy[6], dy[7], dy[8], dy[9], dy[10] = y[8], y[9], y[10], v1, v2, v3
    return y[0], y[1], y[2]


_rkmk4 = make_rkmk4(stage_rhs, stage_inputs, inline=True, third_row=True)  # reads R[2] only


@kernel
def rk4_step(t, y, R, u, dt, P, tab, work, Rwork):
    """One Runge-Kutta-Munthe-Kaas step (`mf_envs.frames.kernels`, RK4 tableau, the attitude in
    the Lie algebra: 4th order in R and w, R orthogonal to round-off) of y and R in place.
    A prescribed gimbal is set to its value at t + dt; a torque-driven gimbal with
    `gimbal_limits` then meets its inelastic end stops (`_stop_gimbal`). work (5, n),
    Rwork (2, 3, 3): the stepper's scratch (`frames.kernels.rk4_work`, `rkmk4_rwork`).
    Returns the wave moment (N m) at t + dt."""
    return rk4_step_near(t, y, R, u, dt, P, tab, work, Rwork, start_values(t, y[3], P))


@kernel
def rk4_step_near(t, y, R, u, dt, P, tab, work, Rwork, near):
    """`rk4_step` with the step's start values `near` given (`start_values`: libm, or
    `start_values_from` an earlier start)."""
    inp = _rkmk4(t, y, R, dt, (u, P, tab, near), work, Rwork)
    return end_step(y, R, dt, P, work, Rwork, inp)


@kernel(forceinline=True)
def end_step(y, R, dt, P, work, Rwork, inp):
    """The end of `rk4_step_near` after its stepper:
    y += the increment work[0], R <- the new attitude Rwork[1], then the prescribed gimbal's
    value, the rate cap or the hard stops; returns the wave moment of inp, the stage inputs
    at t + dt."""
    dy, R1 = work[0], Rwork[1]
    for i in range(y.shape[0]):
        y[i] += dy[i]
    for i in range(3):
        R[i, 0], R[i, 1], R[i, 2] = R1[i, 0], R1[i, 1], R1[i, 2]
    mode = int(P[S.GMODE])
    if mode == GIMBAL_SINUSOIDAL or mode == GIMBAL_CONTINUOUS:
        y[3], y[4] = inp[2][0], inp[2][1]
    elif mode == GIMBAL_TORQUE and P[S.LIMITS] > 0.5:
        if P[DRV0 + DKS] > 0.0 or P[DRV0 + DRCAP] > 0.0:
            _cap_gimbal(y, dt, P)  # the unit's rate cap; its cushions act inside the stages
        else:
            _stop_gimbal(y, P)
    return inp[0]


@kernel(forceinline=True)
def start_values(t, phi, P):
    """(phi, cos phi, sin phi, t, cos a, sin a) at a step's start: gimbal angle phi (rad) of the
    servo and torque drives and the regular wave's phase a = omega t + eps (rad), from which
    the stages get theirs (`frames.kernels.sincos_near`; zeros where unused)."""
    mode = int(P[S.GMODE])
    c = s = cw = sw = 0.0
    if mode == GIMBAL_SERVO or mode == GIMBAL_TORQUE:
        c, s = math.cos(phi), math.sin(phi)
    if int(P[S.WMODE]) == WAVE_REGULAR:
        a = P[S.WOMEGA] * t + P[S.WPHASE]
        cw, sw = math.cos(a), math.sin(a)
    return phi, c, s, t, cw, sw


@kernel(forceinline=True)
def start_values_from(near0, t, phi, P):
    """`start_values` at (t, phi) from the values near0 of an earlier start (`sincos_near`: the
    addition formulas while within 0.1 rad of it, libm beyond; no libm sin/cos for a control
    step's later substeps, whose angles move by ~0.05 rad each)."""
    c, s, cw, sw = near0[1], near0[2], near0[4], near0[5]
    mode = int(P[S.GMODE])
    if mode == GIMBAL_SERVO or mode == GIMBAL_TORQUE:
        c, s = sincos_near(phi, near0[0], c, s)
    if int(P[S.WMODE]) == WAVE_REGULAR:
        om, ph = P[S.WOMEGA], P[S.WPHASE]
        cw, sw = sincos_near(om * t + ph, om * near0[3] + ph, cw, sw)
    return phi, c, s, t, cw, sw


@kernel
def _stop_gimbal(y, P):
    """Inelastic end stop of the free gimbal (`ship.drive.end_stop`) at +-phi_max; one gyro's
    hull takes the reaction that keeps L_2 = J_yy w2 + J_g phi' (the pair's cancels)."""
    phi, phid, jump = end_stop(y[3], y[4], P[S.PHIMAX])
    y[3], y[4] = phi, phid
    if jump != 0.0 and int(P[S.NGYRO]) == 1:
        y[1] -= P[S.D2] * jump / (P[S.J2] + P[S.D2])


@kernel
def _cap_gimbal(y, dt, P):
    """The unit's precession-rate cap (`ship.drive.cap_rate`) after a step of dt (s); one gyro's
    hull takes the reaction that keeps L_2 = J_yy w2 + J_g phi' (the pair's cancels)."""
    phid, jump = cap_rate(y[4], dt, P[S.D2], P, DRV0)
    y[4] = phid
    if jump != 0.0 and int(P[S.NGYRO]) == 1:
        y[1] -= P[S.D2] * jump / (P[S.J2] + P[S.D2])


@numba.njit(cache=True)
def advance(t, y, R, u, dt, n_sub, P, tab, out):
    """n_sub RK4 steps of size dt with the command u held; returns the new time.
    out[0], out[1] <- gyro roll moment and wave moment (N m) at the end; out[2], out[3] <- gyro
    1's drive torque (N m) and the drive power n tau phi' (W) at the end (`drive_output`);
    out[4] <- the mount moment per unit (N m, `mount_moment`), out[5] <- rotor power (W)."""
    return advance_with(t, y, R, u, dt, n_sub, P, tab, out, rk4_work(y.shape[0]), rkmk4_rwork())


@kernel
def advance_with(t, y, R, u, dt, n_sub, P, tab, out, work, Rwork):
    """`advance` with the caller's stepper scratch work (5, N_STATE), Rwork (2, 3, 3) (the batch
    reuses one pair for every row)."""
    mw = wave_loads(t, P, tab)[0] if n_sub == 0 else 0.0
    near0 = start_values(t, y[3], P)  # libm once; the later substeps and the outputs start from it
    near = near0
    for k in range(n_sub):
        if k > 0:
            near = start_values_from(near0, t, y[3], P)
        mw = rk4_step_near(t, y, R, u, dt, P, tab, work, Rwork, near)
        t += dt
    step_outputs(t, y, R, u, P, out, mw, near0)
    return t


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
    if int(P[S.GMODE]) == GIMBAL_SINUSOIDAL or int(P[S.GMODE]) == GIMBAL_CONTINUOUS:
        y[3] = phi
        y[4] = phid
    ts[0] = 0.0
    ys[0] = y
    Rs[0] = R
    mg[0] = gyro_moment(y, P, math.nan)
    t = 0.0
    work, Rwork = rk4_work(y.shape[0]), rkmk4_rwork()
    for k in range(n):
        rk4_step(t, y, R, 0.0, dt, P, tab, work, Rwork)
        t = (k + 1) * dt  # k dt, not a running sum
        ts[k + 1] = t
        ys[k + 1] = y
        Rs[k + 1] = R
        mg[k + 1] = gyro_moment(y, P, math.nan)
    return ts, ys, Rs, mg
