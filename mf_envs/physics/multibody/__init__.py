"""The general moving-frame multibody engine (Rios 2017, ch. 3 Eqs. 5-7, 21-75).

Bodies form a tree. Each body b has a frame e^(b) at its centre of mass, joined to its parent p
(or the inertial frame) by a relative frame connection matrix (Eq. 6)

    E^(b/p)(q) = E_pre . E_joint(q) . E_post,      E^(b) = E^(p) E^(b/p)          (Eq. 7)

    E_pre  = [[rotation, offset], [0, 1]]              fixed: joint frame seen from the parent
    E_joint= revolute: [[exp(q hat(axis)), 0], ...]    prismatic: [[I, q axis], ...]
             spherical: [[R, 0], ...]                   free: [[R, x], ...]
    E_post = [[child_rotation, child_offset], [0, 1]]  fixed: body frame seen from the joint

The essential generalized velocities u (Eq. 48) are, per joint: q' (revolute, prismatic), the
relative body angular velocity omega (spherical; quasi-velocities, no Euler angles) and (v, omega)
(free; v = dx/dt in the joint's pre-frame, the inertial frame for a root body). The stacked body
velocities X' = [x_c'^(1) (inertial), omega^(1) (body), x_c'^(2), omega^(2), ...] = B(q) u (Eqs.
49-50) and its rate B' come from one recursion over the tree. With M = diag(m I, J_C) (Eq. 56),
D = diag(0, hat(omega)) (Eq. 65) and Q the applied wrenches (Eq. 58):

    M* u' + N* u = F*,   M* = B^T M B,  N* = B^T (M B' + D M B),  F* = B^T Q + tau   (Eqs. 73-75)

tau holds generalized forces on joint coordinates (a generator torque on a gimbal axis; an
action-reaction pair between parent and child, so nothing is added to the parent separately).

Prescribed (rheonomic) joints: give `prescribed=f` with f(t) -> (q, q', q'') in that joint's
coordinates (scalar joints: floats; spherical: (R (3,3), omega (3,), omega' (3,)); free:
((R, x), (v, omega), (v', omega'))). Eq. 74 is then solved for the free slots only and the
generalized forces the actuators must supply along the prescribed coordinates are returned by
`reactions` (lam = (M* u' + N* u - F*)_p). Power balance: d/dt(K + U) = u.(F* without gravity)
+ u_p.lam, which the tests check.

Integration: `step` is a 4th-order Runge-Kutta-Munthe-Kaas step: rotations are advanced as
R0 exp(hat(theta)) with the ch. 2 Rodrigues formula, so R stays orthogonal to round-off.
All kernels are numba-compiled (`multibody.kernels`, stepping through `mf_envs.frames.steppers`);
the Python layer (`multibody.model`) only packs arrays; joints and bodies in `multibody.joints`.

Worked example: a heavy symmetric top on a fixed pivot, and the GOWEC's buoy/gimbal/rotor.

    >>> import numpy as np
    >>> from mf_envs.frames import rot_x
    >>> from mf_envs.physics.multibody import Body, Multibody, Revolute, Spherical, constant_rate
    >>> top = Multibody([Body("top", mass=1.0, inertia=(0.02, 0.02, 0.01),
    ...                       joint=Spherical(child_offset=(0, 0, 0.1)))], gravity=(0, 0, -9.81))
    >>> s = top.initial_state(q={"top": rot_x(0.3)}, u={"top": (0.0, 0.0, 50.0)})
    >>> for _ in range(100):
    ...     s = top.step(s, 1e-3)
    >>> E = top.kinetic_energy(s) + top.potential_energy(s)      # conserved to ~1e-9 J
    >>> R, x = top.poses(s)                 # body attitude (1,3,3) and centre of mass (1,3)

    Buoy rocking prescribed about e1, free gimbal about e2 with a generator torque, rotor spun
    about e3 at a constant rate (ch. 3 Fig. 3-2; `mf_envs.physics.gowec.engine` builds this):

    >>> rock = lambda t: (rot_x(0.1 * np.sin(t)), (0.1 * np.cos(t), 0, 0), (-0.1 * np.sin(t), 0, 0))
    >>> m = Multibody([
    ...     Body("buoy", 1e3, (1e3, 1e3, 1e3), Spherical(), prescribed=rock),
    ...     Body("gimbal", 5.0, (1.0, 1.0, 1.0), Revolute((0, 1, 0), offset=(0, 0, 0.3)),
    ...          parent="buoy"),
    ...     Body("rotor", 20.0, (2.0, 2.0, 4.0), Revolute((0, 0, 1)), parent="gimbal",
    ...          prescribed=constant_rate(500.0))])
    >>> s = m.initial_state()
    >>> s = m.step(s, 1e-3, tau=m.joint_forces(gimbal=-10.0))   # generator torque M_g = 10 N m
    >>> phi, phid = m.coordinate(s, "gimbal"), m.velocity(s, "gimbal")
    >>> motor = m.reactions(s)["rotor"]       # torque the rotor motor needs to hold psi' (N m)
    >>> Ms, Ns, Fs = m.matrices(s)            # M*, N*, F* of Eqs. 73-75 (free + prescribed slots)
    >>> bool(np.all(np.linalg.eigvalsh(Ms) > 0))
    True
"""

from mf_envs.physics.multibody.joints import (
    Body,
    Fixed,
    Free,
    Joint,
    MBState,
    Prescription,
    Prismatic,
    Revolute,
    Spherical,
    constant_rate,
    harmonic,
)
from mf_envs.physics.multibody.model import Multibody

__all__ = [
    "Body",
    "Fixed",
    "Free",
    "Joint",
    "MBState",
    "Multibody",
    "Prescription",
    "Prismatic",
    "Revolute",
    "Spherical",
    "constant_rate",
    "harmonic",
]
