"""Compiled control step of the inchworm on friction feet (the hot loop of Inchworm-v0).

One control step of `drive.DrivenInchworm` with the `friction` effect, in one compiled call:
the actuator lag (A1) gives kappa# at the control points at the substep ends, linear
interpolation carries it to the Gauss points, the feet's engagement follows its exact
first-order response, and every substep is one actuation increment of the beam on its two
friction feet (`mf_envs.physics.beam.contact.stick_slip.increment`) whose actuation work is
the trapezoid of (A2) (`mf_envs.physics.actuators.kernels`). This module wires them into the
inchworm's step; used by `DrivenInchworm.step` and the batched vector env
(`mf_envs.envs.inchworm.rows`, one worm per row). Status codes and report slots are those of
`stick_slip`.
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.physics.actuators.kernels import increment_work, lag_at, n_substeps
from mf_envs.physics.beam.contact.friction import grip_response
from mf_envs.physics.beam.contact.stick_slip import (
    OK,
    REP_INC,
    REP_NET,
    REP_POS,
    ROW_DA,
    increment,
)


@numba.njit(cache=True)
def drive_step(
    state, command, grip_cmd, dt, min_sub, act, feet, s_ctrl, gauss_s, f_ext, bc, sc, rep
):
    """One control step of the driven inchworm on friction feet (`drive.DrivenInchworm.step`).

    state: (d (n_dof,), lag kappa# (n,), realised kappa_ctrl (n,), engagement g (2,),
    slipping (2,) int), updated in place on success; command (n,) [1/m]; grip_cmd (2,) 0/1;
    act = (has_lag, tau [s], rate [1/(m s)], increment limit [1/m], EI [N m^2]);
    feet = (x dofs (2,), z dofs (2,), mu (4,), engage [s], release [s]); rep (N_REPORT,) zeroed
    here: slip, friction work, ground forces, iterations, onsets, positive and net actuation
    work [J], increments. Returns a status code (state untouched unless OK)."""
    d, lag_k, kappa_ctrl, g, slipping = state
    has_lag, tau, rate, limit, ei = act
    xd, zd, mu4, engage, release = feet
    le = bc[0]
    rep[:] = 0.0
    n = n_substeps(lag_k, kappa_ctrl, command, dt, min_sub, has_lag, tau, rate, limit)
    rep[REP_INC] = n
    vec = sc[0]
    d_prev, d_cur = vec[ROW_DA], np.empty_like(d)
    d_prev[:] = d
    nc = command.shape[0]
    ka, kb = np.empty(nc), np.empty(nc)
    ga, gb = g.copy(), np.empty(2)
    gauss_flat = gauss_s.ravel()
    kga = np.interp(gauss_flat, s_ctrl, lag_k if has_lag else kappa_ctrl).reshape(gauss_s.shape)
    ka[:] = lag_k if has_lag else kappa_ctrl
    slip_state = slipping.copy()
    for j in range(1, n + 1):
        t = dt * j / n
        if has_lag:
            lag_at(lag_k, command, t, tau, rate, kb)
        else:
            kb[:] = kappa_ctrl + (j / n) * (command - kappa_ctrl)
        kgb = np.interp(gauss_flat, s_ctrl, kb).reshape(gauss_s.shape)
        grip_response(g, grip_cmd, t, engage, release, gb)
        status = increment(
            d_prev, kga, kgb, f_ext, ga, gb, slip_state, xd, zd, mu4, bc, sc, rep, d_cur
        )
        if status != OK:
            return status
        w = increment_work(d_prev, d_cur, kga, kgb, ei, le)
        rep[REP_POS] += max(w, 0.0)
        rep[REP_NET] += w
        d_prev[:] = d_cur
        kga = kgb
        ka[:] = kb
        ga[:] = gb
    d[:] = d_cur
    if has_lag:
        lag_at(lag_k, command, dt, tau, rate, lag_k)
    kappa_ctrl[:] = ka
    g[:] = ga
    slipping[:] = slip_state
    return OK
