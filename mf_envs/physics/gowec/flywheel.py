"""The running loss of a GOWEC flywheel as a function of its speed.

A flywheel held at speed psi' by its motor pays, per unit,

    P_loss(psi') = T_f |psi'| + k_w |psi'|^3            (W)

- T_f (N m): the friction torque of the bearings and seals, independent of speed (SKF's
  simplified bearing model M = 1/2 mu F d: a friction coefficient mu times the load F on a
  bearing of bore d; SKF, "Rolling bearings", catalogue 17000 (2018), "Friction"), so its
  power grows linearly with speed;
- k_w (W s^3/rad^3): windage, the gas's drag on the disc, whose moment on a disc in a
  close casing is C_M 1/2 rho psi'^2 R^5 with C_M ~ Re^-1/5 (Daily & Nece 1960, J. Basic Eng.
  82, 217-230, regime IV), power ~ psi'^3 (the Re^-1/5 dependence dropped).

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
    """P_loss = friction_torque |w| + windage |w|^3 per unit (W, w in rad/s): module doc."""

    friction_torque: float  # N m, bearings and seals
    windage: float  # W s^3 / rad^3

    def __post_init__(self) -> None:
        check_nonnegative("friction_torque", self.friction_torque)
        check_nonnegative("windage", self.windage)

    def power(self, speed: float) -> float:
        """Running loss (W) of one flywheel at `speed` (rad/s)."""
        w = abs(float(speed))
        return self.friction_torque * w + self.windage * w**3

    @classmethod
    def through(cls, speed: float, total: float, windage_power: float) -> FlywheelLoss:
        """The model whose loss at `speed` (rad/s) is `total` (W), `windage_power` (W) of it
        windage and the rest friction (the single published/estimated figure it is fitted to)."""
        w = abs(float(speed))
        if not (w > 0.0 and 0.0 <= windage_power <= total and math.isfinite(total)):
            raise ValueError(
                f"total: needs speed > 0 and 0 <= windage_power <= total, got speed={speed!r}, "
                f"total={total!r}, windage_power={windage_power!r}"
            )
        return cls((total - windage_power) / w, windage_power / w**3)
