"""Eel-v0's compiled step, shared by the single env and the native vector env so both give the
same bits.

- `observe_row`: the observation (`spec.observation_layout`) in one compiled function; the
  centre of mass, its velocity and the mean frame angle come from the beam robots'
  `body_state` (`envs._beam_rows`, with the configuration `Cfg`);
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
from collections import namedtuple

import numba
import numpy as np

from mf_envs.envs import _beam_rows as br
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.fused import quadrature_tables
from mf_envs.physics.swimmer.fluid import shape_tables
from mf_envs.physics.swimmer.kernels import _scratch as _kernel_scratch
from mf_envs.physics.swimmer.kernels import advance_linear

THETA = 0.5  # the water force at the step's midpoint (`physics.swimmer.kernels`)
Wave = namedtuple("Wave", "max_change wave_mode envelope u ranges control_dt")
Wave.__doc__ = """`Cfg.robot` of the eel: max_change [1/m] the command's largest change per
control step (max_curvature_rate x control_dt); wave_mode 1 with action_mode "wave" (0:
"curvature"); envelope (n,) the wave's amplitude envelope and u (n,) the distance from the head
/ L at the control points; ranges (wavelength min, max [L], frequency min, max [Hz]);
control_dt [s]."""


def pack(scene, model, n_substeps: int, physics_dt: float, control_dt: float,
         target: float):  # fmt: skip
    """The rows' `Cfg` of a `build.Scene` on its `BeamModel` (module docstring)."""
    from mf_envs.envs.eel.build import HEAD_RATIO, WAVE_FREQUENCY, WAVE_WAVELENGTH

    le = model.le
    s_ctrl = np.linspace(0.0, 1.0, scene.n_ctrl)  # S / L of the control points
    water = (*shape_tables(le), scene.water.packed())
    qxi, qw, stiff = model.quad
    quad = (qw, stiff, model.u_scale, quadrature_tables(le, qxi))
    wave = Wave(
        scene.max_curvature_rate * float(control_dt), 1 if scene.action_mode == "wave" else 0,
        HEAD_RATIO + (1.0 - HEAD_RATIO) * (1.0 - s_ctrl), 1.0 - s_ctrl,
        np.array([*WAVE_WAVELENGTH, *WAVE_FREQUENCY]), float(control_dt),
    )  # fmt: skip
    body = (quad, water, (THETA, scene.stress_theta), 0.0)
    return br.pack_cfg(scene, model, (n_substeps, physics_dt), target, body, wave)


@numba.njit(cache=True, nogil=True)
def _scratch(n_dof, n_el, n_ctrl):
    ks = _kernel_scratch(n_dof, n_el)
    return (ks, np.empty((n_el, 4)), np.empty((n_el, 4)), np.empty((n_el, 4)),
            np.empty((n_el, 4)), np.zeros(2), np.empty(n_ctrl))  # fmt: skip


def scratch(model, n_ctrl: int) -> tuple:
    """An eel's scratch (no state: every entry is written before it is read): the Newton
    solver's (`swimmer.kernels.make_scratch`), four kappa# tables at the Gauss points (n_el, 4),
    the work sums and the new command at the control points (n_ctrl,)."""
    return _scratch(model.n_dof, model.n_elements, n_ctrl)


@numba.njit(cache=True, nogil=True)
def observe_row(d, v, cmd, cfg, body, out):
    """The observation into out (float32, 2 n + 6) and the body state into body (5,)."""
    le, ce, cxi, length = cfg.body.le, cfg.ce, cfg.cxi, cfg.length
    n = cmd.shape[0]
    for j in range(n):
        out[j] = el.kappa_at(d, 6 * ce[j], le[ce[j]], cxi[j]) * length
        out[n + 6 + j] = cmd[j] / cfg.max_curvature
    br.body_state(d, v, le, cfg.nz, cfg.npsi, body)
    rel = body[4] - cfg.target
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
    max_curvature, wave = cfg.max_curvature, cfg.robot
    if wave.wave_mode == 0:
        for j in range(cmd.shape[0]):
            out[j] = max_curvature * action[j]
        return
    envelope, u, ranges, dt = wave.envelope, wave.u, wave.ranges, wave.control_dt
    amp = 0.5 * (action[0] + 1.0) * max_curvature
    lam = ranges[0] + 0.5 * (action[1] + 1.0) * (ranges[1] - ranges[0])
    freq = ranges[2] + 0.5 * (action[2] + 1.0) * (ranges[3] - ranges[2])
    phase[0] = (phase[0] + 2.0 * math.pi * freq * dt) % (2.0 * math.pi)
    for j in range(cmd.shape[0]):
        out[j] = amp * envelope[j] * math.sin(2.0 * math.pi * u[j] / lam - phase[0])


@numba.njit(cache=True, nogil=True)
def step_row(d, v, cmd, phase, action, cfg, sc, body, obs, rep):
    """One control step of one eel in place (module docstring): d, v (n_dof,), cmd (n,) [1/m]
    the previous command, phase (1,) the wave's phase [rad] (action_mode "wave"), action in
    [-1, 1] ((n,) or (3,)); obs (2 n + 6) float32, body (5,), rep (N_REPORT,) the report; sc
    `scratch` (no state). A failed substep stops the step (rep[REP_OK] = 0)."""
    n_sub, h, max_change = cfg.n_sub, cfg.h, cfg.robot.max_change
    ks, k_old, k_new, ka, kb, acc, new = sc
    ne, n = cfg.body.le.shape[0], cmd.shape[0]
    target_row(cmd, phase, action, cfg, new)
    for j in range(n):
        change = new[j] - cmd[j]
        new[j] = cmd[j] + min(max(change, -max_change), max_change)
    br.to_gauss(cfg.interp, cmd, new, k_old, k_new)
    br.open_report(d, v, cfg, body, rep, acc)
    total, ok = 0, 1.0
    for s in range(n_sub):
        for e in range(ne):
            for g in range(4):
                ka[e, g] = k_old[e, g] + s / n_sub * (k_new[e, g] - k_old[e, g])
                kb[e, g] = k_old[e, g] + (s + 1) / n_sub * (k_new[e, g] - k_old[e, g])
        its = advance_linear(d, v, ka, kb, h, cfg.body, ks, acc)
        total += abs(its)
        if its < 0:
            ok = 0.0
            break
    for j in range(n):
        cmd[j] = new[j]
    br.close_report(rep, ok, acc, total)
    observe_row(d, v, cmd, cfg, body, obs)


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, actions, state, cmd, phase, cfg, body, obs, rep):
    """`step_row` for the active rows lo <= i < hi: state (N, 2, n_dof) (d, v), cmd (N, n),
    phase (N, 1), actions (N, n or 3), body (N, 5), obs (N, 2 n + 6) float32, rep
    (N, N_REPORT). One scratch serves the block (it holds no state)."""
    sc = _scratch(state.shape[2], cfg.body.le.shape[0], cmd.shape[1])
    for i in range(lo, hi):
        if active[i]:
            step_row(state[i, 0], state[i, 1], cmd[i], phase[i], actions[i], cfg, sc, body[i],
                     obs[i], rep[i])  # fmt: skip
