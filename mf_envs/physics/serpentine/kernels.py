"""Compiled time loop of the serpentine beam: the energy-momentum step of `beam.dynamics` (Simo &
Tarnow 1992; `beam.algorithmic`) with the ground as a configuration- and velocity-dependent
distributed load, solved by Newton with its consistent tangent.

Unknown d = d_{n+1}; v_{n+1} = 2 (d - d_n) / dt - v_n (trapezoidal kinematics). Residual

    R(d) = (2 / dt^2) M (d - d_n - dt v_n) + Pbar(d_n, d) - F_g(d_th, v_th),
    d_th = d_n + th (d - d_n),  v_th = (1 - th) v_n + th v_{n+1},

tangent dR/dd = (2 / dt^2) M + dPbar/dd - th dF_g/dd - (2 th / dt) dF_g/dv. Pbar (the
algorithmic internal force, active curvature kappa# at t_n and t_{n+1}) makes the step conserve
linear and angular momentum and, with F_g = 0 and a constant kappa#, the energy (to the Newton
tolerance). The ground force is evaluated at th in [1/2, 1]:

* th = 1 (default): the ground force at the end of the step. Regularised Coulomb friction is
  stiff in the slip speed (df/dv ~ mu p / v_eps, a relaxation time v_eps / (mu g) ~ 1e-4 s
  with v_eps = 0.1 mm/s), far below any useful step; implicit Euler on it is L-stable, so a
  body that stops slipping stops (no velocity chatter), at a first-order error in a bounded
  force.
* th = 1/2: the midpoint. The ground's discrete work is dt F_g(v_mid) . v_mid <= 0, an exact
  discrete energy balance, but v_{n+1} = 2 v_mid - v_n rings (sign flips) while a point sticks.

A step whose Newton fails is retried as 2, 4, ... sub-steps (actuation interpolated exactly:
kappa# is a function of t), at most 2^max_halvings.
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.algorithmic import assemble_algorithmic
from mf_envs.physics.beam.banded import HALF_BW, band_solve_into
from mf_envs.physics.serpentine.friction import assemble_ground
from mf_envs.physics.serpentine.gait import gait_kappa_into


@numba.njit(cache=True)
def _newton_step(d0, v0, k0, k1, dt, mass, le, quad, ground, th, tol, max_iter, d, v, work, piv):
    """One step from (d0, v0) with kappa# k0 -> k1 (module docstring). d, v receive the result,
    from the constant-velocity predictor d = d0 + dt v0. Returns the Newton iterations, or -1
    on failure."""
    for i in range(d0.shape[0]):
        d[i] = d0[i] + dt * v0[i]  # predictor: constant velocity
    qxi, qw, stiff, u_scale = quad
    p, m_a, law = ground
    nd = d0.shape[0]
    shift = np.zeros((le.shape[0], qxi.shape[0], 3))
    c_a = 2.0 / (dt * dt)
    r = np.empty(nd)
    x = np.empty(nd)
    dth = np.empty(nd)
    vth = np.empty(nd)
    for it in range(1, max_iter + 1):
        pbar, ab, _ = assemble_algorithmic(d0, d, le, k0, k1, qxi, qw, stiff, 0.5, shift, True, 1.0)
        for i in range(nd):
            x[i] = d[i] - d0[i] - dt * v0[i]
            v[i] = 2.0 * (d[i] - d0[i]) / dt - v0[i]
            dth[i] = d0[i] + th * (d[i] - d0[i])
            vth[i] = (1.0 - th) * v0[i] + th * v[i]
            r[i] = -pbar[i]
        for j in range(nd):  # r -= c_a M x; ab += c_a M
            for i in range(max(0, j - HALF_BW), min(nd, j + HALF_BW + 1)):
                mij = mass[HALF_BW + i - j, j]
                r[i] -= c_a * mij * x[j]
                ab[HALF_BW + i - j, j] += c_a * mij
        assemble_ground(dth, vth, le, p, m_a, law, r, ab, -th, -2.0 * th / dt)
        if band_solve_into(ab, r, work, piv, x) != 0:
            return -1
        step = 0.0
        for i in range(nd):
            if not np.isfinite(x[i]):
                return -1
            d[i] += x[i]
            step = max(step, abs(x[i]) / u_scale[i])
        if step < tol:
            for i in range(nd):
                v[i] = 2.0 * (d[i] - d0[i]) / dt - v0[i]
            return it
    return -1


@numba.njit(cache=True)
def advance(d, v, t, dt, mass, le, quad, ground, gait, th, tol, max_iter, max_halvings, scratch):
    """d, v at t -> t + dt in place, splitting the step on Newton failure. Returns the Newton
    iterations used, or -1 if even 2^max_halvings sub-steps failed."""
    a_gp, phi_gp, w, t_ramp = gait
    work, piv, k0, k1, d0, v0, d1, v1 = scratch
    for level in range(max_halvings + 1):
        n_sub = 2**level
        h = dt / n_sub
        for i in range(d.shape[0]):
            d0[i] = d[i]
            v0[i] = v[i]
        total = 0
        ok = True
        for k in range(n_sub):
            gait_kappa_into(a_gp, phi_gp, w, t_ramp, t + k * h, k0)
            gait_kappa_into(a_gp, phi_gp, w, t_ramp, t + (k + 1) * h, k1)
            its = _newton_step(
                d0, v0, k0, k1, h, mass, le, quad, ground, th, tol, max_iter, d1, v1, work, piv
            )
            if its < 0:
                ok = False
                break
            total += its
            for i in range(d.shape[0]):
                d0[i] = d1[i]
                v0[i] = v1[i]
        if ok:
            for i in range(d.shape[0]):
                d[i] = d0[i]
                v[i] = v0[i]
            return total
    return -1


@numba.njit(cache=True)
def run(
    d,
    v,
    t0,
    dt,
    n_steps,
    every,
    mass,
    le,
    quad,
    ground,
    gait,
    th,
    tol,
    max_iter,
    max_halvings,
    d_out,
    v_out,
    t_out,
):
    """n_steps steps of dt from (d, v) at t0 (in place); every `every` steps (and at the start)
    the state goes to row j of d_out, v_out (rows, n_dof) and t_out. Returns (total Newton
    iterations, index of the failed step or -1)."""
    nd = d.shape[0]
    ne = le.shape[0]
    scratch = (
        np.empty((nd, 3 * HALF_BW + 1)),
        np.empty(nd, np.int64),
        np.empty((ne, 4)),
        np.empty((ne, 4)),
        np.empty(nd),
        np.empty(nd),
        np.empty(nd),
        np.empty(nd),
    )
    total = 0
    j = 0
    for i in range(nd):
        d_out[0, i] = d[i]
        v_out[0, i] = v[i]
    t_out[0] = t0
    for n in range(n_steps):
        t = t0 + n * dt
        its = advance(
            d, v, t, dt, mass, le, quad, ground, gait, th, tol, max_iter, max_halvings, scratch
        )
        if its < 0:
            return total, n
        total += its
        if (n + 1) % every == 0 and j + 1 < t_out.shape[0]:
            j += 1
            for i in range(nd):
                d_out[j, i] = d[i]
                v_out[j, i] = v[i]
            t_out[j] = t0 + (n + 1) * dt
    return total, -1


@numba.njit(cache=True)
def bending_work(d, k, ka, kb, le, ei):
    """int EI (kappa(d) - k) (kb - ka) dS at the 4 Gauss points [J]: M3 at d with kappa# = k
    times a change kb - ka of kappa#."""
    acc = 0.0
    for e in range(le.shape[0]):
        for g in range(4):
            kap = el.kappa_at(d, 6 * e, le[e], el.GAUSS_XI[g])
            acc += el.GAUSS_W[g] * le[e] * (kap - k[e, g]) * (kb[e, g] - ka[e, g])
    return ei * acc


