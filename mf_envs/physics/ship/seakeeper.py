"""Seakeeper gyro units as typed presets, and a capacity check of a unit on a hull.

`GyroUnit` holds what a maker publishes about one gyro model; a field is None where no
source was verified (nothing is filled in). Every preset names its sources in `source`
(docs/stabilizer_physics.md lists what was verified and where):

- `SEAKEEPER_7000`: the Model 7000 (2009). Precession +-60 deg and the closed-circuit
  hydraulic brake: Seakeeper Model 7000 Gyro Operation Manual, doc. 90021 rev 4 (Mar 2009),
  §1.1 and §4.2. Boat range 35,000-55,000 lb full-load displacement (15.9-24.9 t) for a
  single gyro: seakeeper.com/products_sizing.php (the M7000-era sizing page). Flywheel
  J = 6.7 kg m^2 at 10,000 rpm = 1047 rad/s, L = 7015 N m s: seakeeper.com/
  design_theoryofoperation.php (7,016 N m s with 10,000 rpm exactly).
- `SEED_TABLE_3_1`: the six units of Rios 2017, Table 3-1 (rpm, H, spool-up power), kept as
  the seed prints them (`mf_envs.physics.gyros.SEAKEEPER`); the seed gives no boat range,
  precession limit or torque rating.

`capacity` is the fraction of a design beam-sea roll moment that n units can cancel
(docs/derivations.md, "Stabilizer capacity"): cancelling M0 cos(w t) needs
n H sin(beta) = (M0 / w) sin(w t), so |beta| <= beta_max needs M0 <= n H w sin(beta_max);
the precession rate it needs peaks at beta' = M0 / (n H), so a rate cap beta'_max needs
M0 <= n H beta'_max. capacity = min(n H w sin(beta_max), n H beta'_max) / M0 (>= 1: the
unit can hold the hull level in that sea). The design sea is a regular beam sea at the
hull's natural roll frequency with wave steepness H_w / lambda (`DESIGN_STEEPNESS`), whose
roll moment on the hull is M0 = C44 r_eff k a = C44 r_eff pi H_w / lambda (`ship.seas`).
The maker's own sizing model is not public in the sources found; this is a physics bound.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

from mf_envs._validate import check_int, positive_scalar
from mf_envs.physics.constants import RPM
from mf_envs.physics.gyros import SEAKEEPER
from mf_envs.physics.ship.hulls import Hull
from mf_envs.physics.ship.params import GyroParams, capacity_ratio

LB = 0.45359237  # kg per pound
DESIGN_STEEPNESS = 1.0 / 50.0  # H_w / lambda of the design sea (an assumption, module doc)


@dataclass(frozen=True)
class GyroUnit:
    """One gyro model as its maker publishes it; None = no verified source (SI units).

    name: model name; angular_momentum: H at rated speed, N m s; rotor_speed_rpm: rated
    flywheel speed, rpm; max_precession: +-beta_max, rad; spool_up_power: W;
    spool_up_time: s; running_power: W; anti_roll_torque: rated, N m; weight: kg;
    displacement_range: (low, high) full-load boat displacement for one unit, kg;
    source: where each number comes from.
    """

    name: str
    angular_momentum: float
    rotor_speed_rpm: float
    source: str
    max_precession: float | None = None
    spool_up_power: float | None = None
    spool_up_time: float | None = None
    running_power: float | None = None
    anti_roll_torque: float | None = None
    weight: float | None = None
    displacement_range: tuple[float, float] | None = None

    def __post_init__(self) -> None:
        positive_scalar("angular_momentum", self.angular_momentum)
        positive_scalar("rotor_speed_rpm", self.rotor_speed_rpm)
        for f in ("max_precession", "spool_up_power", "spool_up_time", "running_power"):
            if getattr(self, f) is not None:
                positive_scalar(f, getattr(self, f))
        for f in ("anti_roll_torque", "weight"):
            if getattr(self, f) is not None:
                positive_scalar(f, getattr(self, f))
        if self.max_precession is not None and self.max_precession > math.pi / 2:
            raise ValueError(f"max_precession: must be <= pi/2 rad, got {self.max_precession!r}")
        if self.displacement_range is not None:
            lo, hi = (positive_scalar("displacement_range", v) for v in self.displacement_range)
            if lo > hi:
                raise ValueError(f"displacement_range: low > high in {self.displacement_range!r}")

    @property
    def rotor_speed(self) -> float:
        """Flywheel speed, rad/s."""
        return self.rotor_speed_rpm * RPM

    @property
    def rotor_inertia(self) -> float:
        """Flywheel polar inertia J = H / psi', kg m^2."""
        return self.angular_momentum / self.rotor_speed

    def gyro_params(self, gimbal_inertia: float | None = None) -> GyroParams:
        """The `GyroParams` of this unit; gimbal_inertia (kg m^2) None assumes it equals the
        rotor's J (Seakeeper publishes no gimbal inertia; as `params.seakeeper_gyro`)."""
        j = self.rotor_inertia
        jg = j if gimbal_inertia is None else positive_scalar("gimbal_inertia", gimbal_inertia)
        return GyroParams(rotor_inertia=j, gimbal_inertia=jg, rotor_speed=self.rotor_speed)


