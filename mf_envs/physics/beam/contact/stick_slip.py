"""Compiled quasi-static stick-slip of a beam on two friction feet (its end nodes).

One actuation increment kappa# k0 -> k1 of a beam whose tail (S = 0) and head (S = L) rest on
the ground and hold in x by friction (`friction`), in one compiled call (`increment`; a
sequence of them: `feet_step`): stick; else the slip onset on the stuck path (`_onset`), then
the slipping foot under its friction load, the normal load refreshed once; the tie rule. The
algorithm and its physics are documented in `feet`; this module is its compiled form (no
Python objects, failures as status codes), used by `FrictionFeet.step` and by the compiled
control steps of the robots standing on such feet (`mf_envs.physics.inchworm.quasistatic`).

Status codes: OK, NEWTON_FAILED (halving could not rescue Newton), NO_EQUILIBRIUM (both feet
over their limits beyond the tie tolerance). The report array has the feet's slots, then those
of the actuation of a control step that runs the increments (positive and net work,
increments), then the lambda* of the slip onsets.
"""

from __future__ import annotations

from collections import namedtuple

import numba
import numpy as np

from mf_envs.physics.beam import banded, static
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.contact.friction import (
    BACKWARD,
    FORWARD,
    friction_coefficient,
    holding_limit,
)

OK, NEWTON_FAILED, NO_EQUILIBRIUM = 0, 1, 2
TIE_TOLERANCE = 1e-2  # accepted relative excess of the other foot in a near tie
# Scratch.vec rows of this module (after static's own; ROW_DA: a control step's start)
_R0 = static.N_ROWS_OWN
ROW_TRIAL, ROW_DLO, ROW_DL, ROW_BEST = _R0, _R0 + 1, _R0 + 2, _R0 + 3
ROW_STAR, ROW_D1 = _R0 + 4, _R0 + 6  # two rows each: one per candidate foot
ROW_FA, ROW_FB, ROW_FEXT, ROW_ZERO, ROW_DA = _R0 + 8, _R0 + 10, _R0 + 12, _R0 + 13, _R0 + 14
ROW_DHI, ROW_GUESS1 = _R0 + 15, _R0 + 16
ROW_C, ROW_B, ROW_Y, ROW_Z = _R0 + 17, _R0 + 18, _R0 + 19, _R0 + 20  # the bordered onset's
EXTRA_ROWS = 21
# report slots: slip (2) [m], friction work [J], ground x (2) [N], normal (2) [N],
# slipping (2) direction, iterations, onsets, positive work [J], net work [J], increments
REP_SLIP, REP_FWORK, REP_GX, REP_N, REP_SLIPPING, REP_ITER, REP_ONSETS = 0, 2, 3, 5, 7, 9, 10
REP_POS, REP_NET, REP_INC = 11, 12, 13
N_REPORT = 14


def scratch(n_elements: int) -> static.Scratch:
    """Work arrays for one beam of n_elements."""
    return static.scratch(n_elements, EXTRA_ROWS)


@numba.njit(cache=True)
def _ground(d, kap, f_ext, xd, zd, bc, sc, rx, nz):
    """Ground forces on the feet: rx, nz (2,) [N] = (P(d) - F_ext) at the x and z dofs (only
    the end elements evaluated: `element.forces_at_into`)."""
    p = sc[0][static.ROW_P][:4]  # Newton's scratch row (as the full assembly used)
    el.forces_at_into(d, bc[0], kap, bc[1], bc[2], bc[3], (xd[0], xd[1], zd[0], zd[1]), p)
    for i in range(2):
        rx[i] = p[i] - f_ext[xd[i]]
        nz[i] = p[2 + i] - f_ext[zd[i]]


@numba.njit(cache=True, inline="always")
def _excess(mu4, rx, nz, g, i):
    """|R_x| - F_hold of foot i for the direction it is pulled in [N]."""
    s = BACKWARD if rx[i] > 0.0 else FORWARD
    return abs(rx[i]) - holding_limit(mu4, g[i], s, nz[i])


