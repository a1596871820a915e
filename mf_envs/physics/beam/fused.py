"""Hot kernels of the implicit beam steps (serpentine, swimmer), compiled without reference
counting (`mf_envs._jit.kernel`): the algorithmic internal force and its tangent element by
element, fused with the distributed load's force and tangent, scattered once per element.

The arithmetic is `beam.algorithmic.assemble_algorithmic_into`'s, rearranged:

* the strains, cos and sin at the step's start (configuration a = d_n) do not change over the
  Newton iterations: `start_strains` tabulates them once per step;
* cos, sin of psi_b and of the mid angle psi_m = (psi_a + psi_b) / 2 come from those of psi_a
  and one sin/cos of x = (psi_b - psi_a) / 2 (angle addition), which sinc(x) needs anyway (one
  sincos per point instead of three);
* the material tangent sum_r Bbar_r D_r B(b)_r and the geometric part are 2 x 2 blocks of
  scalars times outer products of the shape functions (the rows of Bbar and B(b) are
  (alpha N_z', beta N_z', gamma N_psi) and the curvature row): 10 coefficients per point;
* the element's force and matrix (internal + load) reach the band once per element.

Equal to the beam's assembly to round-off (tests/test_serpentine.py, tests/test_swimmer.py).
`solve`: the Newton correction by a block tridiagonal LU (`block_solve`).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.physics.beam.banded import HALF_BW, N_BAND, band_solve_into
from mf_envs.physics.beam.element import GAUSS_XI, shape_functions

N_GAUSS = 4
LOC = np.array([0, 1, 6, 7, 2, 3, 8, 9, 4, 10, 5], np.int64)
N_START = 8  # start_strains' values per quadrature point
BS = 6  # block_solve's block: a node's 5 dofs and its element's mid node


def quadrature_tables(le: np.ndarray, qxi: np.ndarray) -> np.ndarray:
    """(n_el, nq, 10): N_z' (4), N_psi (3), N_psi' (3) of every element at the quadrature
    points qxi (`beam.element.quadrature`; Eqs. 69-70, 73)."""
    out = np.empty((le.shape[0], qxi.shape[0], 10))
    for e, h in enumerate(le):
        for g, x in enumerate(qxi):
            _, dnz, npsi, dnpsi = shape_functions(x, h)
            out[e, g] = np.concatenate([dnz, npsi, dnpsi])
    return out


def shape_tables(le: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The shape functions at the 4 Gauss points of every element: N_z (n_el, 4, 4) and N_psi
    (n_el, 4, 3) (the `nzt, npt` arguments of the assemblies; Eqs. 69-70)."""
    nzt = np.array([[shape_functions(x, h)[0] for x in GAUSS_XI] for h in le])
    npt = np.array([[shape_functions(x, h)[2] for x in GAUSS_XI] for h in le])
    return nzt, npt


@kernel(forceinline=True)
def _sinc_half(x):
    """sin(x) / x and its derivative at x (series near 0), with cos x and sin x."""
    c, s = math.cos(x), math.sin(x)
    if abs(x) < 1e-3:
        x2 = x * x
        return 1.0 - x2 / 6.0 + x2 * x2 / 120.0, -x / 3.0 + x * x2 / 30.0, c, s
    sig = s / x
    return sig, (c - sig) / x, c, s


@kernel
def start_strains(da, le, ksh_a, tab, pre):
    """pre[e, g] = (z1', z2', psi, kappa - kappa#, cos psi, sin psi, gamma_1 - 1, gamma_2) of
    configuration da at every quadrature point (tab: `quadrature_tables`;
    kappa# only at the first 4 points, the bending rule)."""
    for e in range(le.shape[0]):
        b = 6 * e
        for g in range(tab.shape[1]):
            t = tab[e, g]
            a1 = t[0] * da[b] + t[1] * da[b + 1] + t[2] * da[b + 6] + t[3] * da[b + 7]
            a2 = t[0] * da[b + 2] + t[1] * da[b + 3] + t[2] * da[b + 8] + t[3] * da[b + 9]
            pa = t[4] * da[b + 4] + t[5] * da[b + 10] + t[6] * da[b + 5]
            ka = t[7] * da[b + 4] + t[8] * da[b + 10] + t[9] * da[b + 5]
            if g < N_GAUSS:
                ka -= ksh_a[e, g]
            ca, sa = math.cos(pa), math.sin(pa)
            q = pre[e, g]
            q[0], q[1], q[2], q[3] = a1, a2, pa, ka
            q[4], q[5] = ca, sa
            q[6] = ca * a1 + sa * a2 - 1.0
            q[7] = -sa * a1 + ca * a2


