"""Inchworm-v0's compiled step, shared by the single env and the native vector env so both give the
same bits.

- `observe_row`: the observation in one compiled function: strain-gauge curvatures at the
  control points (the curvature field sampled 16 times per element, interpolated linearly, as
  `Inchworm.curvature_at`), the commanded curvature, the foot IMU angles, the head-tail
  distance, the grip and the ground reactions (`Inchworm.support_reactions`; with `terrain` the
  caller passes the soil's).
- `step_rows`: N inchworms on friction feet stepped in one compiled call (the native vector
  env's kernel). Every active row runs exactly what the single env runs for one control step
  (the action scaling of `InchwormEnv.step`, `quasistatic.drive_step`, the re-centring of the
  local origin of `Inchworm._recenter`, `observe_row`), so a row is bit-identical to a single
  env. Rows are independent; blocks of rows run on threads (`envs._rows.RowBlocks`), which does
  not change any row's arithmetic.
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.physics.beam import element as el
from mf_envs.physics.beam import fields
from mf_envs.physics.beam.contact import stick_slip as ss
from mf_envs.physics.inchworm import quasistatic as qs

SAMPLES_PER_ELEMENT = 16  # curvature samples per element of the strain gauges


def sample_points(model) -> tuple[np.ndarray, np.ndarray]:
    """(xis (16,), S (16 n_el + 1,)) of the curvature samples of a `BeamModel`."""
    xis = np.linspace(0.0, 1.0, SAMPLES_PER_ELEMENT + 1)[:-1]
    s = (model.node_S[:-1, None] + xis[None, :] * model.le[:, None]).ravel()
    return xis, np.append(s, model.params.length)


@numba.njit(cache=True)
def observe_row(
    d, x_origin, kappa_gauss, kappa_cmd, head_grips, reactions, own_reactions, geometry,
    f_ext, scales, out,
):  # fmt: skip
    """The observation (layout of `spec.observation_layout`) into out (float32, 2 n + 6).

    d (n_dof,) local dofs, x_origin [m]; kappa_gauss (n_el, 4) realised kappa# [1/m];
    kappa_cmd (n,) commanded kappa# [1/m]; head_grips: bool; reactions (2,) [N] used when
    own_reactions is False (terrain), else the residual P - F at the feet's z dofs;
    geometry = (le, qxi, qw, stiff, xis, S samples, S control points);
    scales = (length, max_curvature, weight)."""
    le, qxi, qw, stiff, xis, s_samples, s_ctrl = geometry
    length, max_curvature, weight = scales
    n = kappa_cmd.shape[0]
    ne = le.shape[0]
    nx = xis.shape[0]
    samples = np.empty(ne * nx + 1)
    for e in range(ne):
        for q in range(nx):
            samples[e * nx + q] = el.kappa_at(d, 6 * e, le[e], xis[q])
    samples[ne * nx] = el.kappa_at(d, 6 * (ne - 1), le[ne - 1], 1.0)
    curv = np.interp(s_ctrl, s_samples, samples)
    nd = d.shape[0]
    r_t, r_h = reactions[0], reactions[1]
    if own_reactions:
        p = np.empty(2)
        el.forces_at_into(d, le, kappa_gauss, qxi, qw, stiff, (2, nd - 3), p)
        r_t = p[0] - f_ext[2]
        r_h = p[1] - f_ext[nd - 3]
    for k in range(n):
        out[k] = curv[k] * length
        out[n + k] = kappa_cmd[k] / max_curvature
    x_head = x_origin + d[nd - 5]
    x_tail = x_origin + d[0]
    out[2 * n] = d[4]
    out[2 * n + 1] = d[nd - 1]
    out[2 * n + 2] = (x_head - x_tail) / length
    out[2 * n + 3] = 1.0 if head_grips else -1.0
    out[2 * n + 4] = r_t / weight
    out[2 * n + 5] = r_h / weight


@numba.njit(cache=True, nogil=True)
def _command(action, n, max_curv, switching, cmd, duty, grip):
    """Row action (n [+ 1]) in [-1, 1] as `InchwormEnv.step` scales it: duty (n,) in [0, 1],
    the commanded kappa# cmd = -max_curv x duty [1/m] and the feet's grip (2,) (both unless the
    anchor switches: then the head grips if the last action is positive); returns that."""
    for k in range(n):
        duty[k] = 0.5 * (action[k] + 1.0)
        cmd[k] = -max_curv * 0.5 * (action[k] + 1.0)
    grip[0], grip[1] = 1.0, 1.0
    if not switching:
        return True
    grips_head = action[n] > 0.0
    grip[0] = 0.0 if grips_head else 1.0
    grip[1] = 1.0 if grips_head else 0.0
    return grips_head


@numba.njit(cache=True, nogil=True)
def _before(before, i, xo, d):
    """Row i's position before its step: the local origin x, the tail's local x and, if
    `before` has a third column (gripping feet), the head's."""
    before[i, 0] = xo[i]
    before[i, 1] = d[0]
    if before.shape[1] > 2:
        before[i, 2] = d[d.shape[0] - 5]