Increment = namedtuple("Increment", "k0 k1 f_ext g0 g1 xd zd mu4 bc sc")
Increment.__doc__ = """What the onset and slip searches of one `increment` share: kappa# k0 -> k1
(n_el, 4), the external load f_ext, engagements g0 -> g1 (2,), the feet's x and z dofs xd, zd,
the friction coefficients mu4, the beam constants bc and the scratch sc (as `increment`)."""


@numba.njit(cache=True)
def _onset(d, d_end, i, s, e1, slipping_i, fixed, inc, bracket_only=False):
    """lambda* in [0, 1] where foot i, pulled towards s, reaches its holding limit on the stuck
    path from d (lambda = 0) to d_end (lambda = 1), e1 > 0 the excess at d_end. Newton on
    (d, lambda) together (`_onset_bordered`) from regula falsi's first point on the chord of
    the bracket; should it fail (or with bracket_only), regula falsi with the Illinois
    modification on stuck solves (the algorithm of `feet`; each solve starts on the chord of
    the bracket's solutions). The configuration there goes to the ROW_STAR + i row. Returns
    (lambda*, ok, iterations)."""
    k0, k1, f_ext, g0, g1, xd, zd, mu4, bc, sc = inc
    vec, kap = sc[0], sc[4][1]
    zero, d_lo, dl, best_d = vec[ROW_ZERO], vec[ROW_DLO], vec[ROW_DL], vec[ROW_BEST]
    d_hi, guess1 = vec[ROW_DHI], vec[ROW_GUESS1]
    rx, nz = np.empty(2), np.empty(2)
    _ground(d, k0, f_ext, xd, zd, bc, sc, rx, nz)
    lo, hi, e_hi = 0.0, 1.0, e1
    e_lo = -s * rx[i] - holding_limit(mu4, g0[i], s, nz[i])
    if slipping_i == s or e_lo >= 0.0:
        vec[ROW_STAR + i][:] = d
        return 0.0, True, 0
    lam = min(max(e_lo / (e_lo - e_hi), 1e-6), 1.0 - 1e-6)  # regula falsi's first point
    for k in range(d.shape[0]):  # and the chord of the bracket's solutions there
        dl[k] = d[k] + lam * (d_end[k] - d[k])
    ok, iterations = False, 0
    if not bracket_only:
        lam, ok, iterations = _onset_bordered(lam, dl, i, s, fixed, inc)
    if ok:
        vec[ROW_STAR + i][:] = dl
        return lam, True, iterations
    d_lo[:] = d  # else bracket: regula falsi with the Illinois modification
    d_hi[:] = d_end
    best_e, best_lam = abs(e_lo), 0.0
    best_d[:] = d
    side = 0
    for _ in range(30):
        lam = lo + (hi - lo) * e_lo / (e_lo - e_hi)
        lam = min(max(lam, lo + 1e-6 * (hi - lo)), hi - 1e-6 * (hi - lo))
        w = (lam - lo) / (hi - lo)  # start Newton on the chord of the bracket's solutions
        for k in range(d.shape[0]):
            guess1[k] = d_lo[k] + w * (d_hi[k] - d_lo[k])
        ok, it, _h = static.linear_path(
            d_lo, k0, k1, lo, lam, f_ext, zero, zero, fixed, bc, sc, dl, guess1
        )
        iterations += it
        if not ok:
            return 0.0, False, iterations
        static.lerp_into(k0, k1, lam, kap)
        _ground(dl, kap, f_ext, xd, zd, bc, sc, rx, nz)
        e = -s * rx[i] - holding_limit(mu4, g0[i] + lam * (g1[i] - g0[i]), s, nz[i])
        if abs(e) < best_e:
            best_e, best_lam = abs(e), lam
            best_d[:] = dl
        if e <= 0.0:  # Illinois: halve the stale end's excess when the same side repeats
            if side < 0:
                e_hi *= 0.5
            lo, e_lo, side = lam, e, -1
            d_lo[:] = dl
        else:
            if side > 0:
                e_lo *= 0.5
            hi, e_hi, side = lam, e, 1
            d_hi[:] = dl
        if abs(e) < 1e-9 * max(abs(nz[i]), 1e-12) or hi - lo < 1e-12:
            break
    vec[ROW_STAR + i][:] = best_d
    return best_lam, True, iterations


