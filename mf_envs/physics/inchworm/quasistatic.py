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

from mf_envs.physics.actuators import sma_kernels as sk
from mf_envs.physics.actuators.kernels import increment_work, lag_at, n_substeps, wire_work
from mf_envs.physics.beam.contact import grip_feet as gf
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


# ---------------------------------------------------------------- SMA wires on gripping feet
# actuation modes of `grip_step`
ACT_DIRECT, ACT_LAG, ACT_SMA = 0, 1, 2
# report slots of `grip_step`: the feet's (grip_feet), then the actuation's
REP_ELEC, REP_WIRE, REP_A2POS, REP_A2NET, REP_SUBSTEPS = (
    gf.N_REPORT, gf.N_REPORT + 1, gf.N_REPORT + 2, gf.N_REPORT + 3, gf.N_REPORT + 4,
)  # fmt: skip
N_GRIP_REPORT = gf.N_REPORT + 5
# rows of the SMA state (5, n): temperature [degC], martensite fraction, branch direction,
# reversal temperature [degC], reversal fraction
SMA_T, SMA_XI, SMA_DIR, SMA_TR, SMA_XIR = range(5)


@numba.njit(cache=True)
def sma_advance(sma, duty, dt, thermal, tt, power_full, kappa_full, out_kappa):
    """Advance every control point's wire group (sma (5, n), in place) by dt [s] under its duty
    (n,) in [0, 1] of the rated Joule power power_full [W/m per wire]; kappa# [1/m] after the
    step into out_kappa: -kappa_full (1 - xi) (the wires' recovery strain over their lever)."""
    hp, cap, t_amb = thermal
    a_s, a_f, m_s, m_f, lat = tt
    for k in range(duty.shape[0]):
        t1, xi1, dr, t_r, xi_r, _q = sk.sma_step(
            sma[SMA_T, k], sma[SMA_XI, k], sma[SMA_DIR, k], sma[SMA_TR, k], sma[SMA_XIR, k],
            duty[k] * power_full, hp, cap, t_amb, dt, (a_s, a_f, m_s, m_f), lat,
        )  # fmt: skip
        sma[SMA_T, k], sma[SMA_XI, k], sma[SMA_DIR, k] = t1, xi1, dr
        sma[SMA_TR, k], sma[SMA_XIR, k] = t_r, xi_r
        out_kappa[k] = -kappa_full * (1.0 - xi1)


@numba.njit(cache=True)
def grip_step(
    state, command, grip_cmd, dt, min_sub, act, feet, s_ctrl, gauss_s, f_ext, bc, sc, rep
):
    """One control step of the inchworm on gripping feet (`grip_feet`), kappa# from the
    actuation mode act[0]: ACT_DIRECT (command = kappa# [1/m], linear over the step), ACT_LAG
    (the rate-limited lag A1 towards command), ACT_SMA (command = duty cycle (n,) in [0, 1] of
    each control point's wire group; kappa# = -kappa_full (1 - xi)).

    state: (d (n_dof,), lag kappa# (n,), realised kappa_ctrl (n,), feet (4,) = (engagement
    tail, head, last velocity tail, head [m/s]), SMA state (5, n)), updated in place on
    success; grip_cmd (2,) engagement commands in [0, 1];
    act = (mode, tau [s], rate [1/(m s)], increment limit [1/m], EI [N m^2], (hp, cap, T_amb),
    (As, Af, Ms, Mf, L/c), rated Joule power [W/m per wire], kappa_full [1/m], electrical
    power of a group at duty 1 [W]); feet = (x dofs (2,), z dofs (2,), law (7,), engage [s],
    release [s]); rep (N_GRIP_REPORT,) zeroed here. Substeps: no control point's kappa# moves
    more than the increment limit in one (the SMA and lag paths are monotone within a step).
    Returns a status code (state untouched unless OK)."""
    d, lag_k, kappa_ctrl, feet_state, sma = state
    g, v_feet = feet_state[:2], feet_state[2:].copy()
    mode, tau, rate, limit, ei, thermal, tt, p_full, k_full, group_power = act
    xd, zd, law, engage, release = feet
    le = bc[0]
    rep[:] = 0.0
    nc = command.shape[0]
    kend = np.empty(nc)
    sma_w = sma.copy()
    if mode == ACT_SMA:
        sma_advance(sma_w, command, dt, thermal, tt, p_full, k_full, kend)
        big = 0.0
        for k in range(nc):
            big = max(big, abs(kend[k] - kappa_ctrl[k]))
        n = max(1, min_sub, int(np.ceil(big / limit - 1e-12)))
        sma_w[:, :] = sma
    else:
        n = n_substeps(lag_k, kappa_ctrl, command, dt, min_sub, mode == ACT_LAG, tau, rate, limit)
    rep[REP_SUBSTEPS] = n
    vec = sc[0]
    d_prev, d_cur = vec[gf.ROW_CALLER], np.empty_like(d)
    d_prev[:] = d
    ka, kb = np.empty(nc), np.empty(nc)
    ga, gb = g.copy(), np.empty(2)
    gauss_flat = gauss_s.ravel()
    ka[:] = lag_k if mode == ACT_LAG else kappa_ctrl
    kga = np.interp(gauss_flat, s_ctrl, ka).reshape(gauss_s.shape)
    h = dt / n
    for j in range(1, n + 1):
        t = dt * j / n
        if mode == ACT_LAG:
            lag_at(lag_k, command, t, tau, rate, kb)
        elif mode == ACT_SMA:
            sma_advance(sma_w, command, h, thermal, tt, p_full, k_full, kb)
        else:
            kb[:] = kappa_ctrl + (j / n) * (command - kappa_ctrl)
        kgb = np.interp(gauss_flat, s_ctrl, kb).reshape(gauss_s.shape)
        grip_response(g, grip_cmd, t, engage, release, gb)
        status = gf.increment(
            d_prev, kga, kgb, f_ext, ga, gb, h, v_feet, (xd, zd), law, bc, sc, rep, d_cur
        )
        if status != gf.OK:
            return status
        w = increment_work(d_prev, d_cur, kga, kgb, ei, le)
        rep[REP_A2POS] += max(w, 0.0)
        rep[REP_A2NET] += w
        rep[REP_WIRE] += max(wire_work(d_prev, d_cur, kga, kgb, ei, le), 0.0)
        d_prev[:] = d_cur
        kga = kgb
        ka[:] = kb
        ga[:] = gb
    d[:] = d_cur
    if mode == ACT_LAG:
        lag_at(lag_k, command, dt, tau, rate, lag_k)
    if mode == ACT_SMA:
        sma[:, :] = sma_w
        for k in range(nc):
            rep[REP_ELEC] += command[k] * group_power * dt
    kappa_ctrl[:] = ka
    g[:] = ga
    feet_state[2:] = v_feet
    return OK
