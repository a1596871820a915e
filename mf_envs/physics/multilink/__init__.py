"""Planar n-link chain with torsional springs and actuation offsets (Rios 2017, ch. 4 §4.2).

::

    clamp  k_0      k_1      k_2            k_(n-1)
    |//|---o------o------o------ ... ------o------>  tip
    |//| link 1  link 2  link 3           link n
         <--l-->                            (C^(a) at each link centre)

n identical rigid links of length l, mass m and centroidal inertia J_c, joined by torsional
springs k_j acting on the *elastic* joint angle theta_j - theta#_j (Eqs. 15-16), where theta#_j
is the prescribed actuation offset of joint j. Coordinates (x, z) are inertial, z up; link
angles psi are measured counter-clockwise from e_1 (Eq. 2).

Two supports:

- ``"free"``: the seed's floating chain, essential coordinates q = (x_1c, z_1c, psi_1..psi_n)
  (Eq. 14, n + 2 dofs) and n - 1 joints.
- ``"clamped"``: link 1 hinged at a clamp (base point, base angle psi_0) through a spring k_0,
  q = (psi_1..psi_n) (n dofs) and n joints (joint 0 at the clamp).

Link frames come from the recursion E^(a+1) = E^(a) E^(a+1/a) (Eqs. 8-9, built with
`mf_envs.frames`); the B-matrix X_dot = B q_dot (Eqs. 20-21) gives M* = B^T M B (Eq. 28b),
N* = B^T M B_dot (Eq. 28c), K* and F# (Eq. 17) and the reduced loads B^T F_ex (Eq. 28d; the seed
prints B where B^T is meant). Eqs. 21e/21h also print -l/2 psi_dot cos psi where the derivative
of l/2 sin psi is +l/2 psi_dot cos psi; the code uses the correct sign.

All link centres are affine in the link directions: x_c^(b) = x_origin + sum_a C[b, a] e(psi_a)
with e(psi) = (cos psi, sin psi) and a constant lower-triangular coefficient matrix C (Eq. 13).
Everything below is written in terms of C and is vectorised (O(n^2) per evaluation).

Discretisation of a beam (`chain_from_beam`): the link angle stands for the beam angle at the link
centre, so joint j spans the arc between two link centres (length l) and the clamp spring spans
half a link (l/2). Matching the bending energy EI kappa^2/2 over that span gives

    k_j = EI / l   (interior joints),      k_0 = 2 EI / l   (clamp: half-link rule),

and the actuation offsets theta#_j = integral of kappa# over the same span (kappa# l, kappa# l/2).
With this rule the tip position converges to the elastica at second order in 1/n (the linear
tip-loaded cantilever: w_n = P L^3 / (3 EI) (1 + 1 / (2 n^2)), derived in tests/test_multilink.py).
Measured (benchmarks/accuracy/multilink.py): rate 2.00 against the elastica, the circle and the
C1 beam FE, ~2e-8 L at n = 4096; the first three natural frequencies also converge at rate 2.

Companion modules: `multilink_solve` (dynamics by solve_ivp, statics by banded Newton),
`multilink_kernels` (the compiled right-hand side), `multilink_loads` (line loads lumped at
Gauss points, e.g. `terrain` contact), `multilink_elastica` (solve_bvp elastica reference).

Example::

    from mf_envs.physics.multilink import chain_from_beam
    from mf_envs.physics.multilink.solve import simulate, solve_static
    p = chain_from_beam(length=1.0, EI=1.0, mass_per_length=1.0, n_links=16)
    st = solve_static(p, tip_force=(0.0, -1.0))  # tip (0.9434, -0.3023); elastica (0.9436, -0.3017)
    g = chain_from_beam(1.0, 1.0, 1.0, 16, gravity=(0.0, -3.0))
    tr = simulate(g, q0=np.zeros(16), qdot0=np.zeros(16), t_end=2.0)   # released from straight
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import (
    check_choice,
    check_finite,
    check_int,
    check_nonnegative,
    check_positive,
    check_shape,
)
from mf_envs.frames import compose, frame_connection, rot_z

BASES = ("clamped", "free")


@dataclass(frozen=True, eq=False)
class ChainParams:
    """Parameters of the planar n-link chain (SI units).

    n_links: number of links n (>= 1; >= 2 for "free").
    link_length: l, m.
    link_mass: m, kg (per link).
    link_inertia: J_c, kg m^2, about the link centre.
    joint_stiffness: (n_joints,) N m/rad; n_joints = n ("clamped", joint 0 at the clamp) or n - 1.
    joint_damping: N m s/rad on every elastic joint rate (0 = conservative).
    base: "clamped" or "free".
    base_position: (2,) m, the clamp point (clamped only).
    base_angle: psi_0, rad, the clamp direction (clamped only).
    gravity: (2,) m/s^2, inertial gravity vector, e.g. (0, -9.81); zeros = off.
    """

    n_links: int
    link_length: float
    link_mass: float
    link_inertia: float
    joint_stiffness: NDArray[np.float64]
    joint_damping: float = 0.0
    base: str = "clamped"
    base_position: NDArray[np.float64] = field(default_factory=lambda: np.zeros(2))
    base_angle: float = 0.0
    gravity: NDArray[np.float64] = field(default_factory=lambda: np.zeros(2))

    def __post_init__(self) -> None:
        check_choice("base", self.base, BASES)
        n = check_int("n_links", self.n_links, low=2 if self.base == "free" else 1)
        set_ = object.__setattr__
        set_(self, "n_links", n)
        set_(self, "link_length", float(check_positive("link_length", self.link_length)))
        set_(self, "link_mass", float(check_positive("link_mass", self.link_mass)))
        set_(self, "link_inertia", float(check_nonnegative("link_inertia", self.link_inertia)))
        set_(self, "joint_damping", float(check_nonnegative("joint_damping", self.joint_damping)))
        set_(self, "base_angle", float(check_finite("base_angle", self.base_angle)))
        k = check_nonnegative("joint_stiffness", np.atleast_1d(self.joint_stiffness))
        k = check_shape("joint_stiffness", k, (self.n_joints,)).copy()
        for name, arr in (
            ("joint_stiffness", k),
            ("base_position", check_shape("base_position", self.base_position, (2,)).copy()),
            ("gravity", check_shape("gravity", self.gravity, (2,)).copy()),
        ):
            arr.setflags(write=False)
            set_(self, name, arr)

    @property
    def n_joints(self) -> int:
        """Number of spring joints: n (clamped) or n - 1 (free)."""
        return self.n_links if self.base == "clamped" else self.n_links - 1

    @property
    def n_dof(self) -> int:
        """Number of essential coordinates: n (clamped) or n + 2 (free, Eq. 14)."""
        return self.n_links if self.base == "clamped" else self.n_links + 2

    @property
    def n_trans(self) -> int:
        """Leading translational dofs in q: 0 (clamped) or 2 (free)."""
        return 0 if self.base == "clamped" else 2

    @property
    def length(self) -> float:
        """Total length n l, m."""
        return self.n_links * self.link_length


def chain_from_beam(
    length: float,
    EI: float,
    mass_per_length: float,
    n_links: int,
    rotary_inertia_per_length: float = 0.0,
    base: str = "clamped",
    joint_damping: float = 0.0,
    gravity: ArrayLike = (0.0, 0.0),
) -> ChainParams:
    """Chain equivalent of a uniform beam (module docstring): k = EI/l inside, 2 EI/l at a clamp.

    length: L, m; EI: N m^2; mass_per_length: kg/m; rotary_inertia_per_length: J_3, kg m (per
    unit length, e.g. rho I); link inertia J_c = m l^2 / 12 + J_3 l.
    """
    L = float(check_positive("length", length))
    EI = float(check_positive("EI", EI))
    rho = float(check_positive("mass_per_length", mass_per_length))
    J3 = float(check_nonnegative("rotary_inertia_per_length", rotary_inertia_per_length))
    n = check_int("n_links", n_links, low=1)
    l = L / n
    check_choice("base", base, BASES)
    k = np.full(n if base == "clamped" else n - 1, EI / l)
    if base == "clamped":
        k[0] = 2.0 * EI / l
    m = rho * l
    return ChainParams(n, l, m, m * l * l / 12.0 + J3 * l, k, joint_damping, base, gravity=gravity)


def actuation_from_curvature(params: ChainParams, kappa_sharp: ArrayLike) -> NDArray[np.float64]:
    """theta#_j = integral of kappa#(S) over the span of joint j (module docstring rule).

    kappa_sharp: scalar (uniform, 1/m) or (n_links,) values at the link centres (piecewise
    linear between centres). Returns (n_joints,) rad.
    """
    kap = np.broadcast_to(check_finite("kappa_sharp", kappa_sharp), (params.n_links,))
    l = params.link_length
    interior = 0.5 * l * (kap[:-1] + kap[1:])  # trapezoid between link centres
    if params.base == "free":
        return interior
    return np.concatenate(([0.5 * l * kap[0]], interior))


# --- kinematics ----------------------------------------------------------------------------


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
    out[-1] += float(check_finite("tip_moment", tip_moment))
    if t:
        out[:2] = F.sum(axis=0) + P
    return out
