"""Parameters of a ship with one or two gyroscopic roll stabilizers (Rios 2017, ch. 3 §3.3).

Frozen dataclasses in SI units, validated once in `__post_init__` (ValueError naming the field),
and presets:

- `seed_test_hull()`: the seed's demonstration values (§3.3.4.1): J^(1) = (1e6, 1e9, 1e10) kg m^2,
  J2^(2) = 10, J3^(3) = 50 kg m^2, 8050 rpm (they "do not reflect a marine vessel").
- The hulls (the yacht, the MSS naval vessel) are one family, `hulls.Hull` with its presets;
  `ShipParams` is the kernels' view of a hull (`Hull.ship_params()`, `hulls.small_yacht()`,
  `hulls.mss_naval_vessel()`).
- `SEAKEEPER`: Table 3-1 of the seed (model: rpm, angular momentum N m s, spool-up power W);
  `seakeeper_gyro(model)` turns a row into a `GyroParams` (rotor polar inertia J3 = H / psi').

The gimbal (precession) axis is the ship's e_2 (athwartships), the rotor spins about the gimbal's
e_3; with two gyros the second gimbal and rotor turn by -phi and -psi (Eqs. 98-99, 106-107).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from mf_envs._validate import check_finite, check_int, check_nonnegative, check_positive
from mf_envs.physics.constants import RPM
from mf_envs.physics.gyros import SEAKEEPER  # seed Table 3-1, shared with the GOWEC


@dataclass(frozen=True)
class GyroParams:
    """One gyro unit: a symmetric gimbal carrying a thin-disk rotor (Eq. 117 by default).

    rotor_inertia: polar J3^(3) of the rotor about its spin axis, kg m^2.
    rotor_transverse_inertia: J1^(3) = J2^(3) of the rotor, kg m^2 (None -> J3/2, thin disk).
    gimbal_inertia: J1^(2) = J2^(2) = J3^(2) of the gimbal frame, kg m^2 (symmetric, Eq. 117).
    rotor_speed: psi' in rad/s (prescribed, constant).
    """

    rotor_inertia: float = 50.0
    gimbal_inertia: float = 10.0
    rotor_speed: float = 8050.0 * RPM
    rotor_transverse_inertia: float | None = None

    def __post_init__(self) -> None:
        check_positive("rotor_inertia", self.rotor_inertia)
        check_nonnegative("gimbal_inertia", self.gimbal_inertia)
        check_finite("rotor_speed", self.rotor_speed)
        if self.rotor_transverse_inertia is not None:
            check_positive("rotor_transverse_inertia", self.rotor_transverse_inertia)

    @property
    def rotor_j1(self) -> float:
        """Transverse rotor inertia J1^(3) = J2^(3), kg m^2 (thin disk J3/2 unless given)."""
        if self.rotor_transverse_inertia is None:
            return 0.5 * self.rotor_inertia
        return float(self.rotor_transverse_inertia)

    @property
    def angular_momentum(self) -> float:
        """Rotor spin angular momentum H = J3^(3) psi', N m s."""
        return self.rotor_inertia * self.rotor_speed


