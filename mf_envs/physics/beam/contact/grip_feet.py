"""Compiled quasi-static increment of a beam on two feet that must grip: the
regularised friction law of `grip.GripLaw` at the end nodes, solved together with the beam.

Why not `stick_slip`: in its rate-independent Coulomb law the foot with the lower holding limit
slips and the other holds however small the difference, so a 1 % difference in engagement
decides which foot anchors. Here each foot's ground force is the regularised law of `grip`
(force on a foot of normal load N moving at v = u / h, u its x-displacement in the increment of
duration h):

    F(u) = -N [ mu_s v / sqrt(v^2 + v_s^2) + phi(g) (mu_grip(s) - mu_s) v / sqrt(v^2 + v_g^2) ]

(phi the C1 smoothstep from the engagement threshold g_th to g_th + width, s = sign v): below the
threshold a foot slides on its isotropic smooth face (mu_s), above it the grip's anisotropic
surplus is added. The increment's equilibrium P(d, kappa#) = F_ext + F_feet(d) on every dof but
the feet's z (held on the ground, Eq. 100a) is one smooth nonlinear system: Newton with the
full Jacobian, the law's -dF/du (>= 0) on the feet's x diagonal and -(F / N) dN/dd on their x
rows (N = the feet's z reaction P_z - F_ext,z, so dN/dd is the tangent's z row; the matrix is
then not symmetric: banded LU), halving the increment when Newton fails. One well-posed
solution for any engagements: both terms are odd and increasing in v. The feet's steps are
controlled (the law saturates) and the first solve holds them where their last velocities take
them (`increment`).

law = (threshold, width, mu_slide, grip_forward, grip_backward, v_slide [m/s], v_grip [m/s]),
`GripLaw.kernel_args()`.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs.physics.beam import banded, static
from mf_envs.physics.beam import element as el

OK, NEWTON_FAILED = 0, 1
DEBUG = False
# report slots (shared layout with the robots' steps that run these increments)
REP_SLIP, REP_FWORK, REP_GX, REP_N, REP_ITER, REP_INC = 0, 2, 3, 5, 7, 8
N_REPORT = 9
_R0 = static.N_ROWS_OWN
ROW_START, ROW_TRIAL, ROW_CALLER = _R0, _R0 + 1, _R0 + 2  # ROW_CALLER: free for the caller
EXTRA_ROWS = 4


def scratch(n_elements: int) -> static.Scratch:
    """Work arrays for one beam of n_elements."""
    return static.scratch(n_elements, EXTRA_ROWS)


@numba.njit(cache=True, inline="always")
def grip_fraction(g, threshold, width):
    """phi(g): C1 smoothstep, 0 at and below the threshold, 1 at threshold + width."""
    x = min(max((g - threshold) / width, 0.0), 1.0)
    return x * x * (3.0 - 2.0 * x)


@numba.njit(cache=True)
def foot_force(u, h, g, normal, law):
    """(F [N], dF/du [N/m]) of a foot displaced by u [m] in an increment of h [s] with
    engagement g and normal load `normal` [N] (module docstring; dF/du <= 0)."""
    threshold, width, mu_s, mu_f, mu_b, v_s, v_g = (
        law[0], law[1], law[2], law[3], law[4], law[5], law[6],
    )  # fmt: skip
    n = max(normal, 0.0)
    v = u / h
    mu_g = mu_f if v > 0.0 else mu_b
    extra = grip_fraction(g, threshold, width) * (mu_g - mu_s)
    qs = math.sqrt(v * v + v_s * v_s)
    qg = math.sqrt(v * v + v_g * v_g)
    f = -n * (mu_s * v / qs + extra * v / qg)
    df = -n / h * (mu_s * v_s * v_s / (qs * qs * qs) + extra * v_g * v_g / (qg * qg * qg))
    return f, df


@numba.njit(cache=True)
def _newton(d, d0, kap, f_ext, g, h, xd, zd, law, fixed, bc, sc):
    """Newton for the increment's equilibrium (module docstring) in place on d (the start),
    the feet's displacements measured from d0. Returns (converged, iterations)."""
    le, qxi, qw, stiff, u_scale, dtol, max_iter = bc[0], bc[1], bc[2], bc[3], bc[4], bc[9], bc[10]
    vec, ab, work, piv = sc[0], sc[1], sc[2], sc[3]
    p, r, delta = vec[static.ROW_P], vec[static.ROW_R], vec[static.ROW_DELTA]
    nd = d.shape[0]
    f_ref, tol_r = static.residual_scale(d, f_ext, bc)
    res_first = np.inf
    hb = el.HALF_BW
    coupling = vec[ROW_CALLER + 1]
    for it in range(1, 2 * max_iter + 1):
        el.assemble_into(d, le, kap, qxi, qw, stiff, True, p, ab)
        for i in range(nd):
            r[i] = f_ext[i] - p[i]
        support = 0.0
        for k in range(2):
            xi, zi = xd[k], zd[k]
            normal = p[zi] - f_ext[zi]
            fk, dfk = foot_force(d[xi] - d0[xi], h, g[k], normal, law)
            r[xi] += fk
            ab[hb, xi] -= dfk
            support -= dfk
            # F is linear in N = P_z - F_ext,z: row x_k of the Jacobian gets -(F / N) K[z_k, :]
            if normal > 0.0:
                dfn = fk / normal
                for j in range(max(0, zi - hb), min(nd, zi + hb + 1)):
                    if abs(xi - j) <= hb:
                        coupling[j] = ab[hb + zi - j, j]
                for j in range(max(0, zi - hb), min(nd, zi + hb + 1)):
                    if abs(xi - j) <= hb:
                        ab[hb + xi - j, j] -= dfn * coupling[j]
        if not support > 0.0:  # frictionless feet: nothing holds the body in x (singular)
            return False, it
        banded.constrain_band(ab, r, fixed)
        res = banded.scaled_residual(r, u_scale, f_ref)
        if it == 1:
            res_first = res
        if DEBUG:
            print(
                "  it",
                it,
                "res",
                res,
                "tol",
                tol_r,
                "u",
                d[xd[0]] - d0[xd[0]],
                d[xd[1]] - d0[xd[1]],
                "h",
                h,
            )
        if not np.isfinite(res) or (it >= 3 and res > 1e3 * max(res_first, tol_r)):
            return False, it
        if res < 1e-2 * tol_r:
            return True, it
        if banded.band_solve_into(ab, r, work, piv, delta) != 0:  # not symmetric: LU
            return False, it
        # step control on the feet (the law saturates: its tangent far out on the flat part
        # lets Newton throw a foot along the soft rigid mode or across zero and back): a
        # foot's displacement may at most triple per iteration (or grow to the grip's
        # regularisation length v_g h / 2), and cross zero by at most v_g h / 2 (Newton on
        # v / sqrt(v^2 + v_g^2) maps v to -v^3 / v_g^2: it cycles from |v| = v_g, converges
        # inside)
        alpha = 1.0
        ell = 0.5 * law[6] * h
        for k in range(2):
            u, du = d[xd[k]] - d0[xd[k]], delta[xd[k]]
            reach = abs(u) + ell if u * (u + du) < 0.0 else max(2.0 * abs(u), ell)
            if abs(du) > reach:
                alpha = min(alpha, reach / abs(du))
        step = 0.0
        for i in range(nd):
            d[i] += alpha * delta[i]
            step = max(step, abs(alpha * delta[i] / u_scale[i]))
        if not np.isfinite(step):
            return False, it
        if alpha == 1.0 and res < tol_r and (step < dtol or res < 1e-2 * tol_r):
            return True, it
    return False, 2 * max_iter