@numba.njit(cache=True, nogil=True)
def _recenter(d, xo, i, length):
    """`Inchworm._recenter`: row i's local origin follows the tail once it is a body length
    away (the x dofs shifted, xo[i] moved by as much)."""
    shift = d[0]
    if abs(shift) > length:
        for j in range(0, d.shape[0], 6):
            d[j] -= shift
        xo[i] += shift


@numba.njit(cache=True, nogil=True)
def _open_row(i, action, d_all, work, cfg, before, xo, cmd, duty, grip):
    """Row i's control step begins (cfg as `step_rows`): its command from `action`
    (`_command`: cmd, duty, grip), its position before (`_before`); returns its dofs d, whether
    the head grips and its Newton scratch."""
    vec, ab, wk, piv, kap = work
    grips_head = _command(action, cmd.shape[0], cfg[1], cfg[0], cmd, duty, grip)
    d = d_all[i]
    _before(before, i, xo, d)
    return d, grips_head, (vec[i], ab[i], wk[i], piv[i], kap[i])


@numba.njit(cache=True, nogil=True)
def _finish_row(i, d, xo, kc_i, second, head_i, cfg, vec_i, ab_i, out):
    """Row i after its step (cfg, out as `step_rows`): kappa# at the Gauss points from the
    realised kc_i, the elastic energy, the observation (`second`: the block after the
    curvatures, the command or the wires' temperatures) and the centreline."""
    s_ctrl, gauss_s, f_ext, bc, geo, scales, xis = cfg[6:13]
    energy, line, kg, obs = out[4], out[5], out[6], out[3]
    kg[i] = np.interp(gauss_s.ravel(), s_ctrl, kc_i).reshape(gauss_s.shape)
    energy[i] = el.assemble_into(d, bc[0], kg[i], bc[1], bc[2], bc[3], False, vec_i[0], ab_i)
    observe_row(d, xo[i], kg[i], second, head_i, np.zeros(2), True, geo, f_ext, scales, obs[i])
    fields.centerline_into(d, xo[i], bc[0], xis, line[i])


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, actions, state, work, cfg, out):
    """Advance the active rows among lo..hi - 1 one control step (releases the GIL: blocks of
    rows run on threads, `envs._rows.RowBlocks`).

    actions (N, n [+ 1]) in [-1, 1]; state = (d (N, n_dof), x_origin (N,), lag kappa# (N, n),
    realised kappa_ctrl (N, n), engagement (N, 2), slipping (N, 2) int, commanded kappa#
    (N, n), head grips (N,) bool); work = (vec, ab, work, piv, kap) scratch with a leading N
    axis; cfg = (switching, max_curvature, control_dt, min_substeps, act, feet, S_ctrl,
    gauss_S, f_ext, beam constants, observation geometry, (length, max_curvature, weight),
    centerline xis); out = (status (N,) int, report (N, ss.N_REPORT), tail before (N, 2) =
    (x_origin, local x), obs (N, 2 n + 6) float32, elastic energy (N,), centerline (N, P, 2),
    kappa# at the Gauss points (N, n_el, 4))."""
    d_all, xo, lag, kc, g, slip, cmd_all, head = state
    vec, ab = work[0], work[1]
    dt, min_sub, act, feet, s_ctrl, gauss_s, f_ext, bc = cfg[2:10]
    status, rep, before = out[0], out[1], out[2]
    n = cmd_all.shape[1]
    cmd, duty, grip = np.empty(n), np.empty(n), np.empty(2)
    for i in range(lo, hi):
        if not active[i]:
            continue
        d, grips_head, sc = _open_row(i, actions[i], d_all, work, cfg, before, xo, cmd, duty, grip)
        st = qs.drive_step(
            (d, lag[i], kc[i], g[i], slip[i]), cmd, grip, dt, min_sub, act, feet, s_ctrl,
            gauss_s, f_ext, bc, sc, rep[i],
        )  # fmt: skip
        status[i] = st
        if st == ss.OK:
            cmd_all[i] = cmd
            head[i] = grips_head
            _recenter(d, xo, i, cfg[11][0])
        _finish_row(i, d, xo, kc[i], cmd_all[i], head[i], cfg, vec[i], ab[i], out)


