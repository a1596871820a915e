"""Dynamic and static solves of the n-link chain of `mf_envs.physics.multilink` (ch. 4 Eq. 28).

Dynamics: M*(q) q_dd + N*(q, q_d) q_d + K* q = F#(t) + B^T F_ex - D^T c D q_d (Eq. 28a plus
optional joint damping c), integrated with scipy's `solve_ivp` on y = (q, q_dot). The spring
frequencies grow like n^2 for a fixed beam, so the system turns stiff as n grows: the accuracy
benchmark (`benchmarks/accuracy/multilink.py`, scene multilink_dynamics) measures RK45, DOP853 and
Radau side by side; DOP853 is the default.

Statics (clamped chain): Newton on the total potential
Pi(psi) = sum k (theta - theta#)^2 / 2 - sum F_b . x_c^(b) - P . x_tip - M_tip psi_n - sum m_b psi_b
under dead loads. Its Hessian is K* + diag(e(psi_a) . A_a) with A = C^T F + c_tip P: tridiagonal,
so each Newton step is one banded Cholesky (`scipy.linalg.solveh_banded`), O(n). When the Hessian
is not positive definite the step is shifted (Levenberg) and every step is backtracked on Pi.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.integrate import solve_ivp
from scipy.linalg import LinAlgError, solveh_banded

from mf_envs._validate import (
    check_choice,
    check_finite,
    check_shape,
    finite_scalar,
    positive_scalar,
)
from mf_envs.physics.multilink.kernels import chain_constants, eom_kernel
from mf_envs.physics.multilink.model import (
    _difference,
    actuation_forces,
    centerline,
    generalized_loads,
    gravity_energy,
    kinetic_energy,
    mass_matrix,
    spring_energy,
    stiffness_matrix,
    velocity_forces,
)
from mf_envs.physics.multilink.params import ChainParams

METHODS = ("DOP853", "RK45", "Radau", "BDF", "LSODA")

ActuationFn = Callable[[float], ArrayLike]
LoadFn = Callable[[float, NDArray[np.float64], NDArray[np.float64]], dict[str, Any]]


def accelerations(
    params: ChainParams,
    q: ArrayLike,
    qdot: ArrayLike,
    theta_sharp: ArrayLike | None = None,
    loads: dict[str, Any] | None = None,
    reference: bool = False,
) -> NDArray[np.float64]:
    """q_dd (n_dof,) from Eq. 28a; `loads` are keyword arguments of `generalized_loads`.

    Evaluated by the compiled `eom_kernel`; with `reference`, assembled term by term with the
    numpy functions of `multilink` instead (the plain numpy route, `accelerations_reference`).
    """
    q = np.asarray(q, dtype=np.float64)
    qdot = np.asarray(qdot, dtype=np.float64)
    if reference:
        rhs = actuation_forces(params, theta_sharp) + generalized_loads(params, q, **(loads or {}))
        rhs -= stiffness_matrix(params) @ q + velocity_forces(params, q, qdot)
        if params.joint_damping > 0.0:
            D = _difference(params)
            rhs -= params.joint_damping * (D.T @ (D @ qdot))
        return np.linalg.solve(mass_matrix(params, q), rhs)
    ctc, colsum = chain_constants(params)
    off = np.zeros(params.n_joints)
    if theta_sharp is not None:
        off = off + check_shape("theta_sharp", theta_sharp, (params.n_joints,))
    if params.base == "clamped":
        off[0] += params.base_angle
    extra = np.zeros(params.n_dof)
    if loads:
        extra = generalized_loads(params, q, include_gravity=False, **loads)
    clamped = params.base == "clamped"
    return eom_kernel(
        q,
        qdot,
        ctc,
        colsum,
        params.link_mass,
        params.link_inertia,
        params.joint_stiffness,
        params.joint_damping,
        off,
        params.gravity,
        clamped,
        extra,
    )


def accelerations_reference(*args: Any, **kwargs: Any) -> NDArray[np.float64]:
    """q_dd from Eq. 28a assembled term by term with the numpy functions of `multilink`:
    `accelerations(..., reference=True)` (same arguments)."""
    return accelerations(*args, reference=True, **kwargs)


def total_energy(params: ChainParams, q: ArrayLike, qdot: ArrayLike) -> float:
    """Kinetic + spring + gravity energy, J (no actuation, no other loads): conserved undamped."""
    return kinetic_energy(params, q, qdot) + spring_energy(params, q) + gravity_energy(params, q)


@dataclass(frozen=True, eq=False)
class ChainTrajectory:
    """t (N,) s; q (N, n_dof); qdot (N, n_dof); nfev: right-hand-side evaluations."""

    params: ChainParams
    t: NDArray[np.float64]
    q: NDArray[np.float64]
    qdot: NDArray[np.float64]
    nfev: int

    def centerline(self, i: int = -1) -> NDArray[np.float64]:
        """(n + 1, 2), m, the polyline at sample i."""
        return centerline(self.params, self.q[i])

    def energy(self) -> NDArray[np.float64]:
        """(N,), J, `total_energy` along the trajectory."""
        return np.array([total_energy(self.params, q, v) for q, v in zip(self.q, self.qdot)])


def simulate(
    params: ChainParams,
    q0: ArrayLike,
    qdot0: ArrayLike,
    t_end: float,
    method: str = "DOP853",
    rtol: float = 1e-8,
    atol: float = 1e-10,
    t_eval: ArrayLike | None = None,
    theta_sharp: ActuationFn | None = None,
    loads: LoadFn | None = None,
) -> ChainTrajectory:
    """Integrate Eq. 28a from (q0, qdot0) over [0, t_end] s with `solve_ivp(method)`.

    theta_sharp(t) -> (n_joints,) rad actuation offsets; loads(t, q, qdot) -> kwargs of
    `generalized_loads` (link_forces, link_moments, tip_force, tip_moment). Raises RuntimeError
    if the integrator fails.
    """
    check_choice("method", method, METHODS)
    t_end = positive_scalar("t_end", t_end)
    n = params.n_dof
    y0 = np.concatenate([check_shape("q0", q0, (n,)), check_shape("qdot0", qdot0, (n,))])

    def f(t: float, y: NDArray[np.float64]) -> NDArray[np.float64]:
        q, v = y[:n], y[n:]
        ts = None if theta_sharp is None else theta_sharp(t)
        ld = None if loads is None else loads(t, q, v)
        return np.concatenate([v, accelerations(params, q, v, ts, ld)])

    sol = solve_ivp(f, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, t_eval=t_eval)
    if not sol.success:
        raise RuntimeError(f"solve_ivp({method}) failed: {sol.message}")
    return ChainTrajectory(params, sol.t, sol.y[:n].T.copy(), sol.y[n:].T.copy(), int(sol.nfev))


@dataclass(frozen=True, eq=False)
class ChainStatic:
    """Static equilibrium: psi (n,) rad; centerline (n+1, 2) m; tip_position (2,) m;
    tip_angle rad (psi_n); potential J; iterations (Newton steps)."""

    psi: NDArray[np.float64]
    centerline: NDArray[np.float64]
    tip_position: NDArray[np.float64]
    tip_angle: float
    potential: float
    iterations: int


def _link_forces(params: ChainParams, distributed_load: ArrayLike) -> NDArray[np.float64]:
    q = check_finite("distributed_load", distributed_load)
    if q.shape not in ((2,), (params.n_links, 2)):
        raise ValueError(f"distributed_load: expected (2,) or ({params.n_links}, 2), got {q.shape}")
    # a load uniform over each link lumps exactly into q l at the centre, no moment
    return np.broadcast_to(q, (params.n_links, 2)) * params.link_length


def solve_static(
    params: ChainParams,
    tip_force: ArrayLike = (0.0, 0.0),
    tip_moment: float = 0.0,
    distributed_load: ArrayLike = (0.0, 0.0),
    theta_sharp: ArrayLike | None = None,
    psi0: ArrayLike | None = None,
    tol: float = 1e-10,
    max_iter: int = 200,
) -> ChainStatic:
    """Equilibrium of a clamped chain under dead loads (module docstring): tip force (2,) N and
    moment N m, distributed load (2,) or (n, 2) N/m (inertial, uniform per link), gravity from
    params, actuation offsets theta# (n_joints,) rad. Converged when the Newton step is below
    `tol` rad; raises RuntimeError after `max_iter` steps."""
    if params.base != "clamped":
        raise ValueError("params: base must be 'clamped' for a static solve (a free chain floats)")
    n, l = params.n_links, params.link_length
    F = _link_forces(params, distributed_load)
    P = check_shape("tip_force", tip_force, (2,))
    M0 = finite_scalar("tip_moment", tip_moment)
    Fg = F + params.link_mass * params.gravity
    # A = C^T F + c_tip P by suffix sums, O(n): the dead load seen by each link direction
    beyond = np.cumsum(Fg[::-1], axis=0)[::-1] - Fg
    A = 0.5 * l * Fg + l * beyond + l * P
    k = params.joint_stiffness
    ts = np.zeros(n) if theta_sharp is None else check_shape("theta_sharp", theta_sharp, (n,))
    ts = ts + np.eye(1, n)[0] * params.base_angle  # the clamp direction acts like theta#_0

    psi = np.zeros(n) if psi0 is None else check_shape("psi0", psi0, (n,)).copy()
    psi, iterations = _minimise(psi, A, k, ts, M0, tol, max_iter)
    cl = centerline(params, psi)
    energy = _potential(psi, A, k, ts, M0)
    return ChainStatic(psi, cl, cl[-1].copy(), float(psi[-1]), energy, iterations)


def _potential(psi: NDArray[np.float64], A, k, ts, M0: float) -> float:
    """Total potential of the chain: joint strain energy minus the work of the dead loads."""
    el = np.diff(psi, prepend=0.0) - ts
    work = np.sum(np.cos(psi) * A[:, 0] + np.sin(psi) * A[:, 1]) + M0 * psi[-1]
    return float(0.5 * np.sum(k * el * el) - work)


def _gradient(psi: NDArray[np.float64], A, k, ts, M0: float) -> NDArray[np.float64]:
    """d potential / d psi."""
    km = k * (np.diff(psi, prepend=0.0) - ts)  # joint moments
    g = km - np.append(km[1:], 0.0) + np.sin(psi) * A[:, 0] - np.cos(psi) * A[:, 1]
    g[-1] -= M0
    return g


def _minimise(psi, A, k, ts, M0: float, tol: float, max_iter: int) -> tuple[NDArray, int]:
    """Newton on the tridiagonal Hessian with Armijo backtracking, from psi; (psi, steps)."""
    n = psi.shape[0]
    ab = np.zeros((2, n))
    ab[0, 1:] = -k[1:]
    kd = k.copy()
    kd[:-1] += k[1:]
    eps = np.finfo(float).eps
    g_prev = np.inf
    iterations = 0
    for iterations in range(1, max_iter + 1):  # noqa: B007 (reported below)
        g = _gradient(psi, A, k, ts, M0)
        g_max = float(np.max(np.abs(g)))
        # round-off floor of the joint moments k (theta - theta#), and stagnation at that level
        floor = 16.0 * eps * float(np.max(k)) * (1.0 + float(np.max(np.abs(psi))))
        if g_max <= floor or (g_max > 0.5 * g_prev and g_max < 1e3 * floor):
            break
        g_prev = g_max
        ab[1] = kd + np.cos(psi) * A[:, 0] + np.sin(psi) * A[:, 1]
        d = _shifted_solve(ab, -g)
        step, pi0 = 1.0, _potential(psi, A, k, ts, M0)
        while np.max(np.abs(d)) * step > 1e-6 and step > 1e-10:
            if _potential(psi + step * d, A, k, ts, M0) <= pi0 + 1e-4 * step * (g @ d):
                break
            step *= 0.5
        psi = psi + step * d
        if step == 1.0 and np.max(np.abs(d)) < tol:
            break
    else:
        raise RuntimeError(f"solve_static: no convergence in {max_iter} Newton steps")
    return psi, iterations


def _shifted_solve(ab: NDArray[np.float64], rhs: NDArray[np.float64]) -> NDArray[np.float64]:
    """Solve the symmetric tridiagonal system (upper banded `ab`), shifting the diagonal
    (Levenberg) until it is positive definite, so that the step is a descent direction."""
    shift, scale = 0.0, float(np.max(np.abs(ab)))
    for _ in range(60):
        a = ab.copy()
        a[1] += shift
        try:
            return solveh_banded(a, rhs)
        except LinAlgError:
            shift = max(2.0 * shift, 1e-8 * scale)
    raise RuntimeError("solve_static: could not make the Hessian positive definite")
