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
from mf_envs.envs.eel.spec import TAIL_RATE_UNIT
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.fused import quadrature_tables
from mf_envs.physics.serpentine.stepping import bending_work
from mf_envs.physics.swimmer.fluid import shape_tables
from mf_envs.physics.swimmer.kernels import _scratch as _kernel_scratch
from mf_envs.physics.swimmer.kernels import advance_linear

THETA = 0.5  # the water force at the step's midpoint (`physics.swimmer.kernels`)
# the power limit (`step_row`): a step whose positive work exceeds the limit by more than this
# fraction is redone, at most POWER_RETRIES times
POWER_TOLERANCE = 0.01
POWER_RETRIES = 3
Wave = namedtuple("Wave", "max_change wave_mode envelope u ranges control_dt max_work")
Wave.__doc__ = """`Cfg.robot` of the eel: max_change [1/m] the command's largest change per
control step (max_curvature_rate x control_dt); wave_mode 1 with action_mode "wave" (0:
"curvature"); envelope (n,) the wave's amplitude envelope and u (n,) the distance from the head
/ L at the control points; ranges (wavelength min, max [L], frequency min, max [Hz]);
control_dt [s]; max_work [J] the muscles' largest positive work in a control step (their power
limit x control_dt; inf: none)."""


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
        scene.max_muscle_power * float(control_dt),
    )  # fmt: skip
    body = (quad, water, (THETA, scene.stress_theta), 0.0)
    return br.pack_cfg(scene, model, (n_substeps, physics_dt), target, body, wave)


@numba.njit(cache=True, nogil=True)
def _scratch(n_dof, n_el, n_ctrl):
    ks = _kernel_scratch(n_dof, n_el)
    return (ks, np.empty((n_el, 4)), np.empty((n_el, 4)), np.empty((n_el, 4)),
            np.empty((n_el, 4)), np.zeros(2), np.empty(n_ctrl), np.empty((2, n_dof)))  # fmt: skip


def scratch(model, n_ctrl: int) -> tuple:
    """An eel's scratch (no state: every entry is written before it is read, but for the
    Newton predictor's hint, which orders its work and changes no result): the Newton
    solver's (`swimmer.kernels.make_scratch`), four kappa# tables at the Gauss points (n_el, 4),
    the work sums, the new command at the control points (n_ctrl,) and the step's start state
    (2, n_dof) (a step redone under the power limit)."""
    return _scratch(model.n_dof, model.n_elements, n_ctrl)


@numba.njit(cache=True, nogil=True)
def observe_row(d, v, cmd, cfg, body, out):
    """The observation into out (float32, 2 n + 6) and the body state into body (5,)."""
    br.observe_curvature(d, cmd, cfg, 6, out)
    n, length = cmd.shape[0], cfg.length
    br.body_state(d, v, cfg.body.le, cfg.nz, cfg.npsi, body)
    rel = body[4] - cfg.target
    out[n] = math.sin(rel)
    out[n + 1] = math.cos(rel)
    c, s = math.cos(body[4]), math.sin(body[4])
    out[n + 2] = (c * body[2] + s * body[3]) / length
    out[n + 3] = (-s * body[2] + c * body[3]) / length
    tail = d[4] - body[4]
    out[n + 4] = math.atan2(math.sin(tail), math.cos(tail))
    out[n + 5] = v[4] / TAIL_RATE_UNIT  # in the slot's fixed unit (`spec.TAIL_RATE_UNIT`)


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
def _work_model(d, k_old, k_new, le, ei):
    """(A, B) of the muscles' work in a step that changes kappa# from k_old to k_new (n_el, 4),
    predicted at its start d for a fraction s of the change: W(s) = s A + s^2 B,
    A = -int EI (kappa(d) - k_old) dk dS (the start's moment), B = int EI dk^2 / 2 dS (the
    moment the change itself adds, half of it on average over the step), dk = k_new - k_old."""
    b = 0.0
    for e in range(le.shape[0]):
        for g in range(4):
            b += el.GAUSS_W[g] * le[e] * (k_new[e, g] - k_old[e, g]) ** 2
    return -bending_work(d, k_old, k_old, k_new, le, ei), 0.5 * ei * b


@numba.njit(cache=True, nogil=True, inline="always")
def _fraction(a, b, max_work):
    """The largest s in (0, 1] with s a + s^2 b <= max_work (b >= 0, max_work > 0)."""
    if a + b <= max_work:
        return 1.0
    return 2.0 * max_work / (a + math.sqrt(a * a + 4.0 * b * max_work))