@kernel(forceinline=True)
def gather(d, e, out):
    """The 11 dofs of element e (element order, Eq. 71c) into out."""
    b = 6 * e
    for k in range(11):
        out[k] = d[b + LOC[k]]


@kernel(forceinline=True)
def element_internal(e, deb, le_e, ksh_a, ksh_b, qw, stiff, theta, rate, tab, pre, fe, ke,
                     tangent=True):  # fmt: skip
    """fe += the element's algorithmic internal force Pbar, ke += dPbar/db (11 x 11, element
    order; tangent=False: ke untouched, fe the same bits) at b = deb (`beam.algorithmic`:
    stresses at theta, the strain shift -rate (kappa#_b - kappa#_a) in the bending stress, the
    Kelvin-Voigt damper of `serpentine.kernels`). pre: `start_strains` of configuration a."""
    for g in range(qw.shape[0]):
        t = tab[e, g]
        q = pre[e, g]
        b1 = t[0] * deb[0] + t[1] * deb[1] + t[2] * deb[2] + t[3] * deb[3]
        b2 = t[0] * deb[4] + t[1] * deb[5] + t[2] * deb[6] + t[3] * deb[7]
        pb = t[4] * deb[8] + t[5] * deb[9] + t[6] * deb[10]
        eb2 = t[7] * deb[8] + t[8] * deb[9] + t[9] * deb[10]
        sh2 = 0.0
        if g < N_GAUSS:
            eb2 -= ksh_b[e, g]
            sh2 = -rate * (ksh_b[e, g] - ksh_a[e, g])
        a1, a2, pa, ea2, ca, sa, ea0, ea1 = q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7]
        sig, dsig, cx, sx = _sinc_half(0.5 * (pb - pa))
        cm, sm = ca * cx - sa * sx, sa * cx + ca * sx  # psi_m = psi_a + x
        cb, sb = cm * cx - sm * sx, sm * cx + cm * sx  # psi_b = psi_m + x
        g1b, g2b = cb * b1 + sb * b2, -sb * b1 + cb * b2
        cbar, sbar = 0.5 * (ca + cb), 0.5 * (sa + sb)
        z1m, z2m = 0.5 * (a1 + b1), 0.5 * (a2 + b2)
        u1, u2 = -sm * z1m + cm * z2m, -cm * z1m - sm * z2m
        s0, s1, s2 = stiff[g, 0], stiff[g, 1], stiff[g, 2]
        n1 = s0 * (theta * (g1b - 1.0) + (1.0 - theta) * ea0)
        n2 = s1 * (theta * g2b + (1.0 - theta) * ea1)
        m3 = s2 * (theta * eb2 + (1.0 - theta) * ea2 - sh2)
        w = qw[g] * le_e
        # force: Bbar^T sigma
        fz1 = w * (cbar * n1 - sbar * n2)
        fz2 = w * (sbar * n1 + cbar * n2)
        fp = w * sig * (u1 * n1 + u2 * n2)
        fk = w * m3
        for k in range(4):
            fe[k] += fz1 * t[k]
            fe[4 + k] += fz2 * t[k]
        for m in range(3):
            fe[8 + m] += fp * t[4 + m] + fk * t[7 + m]
        if not tangent:
            continue
        # tangent: material Bbar^T D theta B(b) plus the geometric part (`beam.algorithmic._geo`)
        wt = w * theta
        dh00, dh01 = -0.5 * sig * sm, 0.5 * sig * cm
        dh10, dh11 = -0.5 * sig * cm, -0.5 * sig * sm
        dh02 = 0.5 * dsig * u1 - 0.5 * sig * (cm * z1m + sm * z2m)
        dh12 = 0.5 * dsig * u2 - 0.5 * sig * (-sm * z1m + cm * z2m)
        c11 = wt * (s0 * cbar * cb + s1 * sbar * sb)
        c12 = wt * (s0 * cbar * sb - s1 * sbar * cb)
        c21 = wt * (s0 * sbar * cb - s1 * cbar * sb)
        c22 = wt * (s0 * sbar * sb + s1 * cbar * cb)
        c1p = wt * (s0 * cbar * g2b + s1 * sbar * g1b) + 0.5 * w * (-n1 * sb - n2 * cb)
        c2p = wt * (s0 * sbar * g2b - s1 * cbar * g1b) + 0.5 * w * (n1 * cb - n2 * sb)
        cp1 = wt * sig * (s0 * u1 * cb - s1 * u2 * sb) + w * (n1 * dh00 + n2 * dh10)
        cp2 = wt * sig * (s0 * u1 * sb + s1 * u2 * cb) + w * (n1 * dh01 + n2 * dh11)
        cpp = wt * sig * (s0 * u1 * g2b - s1 * u2 * g1b) + w * (n1 * dh02 + n2 * dh12)
        ckk = wt * s2
        for k in range(4):
            dk = t[k]
            for m in range(4):
                dkm = dk * t[m]
                ke[k, m] += c11 * dkm
                ke[k, 4 + m] += c12 * dkm
                ke[4 + k, m] += c21 * dkm
                ke[4 + k, 4 + m] += c22 * dkm
            for m in range(3):
                dkm = dk * t[4 + m]
                ke[k, 8 + m] += c1p * dkm
                ke[4 + k, 8 + m] += c2p * dkm
                ke[8 + m, k] += cp1 * dkm
                ke[8 + m, 4 + k] += cp2 * dkm
        for m in range(3):
            for j in range(3):
                ke[8 + m, 8 + j] += cpp * t[4 + m] * t[4 + j] + ckk * t[7 + m] * t[7 + j]


