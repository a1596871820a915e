"""Serpentine-v0's compiled step, shared by the single env and the native vector env so both give
the same bits.

- `body_state`: centre of mass, its velocity and the mean frame angle (4-point Gauss, uniform
  m_A, as `SnakeHistory.com`);
- `observe_row`: the observation (`spec.observation_layout`) in one compiled function;
- `step_row`: one control step of one snake: the action scaled to kappa# at the control
  points, linear in S between them (`build.interpolation`); in time the muscles follow it as
  the rate-limited lag of `physics.actuators` (`actuator_dynamics`) or linearly from the
  previous command over the control step (a first-order hold), integrated by
  `physics.serpentine.kernels.advance_linear` in `n_substeps` physics steps; the muscles'
  positive work (actuation energy) and the observation;
- `step_rows`: `step_row` for every active row of a batch (the native vector env), in blocks on
  threads (`envs._rows.RowBlocks`), which does not change any row's arithmetic.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs.envs._beam_robot import REP_ENERGY, REP_ITER, REP_NET, REP_OK, REP_X0, REP_Y0
from mf_envs.physics.actuators.kernels import lag_at
from mf_envs.physics.beam import element as el
from mf_envs.physics.serpentine.kernels import _scratch as _kernel_scratch
from mf_envs.physics.serpentine.kernels import advance_linear, quad_tables

# report of a step: ok (1/0), actuation energy [J], Newton iterations, com before (x, y) [m],
# the muscles' signed (net) work [J]
N_REPORT = 6
TOLERANCE, MAX_ITER, MAX_HALVINGS, THETA = 1e-6, 12, 6, 1.0  # the Newton settings


def pack(scene, model, n_substeps: int, physics_dt: float, target: float) -> tuple:
    """The kernels' configuration of a `build.Scene` on its `BeamModel` (module docstring)."""
    from mf_envs.envs.serpentine.build import control_points, interpolation

    p, ne = scene.params, model.n_elements
    le = model.le
    nz = np.array([el.shape_functions(x, le[0])[0] for x in el.GAUSS_XI])
    npsi = np.array([el.shape_functions(x, le[0])[2] for x in el.GAUSS_XI])
    ce, cxi = control_points(p.length, scene.n_ctrl, ne)
    ground = (p.mass_per_length * scene.gravity, p.mass_per_length, scene.ground.packed())
    return (
        le, model.mass, quad_tables(model), ground, THETA, TOLERANCE, MAX_ITER,
        MAX_HALVINGS, interpolation(model.gauss_S, p.length, scene.n_ctrl), nz, npsi, ce, cxi,
        scene.max_curvature, int(n_substeps), p.length, p.EI, float(target), float(physics_dt),
        float(scene.material_damping), float(scene.actuator_time_constant),
        float(scene.actuator_rate_limit),
    )  # fmt: skip


@numba.njit(cache=True, nogil=True)
def _scratch(n_dof, n_el, n_ctrl):
    ks = _kernel_scratch(n_dof, n_el)
    return (ks, np.empty((n_el, 4)), np.empty((n_el, 4)), np.empty((n_el, 4)),
            np.empty((n_el, 4)), np.zeros(2), np.empty(n_ctrl), np.empty(n_ctrl),
            np.empty(n_ctrl))  # fmt: skip


def scratch(model, n_ctrl: int) -> tuple:
    """A snake's scratch (no state: every entry is written before it is read): the Newton
    solver's (`kernels.make_scratch`), kappa# tables at the Gauss points (n_el, 4), the work sums
    and kappa# at the control points (n_ctrl,)."""
    return _scratch(model.n_dof, model.n_elements, n_ctrl)


@numba.njit(cache=True, nogil=True)
def body_state(d, v, le, nz, npsi, out):
    """out = (x_com, y_com [m], vx_com, vy_com [m/s], mean frame angle [rad])."""
    for k in range(5):
        out[k] = 0.0
    length = 0.0
    for e in range(le.shape[0]):
        b = 6 * e
        for g in range(4):
            w = el.GAUSS_W[g] * le[e]
            for i in range(4):
                out[0] += w * nz[g, i] * d[b + el.LOC[i]]
                out[1] += w * nz[g, i] * d[b + el.LOC[4 + i]]
                out[2] += w * nz[g, i] * v[b + el.LOC[i]]
                out[3] += w * nz[g, i] * v[b + el.LOC[4 + i]]
            for i in range(3):
                out[4] += w * npsi[g, i] * d[b + el.LOC[8 + i]]
        length += le[e]
    for k in range(5):
        out[k] /= length


