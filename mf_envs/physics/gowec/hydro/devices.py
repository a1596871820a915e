"""Named floating GOWEC devices: a hull, its gyroscope units, PTO limits and losses.

`FloatingGOWEC-v0(device=...)` starts from one of these; any of its kwargs overrides a field.

- ``"iswec_box"`` (the default): a device sized like ISWEC, the gyroscopic wave energy
  converter of Politecnico di Torino / Wave for Energy deployed off Pantelleria in 2015, on
  its own hull: the 15 x 8 m box of 3.2 m draft (4.5 m high) in 35 m of water
  (`three_dof.ISWEC_BOX_FILE`; its mass properties chosen, docs/gowec_v1.md "ISWEC's box
  hull"), its length along the default sea (e2): pitch and roll each with their own block
  (`axes`), roll's wave moment from the heading table; two gyroscope units with flywheels over
  2 m in diameter, slack mooring. What is chosen, not published (docs/gowec_v1.md says why):
  the flywheel (a steel disc 2.4 m across and 0.35 m thick, J = 1.2e4 kg m^2 at 250 rpm,
  H = 3.14e5 N m s per unit), the gimbal frame's inertia, the PTO limits (150 kN m and 130 kW
  per unit), the running loss (1.5 kW per unit at the rated 250 rpm: bearings by SKF's friction
  model plus seals and windage in the evacuated casing, growing with speed, `flywheel`) and the
  speed range the baseline schedules the flywheels over (50-250 rpm), 90 % drive efficiency
  each way, drag coefficient 1, the gimbal's end stops (+-70 deg, 10 deg of cushion), the
  survival brake and the operating range (sea height <= 2.5 m).
- ``"iswec_class"``: the same gyro units, PTO, limits and supervisor on the stand-in hull the
  default used before the box: the vertical cylinder of ISWEC's footprint, radius 6 m, draft
  2.5 m (`three_dof.ISWEC_HULL_FILE`, axisymmetric: one pitch block for both axes; why a
  cylinder: docs/gowec_v1.md).
- ``"seed_buoy"``: the device of mf_envs 0.1-0.4: the 5 m cylinder of GOWEC-v0's irregular
  sea (converged BEM table) carrying the seed's mirrored pair of Seakeeper 26 rotors (Table
  3-1), 3 kW rotor loss, 5 %-of-critical linear viscous damping, no drag, no ramp, episode
  end at 1 rad of tilt. It nets no power with any controller (docs/gowec_v1.md); its figures
  (free decay, RAO, stiff-hull Eq. 95) are the regression tests of the model.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from mf_envs.physics.constants import RPM
from mf_envs.physics.end_stops import size_cushion
from mf_envs.physics.gowec.flywheel import FlywheelLoss
from mf_envs.physics.gowec.hydro import DEFAULT_HULL_FILE, HullCoefficients
from mf_envs.physics.gowec.hydro.axes import pitch_hull
from mf_envs.physics.gowec.hydro.three_dof import (
    ISWEC_BOX_FILE,
    ISWEC_HULL_FILE,
    ThreeDofCoefficients,
)


@dataclass(frozen=True)
class FloatingDevice:
    """One floating GOWEC as built: every number SI. `rotor_loss` is the running loss of all
    units together (W); limits are per unit; `viscous_fraction` a linear damping as a fraction
    of critical (0 = none) and `drag_coefficient` the quadratic drag's C_d (0 = none);
    `pitch_limit` (rad) is the tilt beyond which the supervisor puts the device in survival
    (`gimbal` module doc); `wave_ramp` (s) ramps the incident wave in. The gimbal's end stops
    engage at +-`stop_angle` (rad) with a cushion of `stop_travel` (rad) sized by
    `cushion` (`end_stops.size_cushion`); the survival brake is `brake_damping` (N m s/rad per
    unit), held `survival_hold` s after its trigger; seas of (significant) wave height above
    `max_operating_height` (m) are met in survival from the start."""

    name: str
    hull_file: Path
    three_dof: bool  # a surge/heave/pitch table (`three_dof`): pitch, and roll if it has sway/roll
    rotor_inertia: float  # kg m^2 (axial, per unit)
    rotor_speed: float  # rad/s
    gimbal_inertia: tuple[float, float, float]  # kg m^2 (gimbal frame, per unit)
    gyro_units: int
    rotor_loss: float | None  # W, all units (None: `flywheel_loss` at the speed, x units)
    max_generator_torque: float  # N m per unit
    max_generator_power: float  # W per unit
    generator_efficiency: float
    drag_coefficient: float
    viscous_fraction: float
    pitch_limit: float  # rad
    wave_ramp: float  # s
    mooring_stiffness: float  # N/m, linear surge spring (with surge free)
    effects: tuple[str, ...]  # the env's default effects on this device
    physics_dt: float  # s, the env's default RK4 substep (docs/gowec_v1.md: accuracy)
    stop_angle: float = math.inf  # rad, where the cushions engage (inf: no end stops)
    stop_travel: float = math.radians(10.0)  # rad, the cushion's travel d_max
    stop_contact_rate: float = 3.0  # rad/s, gimbal rate the cushion is sized to stop
    stop_hull_rate: float = 0.5  # rad/s, hull rate of the gyroscopic torque it is sized for
    brake_damping: float = 0.0  # N m s/rad per unit, the survival brake
    survival_hold: float = 30.0  # s
    max_operating_height: float = math.inf  # m
    flywheel_loss: FlywheelLoss | None = None  # speed-dependent loss per unit (`flywheel`)
    rotor_speed_range: tuple[float, float] = (0.0, math.inf)  # rad/s, the speed schedule's

    def cushion(self, gimbal_inertia: float, angular_momentum: float) -> dict[str, float]:
        """The end stops' PTO fields (`gimbal.PTO_NAMES`) for a gimbal + rotor inertia about
        the gimbal axis (kg m^2) and a rotor of angular momentum H (N m s): k_s, c_s (damping
        ratio 0.5) by `end_stops.size_cushion`,
        and the stroke a_s + d_max; none when stop_angle is inf."""
        if not math.isfinite(self.stop_angle):
            return {}
        ks, cs = size_cushion(gimbal_inertia, self.stop_contact_rate, abs(angular_momentum),
                              self.stop_hull_rate, self.stop_travel, 0.5)  # fmt: skip
        return dict(stop_angle=self.stop_angle, stop_stiffness=ks, stop_damping=cs,
                    stroke=self.stop_angle + self.stop_travel)  # fmt: skip

    def hull(self) -> HullCoefficients:
        """The hull's pitch coefficients about G."""
        three = self.three_dof_table()
        return HullCoefficients.load(self.hull_file) if three is None else pitch_hull(three)

    def three_dof_table(self) -> ThreeDofCoefficients | None:
        """The surge/heave/pitch table of the hull (None for a pitch-only file)."""
        return ThreeDofCoefficients.load(self.hull_file) if self.three_dof else None

    def running_loss(self, speed: float, units: int, fixed: float | None = None) -> float:
        """Running loss (W) of `units` flywheels at `speed` (rad/s; 0 when stopped): `fixed`
        (W, all units) if given, else units x `flywheel_loss` at that speed."""
        if fixed is not None or self.flywheel_loss is None:
            return float(fixed or 0.0) * (speed != 0.0)
        return units * self.flywheel_loss.power(speed)

    @property
    def angular_momentum(self) -> float:
        """H = J psi' of one unit (N m s)."""
        return self.rotor_inertia * self.rotor_speed


