"""Inchworm robot as an active C1 beam (Rios 2017, ch. 4 §4.10, Eqs. 99-103).

::

     tail (S = 0)        kappa#(S, t) < 0 curls the body into a hump        head (S = L)
          \\                     ___                                        /
           \\               .-'     '-.                                    /
            o-------------'           '------------------------------o   -> +x (forward)
     ///////^///////////////////////////////////////////////////////^//////  ground z = 0
       z2 = 0 (Eq. 100a), x held while anchored          z2 = 0, x held while anchored

Quasi-static (inertia off, the seed's setting) or dynamics (inertia on; energy-momentum scheme
by default) of a simply supported sliding beam under gravity (Eq. 99) with the actuation
curvature kappa#(S, t) of the active law M3 = EI (kappa - kappa#) (Eq. 53). The grip is the
kinematic anchor switching of Eq. 102: while kappa# decreases (loading, curling) the head's x is
held, while it increases (unloading) the tail's x is held. The seed gaits: uniform kappa#(t) =
-kappa0 (1 + cos(t - pi))/2 (Eq. 101) and the linear field kappa0#(S) = kappa0 (c1 + c2 S / L)
(Eq. 103), bookkeeping time with period 2 pi. Per increment |Delta kappa#| <= 2h/L^2 (the seed's
limit: h/4 mid-span rise).

Effects: gravity (Eq. 99), inertia (off = quasi-static), shear_deformation (off = shear-rigid by
a GA_s penalty of 100x), anchor_switching (Eq. 102; off = the head is held, fig. 4-8), terrain
(Bekker/Janosi soil of `mf_envs.physics.beam.contact.terrain` instead of the kinematic
supports; the anchor choice then sets which half of the body grips; implies the weight).

Coordinates: the nodal x dofs of `state.d` are relative to a moving origin `x_origin` [m]
(inertial x = x_origin + local x), re-centred on the tail whenever the body has crawled more
than a body length from it. The equations are translation invariant, but their discretisation
in absolute x is not: the strain z' = sum N_i' z_i of nodes at |x| carries a round-off
eps |x| / l_e, i.e. an axial force error EA eps |x| / l_e that grows with the distance crawled
until Newton cannot meet its tolerance (with the defaults: failure past ~8 m). Local
coordinates keep every run bit-identical to the same run started at the origin.

Layout: `model` (InchwormParams, INCHWORM_EFFECTS, Inchworm), `gaits` (the seed's gaits
Eqs. 101-103, run_gait), `drive` (DrivenInchworm: the robot through its actuators and feet, open
loop gaits), `quasistatic` (its compiled control step on friction feet). What the coming robots
on the same active beam share lives outside this package: the curvature actuator in
`mf_envs.physics.actuators`, friction feet and terrain contact of a beam in
`mf_envs.physics.beam.contact`.
"""

from mf_envs.physics.inchworm.gaits import (
    GaitHistory,
    chord_of_stress_free_shape,
    run_gait,
    seed_linear_kappa,
    seed_uniform_kappa,
)
from mf_envs.physics.inchworm.model import (
    INCHWORM_EFFECTS,
    SHEAR_RIGID_FACTOR,
    STANDARD_GRAVITY,
    Inchworm,
    InchwormParams,
    StepReport,
)

__all__ = [
    "INCHWORM_EFFECTS",
    "SHEAR_RIGID_FACTOR",
    "STANDARD_GRAVITY",
    "GaitHistory",
    "Inchworm",
    "InchwormParams",
    "StepReport",
    "chord_of_stress_free_shape",
    "run_gait",
    "seed_linear_kappa",
    "seed_uniform_kappa",
]