@numba.njit(cache=True, nogil=True)
def observe_row(d, v, cmd, cfg, body, out):
    """The observation into out (float32, 2 n + 4) and the body state into body (5,)."""
    le, nz, npsi, ce, cxi = cfg[0], cfg[9], cfg[10], cfg[11], cfg[12]
    max_curvature, length, target = cfg[13], cfg[15], cfg[17]
    n = cmd.shape[0]
    for j in range(n):
        out[j] = el.kappa_at(d, 6 * ce[j], le[ce[j]], cxi[j]) * length
        out[n + 4 + j] = cmd[j] / max_curvature
    rel = d[d.shape[0] - 1] - target
    out[n] = math.sin(rel)
    out[n + 1] = math.cos(rel)
    body_state(d, v, le, nz, npsi, body)
    c, s = math.cos(body[4]), math.sin(body[4])
    out[n + 2] = (c * body[2] + s * body[3]) / length
    out[n + 3] = (-s * body[2] + c * body[3]) / length


@numba.njit(cache=True, nogil=True)
def step_row(d, v, cmd, action, cfg, sc, body, obs, rep):
    """One control step of one snake in place (module docstring): d, v (n_dof,), cmd (n,)
    [1/m] the muscles' kappa# at the control points (the previous command, or with actuator
    dynamics the lagged state), action (n,) in [-1, 1]; sc: `scratch`; obs (2 n + 4)
    float32, body (5,), rep (N_REPORT,) the report. A failed substep stops the step
    (rep[REP_OK] = 0)."""
    le, mass, quad, ground, th, tol, max_iter, max_halvings, interp = cfg[:9]
    max_curvature, n_sub, ei, h = cfg[13], cfg[14], cfg[16], cfg[18]
    damping = cfg[19]
    tau_a, rate_a = cfg[20], cfg[21]
    ks, k_old, k_new, ka, kb, acc, c0, c1, u = sc
    ne, n = le.shape[0], cmd.shape[0]
    for j in range(n):
        u[j] = max_curvature * action[j]
        c1[j] = cmd[j]
    body_state(d, v, le, cfg[9], cfg[10], body)
    rep[REP_X0], rep[REP_Y0] = body[0], body[1]
    total, ok = 0, 1.0
    acc[0], acc[1] = 0.0, 0.0
    for s in range(n_sub):
        # kappa# at the control points at the substep's ends: linear from the old command to
        # the new one (a first-order hold) or, with actuator dynamics, the exact response of
        # the rate-limited lag (`physics.actuators.curvature`, A1); linear in S between them
        for j in range(n):
            c0[j] = c1[j]
            if tau_a > 0.0:
                c1[j] = cmd[j]
            elif s + 1 == n_sub:
                c1[j] = u[j]  # the command itself at the step's end (no rounding)
            else:
                c1[j] = cmd[j] + (s + 1) / n_sub * (u[j] - cmd[j])
        if tau_a > 0.0:
            lag_at(cmd, u, (s + 1) * h, tau_a, rate_a, c1)
        for e in range(ne):
            for g in range(4):
                a, b = 0.0, 0.0
                for j in range(n):
                    a += interp[4 * e + g, j] * c0[j]
                    b += interp[4 * e + g, j] * c1[j]
                ka[e, g], kb[e, g] = a, b
        its = advance_linear(d, v, ka, kb, h, mass, le, quad, ground, th, tol, max_iter,
                             max_halvings, ks, ei, acc, damping)  # fmt: skip
        total += abs(its)
        if its < 0:
            ok = 0.0
            break
    for j in range(n):
        cmd[j] = c1[j]
    rep[REP_OK], rep[REP_ENERGY], rep[REP_ITER], rep[REP_NET] = ok, acc[0], total, acc[1]
    observe_row(d, v, cmd, cfg, body, obs)


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, actions, state, cmd, cfg, body, obs, rep):
    """`step_row` for the active rows lo <= i < hi: state (N, 2, n_dof) (d, v), cmd (N, n),
    actions (N, n), body (N, 5), obs (N, 2 n + 4) float32, rep (N, N_REPORT). One scratch
    serves the block (it holds no state)."""
    sc = _scratch(state.shape[2], cfg[0].shape[0], cmd.shape[1])
    for i in range(lo, hi):
        if active[i]:
            step_row(state[i, 0], state[i, 1], cmd[i], actions[i], cfg, sc, body[i], obs[i],
                     rep[i])  # fmt: skip