@numba.njit(cache=True)
def _onset_bordered(lam, d, i, s, fixed, inc):
    """Newton on the stuck configuration d and the onset lambda together: the equilibrium on
    the free dofs, P(d, kappa#(lambda)) = F, bordered by the onset condition e(d, lambda) =
    -s R_x,i - mu(g_i(lambda)) max(N_i, 0) = 0. Per iteration one tangent K, one LDL^T and two
    solves: K y = F - P, K z = dP/dlambda (`element.actuation_load_into`, psi dofs only), then
    dlambda = -(e + c.y) / (de/dlambda - c.z) with c = de/dd = -s K[x_i, :] - mu K[z_i, :] (the
    unconstrained rows of the foot's dofs) and dd = y - z dlambda. From a start on the chord
    of the bracket it converges quadratically, where the bracketing search needs a stuck
    solve per trial lambda. d (the start) is updated in place. Returns (lambda, ok,
    iterations); not ok when it fails to converge inside (0, 1) within max_iter iterations or
    the tangent is not positive definite (the caller brackets instead)."""
    k0, k1, f_ext, g0, g1, xd, zd, mu4, bc, sc = inc
    le, qxi, qw, stiff, u_scale, dtol, max_iter = bc[0], bc[1], bc[2], bc[3], bc[4], bc[9], bc[10]
    vec, ab, work, kap, dk = sc[0], sc[1], sc[2], sc[4][1], sc[4][2]
    p, r = vec[static.ROW_P], vec[static.ROW_R]
    c, b, y, z = vec[ROW_C], vec[ROW_B], vec[ROW_Y], vec[ROW_Z]
    nd, hb = d.shape[0], el.HALF_BW
    xi, zi = xd[i], zd[i]
    for e in range(dk.shape[0]):
        for q in range(dk.shape[1]):
            dk[e, q] = k1[e, q] - k0[e, q]
    el.actuation_load_into(le, qxi, qw, stiff, dk, b)
    for j in range(nd):
        if fixed[j]:
            b[j] = 0.0
    f_ref, tol_r = static.residual_scale(d, f_ext, bc)
    dg = g1[i] - g0[i]
    dmu_dg = (mu4[0] - mu4[2]) if s == FORWARD else (mu4[1] - mu4[3])
    for it in range(1, max_iter + 1):
        static.lerp_into(k0, k1, lam, kap)
        el.assemble_into(d, le, kap, qxi, qw, stiff, True, p, ab)
        g = g0[i] + lam * dg
        nz = p[zi] - f_ext[zi]
        e = -s * (p[xi] - f_ext[xi]) - holding_limit(mu4, g, s, nz)
        mu_n = friction_coefficient(mu4, g, s) if nz > 0.0 else 0.0
        # kappa# loads only psi dofs (b = 0 at x_i, z_i): e depends on lambda through mu(g)
        de_dlam = -dmu_dg * dg * max(nz, 0.0)
        c[:] = 0.0
        for j in range(max(0, xi - hb), min(nd, xi + hb + 1)):
            c[j] -= s * ab[hb + xi - j, j]
        for j in range(max(0, zi - hb), min(nd, zi + hb + 1)):
            c[j] -= mu_n * ab[hb + zi - j, j]
        res = 0.0
        for j in range(nd):
            r[j] = f_ext[j] - p[j]
            if fixed[j]:
                c[j] = 0.0
        banded.constrain_band(ab, r, fixed)
        for j in range(nd):
            res = max(res, abs(r[j] * u_scale[j]))
        res /= f_ref
        if not (np.isfinite(res) and np.isfinite(e)) or banded.band_ldl_factor(ab, work) != 0:
            return lam, False, it
        banded.band_ldl_solve(work, r, y)
        banded.band_ldl_solve(work, b, z)
        cy, cz = 0.0, 0.0
        for j in range(nd):
            cy += c[j] * y[j]
            cz += c[j] * z[j]
        dlam = -(e + cy) / (de_dlam - cz)
        if not np.isfinite(dlam):
            return lam, False, it
        step = 0.0
        for j in range(nd):
            dj = y[j] - z[j] * dlam
            d[j] += dj
            step = max(step, abs(dj / u_scale[j]))
        lam += dlam
        if not 0.0 < lam < 1.0:
            return lam, False, it
        small_e = abs(e) < 1e-9 * max(abs(nz), 1e-12)
        if res < tol_r and small_e and (step < dtol or res < 1e-2 * tol_r) and abs(dlam) < dtol:
            return lam, True, it
    return lam, False, max_iter