@dataclass(frozen=True)
class ShipParams:
    """Hull and hydrodynamic coefficients (body frame e^(1): e_1 forward/roll, e_2 port/pitch,
    e_3 up/yaw; about the centre of mass).

    inertia: (J1, J2, J3) principal rigid-body inertia of the hull incl. the gyros' mass, kg m^2.
    mass: displacement mass, kg (translation effect only).
    added_roll_inertia: A44, kg m^2 (effect `added_inertia`).
    roll_stiffness: C44 = rho g V GM, N m/rad (effect `hydrostatic_restoring`).
    pitch_stiffness: C55 = rho g V GM_L, N m/rad (effect `hydrostatic_restoring`).
    gz_bm_over_gm: wall-sided GZ = sin(r) (GM + BM/2 tan^2 r); this is BM/GM (0 = linear GM r).
    roll_damping: B44 linear, N m s/rad; roll_damping_quadratic: B44q, N m s^2/rad^2.
    pitch_damping, yaw_damping: N m s/rad (effect `roll_damping` switches all three on).
    heave_stiffness: rho g A_wp, N/m; heave_damping N s/m; surge_sway_damping N s/m (`translation`).
    """

    inertia: tuple[float, float, float] = (1.0e6, 1.0e9, 1.0e10)
    mass: float = 1.0e5
    added_roll_inertia: float = 0.0
    roll_stiffness: float = 0.0
    pitch_stiffness: float = 0.0
    gz_bm_over_gm: float = 0.0
    roll_damping: float = 0.0
    roll_damping_quadratic: float = 0.0
    pitch_damping: float = 0.0
    yaw_damping: float = 0.0
    heave_stiffness: float = 0.0
    heave_damping: float = 0.0
    surge_sway_damping: float = 0.0

    def __post_init__(self) -> None:
        inertia = check_positive("inertia", self.inertia)
        if inertia.shape != (3,):
            raise ValueError(f"inertia: expected 3 principal inertias, got {self.inertia!r}")
        check_positive("mass", self.mass)
        for name in (
            "added_roll_inertia",
            "roll_stiffness",
            "pitch_stiffness",
            "gz_bm_over_gm",
            "roll_damping",
            "roll_damping_quadratic",
            "pitch_damping",
            "yaw_damping",
            "heave_stiffness",
            "heave_damping",
            "surge_sway_damping",
        ):
            check_nonnegative(name, getattr(self, name))

    def roll_inertia(self, added_inertia: bool = True) -> float:
        """J1 + A44 (kg m^2; without A44 if not `added_inertia`): `roll_inertia_of`."""
        return roll_inertia_of(self, added_inertia)

    def natural_roll_period(self, added_inertia: bool = True) -> float:
        """T_n = 2 pi sqrt((J1 + A44) / C44) in s (inf without restoring)."""
        if self.roll_stiffness <= 0.0:
            return math.inf
        return 2.0 * math.pi * math.sqrt(self.roll_inertia(added_inertia) / self.roll_stiffness)


def roll_inertia_of(hull: Any, added_inertia: bool = True) -> float:
    """J1 + A44 (kg m^2) of a `ShipParams` or `hulls.Hull` (their `inertia`, `added_roll_inertia`;
    without A44 if not `added_inertia`): the one definition of the hull's roll inertia that the
    models, the drive sizing and the controllers use."""
    return hull.inertia[0] + (hull.added_roll_inertia if added_inertia else 0.0)


def seakeeper_gyro(model: str = "9", gimbal_inertia: float | None = None) -> GyroParams:
    """A `GyroParams` for a Seakeeper model of seed Table 3-1 (J3 = H / psi').

    gimbal_inertia: kg m^2; None assumes the gimbal's J2^(2) equals the rotor's J3 (an
    assumption: Seakeeper does not publish it).
    """
    if model not in SEAKEEPER:
        raise ValueError(f"model: must be one of {sorted(SEAKEEPER)}, got {model!r}")
    rpm, h, _ = SEAKEEPER[model]
    speed = rpm * RPM
    j3 = h / speed
    return GyroParams(
        rotor_inertia=j3,
        gimbal_inertia=j3 if gimbal_inertia is None else gimbal_inertia,
        rotor_speed=speed,
    )


def seed_test_hull() -> tuple[ShipParams, GyroParams]:
    """The seed's test values (§3.3.4.1): no hydrostatics, damping or added inertia."""
    return ShipParams(inertia=(1.0e6, 1.0e9, 1.0e10)), GyroParams(50.0, 10.0, 8050.0 * RPM)


def capacity_ratio(
    moment_amplitude: float, angular_momentum: float, omega: float, n_gyros: int, beta_max: float
) -> float:
    """M0 / (n H w sin(beta_max)): below 1 the gyros can cancel M0 cos(w t) (docs/design.md bound).

    The gyro roll moment is n H phi' cos(phi) = n H d(sin phi)/dt; holding the roll at zero needs
    n H sin(phi) = (M0/w) sin(w t), possible only if M0 / (n H w) <= sin(beta_max).
    """
    n = check_int("n_gyros", n_gyros, 1, 2)
    check_positive("angular_momentum", angular_momentum)
    check_positive("omega", omega)
    check_positive("beta_max", beta_max)
    return abs(moment_amplitude) / (
        n * angular_momentum * omega * math.sin(min(beta_max, math.pi / 2))
    )
