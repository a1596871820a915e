"""GOWEC-v1's observation (`spec.OBS`) from the state, compiled: one definition for the single
env's step and the native vector env's rows (bit-identical float32 values); `step_one`, the
single env's whole step in one call (fewer dispatches: the env runs near Pendulum-v1's rate)."""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs.physics.gowec.hydro.batch import end_state, step_row


@numba.njit(cache=True)
def observe_one(y, lo, hi, obs):
    """(sin phi, cos phi, phi', hull body rates (cos rho theta', rho', sin rho theta'), theta,
    rho) of the state y as float32 into obs (8,), clipped to [lo, hi]; True if all finite."""
    v = (math.sin(y[2]), math.cos(y[2]), y[5], math.cos(y[1]) * y[3], y[4],
         math.sin(y[1]) * y[3], y[0], y[1])  # fmt: skip
    finite = True
    for j in range(8):
        x = min(max(np.float32(v[j]), lo[j]), hi[j])
        obs[j] = x
        finite = finite and math.isfinite(x)
    return finite


@numba.njit(cache=True)
def observe_rows(active, Y, lo, hi, obs):
    """`observe_one` for the active rows of Y (N, n_state) into obs (N, 8)."""
    for i in range(active.shape[0]):
        if active[i]:
            observe_one(Y[i], lo, hi, obs[i])


@numba.njit(cache=True)
def step_one(t0, t1, y, tau, dt, n, args, amp, eps, dtc, loss, vals, w, lo, hi, obs, limits):
    """The single env's step in one compiled call: `step_row`, then (if the state is finite)
    `observe_one` into obs and the termination tests; limits = (max gimbal rate rad/s, max buoy
    angle rad), w = `step_work`. Returns (ok, y1, finite obs, overspeed, out of range)."""
    ok = step_row(t0, t1, y, tau, dt, n, args, amp, eps, dtc, loss, vals, w)
    y1 = end_state(w, y.shape[0]).copy()  # the env keeps it as its state
    if not ok:
        return False, y1, False, False, False
    finite = observe_one(y1, lo, hi, obs)
    over = abs(y1[5]) > limits[0]
    out = max(abs(y1[0]), abs(y1[1])) > limits[1]
    return True, y1, finite, over, out
