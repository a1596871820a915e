"""Exact torque-free rotation: Euler's solution in Jacobi elliptic functions (Rios 2017, ch. 2).

The polhode of a free body circles one of the two extreme principal axes ("c"); the other extreme
axis is "a" and the intermediate one "b" (ordered by inertia, whatever the user's axis order):

    omega_a = s_a A_a cn(u | m),  omega_b = s_b A_b sn(u | m),  omega_c = s_c A_c dn(u | m),
    u = lam t + u0,   c = largest-J axis if D > J_mid, smallest-J axis if D < J_mid

(Landau-Lifshitz §37, Wittenburg 1977; D from Eq. 33b, J_mid the intermediate inertia). With
M^2 = |H|^2 and 2E = H . J^-1 H, every quantity below is built from sums of terms of ONE sign,
so nothing cancels even a hair away from the separatrix D = J_mid:

    P_c = 2E J_c - M^2 = sum_{i != c} H_i^2 (J_c - J_i) / J_i
    P_a = M^2 - 2E J_a = sum_{i != a} H_i^2 (J_i - J_a) / J_i
    S_b = M^2 - 2E J_b = sum_{i != b} H_i^2 (J_i - J_b) / J_i   (sign picks c; = 2K0 (D - J_b))
    A_a^2 = P_c / (J_a (J_c - J_a)),  A_b^2 = P_c / (J_b (J_c - J_b)),
    A_c^2 = P_a / (J_c (J_c - J_a))
    lam^2 = (J_c - J_b) P_a / (J_a J_b J_c)
    m  = (J_b - J_a) P_c / ((J_c - J_b) P_a),   1 - m = (J_c - J_a) S_b / ((J_c - J_b) P_a)

Signs: s_a = sign(omega_a(0)) (so cn(u0) >= 0), s_c = sign(omega_c(0)), and Euler's equations fix
s_a s_b s_c = parity(a, b, c) * sign(J_c - J_b). The phase u0 = F(phi0 | m) is computed from
sn(u0), cn(u0) with Carlson's R_F (scipy.special.elliprf), again in terms of 1 - m.

scipy.special.ellipj takes m, so it cannot see 1 - m below ~1e-16 and, worse, its m -> 1
branch is wrong for 1 - m < 1e-9 and u > K (scipy gh-8480). `jacobi_sn_cn_dn` therefore
evaluates sn, cn, dn by the arithmetic-geometric mean started from b0 = sqrt(1 - m) (Abramowitz &
Stegun 16.4; the descending Landen sequence), with u reduced modulo 4K first. At 1 - m == 0 it
returns the separatrix limit sn = tanh, cn = dn = sech (a flip that takes infinitely long).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.special import elliprf

from mf_envs._validate import check_finite, check_positive, check_shape
from mf_envs.frames.so3 import hat

_AGM_TOL = 1e-17


def _agm_sequence(m1: float) -> tuple[list[float], list[float]]:
    """a_n and c_n of the AGM from a0 = 1, b0 = sqrt(m1), c0 = sqrt(1 - m1) (A&S 16.4)."""
    a, b, c = 1.0, math.sqrt(m1), math.sqrt(max(0.0, 1.0 - m1))
    As, Cs = [a], [c]
    while abs(c) > _AGM_TOL * a and len(As) < 40:
        a_next = 0.5 * (a + b)
        c = c * c / (4.0 * a_next)  # = (a - b)/2 without the cancellation
        b = math.sqrt(a * b)
        a = a_next
        As.append(a)
        Cs.append(c)
    return As, Cs


def complete_k(m1: float) -> float:
    """Complete elliptic integral K(m) given the complementary parameter m1 = 1 - m (inf at 0)."""
    if m1 <= 0.0:
        return math.inf
    return float(elliprf(0.0, m1, 1.0))


def jacobi_sn_cn_dn(
    u: ArrayLike, m1: float
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Jacobi sn(u|m), cn(u|m), dn(u|m) for parameter m = 1 - m1, accurate for any m1 in [0, 1].

    u: (...,) real. Uses the AGM/descending-Landen recursion started from sqrt(m1), after
    reducing u modulo the period 4K; m1 == 0 gives the separatrix limit tanh, sech, sech.
    dn is formed as sqrt(cn^2 + m1 sn^2) (no cancellation when m -> 1).
    """
    u = np.asarray(u, dtype=np.float64)
    if not 0.0 <= m1 <= 1.0:
        raise ValueError(f"m1: expected 0 <= 1 - m <= 1, got {m1!r}")
    if m1 == 0.0:
        sech = 1.0 / np.cosh(u)
        return np.tanh(u), sech, sech.copy()
    As, Cs = _agm_sequence(m1)
    n = len(As) - 1
    quarter = math.pi / (2.0 * As[-1])  # K(m)
    ur = u - 4.0 * quarter * np.round(u / (4.0 * quarter))
    phi = (2.0**n) * As[-1] * ur
    for k in range(n, 0, -1):
        phi = 0.5 * (phi + np.arcsin(np.clip(Cs[k] / As[k] * np.sin(phi), -1.0, 1.0)))
    sn, cn = np.sin(phi), np.cos(phi)
    dn = np.sqrt(cn * cn + m1 * sn * sn)
    return sn, cn, dn