@numba.njit(cache=True)
def _slip(i, s, lam, n_trial, inc, rx1, n1):
    """Foot i slips towards s from lambda to 1 from the ROW_STAR + i configuration, the other
    stuck (the algorithm of `feet`): d1 into ROW_D1 + i, friction loads into ROW_FA + i and
    ROW_FB + i, ground forces into rx1, n1. Returns (violation of the other foot's limit [N],
    ok, iterations)."""
    k0, k1, f_ext, g0, g1, xd, zd, mu4, bc, sc = inc
    vec, kap = sc[0], sc[4][1]
    d_star, d1 = vec[ROW_STAR + i], vec[ROW_D1 + i]
    fa, fb, fext = vec[ROW_FA + i], vec[ROW_FB + i], vec[ROW_FEXT]
    nd = d1.shape[0]
    fixed = np.zeros(nd, np.bool_)
    fixed[zd[0]] = True
    fixed[zd[1]] = True
    fixed[xd[1 - i]] = True
    static.lerp_into(k0, k1, lam, kap)
    rx, n0 = np.empty(2), np.empty(2)
    _ground(d_star, kap, f_ext, xd, zd, bc, sc, rx, n0)
    fa[:] = 0.0
    fb[:] = 0.0
    fa[xd[i]] = -s * holding_limit(mu4, g0[i] + lam * (g1[i] - g0[i]), s, n0[i])
    fb[xd[i]] = -s * holding_limit(mu4, g1[i], s, n_trial)
    ok, iterations, _h = static.linear_path(
        d_star, k0, k1, lam, 1.0, f_ext, fa, fb, fixed, bc, sc, d1
    )
    if not ok:
        return 0.0, False, iterations
    fext[:] = f_ext + fb
    _ground(d1, k1, fext, xd, zd, bc, sc, rx1, n1)
    if abs(n1[i] - n_trial) > 1e-9 * max(abs(n_trial), 1e-12):  # refresh N at the end once
        fext[:] = fb  # the first end load; continue from d1 in the friction load alone (the
        # end equilibrium does not depend on the load path: a few Newton iterations instead
        # of the whole slip path again)
        fb[xd[i]] = -s * holding_limit(mu4, g1[i], s, n1[i])
        ok, it, _h = static.linear_path(d1, k1, k1, 0.0, 1.0, f_ext, fext, fb, fixed, bc, sc, d1)
        iterations += it
        if not ok:
            return 0.0, False, iterations
        fext[:] = f_ext + fb
        _ground(d1, k1, fext, xd, zd, bc, sc, rx1, n1)
    rx1[i] = fb[xd[i]]  # the ground force on the slipping foot is the friction
    j = 1 - i
    s_j = BACKWARD if rx1[j] > 0.0 else FORWARD
    return abs(rx1[j]) - holding_limit(mu4, g1[j], s_j, n1[j]), True, iterations