@numba.njit(cache=True)
def advance_linear(
    d, v, ka, kb, dt, mass, le, quad, ground, th, tol, max_iter, max_halvings, scratch, ei, out
):
    """d, v over one step dt in place with kappa# linear in time from ka to kb (n_el, 4) (a
    commanded actuation held by a first-order hold), splitting the step on Newton failure as
    `advance`. Returns the Newton iterations used, or -1 (d, v untouched) on failure.

    out[0] += the muscles' positive work [J] summed over the (sub)steps, out[1] += their signed
    work: -int sigma_3 (k1 - k0) dS with the step's algorithmic moment sigma_3 = EI ((kappa_0
    - k0) + (kappa_1 - k1)) / 2 (`beam.algorithmic`, theta = 1/2), the exact discrete balance
    dKE + dU = W_muscles + F_ground . dd of the scheme (EI: the bending stiffness [N m^2])."""
    work, piv, k0, k1, d0, v0, d1, v1 = scratch
    ne, ng = ka.shape
    for level in range(max_halvings + 1):
        n_sub = 2**level
        h = dt / n_sub
        for i in range(d.shape[0]):
            d0[i] = d[i]
            v0[i] = v[i]
        total, pos, signed = 0, 0.0, 0.0
        ok = True
        for k in range(n_sub):
            s0, s1 = k / n_sub, (k + 1) / n_sub
            for e in range(ne):
                for g in range(ng):
                    k0[e, g] = ka[e, g] + s0 * (kb[e, g] - ka[e, g])
                    k1[e, g] = ka[e, g] + s1 * (kb[e, g] - ka[e, g])
            its = _newton_step(
                d0, v0, k0, k1, h, mass, le, quad, ground, th, tol, max_iter, d1, v1, work, piv
            )
            if its < 0:
                ok = False
                break
            total += its
            w = -0.5 * (bending_work(d0, k0, k0, k1, le, ei) + bending_work(d1, k1, k0, k1, le, ei))
            pos += max(w, 0.0)
            signed += w
            for i in range(d.shape[0]):
                d0[i] = d1[i]
                v0[i] = v1[i]
        if ok:
            for i in range(d.shape[0]):
                d[i] = d0[i]
                v[i] = v0[i]
            out[0] += pos
            out[1] += signed
            return total
    return -1


def make_scratch(n_dof: int, n_elements: int) -> tuple:
    """The scratch arrays of `advance` / `advance_linear` for a beam of n_elements."""
    return (
        np.empty((n_dof, 3 * HALF_BW + 1)),
        np.empty(n_dof, np.int64),
        np.empty((n_elements, 4)),
        np.empty((n_elements, 4)),
        np.empty(n_dof),
        np.empty(n_dof),
        np.empty(n_dof),
        np.empty(n_dof),
    )
