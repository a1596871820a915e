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

Modules: `params` (ChainParams, chain_from_beam), `model` (kinematics, B, M*, N*, energies),
`solve` (dynamics by solve_ivp, statics by banded Newton), `kernels` (the compiled right-hand
side), `loads` (line loads lumped at Gauss points, e.g. `terrain` contact), `elastica` (solve_bvp
elastica reference).

Example::

    from mf_envs.physics.multilink import chain_from_beam
    from mf_envs.physics.multilink.solve import simulate, solve_static
    p = chain_from_beam(length=1.0, EI=1.0, mass_per_length=1.0, n_links=16)
    st = solve_static(p, tip_force=(0.0, -1.0))  # tip (0.9434, -0.3023); elastica (0.9436, -0.3017)
    g = chain_from_beam(1.0, 1.0, 1.0, 16, gravity=(0.0, -3.0))
    tr = simulate(g, q0=np.zeros(16), qdot0=np.zeros(16), t_end=2.0)   # released from straight
"""

from mf_envs.physics.multilink.model import (
    actuation_forces,
    b_matrix,
    b_matrix_rate,
    centerline,
    coefficient_matrix,
    generalized_loads,
    gravity_energy,
    joint_angles,
    kinetic_energy,
    link_angles,
    link_centers,
    link_frames,
    mass_diagonal,
    mass_matrix,
    spring_energy,
    stiffness_matrix,
    tip_coefficients,
    tip_position,
    velocity_forces,
)
from mf_envs.physics.multilink.params import (
    BASES,
    ChainParams,
    actuation_from_curvature,
    chain_from_beam,
)

__all__ = [
    "BASES",
    "ChainParams",
    "actuation_forces",
    "actuation_from_curvature",
    "b_matrix",
    "b_matrix_rate",
    "centerline",
    "chain_from_beam",
    "coefficient_matrix",
    "generalized_loads",
    "gravity_energy",
    "joint_angles",
    "kinetic_energy",
    "link_angles",
    "link_centers",
    "link_frames",
    "mass_diagonal",
    "mass_matrix",
    "spring_energy",
    "stiffness_matrix",
    "tip_coefficients",
    "tip_position",
    "velocity_forces",
]
