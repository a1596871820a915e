"""Eel-v0's compiled step, shared by the single env and the native vector env so both give the
same bits.

- `observe_row`: the observation (`spec.observation_layout`) in one compiled function; the
  centre of mass, its velocity and the mean frame angle come from the serpentine's
  `body_state` (4-point Gauss, uniform m_A);
- `step_row`: one control step of one eel: the action scaled to a target curvature at the
  control points (or, with action_mode "wave", the anguilliform wave of the action's amplitude,
  wavelength and frequency, `target_row`); the command moves towards it at most
  max_curvature_rate x control_dt per step (muscles have a finite rate of contraction) and
  linearly in time over the step (a first-order hold), linear in S between the control points
  (`serpentine.build.interpolation`); integrated by `physics.swimmer.kernels.advance_linear`
  in `n_substeps` physics steps; the muscles' positive work (actuation energy) and the
  observation;
- `step_rows`: `step_row` for every active row of a batch (the native vector env), in blocks on
  threads (`envs._rows.RowBlocks`), which does not change any row's arithmetic.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs.envs._beam_robot import REP_ENERGY, REP_ITER, REP_NET, REP_OK, REP_X0, REP_Y0
from mf_envs.envs.serpentine.rows import body_state
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.fused import quadrature_tables
from mf_envs.physics.swimmer.fluid import shape_tables
from mf_envs.physics.swimmer.kernels import advance_linear, make_scratch, newton_scratch

# report of a step: ok (1/0), actuation energy [J], Newton iterations, com before (x, y) [m],
# the muscles' signed (net) work [J]
N_REPORT = 6
# the Newton settings: the step test |dd| / u_scale < 1e-6 (or the next correction predicted
# below 1e-9 in the quadratic phase) leaves ~1e-9
TOLERANCE, MAX_ITER, MAX_HALVINGS = 1e-6, 12, 6
THETA = (0.5, 0.5)  # (water force, stresses) theta points (`physics.swimmer.kernels`)


def pack(scene, model, n_substeps: int, physics_dt: float, control_dt: float,
         target: float) -> tuple:  # fmt: skip
    """The kernels' configuration of a `build.Scene` on its `BeamModel` (module docstring)."""
    from mf_envs.envs.eel.build import HEAD_RATIO, WAVE_FREQUENCY, WAVE_WAVELENGTH
    from mf_envs.envs.serpentine.build import control_points, interpolation

    p, ne = scene.params, model.n_elements
    le = model.le
    nz = np.array([el.shape_functions(x, le[0])[0] for x in el.GAUSS_XI])
    npsi = np.array([el.shape_functions(x, le[0])[2] for x in el.GAUSS_XI])
    ce, cxi = control_points(p.length, scene.n_ctrl, ne)
    s_ctrl = np.linspace(0.0, 1.0, scene.n_ctrl)  # S / L of the control points
    water = (*shape_tables(le), scene.water.packed())
    theta = (THETA[0], scene.stress_theta)
    qxi, qw, stiff = model.quad
    quad = (qw, stiff, model.u_scale, quadrature_tables(le, qxi))
    return (
        le, model.mass, quad, water, theta, TOLERANCE, MAX_ITER,
        MAX_HALVINGS, interpolation(model.gauss_S, p.length, scene.n_ctrl), nz, npsi, ce, cxi,
        scene.max_curvature, int(n_substeps), p.length, p.EI, float(target), float(physics_dt),
        scene.max_curvature_rate * float(control_dt), 1 if scene.action_mode == "wave" else 0,
        HEAD_RATIO + (1.0 - HEAD_RATIO) * (1.0 - s_ctrl), 1.0 - s_ctrl,
        np.array([*WAVE_WAVELENGTH, *WAVE_FREQUENCY]), float(control_dt),
    )  # fmt: skip


def scratch(model) -> tuple:
    """A row's scratch: the Newton solver's, four (n_el, 4) kappa# tables and the work sums."""
    ne = model.n_elements
    return (*make_scratch(model.n_dof, ne), *(np.empty((ne, 4)) for _ in range(4)), np.zeros(2))


@numba.njit(cache=True, nogil=True)
def observe_row(d, v, cmd, cfg, body, out):
    """The observation into out (float32, 2 n + 6) and the body state into body (5,)."""
    le, nz, npsi, ce, cxi = cfg[0], cfg[9], cfg[10], cfg[11], cfg[12]
    max_curvature, length, target = cfg[13], cfg[15], cfg[17]
    n = cmd.shape[0]
    for j in range(n):
        out[j] = el.kappa_at(d, 6 * ce[j], le[ce[j]], cxi[j]) * length
        out[n + 6 + j] = cmd[j] / max_curvature
    body_state(d, v, le, nz, npsi, body)
    rel = body[4] - target
    out[n] = math.sin(rel)
    out[n + 1] = math.cos(rel)
    c, s = math.cos(body[4]), math.sin(body[4])
    out[n + 2] = (c * body[2] + s * body[3]) / length
    out[n + 3] = (-s * body[2] + c * body[3]) / length
    tail = d[4] - body[4]
    out[n + 4] = math.atan2(math.sin(tail), math.cos(tail))
    out[n + 5] = v[4]