def _permutation_parity(p: tuple[int, int, int]) -> int:
    return 1 if p in ((0, 1, 2), (1, 2, 0), (2, 0, 1)) else -1


@dataclass(frozen=True)
class EllipticSolution:
    """Parameters of the exact solution for one (J, omega0); see the module docstring.

    axes: (a, b, c) indices into the user's axes (c = the axis the polhode circles, b = the
    intermediate-inertia axis) - the permutation to the canonical frame. amplitude, sign: (3,)
    in the user's axes (rad/s, +-1). lam: rad/s; u0: phase; m, m1 = 1 - m; side = sign(D - J_mid).
    stationary: omega0 is a permanent rotation (Eqs. 20a-c) or all inertias are equal.
    """

    J: NDArray[np.float64]
    omega0: NDArray[np.float64]
    axes: tuple[int, int, int]
    amplitude: NDArray[np.float64]
    sign: NDArray[np.float64]
    lam: float
    u0: float
    m: float
    m1: float
    side: int
    stationary: bool

    @property
    def period(self) -> float:
        """Period of omega(t) in s: 4K/lam (inf on the separatrix, nan if stationary)."""
        if self.stationary:
            return math.nan
        return 4.0 * complete_k(self.m1) / self.lam

    def omega(self, t: ArrayLike) -> NDArray[np.float64]:
        """Body angular velocity omega(t): (N, 3) for t (N,) in s (Eqs. 13a-c exact)."""
        t = np.atleast_1d(np.asarray(t, dtype=np.float64))
        if self.stationary:
            return np.broadcast_to(self.omega0, (t.size, 3)).copy()
        sn, cn, dn = jacobi_sn_cn_dn(self.lam * t + self.u0, self.m1)
        a, b, c = self.axes
        out = np.empty((t.size, 3))
        out[:, a], out[:, b], out[:, c] = cn, sn, dn
        return out * (self.amplitude * self.sign)

    def flip_times(self, t_end: float) -> NDArray[np.float64]:
        """Times in [0, t_end] (s) where omega_b (intermediate axis) changes sign: sn(u) = 0,
        u = 2 K k. On the tennis racket these are the half-turn flips of the head (Fig. 2-7)."""
        if self.stationary or self.m1 == 0.0:
            return np.empty(0)
        twok = 2.0 * complete_k(self.m1)
        k0 = math.ceil(self.u0 / twok - 1e-12)
        k1 = math.floor((self.lam * t_end + self.u0) / twok)
        ks = np.arange(k0, k1 + 1, dtype=np.float64)
        t = (ks * twok - self.u0) / self.lam
        return t[(t > 0.0) & (t <= t_end)]


def _validated(J: ArrayLike, omega0: ArrayLike) -> tuple[NDArray, NDArray]:
    Jv = check_shape("J", check_positive("J", J), (3,))
    w0 = check_shape("omega0", check_finite("omega0", omega0), (3,))
    return Jv, w0