@numba.njit(cache=True, nogil=True)
def _substeps(d, v, k_old, k_new, cfg, ks, ka, kb, acc):
    """The control step's n_sub physics steps under the command k_old -> k_new (linear in
    time); (Newton iterations, 1.0 or 0.0 if a substep failed)."""
    n_sub, h, ne = cfg.n_sub, cfg.h, cfg.body.le.shape[0]
    total = 0
    for s in range(n_sub):
        for e in range(ne):
            for g in range(4):
                ka[e, g] = k_old[e, g] + s / n_sub * (k_new[e, g] - k_old[e, g])
                kb[e, g] = k_old[e, g] + (s + 1) / n_sub * (k_new[e, g] - k_old[e, g])
        its = advance_linear(d, v, ka, kb, h, cfg.body, ks, acc)
        total += abs(its)
        if its < 0:
            return total, 0.0
    return total, 1.0


@numba.njit(cache=True, nogil=True)
def _rescale(cmd, new, k_old, k_new, ratio):
    """The command's change (control points and Gauss points) times ratio."""
    for j in range(cmd.shape[0]):
        new[j] = cmd[j] + ratio * (new[j] - cmd[j])
    for e in range(k_old.shape[0]):
        for g in range(4):
            k_new[e, g] = k_old[e, g] + ratio * (k_new[e, g] - k_old[e, g])


@numba.njit(cache=True, nogil=True)
def step_row(d, v, cmd, phase, action, cfg, sc, body, obs, rep):
    """One control step of one eel in place (module docstring): d, v (n_dof,), cmd (n,) [1/m]
    the previous command, phase (1,) the wave's phase [rad] (action_mode "wave"), action in
    [-1, 1] ((n,) or (3,)); obs (2 n + 6) float32, body (5,), rep (N_REPORT,) the report; sc
    `scratch`. A failed substep stops the step (rep[REP_OK] = 0). Under the power
    limit (`Wave.max_work` finite), a step whose muscles did more positive work than the limit
    (by more than POWER_TOLERANCE) is redone from its start, at most POWER_RETRIES times, with
    the change scaled by the fraction s of `_work_model` that keeps its work within the limit:
    the model's A through the work the first attempt did, then A and B through the last two
    attempts' (its B, the moment the change adds if the body did not follow, overestimates the
    work's curvature, so the model is not used before a step has been tried)."""
    max_change, max_work = cfg.robot.max_change, cfg.robot.max_work
    ks, k_old, k_new, ka, kb, acc, new, start = sc
    n = cmd.shape[0]
    target_row(cmd, phase, action, cfg, new)
    for j in range(n):
        change = new[j] - cmd[j]
        new[j] = cmd[j] + min(max(change, -max_change), max_change)
    br.to_gauss(cfg.interp, cmd, new, k_old, k_new)
    limited = max_work < math.inf
    frac, a, b = 1.0, 0.0, 0.0
    if limited:
        a, b = _work_model(d, k_old, k_new, cfg.body.le, cfg.body.ei)
        start[0, :] = d
        start[1, :] = v
    br.open_report(d, v, cfg, body, rep, acc)
    total, ok = _substeps(d, v, k_old, k_new, cfg, ks, ka, kb, acc)
    s_prev, w_prev = 0.0, 0.0
    for _ in range(POWER_RETRIES):
        if not (limited and ok > 0.0 and acc[0] > max_work * (1.0 + POWER_TOLERANCE)):
            break
        if s_prev > 0.0 and frac != s_prev:  # W(s) = s A + s^2 B through the last two
            b_fit = (acc[0] / frac - w_prev / s_prev) / (frac - s_prev)  # attempts, if B >= 0
            if b_fit >= 0.0:
                b = b_fit
        s_prev, w_prev = frac, acc[0]
        a = (acc[0] - frac * frac * b) / frac  # the model through the work done
        s_new = _fraction(a, b, max_work)
        _rescale(cmd, new, k_old, k_new, s_new / frac)
        frac = s_new
        d[:] = start[0]
        v[:] = start[1]
        br.open_report(d, v, cfg, body, rep, acc)
        its, ok = _substeps(d, v, k_old, k_new, cfg, ks, ka, kb, acc)
        total += its
    for j in range(n):
        cmd[j] = new[j]
    br.close_report(rep, ok, acc, total)
    observe_row(d, v, cmd, cfg, body, obs)


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, actions, state, cmd, phase, cfg, body, obs, rep):
    """`step_row` for the active rows lo <= i < hi: state (N, 2, n_dof) (d, v), cmd (N, n),
    phase (N, 1), actions (N, n or 3), body (N, 5), obs (N, 2 n + 6) float32, rep
    (N, N_REPORT). One scratch serves the block (no result depends on what it holds)."""
    sc = _scratch(state.shape[2], cfg.body.le.shape[0], cmd.shape[1])
    for i in range(lo, hi):
        if active[i]:
            step_row(state[i, 0], state[i, 1], cmd[i], phase[i], actions[i], cfg, sc, body[i],
                     obs[i], rep[i])  # fmt: skip
