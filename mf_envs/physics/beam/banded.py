"""Banded linear algebra of the beam's global matrices (hand-written numba kernels).

The storage is scipy.linalg.solve_banded's: ab[HALF_BW + i - j, j] = K[i, j], half-bandwidth
HALF_BW = 10 (the C1 element's dof layout, `beam.element`). Hand-written because the Newton and
Newmark loops call these inside compiled kernels, where scipy's banded LAPACK cannot be called
and a dense solve costs n^3: LU with partial pivoting (LAPACK dgbtf2/dgbtrs's algorithm) and
LDL^T without pivoting for the symmetric positive definite tangents; `constrain_band` applies
Dirichlet conditions; `band_matvec`, `band_to_dense` for products and tests.
"""

from __future__ import annotations

import numba
import numpy as np

HALF_BW = 10  # half-bandwidth of the global matrices
N_BAND = 2 * HALF_BW + 1


@numba.njit(cache=True)
def constrain_band(ab, r, fixed):
    """In place: rows/columns of the `fixed` dofs (bool (n_dof,)) -> identity, rhs -> 0."""
    nd = r.shape[0]
    for j in range(nd):
        if fixed[j]:
            r[j] = 0.0
            for k in range(N_BAND):
                ab[k, j] = 0.0  # column j
            for i in range(max(0, j - HALF_BW), min(nd, j + HALF_BW + 1)):
                ab[HALF_BW + j - i, i] = 0.0  # row j
            ab[HALF_BW, j] = 1.0


@numba.njit(cache=True, inline="always")
def scaled_residual(r, u_scale, f_ref):
    """max_i |r_i u_scale_i| / f_ref: a residual as a share of the load scale f_ref, each
    entry weighted by its dof's scale (the static solvers' convergence test)."""
    res = 0.0
    for i in range(r.shape[0]):
        res = max(res, abs(r[i] * u_scale[i]))
    return res / f_ref


def band_to_dense(ab: np.ndarray) -> np.ndarray:
    """Dense (n, n) matrix from the banded storage used here (for tests and small problems)."""
    n = ab.shape[1]
    k = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - HALF_BW), min(n, i + HALF_BW + 1)):
            k[i, j] = ab[HALF_BW + i - j, j]
    return k


@numba.njit(cache=True)
def band_matvec(ab, x):
    """y = K x for banded K (21, n)."""
    n = x.shape[0]
    y = np.zeros(n)
    for j in range(n):
        for i in range(max(0, j - HALF_BW), min(n, j + HALF_BW + 1)):
            y[i] += ab[HALF_BW + i - j, j] * x[j]
    return y


@numba.njit(cache=True)
def band_solve_into(ab, r, work, piv, x):
    """Solve K x = r for banded K (21, n) (storage above) by LU with partial pivoting (the
    algorithm of LAPACK dgbtf2/dgbtrs: row interchanges within the band, fill-in of U up to
    2 HALF_BW superdiagonals). work (n, 3 HALF_BW + 1) float (column j of the band in row j,
    contiguous) and piv (n,) int are scratch; x (n,) receives the solution. Returns 0, or k + 1
    if the pivot of column k is exactly zero (K singular). Hand-written: scipy's banded LAPACK
    solver cannot be called from cached numba code, and this one runs inside the compiled
    Newton loops of `mf_envs.physics.beam.static`."""
    n = r.shape[0]
    kl = HALF_BW
    kv = 2 * HALF_BW  # position of the diagonal in a row of work
    for j in range(n):
        for k in range(kl):
            work[j, k] = 0.0
        for k in range(N_BAND):
            work[j, kl + k] = ab[k, j]
    ju = 0
    for j in range(n):
        km = min(kl, n - 1 - j)
        col = work[j]
        jp = 0
        big = abs(col[kv])
        for t in range(1, km + 1):
            if abs(col[kv + t]) > big:
                big = abs(col[kv + t])
                jp = t
        piv[j] = j + jp
        if col[kv + jp] == 0.0:
            return j + 1
        ju = max(ju, min(j + HALF_BW + jp, n - 1))
        if jp != 0:
            for c in range(j, ju + 1):
                tmp = work[c, kv + j - c]
                work[c, kv + j - c] = work[c, kv + j + jp - c]
                work[c, kv + j + jp - c] = tmp
        inv = 1.0 / col[kv]
        for t in range(1, km + 1):
            col[kv + t] *= inv
        for c in range(j + 1, ju + 1):
            row = work[c]
            o = kv + j - c
            ujc = row[o]
            if ujc != 0.0:
                for t in range(1, km + 1):
                    row[o + t] -= col[kv + t] * ujc
    for i in range(n):
        x[i] = r[i]
    for j in range(n - 1):
        km = min(kl, n - 1 - j)
        jp = piv[j]
        if jp != j:
            tmp = x[j]
            x[j] = x[jp]
            x[jp] = tmp
        xj = x[j]
        for t in range(1, km + 1):
            x[j + t] -= work[j, kv + t] * xj
    for j in range(n - 1, -1, -1):
        x[j] /= work[j, kv]
        xj = x[j]
        for i in range(max(0, j - kv), j):
            x[i] -= work[j, kv + i - j] * xj
    return 0