@numba.njit(cache=True)
def increment(d, k0, k1, f_ext, g0, g1, h, v_feet, dofs, law, bc, sc, rep, out):
    """One actuation increment kappa# k0 -> k1 (n_el, 4) [1/m] of duration h [s], engagements
    g0 -> g1 (2,), from d converged at k0 (feet's z on the ground): the configuration at k1
    into out; v_feet (2,) [m/s]: the feet's velocities in the last increment, the predictor of
    the first solve, updated; rep (>= N_REPORT,) accumulated (slip (2) [m], friction work [J],
    ground x force (2) [N] and normal load (2) [N] at the end, Newton iterations). Halves the
    increment (up to the settings' max_halvings) when Newton fails. Returns OK or
    NEWTON_FAILED."""
    xd, zd = dofs  # the feet's x and z dofs (2,) each
    max_halvings = bc[11]
    vec, kap = sc[0], sc[4][0]
    start, trial = vec[ROW_START], vec[ROW_TRIAL]
    nd = d.shape[0]
    fixed = np.zeros(nd, np.bool_)
    fixed[zd[0]] = True
    fixed[zd[1]] = True
    stuck = fixed.copy()
    stuck[xd[0]] = True
    stuck[xd[1]] = True
    start[:] = d
    lam, step = 0.0, 1.0
    min_step = 0.5**max_halvings
    g = np.empty(2)
    p2 = np.empty(4)
    while lam < 1.0 - 1e-14:
        step = min(step, 1.0 - lam)
        mu = lam + step
        static.lerp_into(k0, k1, mu, kap)
        for k in range(2):
            g[k] = g0[k] + mu * (g1[k] - g0[k])
        trial[:] = start  # the feet held where their last velocities take them first (a
        for k in range(2):  # well-conditioned solve for the body's shape), then free
            trial[xd[k]] += v_feet[k] * h * step
        ok, it = static.newton(trial, kap, f_ext, stuck, bc, sc)
        rep[REP_ITER] += it
        if ok:
            ok, it = _newton(trial, start, kap, f_ext, g, h * step, xd, zd, law, fixed, bc, sc)
            rep[REP_ITER] += it
        if not ok:
            step *= 0.5
            if step < min_step:
                return NEWTON_FAILED
            continue
        el.forces_at_into(trial, bc[0], kap, bc[1], bc[2], bc[3], (xd[0], xd[1], zd[0], zd[1]), p2)
        for k in range(2):
            u = trial[xd[k]] - start[xd[k]]
            normal = p2[2 + k] - f_ext[zd[k]]
            fk, _df = foot_force(u, h * step, g[k], normal, law)
            rep[REP_SLIP + k] += u
            rep[REP_FWORK] += fk * u  # <= 0: the force opposes the motion
            rep[REP_GX + k] = fk
            rep[REP_N + k] = normal
            v_feet[k] = u / (h * step)
        start[:] = trial
        lam = mu
        if it <= bc[10] // 2:
            step = min(2.0 * step, 1.0)
    out[:] = start
    return OK
