"""Kinematics and mechanics of the planar n-link chain (Rios 2017 ch. 4 Eqs. 2-28): link frames
and centres, B and its rate, M*, N*, K*, F#, energies and reduced loads."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import check_shape, finite_scalar
from mf_envs.frames import compose, frame_connection, rot_z
from mf_envs.physics.multilink.params import ChainParams


def coefficient_matrix(params: ChainParams) -> NDArray[np.float64]:
    """C (n, n): x_c^(b) = x_origin + sum_a C[b, a] e(psi_a) (Eq. 13); origin = clamp or C^(1)."""
    n, l = params.n_links, params.link_length
    C = np.tril(np.full((n, n), l), -1) + np.eye(n) * (0.5 * l)
    if params.base == "free":
        C[0, 0] = 0.0
        C[1:, 0] = 0.5 * l
    return C


def tip_coefficients(params: ChainParams) -> NDArray[np.float64]:
    """c (n,): distal end of link n = x_origin + sum_a c[a] e(psi_a)."""
    c = coefficient_matrix(params)[-1].copy()
    c[-1] += 0.5 * params.link_length
    return c


def _split(params: ChainParams, q: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    q = np.asarray(q, dtype=np.float64)
    if q.shape != (params.n_dof,):
        raise ValueError(f"q: expected shape ({params.n_dof},), got {q.shape}")
    origin = params.base_position if params.base == "clamped" else q[:2]
    return origin, q[params.n_trans :]


def link_angles(params: ChainParams, q: ArrayLike) -> NDArray[np.float64]:
    """psi (n,), rad, link angles from e_1 (Eq. 2)."""
    return _split(params, q)[1].copy()


def joint_angles(params: ChainParams, q: ArrayLike) -> NDArray[np.float64]:
    """theta (n_joints,), rad, relative joint rotations psi^(a+1) - psi^(a) (Eq. 5b)."""
    psi = _split(params, q)[1]
    if params.base == "clamped":
        return np.diff(psi, prepend=params.base_angle)
    return np.diff(psi)


def _start_and_steps(
    params: ChainParams, q: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """First end of the chain (2,) and the link vectors l e(psi_a) (n, 2)."""
    origin, psi = _split(params, q)
    steps = params.link_length * np.stack([np.cos(psi), np.sin(psi)], axis=1)
    start = origin if params.base == "clamped" else origin - 0.5 * steps[0]
    return start, steps


def link_centers(params: ChainParams, q: ArrayLike) -> NDArray[np.float64]:
    """x_c (n, 2), m, inertial link-centre positions (Eqs. 10, 13), O(n) by cumulative sums."""
    start, steps = _start_and_steps(params, q)
    return start + np.cumsum(steps, axis=0) - 0.5 * steps


def centerline(params: ChainParams, q: ArrayLike) -> NDArray[np.float64]:
    """(n + 1, 2), m: the chain polyline from its first end (clamp) to the tip."""
    start, steps = _start_and_steps(params, q)
    return np.vstack([start, start + np.cumsum(steps, axis=0)])


def tip_position(params: ChainParams, q: ArrayLike) -> NDArray[np.float64]:
    """(2,), m, distal end of link n."""
    return centerline(params, q)[-1]


def link_frames(params: ChainParams, q: ArrayLike) -> NDArray[np.float64]:
    """E^(a) (n, 4, 4): link frame connections by the recursion E^(a+1) = E^(a) E^(a+1/a).

    Planar frames embedded in SE(3) (rotation about e_3); the relative connection is Eq. 8b.
    Used as the independent reference for `link_centers` and the B matrix in the tests.
    """
    origin, psi = _split(params, q)
    l = params.link_length
    if params.base == "clamped":
        base = frame_connection(rot_z(params.base_angle), [*params.base_position, 0.0])
        th, ref = psi[0] - params.base_angle, base
        half_step = frame_connection(rot_z(0.0), [0.5 * l, 0.0, 0.0])
        E = [compose(ref, frame_connection(rot_z(th), [0.0, 0.0, 0.0]), half_step)]
    else:
        E = [frame_connection(rot_z(psi[0]), [*origin, 0.0])]
    for a in range(1, params.n_links):
        th = psi[a] - psi[a - 1]
        rel = frame_connection(rot_z(th), [0.5 * l * (1 + np.cos(th)), 0.5 * l * np.sin(th), 0.0])
        E.append(compose(E[-1], rel))
    return np.stack(E)


def _e(psi: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    return np.cos(psi), np.sin(psi)


def b_matrix(params: ChainParams, q: ArrayLike) -> NDArray[np.float64]:
    """B (3n, n_dof): stacked (x_dot_c, z_dot_c, psi_dot) of every link = B q_dot (Eqs. 20-21)."""
    _, psi = _split(params, q)
    n, t = params.n_links, params.n_trans
    C = coefficient_matrix(params)
    c, s = _e(psi)
    B = np.zeros((3 * n, params.n_dof))
    if t:
        B[0::3, 0] = 1.0
        B[1::3, 1] = 1.0
    B[0::3, t:] = -C * s
    B[1::3, t:] = C * c
    B[2::3, t:] = np.eye(n)
    return B


def b_matrix_rate(params: ChainParams, q: ArrayLike, qdot: ArrayLike) -> NDArray[np.float64]:
    """dB/dt (3n, n_dof) along q_dot."""
    _, psi = _split(params, q)
    w = np.asarray(qdot, dtype=np.float64)[params.n_trans :]
    n, t = params.n_links, params.n_trans
    C = coefficient_matrix(params)
    c, s = _e(psi)
    Bd = np.zeros((3 * n, params.n_dof))
    Bd[0::3, t:] = -C * c * w
    Bd[1::3, t:] = -C * s * w
    return Bd


def mass_diagonal(params: ChainParams) -> NDArray[np.float64]:
    """diag of M (3n,): (m, m, J_c) per link (Eq. 19c)."""
    return np.tile([params.link_mass, params.link_mass, params.link_inertia], params.n_links)


# --- dynamics ------------------------------------------------------------------------------


def mass_matrix(params: ChainParams, q: ArrayLike) -> NDArray[np.float64]:
    """M* = B^T M B (n_dof, n_dof), symmetric positive definite (Eq. 28b), closed form."""
    _, psi = _split(params, q)
    m, t = params.link_mass, params.n_trans
    C = coefficient_matrix(params)
    c, s = _e(psi)
    CtC = C.T @ C
    Ms = np.empty((params.n_dof, params.n_dof))
    Ms[t:, t:] = m * CtC * (np.outer(c, c) + np.outer(s, s)) + params.link_inertia * np.eye(c.size)
    if t:
        col = m * C.sum(axis=0)
        Ms[:2, :2] = m * params.n_links * np.eye(2)
        Ms[0, 2:] = Ms[2:, 0] = -col * s
        Ms[1, 2:] = Ms[2:, 1] = col * c
    return Ms


def velocity_forces(params: ChainParams, q: ArrayLike, qdot: ArrayLike) -> NDArray[np.float64]:
    """N* q_dot = B^T M B_dot q_dot (n_dof,): centripetal terms of Eq. 28a (N* of Eq. 28c)."""
    _, psi = _split(params, q)
    w2 = np.asarray(qdot, dtype=np.float64)[params.n_trans :] ** 2
    m, t = params.link_mass, params.n_trans
    C = coefficient_matrix(params)
    c, s = _e(psi)
    CtC = C.T @ C
    sin_diff = np.outer(s, c) - np.outer(c, s)  # sin(psi_a - psi_g)
    out = np.empty(params.n_dof)
    out[t:] = m * (CtC * sin_diff) @ w2
    if t:
        col = m * C.sum(axis=0)
        out[0] = -(col * c) @ w2
        out[1] = -(col * s) @ w2
    return out


def _difference(params: ChainParams) -> NDArray[np.float64]:
    """D (n_joints, n_dof): theta = D q - theta_base (Eq. 16b)."""
    n, t = params.n_links, params.n_trans
    D = np.zeros((params.n_joints, params.n_dof))
    if params.base == "clamped":
        D[:, t:] = np.eye(n) - np.eye(n, k=-1)
    else:
        D[:, t:] = -np.eye(n - 1, n) + np.eye(n - 1, n, k=1)
    return D


def stiffness_matrix(params: ChainParams) -> NDArray[np.float64]:
    """K* = D^T diag(k) D (n_dof, n_dof), constant (Eq. 17a)."""
    D = _difference(params)
    return D.T @ (params.joint_stiffness[:, None] * D)


def actuation_forces(params: ChainParams, theta_sharp: ArrayLike | None) -> NDArray[np.float64]:
    """F# = D^T k (theta# + theta_base) (n_dof,) (Eq. 17c; the clamp angle enters like theta#_0)."""
    ts = np.zeros(params.n_joints)
    if theta_sharp is not None:
        ts = ts + check_shape("theta_sharp", theta_sharp, (params.n_joints,))
    if params.base == "clamped":
        ts[0] += params.base_angle
    return _difference(params).T @ (params.joint_stiffness * ts)


