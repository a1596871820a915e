"""A gyro stabilizer unit as it is built and sold: its rotor, its drive hardware (the rate cap,
the cushioned stops, the torque ratings) and its capacity on a hull (;
docs/stabilizer_physics.md §4). Used by `GyroStabilizer-v0`'s presets (`envs.gyro_stabilizer.
build`); plain functions, no Gymnasium.

- `preset_unit(preset, hull_key)`: the unit, gyro count and units per gyro, running and spool-up
  power of a preset ("seakeeper_7000": one Seakeeper Model 7000 on the yacht, 2 x 4 Table 3-1
  Seakeeper 35 on the MSS vessel; "seed": the seed's Table 3-1 Seakeeper 9).
- `unit_drive`: a drive (`ship.drive.DriveParams`) given the unit's rate cap, cushioned stops
  (`ship.brake.BrakeParams.design`) and torque ratings, and the mount-moment bound.
- `design_roll_rate(hull)`: p_d = 10 deg x the hull's natural roll frequency (the sizing's
  design roll rate, a choice).
- `capacity_message`: the one-line warning text when the capacity is far from 1.
- `preset_defaults(kw)`: the env kwargs a preset fills (GyroStabilizer-v0's `build`).
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from mf_envs._validate import check_choice, check_int
from mf_envs.physics.constants import RPM
from mf_envs.physics.ship import seakeeper as SK
from mf_envs.physics.ship.brake import BrakeParams
from mf_envs.physics.ship.drive import DriveParams
from mf_envs.physics.ship.params import GyroParams, seakeeper_gyro

PRESETS = ("seakeeper_7000", "seed")
# the Seakeeper preset's unit on each hull preset: (unit, gyros, units per gyro)
UNIT_OF_HULL = {
    "yacht": (SK.SEAKEEPER_7000, 1, 1),
    "mss_naval_vessel": (SK.SEED_TABLE_3_1["35"], 2, 4),
}
# W per unit: rotor running power. No maker's figure was found for the Model 7000 (nor any
# Seakeeper); chosen: the spool-up power of the seed's Table 3-1 units of neighbouring H
# (Seakeeper 5 and 9: 2,000 W), an upper bound (docs/stabilizer_physics.md §4); the Table 3-1
# units their own spool-up power. Spool-up power: the same motor's rating.
RUNNING_POWER_7000 = 2000.0
CUSHION_TRAVEL = math.radians(10.0)  # cushion from 50 deg to the Model 7000's 60 deg
CUSHION_START = math.radians(50.0)
CAPACITY_RANGE = (0.5, 2.0)  # outside it `capacity_message` warns


@dataclasses.dataclass(frozen=True)
class PresetUnit:
    """A preset's gyro: one unit's `GyroParams`, gyros n (1 or the mirrored pair), identical
    units per gyro k, the unit's name, running and spool-up power per unit (W)."""

    gyro: GyroParams
    n_gyros: int
    units: int
    name: str
    running_power: float
    spool_up_power: float


UNITS = {"7000": SK.SEAKEEPER_7000, **SK.SEED_TABLE_3_1}  # `gyro_unit` names


def preset_unit(preset: str, hull_key: str, unit_name: str | None = None) -> PresetUnit:
    """The gyro of `preset` (one of PRESETS) on the hull preset `hull_key` (module doc), or the
    unit `unit_name` (a key of UNITS: "7000" or a seed Table 3-1 model) as one gyro."""
    if unit_name is not None:
        unit = check_choice("gyro_unit", unit_name, tuple(UNITS))
        u = UNITS[unit]
        power = RUNNING_POWER_7000 if u is SK.SEAKEEPER_7000 else u.spool_up_power
        return PresetUnit(u.gyro_params(), 1, 1, u.name, 0.0 if preset == "seed" else power,
                          power)  # fmt: skip
    if preset == "seed":
        sk9 = SK.SEED_TABLE_3_1["9"]
        return PresetUnit(seakeeper_gyro("9"), 1, 1, sk9.name, 0.0, sk9.spool_up_power)
    unit, n, k = UNIT_OF_HULL.get(hull_key, UNIT_OF_HULL["yacht"])
    power = RUNNING_POWER_7000 if unit is SK.SEAKEEPER_7000 else unit.spool_up_power
    return PresetUnit(unit.gyro_params(), n, k, unit.name, power, power)


def design_roll_rate(hull: Any) -> float:
    """p_d (rad/s): a 10 deg roll at the hull's natural roll frequency (a choice, module doc);
    a hull without roll stiffness: at a 10 s period (`drive.drive_machine`'s fallback)."""
    if hull.roll_stiffness <= 0.0:
        return math.radians(10.0) * 2.0 * math.pi / 10.0
    return math.radians(10.0) * math.sqrt(hull.roll_stiffness / hull.roll_inertia())


