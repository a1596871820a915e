"""GOWEC-v1's observation (`spec.OBS`) from the state, compiled: one definition for the single
env's step and the native vector env's rows (bit-identical float32 values); `step_one`, the
single env's whole step in one call (fewer dispatches: the env runs near Pendulum-v1's rate),
and `step_rows`, the vector env's (the same `step_row` and `observe_one` for every row)."""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.envs.gowec_v1.spec import I_ELEVATION
from mf_envs.physics.gowec.hydro.batch import (
    V_ELEVATION,
    elevation,
    step_row_into,
    step_views,
    step_work,
)
from mf_envs.physics.gowec.hydro.sea import ramp


# a kernel (`mf_envs._jit`): as a plain njit function, called for every row, its array
# arguments cost 7 atomic increments and 7 decrements per call (4 % of the vector env's step)
@kernel
def observe_one(y, t, amp, om, eps, tramp, preview, lo, hi, obs, eta, trig=None):
    """(sin phi, cos phi, phi', hull body rates (cos rho theta', rho', sin rho theta'), theta,
    rho) of the state y, the incident wave's elevation at the buoy at t, eta (m, ramped: a wave
    probe; `step_row`'s V_ELEVATION) and, when `preview` (s ahead, (n,)) is not empty, at
    t + preview[j] (a perfect forecast of the incident sea, ramped as the sea is), as float32
    into obs (9 + n,), clipped to [lo, hi]; True if all finite. trig: (rho, cos rho, sin rho,
    phi, cos phi, sin phi) of y if the caller has them (`step_row_into`), None: libm."""
    if trig is None:
        sp, cp, cr, sr = math.sin(y[2]), math.cos(y[2]), math.cos(y[1]), math.sin(y[1])
    else:
        sp, cp, cr, sr = trig[5], trig[4], trig[1], trig[2]
    v = (sp, cp, y[5], cr * y[3], y[4], sr * y[3], y[0], y[1])
    finite = True
    for j in range(8):
        x = min(max(np.float32(v[j]), lo[j]), hi[j])
        obs[j] = x
        finite = finite and math.isfinite(x)
    for j in range(preview.shape[0] + 1):
        k = I_ELEVATION + j  # the probe, then the preview slots after the layout
        if j == 0:
            x = np.float32(eta)
        else:
            tj = t + preview[j - 1]
            x = np.float32(elevation(tj, amp, om, eps) * ramp(tj, tramp))
        x = min(max(x, lo[k]), hi[k])
        obs[k] = x
        finite = finite and math.isfinite(x)
    return finite


@numba.njit(cache=True)
def observe_at(y, t, amp, om, eps, tramp, preview, lo, hi, obs):
    """`observe_one` with the probe's elevation computed at t (resets and the single env's
    observation outside a step, where no step has formed it)."""
    eta = elevation(t, amp, om, eps) * ramp(t, tramp)
    return observe_one(y, t, amp, om, eps, tramp, preview, lo, hi, obs, eta)


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, t0, t1, Y, tau, clock, shared, tail, sea, out, view):
    """The native vector env's step of the active rows lo <= i < hi: `step_row`, and where it
    succeeded the new state into Y (N, n_state) and `observe_one` into obs (N, 8); t0, t1, tau
    (N,); clock = (dt, n, dtc, loss) as `step_row`'s; shared = `floating.pack`'s first nine
    entries and tail its last five (sp and the translation; the same for every row); sea = (om,
    cp, cr, dk, amp, eps), each row's sea ((N, M), dk (N, M, nodes)); out = (vals (N, N_VALS),
    ok (N,) bool, obs); view = (lo, hi, preview) the observation's bounds and look-ahead times.
    Releases the GIL (blocks of rows on threads: `envs._rows.RowBlocks`)."""
    _rows(lo, hi, active, t0, t1, Y, tau, clock, shared, tail, sea, out, view,
          step_work(Y.shape[1], sea[0].shape[1]))  # fmt: skip


@kernel
def _rows(lo, hi, active, t0, t1, Y, tau, clock, shared, tail, sea, out, view, w):
    """The row loop of `step_rows` with one `step_work` buffer w (a `mf_envs._jit.kernel`: the
    rows' views of the shared arrays cost no reference counts)."""
    p_in, p_gy, psid, C, bv, Ar, Br, Cr, pto = shared
    om, cp, cr, dk, amp, eps = sea
    vals, ok, obs = out
    o_lo, o_hi, preview = view
    m = Y.shape[1]
    work, ph, y1 = step_views(w, m, om.shape[1])  # carved once (`step_row` carves per call)
    for i in range(lo, hi):
        if not active[i]:
            continue
        args = (p_in, p_gy, psid, C, bv, Ar, Br, Cr, pto, om[i], cp[i], cr[i], dk[i], *tail)
        good, trig = step_row_into(t0[i], t1[i], Y[i], tau[i], clock, args, amp[i], eps[i],
                                   vals[i], work, ph, y1)  # fmt: skip
        ok[i] = good
        if good:
            yi = Y[i]
            for j in range(m):
                yi[j] = y1[j]
            observe_one(yi, t1[i], amp[i], om[i], eps[i], tail[0][1], preview, o_lo, o_hi, obs[i],
                        vals[i, V_ELEVATION], trig)  # fmt: skip


@numba.njit(cache=True)
def step_one(t0, t1, y, tau, clock, args, amp, eps, vals, w, view, obs, limits):
    """The single env's step in one compiled call: `step_row` (clock as its), then (if the
    state is finite) `observe_one` into obs (view = (lo, hi, preview): its bounds and look-ahead
    times) and the termination tests; limits = (max gimbal rate rad/s, the gimbal's stroke rad),
    w = `step_work` (the env's holds n_components; a new one here if w is too small for the
    sea). Returns (ok, y1, finite obs, overspeed, past the stroke's end)."""
    lo, hi, preview = view
    if w.shape[0] < 6 * y.shape[0] + 4 * args[9].shape[0]:
        w = step_work(y.shape[0], args[9].shape[0])
    work, ph, end = step_views(w, y.shape[0], args[9].shape[0])
    ok, trig = step_row_into(t0, t1, y, tau, clock, args, amp, eps, vals, work, ph, end)
    y1 = end.copy()  # the env keeps it as its state
    if not ok:
        return False, y1, False, False, False
    finite = observe_one(y1, t1, amp, args[9], eps, args[13][1], preview, lo, hi, obs,
                         vals[V_ELEVATION], trig)  # fmt: skip
    over = abs(y1[5]) > limits[0]
    out = abs(y1[2]) > limits[1]
    return True, y1, finite, over, out
