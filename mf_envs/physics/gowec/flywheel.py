"""The running loss of a GOWEC flywheel as a function of its speed.

A flywheel held at speed psi' by its motor pays, per unit,

    P_loss(psi') = T_f |psi'| + c_v psi'^2 + k_w |psi'|^3            (W)

- T_f (N m): the load-dependent friction torque of the bearings, independent of speed (SKF's
  simplified bearing model M = 1/2 mu F d: a friction coefficient mu times the load F on a
  bearing of bore d; SKF, "Rolling bearings", catalogue 17000 (2018), "Friction"): power
  linear in speed;
- c_v (N m s): viscous drag, a torque proportional to speed (the shear of the lubricant and of
  the shaft seals' films): power quadratic in speed;
- k_w (W s^3): windage, the gas's drag on the disc, whose moment in a close casing is
  C_M 1/2 rho psi'^2 R^5 with C_M ~ Re^-1/5 (Daily & Nece 1960, J. Basic Eng. 82, 217-230,
  regime IV): power ~ psi'^3 (the weak Re^-1/5 dropped).

ISWEC sets its flywheel speed per sea state because these losses grow with speed (Bracco et al.
2015; Battezzato et al. 2015): a slower flywheel in a small sea costs less while the gyroscopic
coupling, H = J psi', is still enough. `rotor_loss` of `FloatingGOWEC-v0` is n P_loss(psi').
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from mf_envs._validate import check_nonnegative


@dataclass(frozen=True)
class FlywheelLoss:
    """P_loss = friction_torque |w| + viscous w^2 + windage |w|^3 per unit (W, w in rad/s):
    module doc."""

    friction_torque: float  # N m, bearings (load friction)
    viscous: float  # N m s, lubricant and seal films
    windage: float  # W s^3 / rad^3

    def __post_init__(self) -> None:
        check_nonnegative("friction_torque", self.friction_torque)
        check_nonnegative("viscous", self.viscous)
        check_nonnegative("windage", self.windage)

    def power(self, speed: float) -> float:
        """Running loss (W) of one flywheel at `speed` (rad/s)."""
        w = abs(float(speed))
        return (self.friction_torque + (self.viscous + self.windage * w) * w) * w

    @classmethod
    def through(cls, speed: float, friction: float, viscous: float, windage: float) -> FlywheelLoss:
        """The model whose three terms at `speed` (rad/s) are `friction`, `viscous` and
        `windage` W (the estimated figures it is fitted to)."""
        w = abs(float(speed))
        if not (w > 0.0 and math.isfinite(w)):
            raise ValueError(f"speed: a finite speed > 0 (rad/s), got {speed!r}")
        return cls(friction / w, viscous / w**2, windage / w**3)
