"""Torque-free rigid body: the Dzhanibekov / tennis-racket model of Rios 2017, chapter 2.

          e3 (J3, smallest)              body frame e(t) = e^I R(t)            (Eq. 4)
           |   head plane                angular momentum H = J omega (body)   (Eq. 9b)
        .--+--.                          Euler: dH/dt + omega x H = 0          (Eq. 12a/22)
       /   |   \\      e2 (J2, intermediate: unstable, the racket flips)
      |    C----+---->                   attitude: dR/dt = R hat(omega)        (Eq. 24)
       \\  /    /                         centre of mass: m dv/dt = -m g e3^I    (Eq. 3)
        '/----'
        /  e1 (J1, largest, normal to the head plane)

Public API (docs/api.md; `integrators`, `exact`, `kernels`, `polhode` hold the code):
    simulate(J, omega0, t_end, dt, method="rk4_rodrigues", *, R0=None, save_every=1,
             effects=None, x0=(0, 0, 0), v0=(0, 0, 0), g=G) -> RigidBodyTrajectory
    METHODS, analytic_omega(J, omega0, t) (exact, Jacobi elliptic; exact.py),
    attitude_reference(J, omega0, t) (R from the exact omega, DOP853)

Methods (why each exists; kernels in kernels.py):
- "rk4_rodrigues": the seed's scheme - RK4 on H (order 4), R by one Rodrigues step with the
  midpoint angular velocity (Eqs. 29-31), which is order 2: R limits the accuracy.
- "rk4_magnus4": same RK4 on H, R by a 4th-order Magnus step built from omega and d omega/dt at
  both step ends (d omega/dt is RK4's first stage, so no extra right-hand-side evaluations).
  Same cost as the seed's scheme, R error 2 orders of dt better.
- "rk4_magnus4_proj": rk4_magnus4 plus a projection of H back onto the exact polhode (|H| and
  energy at their initial values to round-off). The conserving method: D = |H|^2/(2 K0) is exact,
  so a spin 1e-6 from the separatrix can never cross it, and nothing drifts over 1000 s of flips.
- "splitting2": Lie-Poisson (Strang) splitting into the exact axis rotations of H_i^2/(2 J_i)
  (McLachlan 1993, Touma & Wisdom 1994). Symplectic and reversible, |H| and the inertial momentum
  R H conserved to round-off, energy error bounded (no drift) but O(dt^2): it shows why "conserve
  both invariants or neither" matters next to the separatrix.
- "splitting4": the same composed by Yoshida's triple jump, order 4 at 3x the cost.

Inertias may come in any order (the equations do not care; the exact solution permutes to its
canonical frame and reports `EllipticSolution.axes`); zero, negative or non-finite inputs raise
ValueError naming the argument. The only geometry helpers that need J1 > J2 > J3 are in polhode.py.
Gravity G = 9.81 m/s^2 (the seed's value) (`mf_envs.physics.constants`).
"""

from mf_envs.physics.rigid_body.exact import (
    EllipticSolution,
    analytic_omega,
    attitude_reference,
    elliptic_solution,
    jacobi_sn_cn_dn,
)
from mf_envs.physics.rigid_body.integrators import (
    EFFECTS,
    METHODS,
    RigidBodyTrajectory,
    ballistic_position,
    cuboid_inertia,
    flight_time,
    kinetic_energy,
    simulate,
)

__all__ = [
    "METHODS",
    "EFFECTS",
    "RigidBodyTrajectory",
    "simulate",
    "analytic_omega",
    "attitude_reference",
    "elliptic_solution",
    "EllipticSolution",
    "jacobi_sn_cn_dn",
    "kinetic_energy",
    "ballistic_position",
    "flight_time",
    "cuboid_inertia",
]
