"""Numba step kernels for the torque-free rigid body (Rios 2017, ch. 2 §2.2), reusable elsewhere.

State: body angular momentum H (3,) in kg m^2/s (components on the body frame e(t), Eq. 9a) and
attitude R (3, 3) with e(t) = e^I R(t) (Eq. 4); Jinv (3,) = 1/J of the principal inertias.

Kernels (all `@numba.njit(cache=True)`, float64, no allocation beyond small temporaries):
- `euler_rhs(H, Jinv)`            dH/dt = H x omega, omega = J^-1 H (Eq. 22 / 12a)
- `rk4_momentum_step(H, Jinv, dt)` one classical RK4 step of Eq. 22 (the seed's scheme)
- `rodrigues_midpoint_step(R, w0, w1, dt)`  R exp(dt hat((w0 + w1)/2)) (Eqs. 29-31, order 2);
   generic: any body angular-velocity pair at the step ends, e.g. the ship attitude of ch. 3.
- `magnus4_step(R, w0, w1, wd0, wd1, dt)`   4th-order Magnus reconstruction from end values and
   end derivatives of omega (no extra right-hand-side calls: wd = J^-1 euler_rhs is RK4's k1).
- `project_invariants(H, Jinv, h2, e2)`     put H back on |H|^2 = h2, H.J^-1 H = e2 (exact).
- `splitting_step(H, R, Jinv, dt, order3)`  Strang Lie-Poisson splitting: exact sub-flows of
   H_i^2/(2 J_i), rotations about body axes (|H| and R H conserved to round-off).
- `integrate(...)`                           the loop over one of the five methods.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs.frames.kernels import cross, exp_so3
from mf_envs.frames.steppers import make_rk4, rk4_work

# method codes used by `integrate` (names in rigid_body.METHODS, same order)
RK4_RODRIGUES, RK4_MAGNUS4, RK4_MAGNUS4_PROJ, SPLITTING2, SPLITTING4 = 0, 1, 2, 3, 4

# Yoshida's triple jump: S4(h) = S2(g1 h) S2(g0 h) S2(g1 h)
_CBRT2 = 2.0 ** (1.0 / 3.0)
YOSHIDA_G1 = 1.0 / (2.0 - _CBRT2)
YOSHIDA_G0 = -_CBRT2 / (2.0 - _CBRT2)


@numba.njit(cache=True)
def euler_rhs(H: np.ndarray, Jinv: np.ndarray) -> np.ndarray:
    """dH/dt (3,) = H x (J^-1 H): torque-free Euler equations in body components (Eq. 22a-c)."""
    return cross(H, Jinv * H)


@numba.njit(cache=True)
def _no_inputs(t: float, Jinv: np.ndarray) -> float:
    """The torque-free body has no exogenous inputs."""
    return 0.0


@numba.njit(cache=True)
def _euler_stage(t: float, H: np.ndarray, inp: float, Jinv: np.ndarray, out: np.ndarray) -> None:
    """Eq. 22 in the frames RK4 stepper's signature."""
    out[:] = euler_rhs(H, Jinv)


_rk4 = make_rk4(_euler_stage, _no_inputs)


@numba.njit(cache=True)
def rk4_momentum_step(H: np.ndarray, Jinv: np.ndarray, dt: float) -> np.ndarray:
    """One classical RK4 step of Eq. 22 from H(t) to H(t + dt) (body components, kg m^2/s)."""
    work = rk4_work(3)
    _rk4(0.0, H, dt, Jinv, work)
    return H + work[0]


@numba.njit(cache=True)
def rodrigues_midpoint_step(R: np.ndarray, w0: np.ndarray, w1: np.ndarray, dt: float) -> np.ndarray:
    """R(t + dt) = R(t) exp(dt hat(omega_mid)), omega_mid = (w0 + w1)/2 (ch. 2 Eqs. 29-31).

    R: (3, 3) body-to-inertial attitude; w0, w1: (3,) body angular velocity (rad/s) at t, t + dt.
    Second order in dt (the exact step has the commutator term dt^2/12 w0 x w1 and more).
    """
    return R @ exp_so3((0.5 * dt) * (w0 + w1))


@numba.njit(cache=True)
def magnus4_step(
    R: np.ndarray, w0: np.ndarray, w1: np.ndarray, wd0: np.ndarray, wd1: np.ndarray, dt: float
) -> np.ndarray:
    """Fourth-order Magnus step for dR/dt = R hat(omega): R(t + dt) = R exp(hat(theta)),

    theta = dt/2 (w0 + w1) + dt^2/12 (wd0 - wd1)   [Hermite quadrature of int omega, O(dt^5)]
            + dt^2/12 (w0 x w1)                    [first commutator, right-multiplied flow]
    w0, w1: omega (3,) at t, t + dt; wd0, wd1: d omega/dt (3,) at t, t + dt (rad/s^2).
    """
    h2 = dt * dt / 12.0
    theta = (0.5 * dt) * (w0 + w1) + h2 * (wd0 - wd1) + h2 * cross(w0, w1)
    return R @ exp_so3(theta)


@numba.njit(cache=True)
def _rotate_about(v: np.ndarray, axis: np.ndarray, angle: float) -> np.ndarray:
    """Rotate v by `angle` about the unit vector `axis` (Rodrigues)."""
    c, s = math.cos(angle), math.sin(angle)
    k = cross(axis, v)
    d = axis[0] * v[0] + axis[1] * v[1] + axis[2] * v[2]
    return c * v + s * k + (1.0 - c) * d * axis