def elliptic_solution(J: ArrayLike, omega0: ArrayLike) -> EllipticSolution:
    """Set up the exact solution for principal inertias J (3,) kg m^2 (any order, > 0) and body
    angular velocity omega0 (3,) rad/s at t = 0. The canonical permutation is in `.axes`."""
    J, w0 = _validated(J, omega0)
    big, mid, small = (int(i) for i in np.argsort(-J, kind="stable"))
    # a permanent rotation (Eqs. 20a-c): every spinning axis has the same inertia (exact test)
    stationary = len({float(J[i]) for i in range(3) if w0[i] != 0.0}) <= 1
    # omega(t; c w0) = c omega(c t; w0) and J -> s J changes nothing: work at unit scale
    w_scale = float(np.max(np.abs(w0))) if not stationary else 1.0
    Jn, wn = J / np.max(J), w0 / w_scale
    H = Jn * wn

    def s_of(k: int) -> float:  # sum_{i != k} H_i^2 (J_i - J_k) / J_i, one-signed terms
        return float(sum(H[i] ** 2 * (Jn[i] - Jn[k]) / Jn[i] for i in range(3) if i != k))

    s_b = s_of(mid)
    c, a = (big, small) if s_b >= 0.0 else (small, big)
    b = mid
    side = int(np.sign(s_b))
    p_c, p_a = (-s_of(c), s_of(a)) if not stationary else (0.0, 0.0)
    # p_a ~ 0 or J_c = J_b here only if the deviation from a permanent rotation is below
    # ~1e-140 of the spin (p_a, a square, below 1e-280: subnormal or underflowed, where the
    # ratios below lose every digit): the solution leaves the axis as 1e-140 e^{lam t}, a
    # constant to machine precision for any t < 300 / lam
    if stationary or abs(p_a) < 1e-280 or Jn[c] == Jn[b]:
        one = np.ones(3)
        return EllipticSolution(J, w0, (a, b, c), np.abs(w0), one, 0.0, 0.0, 0.0, 1.0, side, True)
    Ja, Jb, Jc = Jn[a], Jn[b], Jn[c]
    amp = np.empty(3)
    amp[a] = math.sqrt(max(p_c / (Ja * (Jc - Ja)), 0.0))
    amp[b] = math.sqrt(max(p_c / (Jb * (Jc - Jb)), 0.0))
    amp[c] = math.sqrt(max(p_a / (Jc * (Jc - Ja)), 0.0))
    lam = math.sqrt((Jc - Jb) * p_a / (Ja * Jb * Jc))
    m = min(max((Jb - Ja) * p_c / ((Jc - Jb) * p_a), 0.0), 1.0)
    m1 = min(max((Jc - Ja) * s_b / ((Jc - Jb) * p_a), 0.0), 1.0)
    if m1 < 1e-280:  # subnormal: the elliptic functions lose every digit; on the separatrix
        m1 = 0.0
    sign = np.ones(3)
    sign[a] = 1.0 if wn[a] >= 0.0 else -1.0
    sign[c] = 1.0 if wn[c] >= 0.0 else -1.0
    sign[b] = _permutation_parity((a, b, c)) * np.sign(Jc - Jb) * sign[a] * sign[c]
    sn0 = wn[b] * sign[b] / amp[b] if amp[b] > 0.0 else 0.0
    cn0 = abs(wn[a]) / amp[a] if amp[a] > 0.0 else 1.0
    r = math.hypot(sn0, cn0)
    sn0, cn0 = sn0 / r, cn0 / r
    if m1 == 0.0:  # separatrix: u0 = atanh(sn0), finite unless on the saddle itself
        u0 = math.asinh(sn0 / cn0) if cn0 > 0.0 else math.copysign(math.inf, sn0)
    else:
        u0 = sn0 * float(elliprf(cn0 * cn0, cn0 * cn0 + m1 * sn0 * sn0, 1.0))
    amp, lam = amp * w_scale, lam * w_scale
    return EllipticSolution(J, w0, (a, b, c), amp, sign, lam, u0, m, m1, side, False)


def analytic_omega(J: ArrayLike, omega0: ArrayLike, t: ArrayLike) -> NDArray[np.float64]:
    """Exact body angular velocity of a torque-free rigid body (ch. 2 Eqs. 13a-c), Jacobi elliptic.

    J: (3,) principal inertias in kg m^2, any order, all > 0 and finite (ValueError naming `J`).
    omega0: (3,) body components of omega at t = 0 in rad/s. t: scalar or (N,) times in s.
    Returns (N, 3) body components in rad/s (N = 1 for scalar t). Valid on both sides of the
    separatrix (D < J_mid and D > J_mid), on it (sech/tanh limit) and when 1 - m < 1e-10.
    """
    t_arr = check_finite("t", t)
    return elliptic_solution(J, omega0).omega(t_arr)


def attitude_reference(
    J: ArrayLike, omega0: ArrayLike, t: ArrayLike, R0: ArrayLike | None = None, rtol: float = 1e-13
) -> NDArray[np.float64]:
    """Reference attitude R(t) (N, 3, 3) of the torque-free body, inertial <- body, R(0) = R0.

    There is no closed form here for R (it needs Jacobi theta functions), so this integrates the
    kinematics R' = R hat(omega(t)) (ch. 2 Eq. 24) driven by the EXACT omega(t) of
    `analytic_omega`, with scipy's DOP853 at `rtol` (global error ~1e-12 at the default): a
    reference independent of the package's Lie-group steppers. t: (N,) increasing times in s."""
    sol = elliptic_solution(J, omega0)
    t_arr = np.atleast_1d(check_finite("t", t)).astype(float)
    R_init = np.eye(3) if R0 is None else check_shape("R0", R0, (3, 3))

    def rhs(s: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
        w = sol.omega(np.array([s]))[0]
        return (y.reshape(3, 3) @ hat(w)).ravel()

    out = solve_ivp(rhs, (0.0, t_arr[-1]), R_init.ravel(), "DOP853", t_arr, rtol=rtol, atol=rtol)
    return out.y.T.reshape(-1, 3, 3)