@numba.njit(cache=True, nogil=True)
def step_rows_grip(lo, hi, active, actions, state, work, cfg, out):
    """`step_rows` for the scenes on gripping feet (`quasistatic.grip_step`; the
    default: SMA wires): every active row runs what `InchwormEnv.step` runs.

    state = (d (N, n_dof), x_origin (N,), lag kappa# (N, n), realised kappa_ctrl (N, n), feet
    (N, 4), SMA state (N, 5, n), commanded kappa# (N, n), head grips (N,) bool, duty (N, n));
    cfg = (switching, max_curvature, control_dt, min_substeps, act, feet, S_ctrl, gauss_S,
    f_ext, beam constants, observation geometry, (length, max_curvature or 1, weight),
    centerline xis, sma (bool), (T_amb, Af - T_amb, bound) of the temperature observation);
    out = (status, report (N, qs.N_GRIP_REPORT), before (N, 3) = (x_origin, local x of the
    tail, local x of the head), obs, elastic energy, centerline, kappa# at the Gauss points)."""
    d_all, xo, lag, kc, ft, sma, cmd_all, head, duty_all = state
    vec, ab = work[0], work[1]
    dt, min_sub, act, feet, s_ctrl, gauss_s, f_ext, bc = cfg[2:10]
    is_sma, tobs = cfg[13], cfg[14]
    status, rep, before = out[0], out[1], out[2]
    n = cmd_all.shape[1]
    cmd, duty, grip, second = np.empty(n), np.empty(n), np.empty(2), np.empty(n)
    for i in range(lo, hi):
        if not active[i]:
            continue
        d, grips_head, sc = _open_row(i, actions[i], d_all, work, cfg, before, xo, cmd, duty, grip)
        st = qs.grip_step(
            (d, lag[i], kc[i], ft[i], sma[i]), duty if is_sma else cmd, grip, dt, min_sub, act,
            feet, s_ctrl, gauss_s, f_ext, bc, sc, rep[i],
        )  # fmt: skip
        status[i] = st
        if st == 0:
            cmd_all[i] = cmd
            duty_all[i] = duty
            head[i] = grips_head
            _recenter(d, xo, i, cfg[11][0])
        for k in range(n):
            if is_sma:
                second[k] = min(max((sma[i, 0, k] - tobs[0]) / tobs[1], -tobs[2]), tobs[2])
            else:
                second[k] = cmd_all[i, k]
        _finish_row(i, d, xo, kc[i], second, head[i], cfg, vec[i], ab[i], out)