def unit_drive(
    machine: DriveParams,
    gyro: GyroParams,
    units: int,
    p_d: float,
    torque_given: bool = False,
    power_given: bool = False,
) -> tuple[DriveParams, BrakeParams, float]:
    """The Seakeeper preset's drive hardware (docs/stabilizer_physics.md §4): `machine` given
    the unit's rate cap r_cap = max_rate, its cushioned stops (`BrakeParams.design` for the
    lumped gyro: H, J_g, design roll rate p_d, `CUSHION_TRAVEL` beyond max_angle) and torque
    ratings: brake relief T_r (`BrakeParams.relief_torque`), electric max_torque = H p_d (holds
    the gyroscopic torque up to the design roll rate) and motoring power H p_d r_cap (unless
    given: `torque_given`, `power_given`); the passive drives' valve as given, their cap held by
    T_r. Returns (drive, cushion, mount-moment bound per unit in N m):
    sqrt((H r_cap)^2 + (T + M_s)^2) / units, T the drive's torque rating (the cap's too), M_s
    the cushion's largest torque (`BrakeParams.stop_moment_bound`)."""
    h = abs(gyro.angular_momentum)
    jg = gyro.gimbal_inertia + gyro.rotor_j1
    r = machine.max_rate
    cushion = BrakeParams.design(max(h, 1e-9), jg, p_d, r, CUSHION_TRAVEL, machine.max_angle)
    rep: dict[str, Any] = {"rate_cap": r, "stop_stiffness": cushion.stop_stiffness,
                           "stop_damping": cushion.stop_damping}  # fmt: skip
    if machine.kind == "electric":
        if not torque_given:
            rep["max_torque"] = max(h * p_d, machine.max_torque if h == 0.0 else 0.0)
        if not power_given:
            rep["max_power"] = rep.get("max_torque", machine.max_torque) * r
        rep["cap_torque"] = rep.get("max_torque", machine.max_torque)
    elif machine.kind == "brake":
        if not torque_given:
            rep["max_torque"] = cushion.relief_torque
        rep["cap_torque"] = rep.get("max_torque", machine.max_torque)
    else:  # passive: the same relief valve holds the cap
        rep["cap_torque"] = cushion.relief_torque
    drive = dataclasses.replace(machine, **rep)
    t = drive.cap_torque if not drive.active else max(drive.max_torque, drive.cap_torque)
    bound = math.hypot(h * r, t + cushion.stop_moment_bound) / units
    return drive, cushion, bound


def capacity_message(
    hull: Any, gyro: GyroParams, n_gyros: int, units: int, name: str, max_angle: float,
    max_rate: float,
) -> str | None:  # fmt: skip
    """The one-line warning when the gyros' capacity in the design sea (`seakeeper.capacity`:
    regular beam sea at the roll resonance, steepness 1/50, the rate cap) is outside
    `CAPACITY_RANGE` (too small for the hull, or much larger than it needs); None otherwise or
    when it is undefined (no rotor, no restoring)."""
    if gyro.angular_momentum == 0.0 or hull.roll_stiffness <= 0.0:
        return None
    rpm = abs(gyro.rotor_speed) / RPM
    unit = SK.GyroUnit("lumped", abs(gyro.angular_momentum) * n_gyros, rpm, "scene",
                       max_precession=min(max_angle, math.pi / 2))  # fmt: skip
    try:
        cap = SK.capacity(unit, hull, 1, max_precession_rate=max_rate)
    except (ValueError, ZeroDivisionError):
        return None
    if CAPACITY_RANGE[0] <= cap <= CAPACITY_RANGE[1]:
        return None
    return (
        f"GyroStabilizer-v0: capacity {cap:.2f} of {n_gyros} x {units} {name} on this hull "
        "(design sea: beam, resonance, steepness 1/50; ship.seakeeper.capacity), far from 1"
    )


HULL_DAMPINGS = ("ikeda", "rule_of_thumb")


def preset_defaults(kw: dict[str, Any]) -> dict[str, Any]:
    """Fill the kwargs left None from `kw["preset"]` in place; returns the preset's other
    numbers (`ship.unit.preset_unit`: units per gyro, name, running and spool-up power per
    unit; the hull damping). "seed": the electric-drive default (Table 3-1 Seakeeper 9 on the yacht,
    electric drive, inelastic stops, rule-of-thumb damping). "seakeeper_7000": the unit of
    `ship.unit.UNIT_OF_HULL`, the hydraulic brake, cushions, Ikeda damping."""
    preset = check_choice("preset", kw["preset"], PRESETS)
    pu = preset_unit(preset, kw["hull"] if isinstance(kw["hull"], str) else "yacht",
                     kw.get("gyro_unit"))  # fmt: skip
    name = pu.name
    if kw.get("rotor_inertia") is not None or kw.get("rotor_speed") is not None:
        name = f"gyro (rotor kwargs; {preset} preset)"
    seed = preset == "seed"
    fill = {"gimbal_drive": "electric" if seed else "brake",
            "max_gimbal_angle": math.pi / 3 if seed else CUSHION_START,
            "max_drive_power": 1000.0 if seed else None,
            "hull_damping": "rule_of_thumb" if seed else "ikeda",
            "rotor_inertia": pu.gyro.rotor_inertia, "gimbal_inertia": pu.gyro.gimbal_inertia,
            "rotor_speed": pu.gyro.rotor_speed, "n_gyros": pu.n_gyros}  # fmt: skip
    for key, value in fill.items():
        if kw.get(key) is None:
            kw[key] = value
    k = pu.units
    if kw["units_per_gyro"] is not None:
        k = check_int("units_per_gyro", kw["units_per_gyro"], 1, 64)
    damping = check_choice("hull_damping", kw["hull_damping"], HULL_DAMPINGS)
    return {"preset": preset, "units": k, "unit_name": name, "unit_power": pu.running_power,
            "spool_power": pu.spool_up_power, "hull_damping": damping}  # fmt: skip
