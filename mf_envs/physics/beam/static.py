"""Compiled quasi-static solves of the active C1 beam: Newton-Raphson and linear load paths.

The same algorithm as `solver.newton` and `solver.solve_static_path` (Eqs. 93-98: the seed's
two-part convergence test, step halving, secant predictor), compiled for the common case of a
load that is linear along the path and no configuration-dependent extra load:

    kappa#(mu) = k0 + (lam0 + mu (lam1 - lam0)) (k1 - k0),   F(mu) = F_base + Fa + mu (Fb - Fa),

mu from 0 to 1. This is the inner loop of the inchworm (every actuation increment, every slip
onset search, every friction solve), so nothing here allocates: the caller passes a `Scratch`
(`scratch(model)`) and the beam's constants (`constants(model, settings)`). Failures come back
as flags (no exceptions inside compiled code); the Python wrappers raise.

Hand-written: no library solves the nonlinear banded equilibrium of this element from compiled
code; the linear solves are `banded.band_spd_solve_into` (banded LDL^T, the tangent of a stable
configuration is positive definite) with `banded.band_solve_into` (pivoting LU) as fallback.
"""

from __future__ import annotations

from typing import NamedTuple

import numba
import numpy as np

from mf_envs.physics.beam import banded
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.solver import NewtonDivergence

# rows of Scratch.vec (each (n_dof,)): Newton's, the path's, then free for callers
ROW_P, ROW_R, ROW_DELTA, ROW_D, ROW_DPREV, ROW_GUESS, ROW_F = range(7)
N_ROWS_OWN = 7
EPS = float(np.finfo(float).eps)


class Scratch(NamedTuple):
    """Work arrays of one beam: vec (rows, n_dof); ab (21, n_dof); work (n_dof, 31); piv
    (n_dof,) int; kap (3, n_el, 4) for load curvatures."""

    vec: np.ndarray
    ab: np.ndarray
    work: np.ndarray
    piv: np.ndarray
    kap: np.ndarray


def scratch(n_elements: int, extra_rows: int = 0) -> Scratch:
    """Scratch for a beam of n_elements, with extra_rows free rows of vec for the caller."""
    nd = el.n_dof(n_elements)
    return Scratch(
        np.zeros((N_ROWS_OWN + extra_rows, nd)),
        np.zeros((el.N_BAND, nd)),
        np.zeros((nd, 3 * el.HALF_BW + 1)),
        np.zeros(nd, np.int64),
        np.zeros((3, n_elements, el.N_GAUSS)),
    )


def constants(model, settings) -> tuple:
    """The beam's constants for the compiled solves: (le, qxi, qw, stiff, u_scale, EI / L,
    max(EA, GA_s) L, L, rtol, dtol, max_iter, max_halvings) from a `solver.BeamModel` and
    `solver.NewtonSettings`."""
    p = model.params
    qxi, qw, stiff = model.quad
    return (
        model.le,
        qxi,
        qw,
        stiff,
        model.u_scale,
        p.EI / p.length,
        max(p.EA, p.GAs) * p.length,
        float(p.length),
        float(settings.rtol),
        float(settings.dtol),
        int(settings.max_iter),
        int(settings.max_halvings),
    )


@numba.njit(cache=True, inline="always")
def lerp_into(k0, k1, lam, out):
    """out = k0 + lam (k1 - k0) for (n_el, 4) curvature tables, without temporaries."""
    for e in range(k0.shape[0]):
        for g in range(k0.shape[1]):
            out[e, g] = k0[e, g] + lam * (k1[e, g] - k0[e, g])


@numba.njit(cache=True, inline="always")
def residual_scale(d, f, bc):
    """(f_ref, tol_r) of the seed's convergence test (Eqs. 96-98) at the start d under the
    load f: residuals are measured as max |r u_scale| / f_ref against tol_r, raised above
    rtol to what round-off allows at the configuration's reach."""
    u_scale, ei_l, rigid_l, length, rtol = bc[4], bc[5], bc[6], bc[7], bc[8]
    nd = d.shape[0]
    fmax = 0.0
    for i in range(nd):
        fmax = max(fmax, abs(f[i] * u_scale[i]))
    f_ref = ei_l + fmax
    reach = 1.0
    for i in range(0, nd, 6):
        reach = max(reach, abs(d[i]) / length, abs(d[i + 2]) / length)
    return f_ref, max(rtol, 256.0 * EPS * rigid_l * reach / f_ref)