# the ISWEC-class flywheel: a plain steel disc 2.4 m across and 0.35 m thick would be 12.4 t and
# 8.95e3 kg m^2; with a heavier rim (chosen; docs/gowec_v1.md):
ISWEC_ROTOR_INERTIA = 1.2e4  # kg m^2
ISWEC_ROTOR_SPEED = 250.0 * RPM  # rad/s (chosen): the rated (largest) speed
# the running loss per unit at 250 rpm, 1.5 kW as before (docs/gowec_v1.md): the bearings'
# load friction 0.97 kW (SKF's M = 1/2 mu F d = 37 N m), windage 0.1 kW (Daily & Nece 1960 for the
# disc in air at 1 atm, a 6 cm gap: an upper bound in the evacuated casing), the rest (0.43 kW)
# the lubricant's and seals' viscous drag (chosen split; `flywheel` module doc)
_BEARINGS = 0.5 * 0.0018 * 137e3 * 0.3 * ISWEC_ROTOR_SPEED  # W: mu 0.0018, F 137 kN, d 0.3 m
ISWEC_FLYWHEEL_LOSS = FlywheelLoss.through(ISWEC_ROTOR_SPEED, _BEARINGS, 1400.0 - _BEARINGS, 100.0)
ISWEC_SPEED_RANGE = (50.0 * RPM, ISWEC_ROTOR_SPEED)  # rad/s, the schedule's (chosen)

_ISWEC = dict(
        rotor_inertia=ISWEC_ROTOR_INERTIA, rotor_speed=ISWEC_ROTOR_SPEED,
        gimbal_inertia=(4000.0, 4000.0, 4000.0), gyro_units=2, rotor_loss=None,
        max_generator_torque=1.5e5, max_generator_power=1.3e5, generator_efficiency=0.9,
        drag_coefficient=1.0, viscous_fraction=0.0, pitch_limit=math.radians(20.0),
        wave_ramp=10.0, mooring_stiffness=3.0e3,
        effects=("gyroscopic", "radiation", "viscous_damping", "quadratic_drag", "surge_heave"),
        physics_dt=0.02, stop_angle=math.radians(70.0), brake_damping=5.0e5,
        max_operating_height=2.5, flywheel_loss=ISWEC_FLYWHEEL_LOSS,
        rotor_speed_range=ISWEC_SPEED_RANGE,
)  # fmt: skip
DEVICES: dict[str, FloatingDevice] = {
    "iswec_class": FloatingDevice(
        name="iswec_class", hull_file=ISWEC_HULL_FILE, three_dof=True, **_ISWEC,
    ),
    "iswec_box": FloatingDevice(
        name="iswec_box", hull_file=ISWEC_BOX_FILE, three_dof=True, **_ISWEC,
    ),
    "seed_buoy": FloatingDevice(
        name="seed_buoy", hull_file=DEFAULT_HULL_FILE, three_dof=False,
        rotor_inertia=26000.0 / (5000.0 * RPM), rotor_speed=5000.0 * RPM,
        gimbal_inertia=(5.0, 5.0, 5.0), gyro_units=2, rotor_loss=3000.0,
        max_generator_torque=1.0e4, max_generator_power=5.0e4, generator_efficiency=0.8,
        drag_coefficient=0.0, viscous_fraction=0.05, pitch_limit=1.0, wave_ramp=0.0,
        mooring_stiffness=0.0, effects=("gyroscopic", "radiation", "viscous_damping"),
        physics_dt=0.005, brake_damping=5.0e3,
    ),
}  # fmt: skip
DEFAULT_DEVICE = "iswec_box"