@kernel(forceinline=True)
def point_load(fe, ke, w, nz, npsi, law, cd, cv, tangent=True):
    """fe -= the nodal force of a line force (f1, f2) at a point (weight w, shape functions nz,
    npsi), ke += cd dF/dd + cv dF/dv of it (not with tangent=False), law = (f1, f2, d11, d12,
    d21, d22, p1, p2) the force and its derivatives (df/dv = ((d11, d12), (d21, d22)), df/dpsi
    = (p1, p2)), as a point law returns them: `serpentine.friction._add_tangent` without the
    couple."""
    f1, f2, d11, d12, d21, d22, p1, p2 = law
    for i in range(4):
        wi = w * nz[i]
        fe[i] -= wi * f1
        fe[4 + i] -= wi * f2
        if not tangent:
            continue
        a11, a12, a21, a22 = cv * wi * d11, cv * wi * d12, cv * wi * d21, cv * wi * d22
        for j in range(4):
            ke[i, j] += a11 * nz[j]
            ke[i, 4 + j] += a12 * nz[j]
            ke[4 + i, j] += a21 * nz[j]
            ke[4 + i, 4 + j] += a22 * nz[j]
        b1, b2 = cd * wi * p1, cd * wi * p2
        for j in range(3):
            ke[i, 8 + j] += b1 * npsi[j]
            ke[4 + i, 8 + j] += b2 * npsi[j]


@kernel(forceinline=True)
def clear_element(fe, ke):
    """fe, ke = 0."""
    for i in range(11):
        fe[i] = 0.0
        for j in range(11):
            ke[i, j] = 0.0


@kernel(forceinline=True)
def scatter(e, fe, ke, r, ab, tangent=True):
    """r -= fe, ab += ke (not with tangent=False) of element e (element order -> global
    band)."""
    b = 6 * e
    for i in range(11):
        gi = b + LOC[i]
        r[gi] -= fe[i]
        if not tangent:
            continue
        for j in range(11):
            gj = b + LOC[j]
            ab[HALF_BW + gi - gj, gj] += ke[i, j]


@kernel
def scale_band(mass, c, out):
    """out = c M (banded, the same storage)."""
    for k in range(mass.shape[0]):
        for j in range(mass.shape[1]):
            out[k, j] = c * mass[k, j]


@kernel(forceinline=True)
def trapezoid_points(d, d0, v0, dt, th, x, v, dth, vth):
    """The Newton iterate d's companions in the trapezoidal (theta) step from (d0, v0): x = d -
    d0 - dt v0 (the inertia's argument), v = 2 (d - d0) / dt - v0 (v_{n+1}), and the load point
    d_th = d0 + th (d - d0), v_th = (1 - th) v0 + th v, all written in place."""
    for i in range(d0.shape[0]):
        x[i] = d[i] - d0[i] - dt * v0[i]
        v[i] = 2.0 * (d[i] - d0[i]) / dt - v0[i]
        dth[i] = d0[i] + th * (d[i] - d0[i])
        vth[i] = (1.0 - th) * v0[i] + th * v[i]


@kernel(forceinline=True)
def start_band(cm, x, r, ab, tangent=True):
    """ab = cm (the banded c_a M of `scale_band`; not with tangent=False), r -= cm x (row by
    row of the band: contiguous)."""
    nd = x.shape[0]
    for k in range(N_BAND):
        o = k - HALF_BW  # ab[k, j] = K[j + o, j]
        if tangent:
            for j in range(nd):
                ab[k, j] = cm[k, j]
        for j in range(max(0, -o), min(nd, nd - o)):
            r[j + o] -= cm[k, j] * x[j]