@numba.njit(cache=True, nogil=True)
def target_row(cmd, phase, action, cfg, out):
    """The target kappa# [1/m] at the control points into out (n,): max_curvature x action
    (action_mode "curvature"), or the anguilliform wave of the action's (amplitude, wavelength,
    frequency) at the step's end, advancing phase[0] by 2 pi f control_dt ("wave")."""
    max_curvature = cfg[13]
    if cfg[20] == 0:
        for j in range(cmd.shape[0]):
            out[j] = max_curvature * action[j]
        return
    envelope, u, ranges, dt = cfg[21], cfg[22], cfg[23], cfg[24]
    amp = 0.5 * (action[0] + 1.0) * max_curvature
    lam = ranges[0] + 0.5 * (action[1] + 1.0) * (ranges[1] - ranges[0])
    freq = ranges[2] + 0.5 * (action[2] + 1.0) * (ranges[3] - ranges[2])
    phase[0] = (phase[0] + 2.0 * math.pi * freq * dt) % (2.0 * math.pi)
    for j in range(cmd.shape[0]):
        out[j] = amp * envelope[j] * math.sin(2.0 * math.pi * u[j] / lam - phase[0])


@numba.njit(cache=True, nogil=True)
def step_row(d, v, cmd, phase, action, cfg, sc, body, obs, rep, newton):
    """One control step of one eel in place (module docstring): d, v (n_dof,), cmd (n,) [1/m]
    the previous command, phase (1,) the wave's phase [rad] (action_mode "wave"), action in
    [-1, 1] ((n,) or (3,)); obs (2 n + 6) float32, body (5,), rep (N_REPORT,) the report; sc
    the row's `scratch`, newton the Newton step's (`swimmer.kernels.newton_scratch`, no state).
    A failed substep stops the step (rep[REP_OK] = 0)."""
    le, mass, quad, water, th, tol, max_iter, max_halvings, interp = cfg[:9]
    n_sub, ei, h, max_change = cfg[14], cfg[16], cfg[18], cfg[19]
    k_old, k_new, ka, kb = sc[8], sc[9], sc[10], sc[11]
    ne, n = le.shape[0], cmd.shape[0]
    new = np.empty(n)
    target_row(cmd, phase, action, cfg, new)
    for j in range(n):
        change = new[j] - cmd[j]
        new[j] = cmd[j] + min(max(change, -max_change), max_change)
    for e in range(ne):
        for g in range(4):
            o, w = 0.0, 0.0
            for j in range(n):
                o += interp[4 * e + g, j] * cmd[j]
                w += interp[4 * e + g, j] * new[j]
            k_old[e, g], k_new[e, g] = o, w
    body_state(d, v, le, cfg[9], cfg[10], body)
    rep[REP_X0], rep[REP_Y0] = body[0], body[1]
    total, ok = 0, 1.0
    acc = sc[12]
    acc[0], acc[1] = 0.0, 0.0
    for s in range(n_sub):
        for e in range(ne):
            for g in range(4):
                ka[e, g] = k_old[e, g] + s / n_sub * (k_new[e, g] - k_old[e, g])
                kb[e, g] = k_old[e, g] + (s + 1) / n_sub * (k_new[e, g] - k_old[e, g])
        its = advance_linear(d, v, ka, kb, h, mass, le, quad, water, th, tol, max_iter,
                             max_halvings, sc[:8], ei, acc, newton)  # fmt: skip
        if its < 0:
            ok = 0.0
            break
        total += its
    for j in range(n):
        cmd[j] = new[j]
    rep[REP_OK], rep[REP_ENERGY], rep[REP_ITER], rep[REP_NET] = ok, acc[0], total, acc[1]
    observe_row(d, v, cmd, cfg, body, obs)


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, actions, state, cmd, phase, cfg, work, body, obs, rep):
    """`step_row` for the active rows lo <= i < hi: state (N, 2, n_dof) (d, v), cmd (N, n),
    phase (N, 1), actions (N, n or 3), work the rows' scratch (tuple of (N, ...) arrays),
    body (N, 5), obs (N, 2 n + 6) float32, rep (N, N_REPORT)."""
    newton = newton_scratch(state.shape[2], cfg[0].shape[0])  # one set for the block's rows
    for i in range(lo, hi):
        if active[i]:
            sc = (work[0][i], work[1][i], work[2][i], work[3][i], work[4][i], work[5][i],
                  work[6][i], work[7][i], work[8][i], work[9][i], work[10][i],
                  work[11][i], work[12][i])  # fmt: skip
            step_row(state[i, 0], state[i, 1], cmd[i], phase[i], actions[i], cfg, sc, body[i],
                     obs[i], rep[i], newton)  # fmt: skip
