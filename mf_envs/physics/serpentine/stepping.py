"""The time loop the crawling and the swimming beam share: a step split on Newton failure, with
the muscles' work, and a run under a wave gait, written once as templates and specialised per
model's Newton step (`make_stepping`; `mf_envs._jit.specialise`: numba cannot cache a function
that receives another jitted function as an argument).

A model gives its Newton step `newton(d0, v0, k0, k1, dt, body, d, v, sc)`: one step from
(d0, v0) with kappa# k0 -> k1 (n_el, 4) into d, v, returning the Newton iterations or minus
those spent on failure; body a `Body`, sc the model's scratch tuple whose entries 2-7 are the
arrays this loop uses (kappa# at the sub-step ends, the states at the sub-step ends).
`physics.serpentine.kernels` (ground) and `physics.swimmer.kernels` (water) are the two.
"""

from __future__ import annotations

from collections import namedtuple
from typing import Any

import numba
import numpy as np

from mf_envs._jit import specialise
from mf_envs.physics.beam import element as el
from mf_envs.physics.serpentine.gait import gait_kappa_into

Body = namedtuple("Body", "mass le quad load th tol max_iter max_halvings ei damping")
Body.__doc__ = """A beam body for the time loop: mass the banded mass matrix; le (n_el,) m the
element lengths; quad the model's quadrature tables; load its external law (the ground's or the
water's, as the model's kernels unpack it); th where the load (and the swimmer's stresses) are
taken in the step; tol, max_iter the Newton settings; max_halvings: a failed step is retried
as 2, 4, ... up to 2^max_halvings sub-steps; ei the bending stiffness EI [N m^2] (the muscles'
work); damping the Kelvin-Voigt retardation time [s] (0: elastic)."""


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
def muscle_work(d0, d1, k0, k1, le, ei):
    """The muscles' signed work [J] over a step from d0 (kappa# k0) to d1 (kappa# k1):
    -int M_el (k1 - k0) dS with the step's elastic moment M_el = EI ((kappa_0 - k0) + (kappa_1
    - k1)) / 2 (the algorithmic moment less any Kelvin-Voigt part: the damper acts on the total
    curvature rate, in parallel with the active spring, and does no work against kappa#)."""
    return -0.5 * (bending_work(d0, k0, k0, k1, le, ei) + bending_work(d1, k1, k0, k1, le, ei))


@numba.njit(cache=True, inline="always")
def correct(d, x, u_scale):
    """d += x (a Newton correction); returns max |x_i| / u_scale_i, or -1 if x is not finite
    (d then partly corrected: the step has failed)."""
    step = 0.0
    for i in range(d.shape[0]):
        if not np.isfinite(x[i]):
            return -1.0
        d[i] += x[i]
        step = max(step, abs(x[i]) / u_scale[i])
    return step


@numba.njit(cache=True, inline="always")
def converged(it, step, back1, tol):
    """Newton's convergence test: this correction below tol, or (quadratic phase, e_k+1 ~
    K e_k^2 with K from the last two corrections) the next one predicted below tol / 1000."""
    quad_next = it > 1 and step < back1 and step * step * step < 1e-3 * tol * back1 * back1
    return step < tol or quad_next


@numba.njit(cache=True, inline="always")
def end_velocity(d, d0, v0, dt, v):
    """v = v_{n+1} = 2 (d - d0) / dt - v0, the trapezoidal kinematics of the step."""
    for i in range(d.shape[0]):
        v[i] = 2.0 * (d[i] - d0[i]) / dt - v0[i]


def _advance_linear(d, v, ka, kb, dt, body, sc, out):
    """d, v over one step dt in place with kappa# linear in time from ka to kb (n_el, 4) (a
    commanded actuation held by a first-order hold), split into 2, 4, ... sub-steps on Newton
    failure; should even 2^max_halvings sub-steps fail, the splits again with the model's
    globalised Newton (a line search; models that have one). Returns the Newton iterations
    spent (failed attempts included), or -1 (d, v untouched) on failure.

    out[0] += the muscles' positive work [J] summed over the (sub)steps, out[1] += their signed
    work (`muscle_work`): the exact discrete balance dKE + dU + D = W_muscles + F_load . dd of
    the scheme (D >= 0 the Kelvin-Voigt dissipation)."""
    k0, k1, d0, v0, d1, v1 = sc[2:8]
    ne, ng = ka.shape
    total = 0
    for attempt in range(_ATTEMPTS):  # noqa: F821 (bound)
        for level in range(body.max_halvings + 1):
            n_sub = 2**level
            h = dt / n_sub
            for i in range(d.shape[0]):
                d0[i] = d[i]
                v0[i] = v[i]
            pos, signed = 0.0, 0.0
            ok = True
            for k in range(n_sub):
                s0, s1 = k / n_sub, (k + 1) / n_sub
                for e in range(ne):
                    for g in range(ng):
                        k0[e, g] = ka[e, g] + s0 * (kb[e, g] - ka[e, g])
                        k1[e, g] = ka[e, g] + s1 * (kb[e, g] - ka[e, g])
                if attempt == 0:
                    its = _newton(d0, v0, k0, k1, h, body, d1, v1, sc)  # noqa: F821 (bound)
                else:
                    its = _globalised(d0, v0, k0, k1, h, body, d1, v1, sc)  # noqa: F821
                total += abs(its)
                if its < 0:
                    ok = False
                    break
                w = muscle_work(d0, d1, k0, k1, body.le, body.ei)
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


def _run(d, v, dt, n_steps, every, body, gait, sc, d_out, v_out, work_out):
    """n_steps steps of dt from (d, v) at t = 0 in place under the wave gait (a, phi, w,
    t_ramp) (`serpentine.gait`, kappa# exact at each step's ends, linear between); every
    `every` steps (and at the start) the state goes to rows of d_out, v_out, the muscles'
    (positive, signed) work so far to work_out. Returns (Newton iterations, index of the failed
    step or -1)."""
    a_gp, phi_gp, w, t_ramp = gait
    ka, kb = np.empty(a_gp.shape), np.empty(a_gp.shape)  # kappa# at the step's ends
    acc = np.zeros(2)
    total, j = 0, 0
    d_out[0] = d
    v_out[0] = v
    for n in range(n_steps):
        gait_kappa_into(a_gp, phi_gp, w, t_ramp, n * dt, ka)
        gait_kappa_into(a_gp, phi_gp, w, t_ramp, (n + 1) * dt, kb)
        its = _advance(d, v, ka, kb, dt, body, sc, acc)  # noqa: F821 (bound)
        if its < 0:
            return total, n
        total += its
        if (n + 1) % every == 0 and j + 1 < d_out.shape[0]:
            j += 1
            d_out[j] = d
            v_out[j] = v
            work_out[j] = acc
    return total, -1


def make_stepping(newton: Any, globalised: Any = None) -> tuple[Any, Any]:
    """(advance_linear, run) on the model's Newton step (module doc) and, if it has one, its
    globalised Newton step (same signature; tried only where every split of the plain one
    failed), compiled and cached beside the model's module."""
    attempts = 1 if globalised is None else 2
    advance = specialise(_advance_linear, newton, "advance_linear", _newton=newton,
                         _globalised=newton if globalised is None else globalised,
                         _ATTEMPTS=attempts)  # fmt: skip
    return advance, specialise(_run, newton, "run", _advance=advance)