@numba.njit(cache=True, inline="always")
def _ldl_column(work, j, m, v):
    """Step j of `band_spd_solve_into`: column j of L (m entries below the diagonal) and the
    update of the trailing band. Called with the literal HALF_BW for the full columns (fixed
    trip counts, which the compiler unrolls) and with m near the end: the same operations
    (so are `_ldl_forward` and `_ldl_back`)."""
    inv = 1.0 / work[j, 0]
    for t in range(1, m + 1):
        v[t] = work[j, t]
        work[j, t] = v[t] * inv
    for t in range(1, m + 1):
        row = work[j + t]
        vt = v[t]
        for u in range(m - t + 1):
            row[u] -= work[j, t + u] * vt


@numba.njit(cache=True)
def band_spd_solve_into(ab, r, work, x):
    """Solve K x = r for a symmetric banded K (21, n) by LDL^T without pivoting (banded
    Cholesky without square roots, right-looking: the updates are contiguous axpys). The
    stiffness of a stable configuration is symmetric positive definite, where this is stable,
    needs no fill and half the work of `band_solve_into`. work (n, >= HALF_BW + 1) is scratch
    (column j of L below the diagonal in work[j, 1:], D in work[j, 0]); x (n,) receives the
    solution. Returns 0, or k + 1 if the pivot of column k is not positive (K is not positive
    definite: use the LU)."""
    status = band_ldl_factor(ab, work)
    if status == 0:
        band_ldl_solve(work, r, x)
    return status


@numba.njit(cache=True)
def band_ldl_factor(ab, work):
    """The LDL^T factors of `band_spd_solve_into` into work; returns its status. Factor once,
    then `band_ldl_solve` for each right-hand side."""
    n = ab.shape[1]
    hb = HALF_BW
    for j in range(n):
        for t in range(hb + 1):
            work[j, t] = ab[hb + t, j] if j + t < n else 0.0
    v = np.empty(hb + 1)
    for j in range(n):
        if not work[j, 0] > 0.0:
            return j + 1
        m = min(hb, n - 1 - j)
        if m == HALF_BW:
            _ldl_column(work, j, HALF_BW, v)
        else:
            _ldl_column(work, j, m, v)
    return 0


@numba.njit(cache=True)
def band_ldl_solve(work, r, x):
    """x (n,) with K x = r from the factors of `band_ldl_factor` in work."""
    n = r.shape[0]
    hb = HALF_BW
    for i in range(n):
        x[i] = r[i]
    for j in range(n):
        m = min(hb, n - 1 - j)
        if m == HALF_BW:
            _ldl_forward(work, x, j, HALF_BW)
        else:
            _ldl_forward(work, x, j, m)
    for j in range(n):
        x[j] /= work[j, 0]
    for j in range(n - 1, -1, -1):
        m = min(hb, n - 1 - j)
        if m == HALF_BW:
            _ldl_back(work, x, j, HALF_BW)
        else:
            _ldl_back(work, x, j, m)


@numba.njit(cache=True, inline="always")
def _ldl_forward(work, x, j, m):
    """Column j of the forward substitution with L (m entries below the diagonal)."""
    xj = x[j]
    for t in range(1, m + 1):
        x[j + t] -= work[j, t] * xj


@numba.njit(cache=True, inline="always")
def _ldl_back(work, x, j, m):
    """Row j of the back substitution with L^T (m entries right of the diagonal)."""
    s = x[j]
    for t in range(1, m + 1):
        s -= work[j, t] * x[j + t]
    x[j] = s
