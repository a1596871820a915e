"""Wires sized to the moment they must deliver: for a beam section bent to a target curvature by
straight wires at a lever arm e from its neutral axis.

    ---------------------------  body: E, width b, height h, EI = E b h^3 / 12
       =====  wires  =====  <- e below the neutral axis: a wire shortened by eps = kappa e
    ---------------------------     pulls with F and bends the body by M = F e

Moment to hold the curvature: M = EI kappa; wire force F = M / e; wires: ceil(F / F_wire),
F_wire = the maker's rated stress x area (`sma.pull_force`); the wires' strain kappa e must lie in
the alloy's repeatable range (ValueError naming `kappa` above it); the body's surface strain
kappa h / 2 is reported (an elastomer takes it; a stiff body's wires at e = h / 2 would need it).
Reset: a cool wire is stretched back by the body itself; the maker's deformation (bias) stress of
70 MPa x area x e is the moment the straightening body must supply at the target curvature
(`reset_margin` > 1 when it does).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from mf_envs._validate import check_positive
from mf_envs.physics.actuators.sma import FLEXINOL_LT, RATED_STRESS, SMAAlloy, pull_force

BIAS_STRESS = 70e6  # [Pa] the maker's cooling deformation stress (10 ksi), Flexinol springs page


@dataclass(frozen=True)
class WireSizing:
    """moment [N m], force [N] of all wires, per_wire [N], count, wire_strain and surface_strain
    (fractions), reset_margin (body moment / wires' bias moment at the target curvature)."""

    moment: float
    force: float
    per_wire: float
    count: int
    wire_strain: float
    surface_strain: float
    reset_margin: float


def section_stiffness(youngs_modulus: float, width: float, height: float) -> float:
    """EI = E b h^3 / 12 [N m^2] of a rectangular section (E [Pa], b, h [m])."""
    for name, v in (("youngs_modulus", youngs_modulus), ("width", width), ("height", height)):
        check_positive(name, v)
    return youngs_modulus * width * height**3 / 12.0


def size_wires(
    youngs_modulus: float,
    width: float,
    height: float,
    kappa: float,
    diameter: float,
    lever_arm: float,
    alloy: SMAAlloy = FLEXINOL_LT,
    stress: float = RATED_STRESS,
) -> WireSizing:
    """Wires of `diameter` [m] at `lever_arm` e [m] that hold the section (E [Pa], width,
    height [m]) at the curvature `kappa` [1/m] (see the module docstring). ValueError naming
    `kappa` when the wires' strain kappa e exceeds the alloy's repeatable strain, naming
    `lever_arm` when the wires would sit outside the section (e > h / 2)."""
    ei = section_stiffness(youngs_modulus, width, height)
    for name, v in (("kappa", kappa), ("lever_arm", lever_arm), ("stress", stress)):
        check_positive(name, v)
    if lever_arm > height / 2.0:
        raise ValueError(f"lever_arm: {lever_arm} m puts the wires outside the section (h/2)")
    eps = kappa * lever_arm
    top = alloy.repeatable_strain[1]
    if eps > top:
        raise ValueError(
            f"kappa: the wires' strain kappa * lever_arm = {eps:.4f} exceeds the repeatable "
            f"{top} of {alloy.name} (lower kappa or lever_arm)"
        )
    moment = ei * kappa
    per_wire = pull_force(diameter, stress)
    force = moment / lever_arm
    count = max(1, math.ceil(force / per_wire - 1e-12))
    bias = count * pull_force(diameter, BIAS_STRESS) * lever_arm
    return WireSizing(moment, force, per_wire, count, eps, kappa * height / 2.0, moment / bias)
