"""Compiled time loop of the swimming beam: the energy-momentum step of the serpentine
(`physics.serpentine.kernels`, Simo & Tarnow 1992) generalised to a body in water, whose entrained
water adds a configuration-dependent momentum (Lighthill's added mass on the normal direction)
and whose resistive and tail forces are a velocity-dependent load (`fluid`).

Unknown d = d_{n+1}; v_{n+1} = 2 (d - d_n) / dt - v_n (trapezoidal kinematics). Residual

    R(d) = (M (v_{n+1} - v_n) + p_w(d, v_{n+1}) - p_w(d_n, v_n)) / dt + Pbar(d_n, d)
           - F_w(d_th, v_th),
    d_th = d_n + th (d - d_n),  v_th = (1 - th) v_n + th v_{n+1},

with p_w the nodal momentum of the water (`fluid.added_momentum`) and F_w the resistive and tail
forces (`fluid.assemble_water`); tangent

    dR/dd = (2 / dt^2) M + (dp_w/dd + (2 / dt) dp_w/dv) / dt + dPbar/dd - th dF_w/dd
            - (2 th / dt) dF_w/dv.

The water's momentum enters as a difference, so body plus entrained water conserve linear
momentum exactly (to the Newton tolerance) when F_w = 0. th = 1/2 (default) takes the resistive
force at the midpoint: second order; th = 1 is implicit Euler on it (first order, L-stable).
The stresses are taken at theta_s of the strains (`beam.algorithmic`): theta_s = 1/2 conserves
the stored energy exactly, theta_s > 1/2 dissipates the strain increments' energy
(theta_s - 1/2) int de^T D de dS per step (the generalised energy-momentum method, Kuhl & Ramm
1999): it damps the stiff axial, shear and high bending modes that a command jump excites and
the energy-conserving scheme would keep ringing (first order in the internal force then).
Why this is a generalisation of `serpentine.kernels.newton_step` rather than a call to it: that
step hard-wires the ground law and has no configuration-dependent mass; the actuation work, the
step splitting (`advance_linear`) and the run are the serpentine's (`serpentine.stepping`), on
this step. The internal force is `beam.fused` (the beam's `assemble_algorithmic` fused with the
water's loads, element by element).
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.physics.beam import fused
from mf_envs.physics.beam.banded import HALF_BW, N_BAND
from mf_envs.physics.beam.element import GAUSS_W, N_GAUSS
from mf_envs.physics.serpentine.kernels import MAX_QUAD, predictor_into, start_choice
from mf_envs.physics.serpentine.stepping import (
    converged,
    correct,
    end_velocity,
    make_stepping,
)
from mf_envs.physics.swimmer.fluid import (
    W_MA,
    W_RESISTIVE,
    added_momentum,
    added_scalars,
    resistive_scalars,
    tail_into,
)


@kernel
def _residual(d0, v0, d, k0, k1, dt, body, sc, buf, ab, v, tangent):
    """buf[0] = -R(d) and ab = dR/dd (module docstring; tangent=False: ab untouched, buf[0]
    the same bits) at the iterate d of `Body` body but for the tail force: the algorithmic
    force (`beam.fused.element_internal`, the start's strains in sc's pre), the water's
    momentum at (d, v) and Taylor's force at (d_th, v_th) element by element; sc's p0 the
    water's nodal momentum at the step's start; buf[1] = d - d0 - dt v0, v = v_{n+1},
    buf[2:4] = d_th, v_th."""
    quad, le = body.quad, body.le
    th, th_s = body.th
    nzt, npt, law = body.load
    cm, e11, ke, pre, p0 = sc[10], sc[13], sc[14], sc[15], sc[16]
    qw, stiff, tab = quad[0], quad[1], quad[3]
    r, x, dth, vth = buf[0], buf[1], buf[2], buf[3]
    db, dv, de, ve = e11[0], e11[1], e11[2], e11[3]
    fe = e11[4]
    fused.trapezoid_points(d, d0, v0, dt, th, x, v, dth, vth)
    for i in range(d0.shape[0]):
        r[i] = p0[i] / dt
    fused.start_band(cm, x, r, ab, tangent)  # r -= c_a M x, ab = c_a M
    m_a = law[W_MA]
    resist = law[W_RESISTIVE] != 0.0
    cd, cv = -th, -2.0 * th / dt
    for e in range(le.shape[0]):
        fused.clear_element(fe, ke)
        fused.gather(d, e, db)
        fused.element_internal(e, db, le[e], k0, k1, qw, stiff, th_s, 0.0, tab, pre, fe, ke,
                               tangent)  # fmt: skip
        fused.gather(v, e, dv)
        fused.gather(dth, e, de)
        fused.gather(vth, e, ve)
        for g in range(N_GAUSS):
            nz, npsi = nzt[e, g], npt[e, g]
            w = GAUSS_W[g] * le[e]
            if m_a != 0.0:  # r -= (p_w(d, v) - p0) / dt, ab += dp_w/dd / dt + 2 dp_w/dv / dt^2
                v1 = nz[0] * dv[0] + nz[1] * dv[1] + nz[2] * dv[2] + nz[3] * dv[3]
                v2 = nz[0] * dv[4] + nz[1] * dv[5] + nz[2] * dv[6] + nz[3] * dv[7]
                psi = npsi[0] * db[8] + npsi[1] * db[9] + npsi[2] * db[10]
                q1, q2, d11, d12, d21, d22, p1, p2 = added_scalars(v1, v2, psi, m_a)
                law_p = (-q1 / dt, -q2 / dt, d11, d12, d21, d22, p1, p2)
                fused.point_load(fe, ke, w, nz, npsi, law_p, 1.0 / dt, 2.0 / (dt * dt), tangent)
            if resist:  # r += F_w(d_th, v_th), ab += -th dF_w/dd - 2 th / dt dF_w/dv
                v1 = nz[0] * ve[0] + nz[1] * ve[1] + nz[2] * ve[2] + nz[3] * ve[3]
                v2 = nz[0] * ve[4] + nz[1] * ve[5] + nz[2] * ve[6] + nz[3] * ve[7]
                psi = npsi[0] * de[8] + npsi[1] * de[9] + npsi[2] * de[10]
                law_r = resistive_scalars(v1, v2, psi, law)
                fused.point_load(fe, ke, w, nz, npsi, law_r, cd, cv, tangent)
        fused.scatter(e, fe, ke, r, ab, tangent)


@numba.njit(cache=True, nogil=True)
def newton_step(d0, v0, k0, k1, dt, body, d, v, sc):
    """One step from (d0, v0) with kappa# k0 -> k1 of `stepping.Body` body in the water (module
    docstring); body.quad = (weights, rigidities, dof scales, `beam.fused.quadrature_tables`),
    body.load = (nzt, npt, law) (`fluid.shape_tables`, `Water.packed()`), body.th = (theta of
    the water force, theta of the stresses). d, v receive the result, from the predictor of
    `serpentine.kernels` (the constant-velocity configuration, or the start if its residual is
    far smaller). Of the two candidates the one the last step chose (sc's hint) is formed with
    its tangent, the other's residual alone, and its tangent only if it is chosen: the same
    bits as forming both (the hint orders the work, not the result). Converged as the
    serpentine's: a correction below tol, or, in the quadratic phase, the next one predicted
    below tol / 1000 from the last two. sc: `make_scratch` (no allocation here). Returns the
    Newton iterations, or minus the iterations spent on failure."""
    nzt, npt, law = body.load
    th = body.th[0]
    m_a = law[W_MA]
    u_scale, tab, tol = body.quad[2], body.quad[3], body.tol
    work, piv = sc[0], sc[1]
    ab, ab2, cm, buf, buf2, pre, p0 = sc[8], sc[9], sc[10], sc[11], sc[12], sc[15], sc[16]
    hint = sc[17]
    added_momentum(d0, v0, body.le, nzt, npt, m_a, p0, work, 0.0, 0.0)
    fused.start_strains(d0, body.le, k0, tab, pre)
    fused.scale_band(body.mass, 2.0 / (dt * dt), cm)
    # predictor (`serpentine.kernels`): the start d0 if its residual is below PREDICTOR_RATIO
    # times the constant-velocity d0 + dt v0's; its residual and tangent are the first
    # iteration's. The last step's choice first, with its tangent; the other's residual alone
    cv_first = hint[0] > 0.0
    predictor_into(d, d0, v0, dt, cv_first)
    _residual(d0, v0, d, k0, k1, dt, body, sc, buf, ab, v, True)
    tail_into(buf[2], buf[3], law, buf[0], ab, -th, -2.0 * th / dt)
    predictor_into(d, d0, v0, dt, not cv_first)
    _residual(d0, v0, d, k0, k1, dt, body, sc, buf2, ab2, v, False)
    tail_into(buf2[2], buf2[3], law, buf2[0], ab2, -th, -2.0 * th / dt)
    n_first, n_other = fused.scaled_norm2(buf[0], u_scale), fused.scaled_norm2(buf2[0], u_scale)
    if start_choice(n_first, n_other, cv_first, hint) == cv_first:
        predictor_into(d, d0, v0, dt, cv_first)
    else:  # the other (in d), with its tangent
        buf, ab = buf2, ab2
        _residual(d0, v0, d, k0, k1, dt, body, sc, buf, ab, v, True)
        tail_into(buf[2], buf[3], law, buf[0], ab, -th, -2.0 * th / dt)
    r, x = buf[0], buf[1]
    back1 = np.inf
    for it in range(1, body.max_iter + 1):
        if it > 1:
            _residual(d0, v0, d, k0, k1, dt, body, sc, buf, ab, v, True)
            tail_into(buf[2], buf[3], law, r, ab, -th, -2.0 * th / dt)
        if fused.solve(ab, r, work, piv, x) != 0:
            return -it
        step = correct(d, x, u_scale)
        if step < 0.0:
            return -it
        if converged(it, step, back1, tol):  # the serpentine's test
            end_velocity(d, d0, v0, dt, v)
            return it
        back1 = step
    return -body.max_iter


def make_scratch(n_dof: int, n_elements: int) -> tuple:
    """The scratch of `advance_linear` / `run` (the step allocates nothing): the band solver's
    (work, pivots), kappa# at the sub-step ends (n_el, 4) x 2, the states at the sub-step ends
    (n_dof) x 4 (the order `serpentine.stepping` unpacks), then `newton_scratch`'s."""
    return _scratch(int(n_dof), int(n_elements))


@numba.njit(cache=True, nogil=True)
def _scratch(n_dof, n_elements):
    ab, ab2, cm, buf, buf2, e11, ke, pre, p0, hint = newton_scratch(n_dof, n_elements)
    return (np.empty((n_dof, 3 * HALF_BW + 1)), np.empty(n_dof, np.int64),
            np.empty((n_elements, 4)), np.empty((n_elements, 4)), np.empty(n_dof),
            np.empty(n_dof), np.empty(n_dof), np.empty(n_dof), ab, ab2, cm, buf, buf2, e11,
            ke, pre, p0, hint)  # fmt: skip


@numba.njit(cache=True, nogil=True)
def newton_scratch(n_dof, n_elements):
    """`newton_step`'s arrays (no state: one set serves every row and step): two tangent bands
    and the inertia's, two sets of Newton vectors, the element vectors and matrix, the start's
    strains, the water's start momentum, and the predictor's hint (1,) (the last choice, 1.0
    for d0 + dt v0: it orders the predictor's work, no result depends on it)."""
    return (
        np.zeros((N_BAND, n_dof)),
        np.zeros((N_BAND, n_dof)),
        np.zeros((N_BAND, n_dof)),
        np.empty((4, n_dof)),
        np.empty((4, n_dof)),
        np.empty((5, 11)),
        np.empty((11, 11)),
        np.empty((n_elements, MAX_QUAD, fused.N_START)),
        np.empty(n_dof),
        np.zeros(1),
    )


# the step split on Newton failure (with the muscles' work) and the run under a wave gait
advance_linear, run = make_stepping(newton_step)
