"""Inchworm-v0's observation in one compiled function, shared by the single env and the batched
vector env (so both produce the same bits): strain-gauge curvatures at the control points (the
curvature field sampled 16 times per element, interpolated linearly, as `Inchworm.curvature_at`),
the commanded curvature, the foot IMU angles, the head-tail distance, the grip and the ground
reactions (`Inchworm.support_reactions`; with `terrain` the caller passes the soil's)."""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.physics.beam import element as el

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