@kernel
def scaled_norm2(r, scale):
    """sum_i (r_i scale_i)^2."""
    acc = 0.0
    for i in range(r.shape[0]):
        acc += (r[i] * scale[i]) ** 2
    return acc


@kernel(forceinline=True)
def _entry(ab, i, k):
    o = HALF_BW + i - k
    if o < 0 or o >= N_BAND:
        return 0.0
    return ab[o, k]


@kernel
def block_solve(ab, r, work, x):
    """Solve K x = r for the beam's banded K (21, n) (`beam.banded` storage) as the block
    tridiagonal matrix it is: dofs in blocks of 6 (node j's 5 and the mid node of element j),
    element j couples blocks j and j + 1 only. Block LU (Thomas): D_J = A_JJ - L_J X_{J-1},
    X_J = D_J^-1 U_J, by Gaussian elimination with partial pivoting within the block on the
    rows [D_J | U_J | y_J]; x_J = z_J - X_J x_{J+1}. About half the operations of the band LU
    (which pivots across blocks and fills 2 HALF_BW superdiagonals). work (n, >= 12) float
    scratch; x (n,) receives the solution. Returns 0, or k + 1 if block pivot k is zero (then
    use `solve`'s band LU)."""
    n = r.shape[0]
    nb = (n + BS - 1) // BS
    for jb in range(nb):
        o = BS * jb
        bs = min(BS, n - o)
        on = o + bs
        bn = min(BS, n - on) if jb + 1 < nb else 0
        # augmented rows [D | U | y], D = A_JJ - L X_{J-1}, y = r_J - L z_{J-1}
        for i in range(bs):
            row = work[o + i]
            for k in range(bs):
                row[k] = _entry(ab, o + i, o + k)
            for k in range(bn):
                row[BS + k] = _entry(ab, o + i, on + k)
            yi = r[o + i]
            if jb > 0:
                for m in range(BS):
                    lim = _entry(ab, o + i, o - BS + m)
                    if lim != 0.0:
                        prow = work[o - BS + m]
                        for k in range(bs):
                            row[k] -= lim * prow[BS + k]
                        yi -= lim * x[o - BS + m]
            x[o + i] = yi
        # Gaussian elimination with partial pivoting within the block, on the augmented rows
        for k in range(bs):
            p = k
            big = abs(work[o + k, k])
            for i in range(k + 1, bs):
                a = abs(work[o + i, k])
                if a > big:
                    big = a
                    p = i
            if not big > 0.0:
                return o + k + 1
            if p != k:
                rk, rp = work[o + k], work[o + p]
                for c in range(bs):
                    t = rk[c]
                    rk[c] = rp[c]
                    rp[c] = t
                for c in range(bn):
                    t = rk[BS + c]
                    rk[BS + c] = rp[BS + c]
                    rp[BS + c] = t
                t = x[o + k]
                x[o + k] = x[o + p]
                x[o + p] = t
            rk = work[o + k]
            inv = 1.0 / rk[k]
            for i in range(k + 1, bs):
                ri = work[o + i]
                lik = ri[k] * inv
                if lik != 0.0:
                    for c in range(k + 1, bs):
                        ri[c] -= lik * rk[c]
                    for c in range(bn):
                        ri[BS + c] -= lik * rk[BS + c]
                    x[o + i] -= lik * x[o + k]
        # back substitution: X_J = D^-1 U_J, z_J = D^-1 y_J
        for k in range(bs - 1, -1, -1):
            rk = work[o + k]
            inv = 1.0 / rk[k]
            for c in range(bn):
                rk[BS + c] *= inv
            x[o + k] *= inv
            for i in range(k):
                ri = work[o + i]
                uik = ri[k]
                if uik != 0.0:
                    for c in range(bn):
                        ri[BS + c] -= uik * rk[BS + c]
                    x[o + i] -= uik * x[o + k]
    # x_J = z_J - X_J x_{J+1}
    for jb in range(nb - 2, -1, -1):
        o = BS * jb
        on = o + BS
        bn = min(BS, n - on)
        for i in range(BS):
            row = work[o + i]
            s = x[o + i]
            for c in range(bn):
                s -= row[BS + c] * x[on + c]
            x[o + i] = s
    return 0


@numba.njit(cache=True, nogil=True)
def solve(ab, r, work, piv, x):
    """x with K x = r by `block_solve`, or `beam.banded.band_solve_into` (pivoting across the
    blocks) if a block pivot is zero. Returns 0, or k + 1 if K is singular."""
    if block_solve(ab, r, work, x) == 0:
        return 0
    return band_solve_into(ab, r, work, piv, x)