@numba.njit(cache=True)
def increment(d, k0, k1, f_ext, g0, g1, slipping, xd, zd, mu4, bc, sc, rep, out):
    """One actuation increment kappa# k0 -> k1 (n_el, 4) [1/m], engagements g0 -> g1 (2,), d
    converged at k0 (the algorithm of `feet`): the configuration at k1 into out, slipping (2,)
    int updated, rep (>= N_REPORT,) accumulated (the lambda* of each slip onset after the
    N_REPORT slots while rep has room). Returns a status code."""
    inc = Increment(k0, k1, f_ext, g0, g1, xd, zd, mu4, bc, sc)
    vec = sc[0]
    nd = d.shape[0]
    zero, trial = vec[ROW_ZERO], vec[ROW_TRIAL]
    zero[:] = 0.0
    both = np.zeros(nd, np.bool_)
    for i in range(2):
        both[zd[i]] = True
        both[xd[i]] = True
    ok, it, _h = static.linear_path(d, k0, k1, 0.0, 1.0, f_ext, zero, zero, both, bc, sc, trial)
    rep[REP_ITER] += it
    if not ok:
        return NEWTON_FAILED
    rx, n = np.empty(2), np.empty(2)
    _ground(trial, k1, f_ext, xd, zd, bc, sc, rx, n)
    e = np.array([_excess(mu4, rx, n, g1, 0), _excess(mu4, rx, n, g1, 1)])
    if e[0] <= 0.0 and e[1] <= 0.0:
        slipping[:] = 0
        out[:] = trial
        _finish(rep, rx, n, slipping)
        return OK
    pulls = np.array([BACKWARD if rx[0] > 0.0 else FORWARD, BACKWARD if rx[1] > 0.0 else FORWARD])
    lams = np.full(2, np.inf)
    for i in range(2):
        if e[i] > 0.0:
            lam, ok, it = _onset(d, trial, i, pulls[i], e[i], slipping[i], both, inc)
            rep[REP_ITER] += it
            if not ok:
                return NEWTON_FAILED
            lams[i] = lam
    order = (0, 1) if lams[0] <= lams[1] else (1, 0)  # a stable sort of the candidates
    best_rel, best_i = np.inf, -1
    rx1, n1 = np.empty(2), np.empty(2)
    best_rx, best_n = np.empty(2), np.empty(2)
    for i in order:
        if not np.isfinite(lams[i]):
            continue
        viol, ok, it = _slip(i, pulls[i], lams[i], n[i], inc, rx1, n1)
        rep[REP_ITER] += it
        if not ok:
            return NEWTON_FAILED
        limit = abs(rx1[1 - i]) - viol
        rel = viol / max(limit, 1e-300)
        if best_i < 0 or rel < best_rel:
            best_rel, best_i = rel, i
            best_rx[:] = rx1
            best_n[:] = n1
        if viol <= 1e-9 * max(abs(n1[1 - i]), 1e-12):
            break
    i = best_i
    if best_rel > TIE_TOLERANCE:
        return NO_EQUILIBRIUM
    if slipping[i] != pulls[i]:  # lambda* kept after the report slots while there is room
        k = N_REPORT + int(rep[REP_ONSETS])
        if k < rep.shape[0]:
            rep[k] = lams[i]
        rep[REP_ONSETS] += 1
    d1, d_star = vec[ROW_D1 + i], vec[ROW_STAR + i]
    dx = d1[xd[i]] - d_star[xd[i]]
    rep[REP_SLIP + i] += dx
    rep[REP_FWORK] += 0.5 * (vec[ROW_FA + i][xd[i]] + vec[ROW_FB + i][xd[i]]) * dx
    slipping[:] = 0
    slipping[i] = pulls[i]
    out[:] = d1
    _finish(rep, best_rx, best_n, slipping)
    return OK


@numba.njit(cache=True, inline="always")
def _finish(rep, rx, n, slipping):
    for k in range(2):
        rep[REP_GX + k] = rx[k]
        rep[REP_N + k] = n[k]
        rep[REP_SLIPPING + k] = slipping[k]


@numba.njit(cache=True)
def feet_step(d, kg, f_ext, gs, slipping, xd, zd, mu4, bc, sc, rep, ds):
    """Increments kg[0] -> kg[1] -> ... ((n + 1, n_el, 4) [1/m]) with the engagements gs
    ((n + 1, 2)) from d: the configurations after each increment into ds (n, n_dof); rep
    accumulated. Returns a status code (the increments done so far are in ds)."""
    n = kg.shape[0] - 1
    for j in range(n):
        start = d if j == 0 else ds[j - 1]
        status = increment(
            start,
            kg[j],
            kg[j + 1],
            f_ext,
            gs[j],
            gs[j + 1],
            slipping,
            xd,
            zd,
            mu4,
            bc,
            sc,
            rep,
            ds[j],
        )
        if status != OK:
            return status
    return OK
