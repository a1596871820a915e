"""Compiled forms of the curvature actuator (`actuators.curvature`): the exact solution of the
rate-limited lag (A1), the trapezoidal actuation work of an increment (A2), and the number of
increments a control step needs under an increment limit. Plain numba functions on arrays (no
Python objects), called by `curvature` and by the compiled control steps of the robots on the
active beam (`mf_envs.physics.inchworm.quasistatic`).
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.physics.beam import element as el


@numba.njit(cache=True)
def lag_at(kappa, u, t, tau, rate, out):
    """Exact solution of the rate-limited lag (A1) at t [s] from kappa under the command u
    (`curvature.rate_limited_lag`), into out (n,)."""
    for k in range(kappa.shape[0]):
        gap = u[k] - kappa[k]
        t_lin = max(abs(gap) - rate * tau, 0.0) / rate
        moved = np.sign(gap) * rate * min(t, t_lin)
        out[k] = u[k] - (gap - moved) * np.exp(-max(t - t_lin, 0.0) / tau)


@numba.njit(cache=True)
def increment_work(d0, d1, k0, k1, ei, le):
    """Actuation work [J] of the increment kappa# k0 -> k1, configuration d0 -> d1 (trapezoid of
    (A2), the module doc of `curvature`)."""
    w = 0.0
    for e in range(le.shape[0]):
        for q in range(el.N_GAUSS):
            kap0 = el.kappa_at(d0, 6 * e, le[e], el.GAUSS_XI[q])
            kap1 = el.kappa_at(d1, 6 * e, le[e], el.GAUSS_XI[q])
            m_mid = 0.5 * (ei * (kap0 - k0[e, q]) + ei * (kap1 - k1[e, q]))
            w += le[e] * el.GAUSS_W[q] * m_mid * (k1[e, q] - k0[e, q])
    return -w


@numba.njit(cache=True)
def n_substeps(lag_k, kappa_ctrl, command, dt, min_sub, has_lag, tau, rate, limit):
    """Substeps of a control step: no control point's kappa# may move more than `limit`
    [1/m] in one (the lag is monotone within a step, so its initial rate is its largest)."""
    big = 0.0
    for k in range(command.shape[0]):
        if has_lag:
            big = max(big, abs(min(max((command[k] - lag_k[k]) / tau, -rate), rate)) * dt)
        else:
            big = max(big, abs(command[k] - kappa_ctrl[k]))
    return max(1, min_sub, int(np.ceil(big / limit - 1e-12)))


@numba.njit(cache=True)
def wire_work(d0, d1, k0, k1, ei, le):
    """Mechanical work [J] the actuator delivers over the increment when it bends the body by
    applying the moment EI kappa# (what wires at a lever arm do: force x shortening): the
    trapezoid of int EI kappa# (d kappa / dt) dS, configuration d0 -> d1, kappa# k0 -> k1
    (n_el, 4). Positive when curling (kappa# and d kappa both negative): the body's elastic
    strain energy the wires must supply (returned to the wires, and lost, on release)."""
    w = 0.0
    for e in range(le.shape[0]):
        for q in range(el.N_GAUSS):
            kap0 = el.kappa_at(d0, 6 * e, le[e], el.GAUSS_XI[q])
            kap1 = el.kappa_at(d1, 6 * e, le[e], el.GAUSS_XI[q])
            w += le[e] * el.GAUSS_W[q] * ei * 0.5 * (k0[e, q] + k1[e, q]) * (kap1 - kap0)
    return w
