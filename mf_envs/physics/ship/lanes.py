"""The ship + gyro step of many rows at once in SIMD lanes (the native vector env's hot path).

`advance_with` (`kernels`) steps one row: a chain of scalar operations with a libm fallback
at each series (the gimbal's sin/cos near the step's start, the pitch's asin, the Rodrigues and
dexp^-1 coefficients) and a branch per model option. LLVM cannot vectorize a loop over rows of
it (a call, even in a branch never taken, stops its loop vectorizer), so one row costs its full
chain of ~3,500 instructions per RK4-Munthe-Kaas step.

Here the four stages of one RKMK4 step run for LANES rows in one loop whose body has no call
and no exception path: the same scalar functions (`ship_accel`, `hull_moment_with`,
`active_torque`, ..., compiled with numpy's error model) with each libm fallback replaced by its
series (`frames.kernels.sincos_series`, `rodrigues_series`, `dexpinv_series`,
`loads.asin_series`) and a flag where the series would not apply; the rows' values sit in flat
arrays at constant offsets (F * LANES + j), so LLVM proves the rows independent and runs them
in AVX lanes. Each operation is the scalar step's, in its order, so each row's bits are those
of `advance_with` (`tests/test_ship_lanes.py` checks this for every supported option); a row
whose flag is set (a series out of range in some stage) is stepped again by `rk4_step_near`
from its unchanged state. What is not per-row arithmetic stays scalar per row: the stage
inputs (wave moments) and the step's start values before the lanes, the new attitude, the
rate cap or stops (`end_step`) and the outputs after them.

Rows share one parameter vector (`P0`): all rows' P must equal it but for the wave phase
(`uniform`), which enters only the scalar stage inputs. Scenes the lanes do not model
(`supported`: prescribed or servo gimbals, passive drives, the sway-roll-yaw coupling, heave,
the linear or cubic GZ) keep `advance_with` for every row.
Hand-written (numba; no library vectorizes a Lie-group integrator across independent rows).
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.frames.kernels import (
    _SERIES_X2,
    SINCOS_NEAR,
    _two_term3,
    dexpinv_series,
    rodrigues_series,
    sincos_series,
)
from mf_envs.frames.steppers import _rk4_combine3, _rk4_weight, row_times_exp, times_exp_into
from mf_envs.physics.ship.drive import (
    DC,
    DKIND,
    DKS,
    KIND_BRAKE,
    KIND_ELECTRIC,
    active_torque,
    cushion_torque,
)
from mf_envs.physics.ship.kernels import (
    E_STATE,
    GIMBAL_TORQUE,
    N_STATE,
    Z_STATE,
    end_step,
    rk4_step_near,
    ship_accel,
    stage_inputs,
    start_values,
    start_values_from,
    step_outputs,
    wave_loads,
)
from mf_envs.physics.ship.layout import DRV0
from mf_envs.physics.ship.layout import Slot as S
from mf_envs.physics.ship.loads import (
    ASIN_SERIES,
    asin_series,
    gyro_torque_cs,
    hull_moment_with,
    pitch_sine,
    roll_needed,
)

LANES = 32  # rows per block (a compile-time constant: the offsets F * LANES + j)
# lane inputs X (field F at F * LANES + j): the RKMK4 step's start state, attitude third row,
# the gimbal's start values, the stage inputs' wave moments at t, t + dt/2, t + dt, command, dt
XW1, XW2, XW3, XPHI, XPHID, XZ, XR0, XR1, XR2, XNPHI, XNC, XNS, XM0, XMH, XM1, XU, XDT = range(17)
N_X = 17
# lane outputs K: the increment of the 7 live states (w1, w2, w3, phi, phi', z, E), the
# Lie-algebra increment theta of the attitude, the fallback flag (1: step the row again)
KDY, KTH, KBAD = 0, 7, 10
N_K = 11
LIVE = (0, 1, 2, 3, 4, Z_STATE, E_STATE)  # the states with a nonzero rate in the lanes' scenes


def supported(P: np.ndarray) -> bool:
    """Whether the lanes model the scene packed in P (module doc): a torque-driven gimbal with
    an active drive (electric or brake), no sway-roll-yaw coupling, no heave, and a hull whose
    restoring moment needs no roll angle (the wall-sided GZ, or none)."""
    kind = int(P[DRV0 + DKIND])
    return (
        int(P[S.GMODE]) == GIMBAL_TORQUE
        and kind in (KIND_ELECTRIC, KIND_BRAKE)
        and P[S.CPLON] <= 0.5
        and P[S.TRANS] <= 0.5
        and not roll_needed(P)
    )


def uniform(P: np.ndarray) -> bool:
    """Whether the rows of P (N, N_PARAMS) can share row 0's in the lanes: equal but for the
    wave phase, and `supported`."""
    other = np.ones(P.shape[1], dtype=bool)
    other[int(S.WPHASE)] = False
    return bool(supported(P[0]) and (P[:, other] == P[0, other]).all())


@kernel(forceinline=True, error_model="numpy")
def _rhs(w1, w2, w3, phi, phid, z, r20, r21, r22, u, mw, nphi, nc, ns, P):
    """`kernels.stage_rhs` of a torque-driven gimbal (its `ang_rates`), operation for
    operation, with the series in place of libm: (w1', w2', w3', phi', phi'', z', drive power
    n |tau phi'|, True where a series was out of its range)."""
    d = phi - nphi
    c, s = sincos_series(d, nc, ns)
    if d == 0.0:  # sincos_near's exact start values
        c, s = nc, ns
    bad = not abs(d) < SINCOS_NEAR
    g = gyro_torque_cs(w1, w3, c, s, P)
    tau = -P[DRV0 + DC] * phid  # drive_torque: the bearing friction, then the machine
    tm, dz = active_torque(phi, phid, z, u, g, P, DRV0)
    tau = tau + tm
    tg = tau
    if P[DRV0 + DKS] > 0.0:
        tg = tau + cushion_torque(phi, phid, P, DRV0)
    x = pitch_sine(r20)
    pitch = 0.0
    if P[S.K55] > 0.0:
        pitch = asin_series(x)
        bad = bad or not abs(x) < ASIN_SERIES
    m1, m2, m3 = hull_moment_with(w1, w2, w3, r21, r22, P, 0.0, pitch)
    a1, a2, a3, _, phidd, _ = ship_accel(
        w1, w2, w3, c, s, phid, 0.0, m1 + mw, m2, m3, P, True, tg, 0.0, 0.0, False
    )
    return a1, a2, a3, phid, phidd, dz, P[S.NGYRO] * abs(tau * phid), bad


@kernel(forceinline=True)
def _stage_row(r0, r1, r2, th):
    """The stage attitude's third row, R's third row times exp(hat(th)) (`times_exp_row2_into`),
    and True if its Rodrigues series was out of range."""
    x, y, z = th
    x2 = x * x + y * y + z * z
    a, b = rodrigues_series(x2)
    q0, q1, q2 = row_times_exp(r0, r1, r2, x, y, z, a, b)
    return q0, q1, q2, not x2 < _SERIES_X2


@kernel(forceinline=True)
def _algebra_rate(th, w):
    """`dexpinv_right3` by its series, and True if out of range."""
    x2 = th[0] * th[0] + th[1] * th[1] + th[2] * th[2]
    return _two_term3(th, w, 0.5, dexpinv_series(x2)), not x2 < _SERIES_X2


@kernel(forceinline=True)
def _point(y, h, k):
    """The stage state y + h k of the live states (`_stage_point`)."""
    return (y[0] + h * k[0], y[1] + h * k[1], y[2] + h * k[2], y[3] + h * k[3],
            y[4] + h * k[4], y[5] + h * k[5])  # fmt: skip


@kernel(forceinline=True)
def _stage(ys, r, u, mw, nphi, nc, ns, P):
    """The right-hand side at the stage state ys (6 live states but E) and attitude row r."""
    return _rhs(ys[0], ys[1], ys[2], ys[3], ys[4], ys[5], r[0], r[1], r[2], u, mw, nphi, nc, ns, P)


@kernel(error_model="numpy")
def lane_block(X, K, P):
    """One RKMK4 step (`frames.steppers._rkmk4_template`, third-row form) of LANES rows from the
    inputs X into K (module doc), all rows with the parameters P (N_PARAMS,)."""
    for j in range(LANES):
        y = (X[XW1 * LANES + j], X[XW2 * LANES + j], X[XW3 * LANES + j], X[XPHI * LANES + j],
             X[XPHID * LANES + j], X[XZ * LANES + j])  # fmt: skip
        r = (X[XR0 * LANES + j], X[XR1 * LANES + j], X[XR2 * LANES + j])
        nphi, nc, ns = X[XNPHI * LANES + j], X[XNC * LANES + j], X[XNS * LANES + j]
        u, dt = X[XU * LANES + j], X[XDT * LANES + j]
        h = 0.5 * dt
        k1 = _stage(y, r, u, X[XM0 * LANES + j], nphi, nc, ns, P)
        q1 = (y[0], y[1], y[2])
        th = (h * q1[0], h * q1[1], h * q1[2])
        s0, s1, s2, b1 = _stage_row(r[0], r[1], r[2], th)
        ys = _point(y, h, k1)
        k2 = _stage(ys, (s0, s1, s2), u, X[XMH * LANES + j], nphi, nc, ns, P)
        q2, b2 = _algebra_rate(th, (ys[0], ys[1], ys[2]))
        th = (h * q2[0], h * q2[1], h * q2[2])
        s0, s1, s2, b3 = _stage_row(r[0], r[1], r[2], th)
        ys = _point(y, h, k2)
        k3 = _stage(ys, (s0, s1, s2), u, X[XMH * LANES + j], nphi, nc, ns, P)
        q3, b4 = _algebra_rate(th, (ys[0], ys[1], ys[2]))
        th = (dt * q3[0], dt * q3[1], dt * q3[2])
        s0, s1, s2, b5 = _stage_row(r[0], r[1], r[2], th)
        ys = _point(y, dt, k3)
        k4 = _stage(ys, (s0, s1, s2), u, X[XM1 * LANES + j], nphi, nc, ns, P)
        q4, b6 = _algebra_rate(th, (ys[0], ys[1], ys[2]))
        theta = _rk4_combine3(dt, q1, q2, q3, q4)
        c = dt / 6.0
        K[KDY * LANES + j] = _rk4_weight(c, k1[0], k2[0], k3[0], k4[0])
        K[(KDY + 1) * LANES + j] = _rk4_weight(c, k1[1], k2[1], k3[1], k4[1])
        K[(KDY + 2) * LANES + j] = _rk4_weight(c, k1[2], k2[2], k3[2], k4[2])
        K[(KDY + 3) * LANES + j] = _rk4_weight(c, k1[3], k2[3], k3[3], k4[3])
        K[(KDY + 4) * LANES + j] = _rk4_weight(c, k1[4], k2[4], k3[4], k4[4])
        K[(KDY + 5) * LANES + j] = _rk4_weight(c, k1[5], k2[5], k3[5], k4[5])
        K[(KDY + 6) * LANES + j] = _rk4_weight(c, k1[6], k2[6], k3[6], k4[6])
        K[KTH * LANES + j] = theta[0]
        K[(KTH + 1) * LANES + j] = theta[1]
        K[(KTH + 2) * LANES + j] = theta[2]
        bad = k1[7] or k2[7] or k3[7] or k4[7] or b1 or b2 or b3 or b4 or b5 or b6
        K[KBAD * LANES + j] = 1.0 if bad else 0.0


@numba.njit(cache=True)
def lane_scratch():
    """The scratch of `advance_block` for one thread: (X, K, near0s, mws, idx, e0s), the float
    ones views of one buffer (e0s: the rows' drive energies before the step, for the caller)."""
    n = LANES
    buf = np.empty((N_X + N_K + 6 + 2) * n)
    a, b, c = N_X * n, (N_X + N_K) * n, (N_X + N_K + 6) * n
    return buf[:a], buf[a:b], buf[b:c], buf[c : c + n], np.empty(n, dtype=np.int64), buf[c + n :]


@kernel(forceinline=True)
def _start(j, near0s):
    """Lane j's control-step start values (`start_values`), kept in near0s."""
    return (near0s[6 * j], near0s[6 * j + 1], near0s[6 * j + 2], near0s[6 * j + 3],
            near0s[6 * j + 4], near0s[6 * j + 5])  # fmt: skip


@kernel(forceinline=True)
def _near(k, j, near0s, t, y, P):
    """Row's start values for substep k (`advance_with`): its control step's own at k = 0,
    from them after (`start_values_from`)."""
    n0 = _start(j, near0s)
    if k == 0:
        return n0
    return start_values_from(n0, t, y[3], P)


@kernel
def advance_block(idx, t, y, R, u, dt, n_sub, P, tab, out, P0, X, K, near0s, mws, work, Rwork):
    """`kernels.advance_with` of the LANES rows idx (LANES,) of the batch arrays (t, y, R, u,
    dt, P, tab, out as `gyro_stabilizer.rows.step_rows`), all with n_sub substeps and the
    parameters P0 but for the wave phase (`uniform`): the stage inputs and start values per
    row, the RKMK4 stages in the lanes (`lane_block`), then per row its new attitude and
    `end_step`, or the scalar step where a lane's series was out of range; the outputs at the
    end. Scratch: X (N_X LANES,), K (N_K LANES,), near0s (6 LANES,), mws (LANES,), and the
    scalar step's work, Rwork. Each row's bits are those of `advance_with`."""
    for j in range(LANES):
        i = idx[j]
        mws[j] = wave_loads(t[i], P[i], tab[i])[0] if n_sub == 0 else 0.0
        n0 = start_values(t[i], y[i, 3], P[i])
        for m in range(6):
            near0s[6 * j + m] = n0[m]
    for k in range(n_sub):
        for j in range(LANES):
            i = idx[j]
            yi, ti, dti = y[i], t[i], dt[i]
            near = _near(k, j, near0s, ti, yi, P[i])
            args = (u[i], P[i], tab[i], near)
            h = 0.5 * dti
            i0, ih, i1 = (
                stage_inputs(ti, args),
                stage_inputs(ti + h, args),
                stage_inputs(ti + dti, args),
            )
            r = R[i]
            vals = (yi[0], yi[1], yi[2], yi[3], yi[4], yi[Z_STATE], r[2, 0], r[2, 1], r[2, 2],
                    near[0], near[1], near[2], i0[0], ih[0], i1[0], u[i], dti)  # fmt: skip
            for m in range(N_X):
                X[m * LANES + j] = vals[m]
        lane_block(X, K, P0)
        dy, R1 = work[0], Rwork[1]
        for j in range(LANES):
            i = idx[j]
            if K[KBAD * LANES + j] != 0.0:  # a series out of range: the scalar step
                near = _near(k, j, near0s, t[i], y[i], P[i])
                mws[j] = rk4_step_near(
                    t[i], y[i], R[i], u[i], dt[i], P[i], tab[i], work, Rwork, near
                )
            else:
                for m in range(N_STATE):
                    dy[m] = 0.0  # dt/6 (0 + 0 + 0 + 0) of the states the scene keeps still
                for m in range(7):
                    dy[LIVE[m]] = K[(KDY + m) * LANES + j]
                th = (K[KTH * LANES + j], K[(KTH + 1) * LANES + j], K[(KTH + 2) * LANES + j])
                times_exp_into(R1, R[i], th)
                inp = (X[XM1 * LANES + j], 0.0, (0.0, 0.0, 0.0))  # end_step reads the moment
                mws[j] = end_step(y[i], R[i], dt[i], P[i], work, Rwork, inp)
            t[i] += dt[i]
    for j in range(LANES):
        i = idx[j]
        step_outputs(t[i], y[i], R[i], u[i], P[i], out[i], mws[j], _start(j, near0s))
