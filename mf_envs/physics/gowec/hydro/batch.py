"""Compiled per-step quantities of the floating GOWEC and their batch over rows (GOWEC-v1).

`step_row` is one control step of one buoy: `floating.rk4_steps` (Rios 2017 ch. 3, the Cummins
equation with the gyro's B-matrix coupling, `floating` module doc) plus what the env reports at
the end of the step: PTO powers from the integrated energies, the excitation moment, the gyro's
moment on the hull (`gyro_moment_pitch`, the compiled twin of `floating.gyro_moment`) and the wave
elevation (Eq. 89 at the origin). The single env (`envs.gowec_v1.env`) calls it for its one row and
the native vector env (`envs.gowec_v1.vector`) calls `batch_step_rows` over N rows, so the two
agree bit for bit. Arrays float64, SI units.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs.physics.gowec.hydro.floating import (
    N_MECH,
    deriv_into,
    excitation,
    mass_rhs_into,
    rk4_steps_into,
)

N_VALS = 12  # step_row's value slots (see its docstring)


@numba.njit(cache=True)
def elevation(t, amp, om, eps):
    """eta (m) at the origin at time t (s): sum a_i cos(-w_i t + eps_i) (Eq. 89)."""
    eta = 0.0
    for i in range(amp.shape[0]):
        eta += amp[i] * math.cos(-om[i] * t + eps[i])
    return eta


@numba.njit(cache=True)
def step_work(n_state):
    """One flat buffer of `step_row`'s temporaries for a state of n_state (one array: cheap to
    pass from Python; `_views` carves it)."""
    return np.zeros(6 * n_state + 54)


@numba.njit(cache=True, inline="always")
def _views(w, n):
    """(RK4 work (5, n), `floating.scratch()`-like (M, v, gy, Q, u', cs), dy (n,), and M (3, 3),
    v, gy (3,), cs (2, 2), zeros (6,) of the hull-only mass) as views of the flat buffer w."""
    o = 5 * n
    sc = (
        w[o : o + 9].reshape((3, 3)),
        w[o + 9 : o + 12],
        w[o + 12 : o + 15],
        w[o + 15 : o + 18],
        w[o + 18 : o + 21],
        w[o + 21 : o + 25].reshape((2, 2)),
    )
    o += 25
    hull = (
        w[o + n : o + n + 9].reshape((3, 3)),
        w[o + n + 9 : o + n + 12],
        w[o + n + 12 : o + n + 15],
        w[o + n + 15 : o + n + 19].reshape((2, 2)),
    )
    zero = w[o + n + 19 : o + n + 25]
    zero[:] = 0.0
    return w[: 5 * n].reshape((5, n)), sc, w[o : o + n], hull, zero


@numba.njit(cache=True)
def gyro_moment_pitch(t, y, tau, args):
    """Moment (N m) of the gyro units on the hull about the pitch axis e1 at (t, y) with the PTO
    command tau: minus the theta row of the gyro's B^T (J B u' + J B' u + w x h) (as
    `floating.gyro_moment`, the matrix-vector product summed in index order)."""
    return gyro_moment_pitch_into(t, y, tau, args, step_work(y.shape[0]))


@numba.njit(cache=True, inline="always")
def gyro_moment_pitch_into(t, y, tau, args, w):
    """`gyro_moment_pitch` with the temporaries w = `step_work(n_state)`."""
    p_in, p_gy, psid = args[0], args[1], args[2]
    _, sc, acc, (Mh, vh, gyh, csh), zero = _views(w, y.shape[0])
    deriv_into(t, y, tau, args, acc, sc)
    q, u = y[0:3], y[3:6]
    Mf, vf, gy, csf = sc[0], sc[1], sc[2], sc[5]
    mass_rhs_into(q, u, p_in, p_gy, psid, Mf, vf, gy, csf)
    mass_rhs_into(q, u, p_in, zero, 0.0, Mh, vh, gyh, csh)
    s = 0.0
    for j in range(3):
        s += (Mf[0, j] - Mh[0, j]) * acc[3 + j]
    return -(s + gy[0])


@numba.njit(cache=True)
def step_row(t0, t1, y, tau, dt, n, args, amp, eps, dtc, loss, vals, w):
    """One control step from (t0, y) to t1 = t0 + dtc (s) with the PTO command tau (N m) held
    over n RK4 substeps of dt. Returns (ok, y1): ok False if the state is not finite (then
    `vals` is untouched); else vals (N_VALS,) = (net electrical power W, mechanical power W,
    pitch rad, roll rad, pitch rate rad/s, roll rate rad/s, excitation moment N m, gyro moment
    N m, gimbal angle rad, gimbal rate rad/s, elevation m, net electrical energy J), the powers
    from the integrated PTO energies over dtc, `loss` (W) the rotor loss subtracted."""
    k = N_MECH + 2 * args[5].shape[0]
    try:  # numba's solve raises on a non-finite mass matrix
        y1 = y.copy()
        work, sc, _, _, _ = _views(w, y.shape[0])
        rk4_steps_into(t0, y1, tau, dt, n, args, work, sc)
    except Exception:  # noqa: BLE001  (numba: any exception of the solve)
        y1 = np.full_like(y, np.nan)
    for i in range(y1.shape[0]):
        if not math.isfinite(y1[i]):
            return False, y1
    p_el = (y1[k + 4] - y[k + 4]) / dtc - loss
    vals[0], vals[1] = p_el, (y1[k + 3] - y[k + 3]) / dtc
    vals[2], vals[3], vals[4], vals[5] = y1[0], y1[1], y1[3], y1[4]
    vals[6] = excitation(t1, args[9], args[10], args[11])[0]
    vals[7] = gyro_moment_pitch_into(t1, y1, tau, args, w)
    vals[8], vals[9] = y1[2], y1[5]
    vals[10] = elevation(t1, amp, args[9], eps)
    vals[11] = p_el * dtc
    return True, y1


@numba.njit(cache=True, nogil=True)
def batch_step_rows(lo, hi, active, t0, t1, Y, tau, dt, n, shared, om, cp, cr, amp, eps, dtc,
                    loss, vals, ok):  # fmt: skip
    """`step_row` for every active row i in lo..hi - 1: Y (N, n_state) updated in place where
    ok; t0, t1, tau (N,); om, cp, cr, amp, eps (N, M) the sea of each row; shared =
    `floating.pack`'s first nine entries (the same for every row); vals (N, N_VALS); ok (N,)
    bool. Releases the GIL (blocks of rows on threads: `envs._vector.run_row_blocks`)."""
    p_in, p_gy, psid, C, bv, Ar, Br, Cr, pto = shared
    w = step_work(Y.shape[1])  # one set of temporaries for the block's rows
    for i in range(lo, hi):
        if not active[i]:
            continue
        args = (p_in, p_gy, psid, C, bv, Ar, Br, Cr, pto, om[i], cp[i], cr[i])
        good, y1 = step_row(t0[i], t1[i], Y[i], tau[i], dt, n, args, amp[i], eps[i], dtc,
                            loss, vals[i], w)  # fmt: skip
        ok[i] = good
        if good:
            Y[i, :] = y1