SEAKEEPER_7000 = GyroUnit(
    name="Seakeeper Model 7000",
    angular_momentum=6.7 * 10_000.0 * RPM,  # J = 6.7 kg m^2 at 10,000 rpm: 7,016 N m s
    rotor_speed_rpm=10_000.0,
    max_precession=math.radians(60.0),
    displacement_range=(35_000.0 * LB, 55_000.0 * LB),
    source=(
        "precession +-60 deg and hydraulic brake: Seakeeper Model 7000 Gyro Operation Manual, "
        "doc. 90021 rev 4 (Mar 2009) §1.1, §4.2; one gyro for 35,000-55,000 lb full-load "
        "displacement: seakeeper.com/products_sizing.php; J = 6.7 kg m^2 at 10,000 rpm "
        "(L = 7015 N m s): seakeeper.com/design_theoryofoperation.php"
    ),
)

SEED_TABLE_3_1: dict[str, GyroUnit] = {
    model: GyroUnit(
        name=f"Seakeeper {model} (seed Table 3-1)",
        angular_momentum=h,
        rotor_speed_rpm=rpm,
        spool_up_power=p,
        source="Rios 2017, Table 3-1 (citing Seakeeper); rpm, H and spool-up power only",
    )
    for model, (rpm, h, p) in SEAKEEPER.items()
}


def design_wave_moment(hull: Hull, steepness: float = DESIGN_STEEPNESS) -> tuple[float, float]:
    """(M0 in N m, w in rad/s): the roll-moment amplitude of a regular beam sea at the
    hull's natural roll frequency w with wave steepness H_w / lambda (module doc)."""
    s = positive_scalar("steepness", steepness)
    if s > 1.0 / 7.0:
        raise ValueError(f"steepness: a wave steeper than 1/7 breaks, got {steepness!r}")
    omega = 2.0 * math.pi / hull.natural_roll_period()
    return hull.roll_stiffness * hull.effective_slope * math.pi * s, omega


def capacity(
    unit: GyroUnit,
    hull: Hull,
    n_units: int = 1,
    steepness: float = DESIGN_STEEPNESS,
    max_precession_rate: float | None = None,
    max_precession: float | None = None,
) -> float:
    """Fraction of the design sea's roll moment n units can cancel (module doc); >= 1 means
    all of it. max_precession (rad) defaults to the unit's (ValueError if it has none);
    max_precession_rate (rad/s) None: no rate cap."""
    n = check_int("n_units", n_units, 1, 8)
    beta = unit.max_precession if max_precession is None else max_precession
    if beta is None:
        raise ValueError(f"max_precession: {unit.name} has no published limit; pass one")
    m0, omega = design_wave_moment(hull, steepness)
    cap = 1.0 / capacity_ratio(m0, unit.angular_momentum * n, omega, 1, beta)
    if max_precession_rate is not None:
        rate = positive_scalar("max_precession_rate", max_precession_rate)
        cap = min(cap, n * unit.angular_momentum * rate / m0)
    return cap


def similar_hull(hull: Hull, mass: float) -> Hull:
    """`hull` scaled geometrically (Froude similarity, length ratio s = (m / m0)^(1/3)) to
    displacement mass `mass` (kg): lengths and GM x s, masses x s^3, inertias x s^5, so
    C44 x s^4, periods x sqrt(s), linear damping (moment per rate) x s^4.5, quadratic x s^5,
    the speed term x s^4."""
    s = (positive_scalar("mass", mass) / hull.mass) ** (1.0 / 3.0)
    d = s**4.5
    return dataclasses.replace(
        hull,
        mass=mass,
        inertia=tuple(j * s**5 for j in hull.inertia),
        added_roll_inertia=hull.added_roll_inertia * s**5,
        roll_stiffness=hull.roll_stiffness * s**4,
        pitch_stiffness=hull.pitch_stiffness * s**4,
        roll_damping=hull.roll_damping * d,
        roll_damping_quadratic=hull.roll_damping_quadratic * s**5,
        roll_damping_speed=hull.roll_damping_speed * s**4,
        pitch_damping=hull.pitch_damping * d,
        yaw_damping=hull.yaw_damping * d,
        heave_stiffness=hull.heave_stiffness * s**2,
        heave_damping=hull.heave_damping * s**2.5,
        surge_sway_damping=hull.surge_sway_damping * s**2.5,
        length=hull.length * s,
        beam=hull.beam * s,
    )


def largest_hull(
    unit: GyroUnit, hull: Hull, n_units: int = 1, steepness: float = DESIGN_STEEPNESS, **kw
) -> float:
    """Displacement mass (kg) of the largest hull similar to `hull` whose capacity is 1
    (bisection in log mass between 1e-3 and 1e3 times the hull's; capacity falls with size)."""
    lo, hi = math.log(hull.mass * 1e-3), math.log(hull.mass * 1e3)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        h = similar_hull(hull, math.exp(mid))
        if capacity(unit, h, n_units, steepness, **kw) >= 1.0:
            lo = mid
        else:
            hi = mid
    return math.exp(0.5 * (lo + hi))