@numba.njit(cache=True)
def project_invariants(H: np.ndarray, Jinv: np.ndarray, h2: float, e2: float) -> np.ndarray:
    """Return H moved onto {|H|^2 = h2, H . J^-1 H = e2} (the polhode through H(0)).

    First a radial scaling fixes |H|; then a rotation of H on that sphere, in the plane of H and
    the tangential energy gradient g, fixes the energy by Newton on the angle (|H| is untouched
    by rotations). Near a permanent rotation g -> 0 and the energy is left as is (it is then
    stationary on the sphere and the step's residual vanishes with it).
    """
    n2 = H[0] * H[0] + H[1] * H[1] + H[2] * H[2]
    if n2 == 0.0:
        return H.copy()
    Hn = H * math.sqrt(h2 / n2)
    for _ in range(16):  # quadratic convergence from a step's tiny residual; more far away
        w = Jinv * Hn
        E2 = Hn[0] * w[0] + Hn[1] * w[1] + Hn[2] * w[2]
        res = E2 - e2
        if abs(res) <= 2e-16 * e2:
            break
        g = w - (E2 / h2) * Hn  # tangential part of grad(E2)/2 on the sphere
        gn = math.sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2])
        if gn <= 1e-300 or gn * math.sqrt(h2) <= 1e-14 * abs(E2):
            break
        axis = cross(Hn, g) / (gn * math.sqrt(h2))  # rotating H about it moves H along +g
        # d(E2)/d(angle) = 2 |H| |g| at angle 0
        Hn = _rotate_about(Hn, axis, -res / (2.0 * math.sqrt(h2) * gn))
    return Hn


@numba.njit(cache=True)
def _axis_flow(H: np.ndarray, R: np.ndarray, Jinv: np.ndarray, i: int, tau: float) -> None:
    """Exact flow for time tau of the sub-Hamiltonian H_i^2/(2 J_i), in place: omega = (H_i/J_i) e_i
    is constant, R <- R exp(theta hat(e_i)), H <- exp(-theta hat(e_i)) H, theta = tau H_i/J_i."""
    theta = tau * H[i] * Jinv[i]
    c, s = math.cos(theta), math.sin(theta)
    j, k = (i + 1) % 3, (i + 2) % 3
    hj, hk = H[j], H[k]
    H[j] = c * hj + s * hk
    H[k] = -s * hj + c * hk
    for r in range(3):
        rj, rk = R[r, j], R[r, k]
        R[r, j] = c * rj + s * rk
        R[r, k] = -s * rj + c * rk


@numba.njit(cache=True)
def splitting_step(H: np.ndarray, R: np.ndarray, Jinv: np.ndarray, dt: float, order3) -> None:
    """One Strang step (in place) of the Lie-Poisson splitting E = sum_i H_i^2/(2 J_i):
    flows (order3[0], dt/2) (order3[1], dt/2) (order3[2], dt) (order3[1], dt/2) (order3[0], dt/2).
    Symplectic, time-reversible, order 2; |H| and the inertial momentum R H conserved exactly."""
    _axis_flow(H, R, Jinv, order3[0], 0.5 * dt)
    _axis_flow(H, R, Jinv, order3[1], 0.5 * dt)
    _axis_flow(H, R, Jinv, order3[2], dt)
    _axis_flow(H, R, Jinv, order3[1], 0.5 * dt)
    _axis_flow(H, R, Jinv, order3[0], 0.5 * dt)


@numba.njit(cache=True)
def integrate(
    H0: np.ndarray,
    R0: np.ndarray,
    Jinv: np.ndarray,
    dt: float,
    n_steps: int,
    save_every: int,
    method: int,
    order3: np.ndarray,
) -> tuple[np.ndarray, np.ndarray]:
    """Integrate n_steps of size dt with `method` (codes above); returns H (N, 3), R (N, 3, 3)
    at steps 0, save_every, 2 save_every, ... (N = n_steps // save_every + 1)."""
    n_out = n_steps // save_every + 1
    H_out = np.empty((n_out, 3))
    R_out = np.empty((n_out, 3, 3))
    H = H0.copy()
    R = R0.copy()
    H_out[0] = H
    R_out[0] = R
    h2 = H[0] * H[0] + H[1] * H[1] + H[2] * H[2]
    e2 = H[0] * H[0] * Jinv[0] + H[1] * H[1] * Jinv[1] + H[2] * H[2] * Jinv[2]
    wd0 = Jinv * euler_rhs(H, Jinv)
    for n in range(1, n_steps + 1):
        if method == SPLITTING2:
            splitting_step(H, R, Jinv, dt, order3)
        elif method == SPLITTING4:
            splitting_step(H, R, Jinv, YOSHIDA_G1 * dt, order3)
            splitting_step(H, R, Jinv, YOSHIDA_G0 * dt, order3)
            splitting_step(H, R, Jinv, YOSHIDA_G1 * dt, order3)
        else:
            H1 = rk4_momentum_step(H, Jinv, dt)
            if method == RK4_MAGNUS4_PROJ:
                H1 = project_invariants(H1, Jinv, h2, e2)
            w0 = Jinv * H
            w1 = Jinv * H1
            if method == RK4_RODRIGUES:
                R = rodrigues_midpoint_step(R, w0, w1, dt)
            else:
                wd1 = Jinv * euler_rhs(H1, Jinv)
                R = magnus4_step(R, w0, w1, wd0, wd1, dt)
                wd0 = wd1
            H = H1
        if n % save_every == 0:
            H_out[n // save_every] = H
            R_out[n // save_every] = R
    return H_out, R_out
