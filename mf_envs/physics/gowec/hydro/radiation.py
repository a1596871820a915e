"""State-space radiation memory for the Cummins equation (Cummins 1962; Perez & Fossen 2009).

The radiation moment is -A_inf theta'' - mu, mu(t) = int_0^t K(t - tau) theta'(tau) dtau, whose
kernel has the transfer function (Ogilvie's relations)

    K(i w) = B(w) + i w (A(w) - A_inf)                                   (N m s/rad)

We fit K(s) ~ N(s)/D(s) with deg N = n - 1, deg D = n (K is strictly proper: K(i w) -> 0 as
w -> inf) and N(0) = 0 (K(0) = B(0) = 0), by the Sanathanan-Koerner iteration: linear least squares
of N(s_k) - K_k D(s_k) weighted by 1/|D_prev(s_k)| on the BEM table s_k = i w_k, frequencies
scaled by the table's w_max for conditioning. Unstable poles are reflected into the left half
plane and the numerator refitted with the poles fixed. The realisation (scipy.signal.tf2ss) is
x' = Ar x + Br theta', mu = Cr x. Hand-written because neither scipy nor python-control has a
frequency-domain rational fit (vector fitting lives in scikit-rf, a large RF package); the
iteration is 20 lines and its error is reported (`RadiationFit.error`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from mf_envs._jit import kernel


@dataclass(frozen=True)
class RadiationFit:
    """x' = A x + B theta', mu = C x (SI; x in N m s/rad-scaled units). `error` = max over the
    table of |K_fit(i w) - K(i w)| / max |K| ; `error_damping` = max |Re K_fit - B| / max B."""

    A: NDArray[np.float64]
    B: NDArray[np.float64]
    C: NDArray[np.float64]
    order: int
    error: float
    error_damping: float

    def response(self, w: NDArray[np.float64]) -> NDArray[np.complex128]:
        """K_fit(i w) (n,) complex, N m s/rad."""
        n = self.A.shape[0]
        eye = np.eye(n)
        return np.array(
            [(self.C @ np.linalg.solve(1j * x * eye - self.A, self.B)).item() for x in w]
        )


def _ls_step(s: NDArray, K: NDArray, n: int, wt: NDArray) -> tuple[NDArray, NDArray]:
    """One SK step: numerator coefficients (s^1..s^{n-1}) and monic denominator (s^0..s^n)."""
    cols = [s**j for j in range(1, n)] + [-K * s**j for j in range(n)]
    M = np.stack(cols, axis=1) * wt[:, None]
    rhs = K * s**n * wt
    Mr = np.concatenate([M.real, M.imag])
    rr = np.concatenate([rhs.real, rhs.imag])
    x = np.linalg.lstsq(Mr, rr, rcond=None)[0]
    num = np.concatenate([[0.0], x[: n - 1]])  # ascending powers, N(0) = 0
    den = np.concatenate([x[n - 1 :], [1.0]])
    return num, den


def _numerator_for_poles(s: NDArray, K: NDArray, den: NDArray, n: int) -> NDArray:
    D = np.polyval(den[::-1], s)
    cols = np.stack([s**j / D for j in range(1, n)], axis=1)
    x = np.linalg.lstsq(
        np.concatenate([cols.real, cols.imag]), np.concatenate([K.real, K.imag]), rcond=None
    )[0]
    return np.concatenate([[0.0], x])


def _fit_order(w: NDArray, K: NDArray, n: int, iters: int = 30) -> tuple[NDArray, NDArray]:
    s = 1j * w
    wt = np.ones_like(w)
    for _ in range(iters):
        num, den = _ls_step(s, K, n, wt)
        wt = 1.0 / np.maximum(np.abs(np.polyval(den[::-1], s)), 1e-12)
    poles = np.roots(den[::-1])
    if np.any(poles.real >= 0):
        poles = -np.abs(poles.real) + 1j * poles.imag
        den = np.real(np.poly(poles))[::-1]
        num = _numerator_for_poles(s, K, den, n)
    return num, den


def fit_radiation(
    omega: NDArray,
    added_mass: NDArray,
    damping: NDArray,
    added_mass_inf: float,
    tol: float = 0.04,
    max_order: int = 10,
) -> RadiationFit:
    """Lowest order n in 2..max_order whose fit error is below tol (else the best one)."""
    w = np.asarray(omega, dtype=float)
    K = np.asarray(damping) + 1j * w * (np.asarray(added_mass) - added_mass_inf)
    scale_w = float(w[-1])
    scale_k = float(np.max(np.abs(K)))
    from scipy import signal  # here: importing scipy.signal costs every process ~0.5 s

    best = None
    for n in range(2, max_order + 1):
        num, den = _fit_order(w / scale_w, K / scale_k, n)
        a, b, c, d = signal.tf2ss(num[::-1] * scale_k, den[::-1])
        fit = RadiationFit(a * scale_w, b * scale_w, c, n, 0.0, 0.0)
        Kf = fit.response(w)
        err = float(np.max(np.abs(Kf - K)) / scale_k)
        errb = float(np.max(np.abs(Kf.real - K.real)) / np.max(np.abs(K.real)))
        stable = bool(np.all(np.linalg.eigvals(fit.A).real < 0))
        fit = RadiationFit(fit.A, fit.B, fit.C, n, err, errb)
        if stable and (best is None or err < best.error):
            best = fit
        if stable and err < tol:
            break
    if best is None:
        raise ValueError("hull: no stable radiation fit found (check the damping table)")
    return best


# the radiation memory's state-space rates, inlined by `floating`'s RK4 stages
@kernel(forceinline=True)
def radiation_rates4(y, dy, Ar, Br, th_d, ro_d):
    """`floating.deriv_into`'s radiation states of 4th-order fits (pitch at y[6:10] with
    Ar[0], Br[0], roll at y[10:14] with Ar[1], Br[1]), its loop's sums in its order, unrolled:
    0.0 + sum_j A[i, j] x_j, then + B[i] u."""
    t0, t1, t2, t3 = y[6], y[7], y[8], y[9]
    r0, r1, r2, r3 = y[10], y[11], y[12], y[13]
    for i in range(4):
        a0, a1, a2, a3 = Ar[0, i, 0], Ar[0, i, 1], Ar[0, i, 2], Ar[0, i, 3]
        dy[6 + i] = (0.0 + a0 * t0 + a1 * t1 + a2 * t2 + a3 * t3) + Br[0, i] * th_d
        a0, a1, a2, a3 = Ar[1, i, 0], Ar[1, i, 1], Ar[1, i, 2], Ar[1, i, 3]
        dy[10 + i] = (0.0 + a0 * r0 + a1 * r1 + a2 * r2 + a3 * r3) + Br[1, i] * ro_d


@kernel(forceinline=True)
def block_rates(y, dy, o, As, Bs, lo, hi, v):
    """dy[o + i] = sum_j As[i, j] y[o + j] + Bs[i] v for the diagonal block lo <= i, j < hi
    (on views from 0: indices the compiler sees are >= 0, so no negative-index wraparound per
    element, which the offsets lo, o cost on every access)."""
    A, B, ys, ds = As[lo:hi, lo:hi], Bs[lo:hi], y[o + lo : o + hi], dy[o + lo : o + hi]
    if B.shape[0] == 4:  # the fits' order: the same sums, unrolled (no loop per 4 terms)
        y0, y1, y2, y3 = ys[0], ys[1], ys[2], ys[3]
        for i in range(4):
            ds[i] = B[i] * v + A[i, 0] * y0 + A[i, 1] * y1 + A[i, 2] * y2 + A[i, 3] * y3
        return
    for i in range(B.shape[0]):
        acc = B[i] * v
        for j in range(B.shape[0]):
            acc += A[i, j] * ys[j]
        ds[i] = acc


@kernel(forceinline=True)
def dot_block(c, y, o, lo, hi):
    """sum_i c[i] y[o + i] over lo <= i < hi, in order from 0.0 (views, as `block_rates`)."""
    cs, ys = c[lo:hi], y[o + lo : o + hi]
    acc = 0.0
    for i in range(cs.shape[0]):
        acc += cs[i] * ys[i]
    return acc