def spring_energy(params: ChainParams, q: ArrayLike, theta_sharp: ArrayLike | None = None) -> float:
    """U = sum k_j (theta_j - theta#_j)^2 / 2, J (Eq. 16a)."""
    th = joint_angles(params, q)
    if theta_sharp is not None:
        th = th - np.asarray(theta_sharp, dtype=np.float64)
    return float(0.5 * np.sum(params.joint_stiffness * th**2))


def gravity_energy(params: ChainParams, q: ArrayLike) -> float:
    """-sum m g . x_c, J (zero when gravity is off)."""
    return float(-params.link_mass * np.sum(link_centers(params, q) @ params.gravity))


def kinetic_energy(params: ChainParams, q: ArrayLike, qdot: ArrayLike) -> float:
    """K = q_dot^T M* q_dot / 2, J (Eq. 19a)."""
    qdot = np.asarray(qdot, dtype=np.float64)
    return float(0.5 * qdot @ mass_matrix(params, q) @ qdot)


def generalized_loads(
    params: ChainParams,
    q: ArrayLike,
    link_forces: ArrayLike | None = None,
    link_moments: ArrayLike | None = None,
    tip_force: ArrayLike = (0.0, 0.0),
    tip_moment: float = 0.0,
    include_gravity: bool = True,
) -> NDArray[np.float64]:
    """F*_ex = B^T F_ex (n_dof,) (Eq. 28d with B^T): link-centre forces (n, 2) N, link moments
    (n,) N m, an inertial tip force (2,) N and tip moment N m, plus gravity m g on every link
    (unless include_gravity is False)."""
    _, psi = _split(params, q)
    n, t = params.n_links, params.n_trans
    F = np.zeros((n, 2)) + params.link_mass * params.gravity * include_gravity
    if link_forces is not None:
        F = F + check_shape("link_forces", link_forces, (n, 2))
    P = check_shape("tip_force", tip_force, (2,))
    A = coefficient_matrix(params).T @ F + np.outer(tip_coefficients(params), P)
    c, s = _e(psi)
    out = np.zeros(params.n_dof)
    out[t:] = -s * A[:, 0] + c * A[:, 1]
    if link_moments is not None:
        out[t:] += check_shape("link_moments", link_moments, (n,))
    out[-1] += finite_scalar("tip_moment", tip_moment)
    if t:
        out[:2] = F.sum(axis=0) + P
    return out