@numba.njit(cache=True)
def newton(d, kap, f, fixed, bc, sc):
    """Newton-Raphson for F - P(d) = 0 on the free dofs, in place on d (the start, prescribed
    dofs at their values); kap (n_el, 4) [1/m], f (n_dof,) dead nodal loads, fixed (n_dof,)
    bool. Returns (converged, iterations): `solver.newton` with dyn = extra = None, except
    that an iterate whose residual is already below 1e-2 rtol is returned as it is (the
    seed's test accepts it whatever the step; solving for a round-off correction is skipped)."""
    le, qxi, qw, stiff, u_scale, dtol, max_iter = bc[0], bc[1], bc[2], bc[3], bc[4], bc[9], bc[10]
    vec, ab, work, piv = sc[0], sc[1], sc[2], sc[3]
    p, r, delta = vec[ROW_P], vec[ROW_R], vec[ROW_DELTA]
    nd = d.shape[0]
    f_ref, tol_r = residual_scale(d, f, bc)
    res_first = np.inf
    for it in range(1, max_iter + 1):
        el.assemble_into(d, le, kap, qxi, qw, stiff, True, p, ab)
        for i in range(nd):
            r[i] = f[i] - p[i]
        banded.constrain_band(ab, r, fixed)
        res = banded.scaled_residual(r, u_scale, f_ref)
        if it == 1:
            res_first = res
        if not np.isfinite(res) or (it >= 3 and res > 1e3 * max(res_first, tol_r)):
            return False, it
        if res < 1e-2 * tol_r:  # converged whatever the step (the test below): skip the solve
            return True, it
        # LDL^T for the (usual) positive definite tangent, else the pivoting LU
        if banded.band_spd_solve_into(ab, r, work, delta) != 0:
            if banded.band_solve_into(ab, r, work, piv, delta) != 0:
                return False, it
        step = 0.0
        for i in range(nd):
            d[i] += delta[i]
            step = max(step, abs(delta[i] / u_scale[i]))
        if not np.isfinite(step):
            return False, it
        if res < tol_r and (step < dtol or res < 1e-2 * tol_r):
            return True, it
    return False, max_iter


@numba.njit(cache=True)
def linear_path(d0, k0, k1, lam0, lam1, f_base, fa, fb, fixed, bc, sc, out, guess1=None):
    """Quasi-static path mu = 0 -> 1 of the linear load (module docstring) from d0 (converged
    at mu = 0) into out (n_dof,) (may be d0); step halving on Newton failure, secant
    predictor. guess1: an optional start for the first (full) step, e.g. an interpolation
    between known solutions (Newton retries from d0 if it fails from there). Returns (ok,
    iterations, halvings): `solver.solve_static_path`."""
    max_iter, max_halvings = bc[10], bc[11]
    vec, kap = sc[0], sc[4][0]
    d, dp, guess, f = vec[ROW_D], vec[ROW_DPREV], vec[ROW_GUESS], vec[ROW_F]
    nd = d0.shape[0]
    d[:] = d0
    lam, h, h_prev, has_prev = 0.0, 1.0, 1.0, False
    min_h = 0.5**max_halvings
    iterations, halvings = 0, 0
    while lam < 1.0 - 1e-14:
        h = min(h, 1.0 - lam)
        first = guess1 is not None and not has_prev and h == 1.0
        for i in range(nd):
            guess[i] = d[i] + (d[i] - dp[i]) * (h / h_prev) if has_prev else d[i]
            if first:
                guess[i] = guess1[i]
            if fixed[i]:
                guess[i] = d[i]
        mu = lam + h
        lk = lam0 + mu * (lam1 - lam0)
        lerp_into(k0, k1, lk, kap)
        for i in range(nd):
            f[i] = f_base[i] + fa[i] + mu * (fb[i] - fa[i])
        ok, it = newton(guess, kap, f, fixed, bc, sc)
        if not ok and (has_prev or first):  # retry without the predictor
            guess[:] = d
            ok, it = newton(guess, kap, f, fixed, bc, sc)
        iterations += it
        if not ok:
            h *= 0.5
            halvings += 1
            if h < min_h:
                return False, iterations, halvings
            continue
        dp[:] = d
        d[:] = guess
        h_prev = h
        has_prev = True
        lam += h
        if it <= max_iter // 2:
            h = min(2.0 * h, 1.0)
    out[:] = d
    return True, iterations, halvings


def solve_linear_path(
    model,
    d0: np.ndarray,
    k0: np.ndarray,
    k1: np.ndarray,
    f_ext: np.ndarray,
    fixed: np.ndarray,
    settings,
    sc: Scratch | None = None,
) -> tuple[np.ndarray, int, int]:
    """Quasi-static path kappa# k0 -> k1 ((n_el, 4) [1/m]) under the dead load f_ext from d0
    (converged at k0) with the prescribed dofs `fixed`: (d, Newton iterations, halvings).
    Raises solver.NewtonDivergence when halving cannot rescue Newton."""
    sc = sc if sc is not None else scratch(model.n_elements)
    zero = np.zeros(model.n_dof)
    out = np.empty(model.n_dof)
    ok, iterations, halvings = linear_path(
        np.asarray(d0, float),
        np.ascontiguousarray(k0, float),
        np.ascontiguousarray(k1, float),
        0.0,
        1.0,
        np.asarray(f_ext, float),
        zero,
        zero,
        np.asarray(fixed, np.bool_),
        constants(model, settings),
        sc,
        out,
    )
    if not ok:
        raise NewtonDivergence(f"Newton failed after {halvings} halvings of the load step")
    return out, iterations, halvings
