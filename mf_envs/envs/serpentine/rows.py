"""Serpentine-v0's compiled step, shared by the single env and the native vector env so both give
the same bits (the configuration `Cfg`, the centre of mass and the Gauss-point map are the beam
robots', `envs._beam_rows`).

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
from collections import namedtuple

import numba
import numpy as np

from mf_envs.envs import _beam_rows as br
from mf_envs.envs.serpentine.spec import VELOCITY_UNIT
from mf_envs.physics.actuators.kernels import lag_at
from mf_envs.physics.serpentine.kernels import _scratch as _kernel_scratch
from mf_envs.physics.serpentine.kernels import advance_linear, quad_tables

THETA = 1.0  # the ground force at the step's end (`physics.serpentine.kernels`)
Muscles = namedtuple("Muscles", "time_constant rate_limit")  # `Cfg.robot`: the actuator lag


def pack(scene, model, n_substeps: int, physics_dt: float, target: float):
    """The rows' `Cfg` of a `build.Scene` on its `BeamModel` (module docstring)."""
    p = scene.params
    ground = (p.mass_per_length * scene.gravity, p.mass_per_length, scene.ground.packed())
    muscles = Muscles(float(scene.actuator_time_constant), float(scene.actuator_rate_limit))
    body = (quad_tables(model), ground, THETA, scene.material_damping)
    return br.pack_cfg(scene, model, (n_substeps, physics_dt), target, body, muscles)


@numba.njit(cache=True, nogil=True)
def _scratch(n_dof, n_el, n_ctrl):
    ks = _kernel_scratch(n_dof, n_el)
    return (ks, np.empty((n_el, 4)), np.empty((n_el, 4)), np.zeros(2), np.empty(n_ctrl),
            np.empty(n_ctrl), np.empty(n_ctrl))  # fmt: skip


def scratch(model, n_ctrl: int) -> tuple:
    """A snake's scratch (no state: every entry is written before it is read): the Newton
    solver's (`kernels.make_scratch`), kappa# tables at the Gauss points (n_el, 4), the work sums
    and kappa# at the control points (n_ctrl,)."""
    return _scratch(model.n_dof, model.n_elements, n_ctrl)


@numba.njit(cache=True, nogil=True)
def observe_row(d, v, cmd, cfg, body, out):
    """The observation into out (float32, 2 n + 4) and the body state into body (5,)."""
    br.observe_curvature(d, cmd, cfg, 4, out)
    n, length = cmd.shape[0], cfg.length
    rel = d[d.shape[0] - 1] - cfg.target
    out[n] = math.sin(rel)
    out[n + 1] = math.cos(rel)
    br.body_state(d, v, cfg.body.le, cfg.nz, cfg.npsi, body)
    c, s = math.cos(body[4]), math.sin(body[4])
    unit = length * VELOCITY_UNIT  # m/s (the slots' fixed unit, `spec.VELOCITY_UNIT` L/s)
    out[n + 2] = (c * body[2] + s * body[3]) / unit
    out[n + 3] = (-s * body[2] + c * body[3]) / unit


@numba.njit(cache=True, nogil=True)
def step_row(d, v, cmd, action, cfg, sc, body, obs, rep):
    """One control step of one snake in place (module docstring): d, v (n_dof,), cmd (n,)
    [1/m] the muscles' kappa# at the control points (the previous command, or with actuator
    dynamics the lagged state), action (n,) in [-1, 1]; sc: `scratch`; obs (2 n + 4)
    float32, body (5,), rep (N_REPORT,) the report. A failed substep stops the step
    (rep[REP_OK] = 0)."""
    n_sub, h = cfg.n_sub, cfg.h
    tau_a, rate_a = cfg.robot
    ks, ka, kb, acc, c0, c1, u = sc
    n = cmd.shape[0]
    for j in range(n):
        u[j] = cfg.max_curvature * action[j]
        c1[j] = cmd[j]
    br.open_report(d, v, cfg, body, rep, acc)
    total, ok = 0, 1.0
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
        br.to_gauss(cfg.interp, c0, c1, ka, kb)
        its = advance_linear(d, v, ka, kb, h, cfg.body, ks, acc)
        total += abs(its)
        if its < 0:
            ok = 0.0
            break
    for j in range(n):
        cmd[j] = c1[j]
    br.close_report(rep, ok, acc, total)
    observe_row(d, v, cmd, cfg, body, obs)


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, actions, state, cmd, cfg, body, obs, rep):
    """`step_row` for the active rows lo <= i < hi: state (N, 2, n_dof) (d, v), cmd (N, n),
    actions (N, n), body (N, 5), obs (N, 2 n + 4) float32, rep (N, N_REPORT). One scratch
    serves the block (it holds no state)."""
    sc = _scratch(state.shape[2], cfg.body.le.shape[0], cmd.shape[1])
    for i in range(lo, hi):
        if active[i]:
            step_row(state[i, 0], state[i, 1], cmd[i], actions[i], cfg, sc, body[i], obs[i],
                     rep[i])  # fmt: skip
