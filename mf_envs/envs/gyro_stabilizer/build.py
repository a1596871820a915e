"""GyroStabilizer-v0's kwargs -> typed physics parameters (`mf_envs.physics.ship`), never the env:
`build(**kwargs)` validates them into a `Scene` (the hull, the gimbal drive and its physics-step
bound, the waves, the reward weights), from which `pack` makes the packed parameter vector and
`irregular_table` the irregular-sea tables. Every hull field reaches the physics
(`ship.hulls.Hull`); the drive is a `ship.drive.DriveParams` machine (or the v0 kinematic
servo); seas are met at the ship's heading and speed (`ship.seas`).

Arguments of `GyroStabilizerEnv` handled here (SI units):

| Argument | default | meaning |
|---|---|---|
| hull | None | `Hull`, "yacht" (default), "mss_naval_vessel" or a dict of Hull fields |
| coupling | None | `ship.coupling.SwayRollYaw`; None/True: MSS's navalvessel.m coefficients
with hull "mss_naval_vessel", off for other hulls; False: off |
| drive (`spec.Drive`), its flat aliases (`spec.DRIVE`): | | |
| gimbal_drive | None | brake (Seakeeper preset), electric (seed preset), damper, pendulous,
spring, kinematic ("servo" = kinematic, "torque" = electric: the v0 names) |
| gimbal_loop_gain | None | K_p of the rate loop, N m s/rad (sets drive_bandwidth) |
| max_gimbal_torque | None | drive torque limit, N m (None: seed 0.1 H; Seakeeper preset:
brake relief T_r, electric H p_d, `ship.unit.unit_drive`) |
| max_drive_power | None | motoring power limit, W (None: seed 1000; Seakeeper H p_d r_cap) |
| drive_bandwidth | 20 | rate-loop bandwidth, rad/s |
| gimbal_damping | None | brake c, N m s/rad (passive default n H^2 / sqrt(C44 J)) |
| gimbal_stiffness | None | m g l (pendulous) or spring k, N m/rad (default J_g w_n^2) |
| heading | pi/2 | wave heading beta, rad (0 following, pi/2 beam, pi head) |
| ship_speed | 0 | U, m/s (encounter frequency; MSS's speed roll damping) |
| wave_spreading | None | cos-2s spreading s of the irregular sea (None: long-crested) |
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from collections.abc import Iterable
from typing import Any

from mf_envs._validate import check_choice, check_int, check_range, check_shape
from mf_envs.effects import resolve_effects
from mf_envs.envs.base import MAX_SUBSTEPS, MIN_DT
from mf_envs.physics.ship import unit as U
from mf_envs.physics.ship.coupling import SwayRollYaw
from mf_envs.physics.ship.drive import DriveParams, drive_machine
from mf_envs.physics.ship.hulls import Hull
from mf_envs.physics.ship.model import SHIP_EFFECTS, GimbalDrive
from mf_envs.physics.ship.params import GyroParams, ShipParams, capacity_ratio
from mf_envs.physics.ship.step_bound import drive_stable_step
from mf_envs.physics.ship.unit import CUSHION_START, CUSHION_TRAVEL  # noqa: F401 (re-exported)


@dataclasses.dataclass(frozen=True)
class Scene:
    """What the env's kwargs become (SI units), validated; the env reads its parameters here."""

    hull: Hull
    coupling: SwayRollYaw | None
    heading: float
    ship_speed: float
    ship: ShipParams
    gyro: GyroParams
    n_gyros: int
    max_precession_rate: float
    max_gimbal_angle: float
    gimbal_drive: str
    drive: GimbalDrive
    effects: frozenset
    physics_dt: float  # the requested step (MFEnv rounds it to whole substeps)
    dt_max: float  # RK4 stability limit of the drive
    form: str
    wave_moment_amplitude: float
    wave_period: float
    significant_wave_height: float
    wave_spreading: float | None
    effective_slope: float
    roll_scale: float
    effort_weight: float
    preset: str = "seed"
    units: int = 1  # identical units lumped in each gyro (`gyro` is their sum)
    unit_name: str = ""
    rotor_power: float = 0.0  # W, running power of all units (0: not modelled, seed preset)
    spool_up_power: float = 0.0  # W, all units' spool-up power (reset option spool_up)
    design_roll_rate: float = math.nan  # rad/s, the drive sizing's p_d (Seakeeper preset)
    cushion: Any = None  # `ship.brake.BrakeParams` of the cushioned stops (None: inelastic)
    mount_moment_bound: float = math.inf  # N m per unit (`ship.unit.unit_drive`)
    hull_damping: str = "rule_of_thumb"
    table_dt: float = math.nan  # the irregular-sea table's step, set by `timed`


def build(kw: dict[str, Any], default_effects: tuple[str, ...]) -> Scene:
    """The `Scene` of the env's kwargs `kw` (all but render_mode); ValueError names the kwarg."""
    kw = dict(kw)
    pre = U.preset_defaults(kw)  # fills the kwargs left None from the preset
    kind = check_choice("gimbal_drive", kw["gimbal_drive"], GIMBAL_DRIVES)
    kind = DRIVE_ALIASES.get(kind, kind)
    tau_s = check_range("servo_time_constant", kw["servo_time_constant"], 1e-3, 10.0)
    speed = check_range("ship_speed", kw["ship_speed"], 0.0, 50.0)
    hull = build_hull(kw["hull"], kw["ship_inertia"], kw["roll_stiffness"], kw["roll_damping"],
                      kw["effective_slope"], pre["hull_damping"], speed)  # fmt: skip
    k = pre["units"]
    c = dict(hull=hull, coupling=build_coupling(kw["coupling"], kw["hull"]),
             heading=check_range("heading", kw["heading"], -4.0 * math.pi, 4.0 * math.pi),
             ship_speed=speed, ship=build_ship_params(hull, speed), gimbal_drive=kind,
             gyro=GyroParams(k * check_range("rotor_inertia", kw["rotor_inertia"], 1e-6, 1e6),
                             k * check_range("gimbal_inertia", kw["gimbal_inertia"], 1e-6, 1e6),
                             check_range("rotor_speed", kw["rotor_speed"], -1e4, 1e4)),
             n_gyros=check_int("n_gyros", kw["n_gyros"], 1, 2),
             max_precession_rate=check_range("max_precession_rate", kw["max_precession_rate"],
                                             1e-9),
             max_gimbal_angle=check_range("max_gimbal_angle", kw["max_gimbal_angle"], 1e-6,
                                          math.pi))  # fmt: skip
    machine = build_machine(kind, c["gyro"], hull, c["n_gyros"], c["max_precession_rate"],
                            c["max_gimbal_angle"], kw)  # fmt: skip
    c.update(preset=pre["preset"], units=k, unit_name=pre["unit_name"],
             rotor_power=pre["unit_power"] * k * c["n_gyros"],
             spool_up_power=pre["spool_power"] * k * c["n_gyros"],
             hull_damping=pre["hull_damping"])  # fmt: skip
    if pre["preset"] != "seed" and machine is not None:  # the Seakeeper unit's hardware
        if c["max_gimbal_angle"] > math.radians(80.0):  # + the cushion's 10 deg < 90 deg
            raise ValueError(
                "max_gimbal_angle: the Seakeeper preset's cushions start there and travel "
                f"10 deg, so it must be <= 80 deg, got {math.degrees(c['max_gimbal_angle']):.1f}"
            )
        p_d = kw["design_roll_rate"]
        p_d = _positive("design_roll_rate", U.design_roll_rate(hull) if p_d is None else p_d, 10)
        given = (kw["max_gimbal_torque"] is not None, kw["max_drive_power"] is not None)
        machine, cushion, bound = U.unit_drive(machine, c["gyro"], k, p_d, *given)
        c.update(design_roll_rate=p_d, cushion=cushion, mount_moment_bound=bound)
    c["drive"] = GimbalDrive("servo" if machine is None else "torque", servo_time_constant=tau_s,
                             max_rate=c["max_precession_rate"], max_angle=c["max_gimbal_angle"],
                             machine=machine)  # fmt: skip
    c["effects"] = resolve_effects(kw["effects"], SHIP_EFFECTS, default_effects)
    c["dt_max"] = stable_step(c["drive"], c["gyro"], hull, c["ship"], c["n_gyros"], c["effects"])
    c["physics_dt"] = kw["physics_dt"]
    if c["physics_dt"] is None:  # see spec.PHYSICS_DT_NOTE for the accuracy of these defaults
        c["physics_dt"] = default_physics_dt(machine, tau_s, kw["control_dt"], c["dt_max"])
    c.update(_sea(kw, c["ship"], c["effects"]), effective_slope=hull.effective_slope,
             roll_scale=check_range("roll_scale", kw["roll_scale"], 1e-6, 10.0))  # fmt: skip
    # effort_weight >= 0: a negative weight would pay for drive energy
    scene = Scene(**c, effort_weight=check_range("effort_weight", kw["effort_weight"], 0.0, 1e6))
    if {"hydrostatic_restoring", "gyroscopic"} <= scene.effects:
        msg = U.capacity_message(scene.hull, scene.gyro, scene.n_gyros, scene.units,
                                 scene.unit_name or "gyro", scene.max_gimbal_angle,
                                 scene.max_precession_rate)  # fmt: skip
        if msg:
            warnings.warn(msg, stacklevel=3)
    return scene


def _sea(kw: dict[str, Any], ship: ShipParams, effects: frozenset) -> dict[str, Any]:
    """form, the regular wave (period default: the roll resonance) and the irregular sea."""
    form = check_choice("form", kw["form"], ("exact", "seed"))
    m0 = check_range("wave_moment_amplitude", kw["wave_moment_amplitude"], -1e9, 1e9)
    period = kw["wave_period"]
    if period is None:
        period = ship.natural_roll_period("added_inertia" in effects)
        if "hydrostatic_restoring" not in effects or not math.isfinite(period):
            period = 10.0  # no restoring, no resonance: the seed's cases use T = 10 s
        elif not 0.5 <= period <= 60.0:
            raise ValueError(
                f"wave_period: None (roll resonance) gives {period:.3g} s from "
                "roll_stiffness and ship_inertia, outside [0.5, 60] s; pass wave_period"
            )
    hs = check_range("significant_wave_height", kw["significant_wave_height"], 1e-6, 30.0)
    spreading = kw["wave_spreading"]
    if spreading is not None:
        spreading = check_range("wave_spreading", spreading, 1e-3, 1e3)
    return dict(form=form, wave_moment_amplitude=m0,
                wave_period=check_range("wave_period", period, 0.5, 60.0),
                significant_wave_height=hs, wave_spreading=spreading)  # fmt: skip


def timed(scene: Scene, physics_dt: float) -> Scene:
    """The scene with the irregular-sea table step of the env's (rounded) physics step."""
    return dataclasses.replace(scene, table_dt=min(0.5 * physics_dt, 0.01))


GIMBAL_DRIVES = (
    "electric", "brake", "damper", "pendulous", "spring", "kinematic", "servo", "torque",
)  # fmt: skip
DRIVE_ALIASES = {"servo": "kinematic", "torque": "electric"}  # v0 names
HULL_PRESETS = {"yacht": Hull.yacht, "mss_naval_vessel": Hull.mss_naval_vessel}


def build_hull(
    hull: Hull | str | dict | None,
    ship_inertia: Iterable[float] | None,
    roll_stiffness: float | None,
    roll_damping: float | None,
    effective_slope: float | None,
    hull_damping: str = "rule_of_thumb",
    speed: float = 0.0,
) -> Hull:
    """The `Hull`: a `Hull`, a preset name, or a dict of field overrides on the yacht; the v0
    kwargs ship_inertia, roll_stiffness, roll_damping, effective_slope override it last.
    hull_damping "ikeda": the yacht preset's roll damping from its particulars
    (`Hull.yacht(roll_damping_method="ikeda")`); a given Hull keeps its own."""
    if hull is None:
        base = Hull.yacht(roll_damping_method=hull_damping, speed=speed)
    elif isinstance(hull, Hull):
        base = hull
    elif isinstance(hull, str):
        if hull not in HULL_PRESETS:
            raise ValueError(f"hull: must be one of {sorted(HULL_PRESETS)}, got {hull!r}")
        base = (Hull.yacht(roll_damping_method=hull_damping, speed=speed) if hull == "yacht"
                else HULL_PRESETS[hull]())  # fmt: skip
    elif isinstance(hull, dict):
        bad = sorted(set(hull) - {f.name for f in dataclasses.fields(Hull)})
        if bad:
            raise ValueError(f"hull: unknown fields {bad}")
        try:
            base = dataclasses.replace(
                Hull.yacht(roll_damping_method=hull_damping, speed=speed), **hull
            )
        except ValueError as exc:  # Hull names its field: say it is inside `hull`
            raise ValueError(f"hull.{exc}") from None
    else:
        raise ValueError(f"hull: expected a Hull, a preset name or a dict, got {hull!r}")
    over: dict[str, Any] = {}
    if ship_inertia is not None:
        inertia = check_shape("ship_inertia", ship_inertia, (3,))
        over["inertia"] = tuple(check_range("ship_inertia", v, 1e-6, 1e12) for v in inertia)
    for name, value, lo, hi in (
        ("roll_stiffness", roll_stiffness, 0.0, 1e12),
        ("roll_damping", roll_damping, 0.0, 1e12),
        ("effective_slope", effective_slope, 1e-6, 10.0),
    ):
        if value is not None:
            over[name] = check_range(name, value, lo, hi)
    return dataclasses.replace(base, **over) if over else base


def build_ship_params(hull: Hull, speed: float) -> ShipParams:
    """The kernels' `ShipParams` of the hull at ship speed U (m/s): B44 + K_|u|p |U|."""
    sp = hull.ship_params()
    if hull.roll_damping_speed > 0.0 and speed > 0.0:
        sp = dataclasses.replace(sp, roll_damping=sp.roll_damping + hull.roll_damping_speed * speed)
    return sp


MAX_DRIVE_GAIN = 1e12  # SI (N m, W, N m s/rad, N m/rad): far above any gimbal drive
MAX_BANDWIDTH = 1e5  # rad/s: a rate loop's w_b (w_b^2 J_g must stay a finite stiffness)


def _positive(name: str, value: Any, high: float) -> float:
    """A finite number in (0, high]; ValueError naming `name` (None too)."""
    x = check_range(name, value, 0.0, high)
    if x <= 0.0:
        raise ValueError(f"{name}: must be > 0, got {value!r}")
    return x


def _optional(name: str, value: Any, high: float, positive: bool = False) -> float | None:
    """None, or a finite number in [0, high] (> 0 when `positive`); ValueError naming `name`."""
    if value is None:
        return None
    x = check_range(name, value, 0.0, high)
    if positive and x <= 0.0:
        raise ValueError(f"{name}: must be > 0, got {value!r}")
    return x


def build_machine(
    kind: str,
    gyro: GyroParams,
    hull: Hull,
    n: int,
    max_rate: float,
    max_angle: float,
    kw: dict[str, Any],
) -> DriveParams | None:
    """The `DriveParams` of `gimbal_drive` (None for the kinematic servo), env doc defaults
    (`ship.drive.drive_machine`). Every drive kwarg of `kw` is validated whichever drive is
    chosen (a bad value is an error even where the drive ignores it)."""
    loop_gain = _optional("gimbal_loop_gain", kw["gimbal_loop_gain"], MAX_DRIVE_GAIN, True)
    max_torque = _optional("max_gimbal_torque", kw["max_gimbal_torque"], MAX_DRIVE_GAIN, True)
    max_power = 1000.0  # None: the Seakeeper preset sizes it (`ship.unit.unit_drive`)
    if kw["max_drive_power"] is not None:
        max_power = _positive("max_drive_power", kw["max_drive_power"], MAX_DRIVE_GAIN)
    bandwidth = _positive("drive_bandwidth", kw["drive_bandwidth"], MAX_BANDWIDTH)
    damping = _optional("gimbal_damping", kw["gimbal_damping"], MAX_DRIVE_GAIN)
    stiffness = _optional("gimbal_stiffness", kw["gimbal_stiffness"], MAX_DRIVE_GAIN)
    if kind == "kinematic":
        return None
    return drive_machine(kind, gyro, hull, n, max_rate, max_angle, loop_gain, max_torque,
                         max_power, bandwidth, damping, stiffness)  # fmt: skip


def stable_step(
    drive: GimbalDrive, gyro: GyroParams, hull: Hull, ship: ShipParams, n: int, eff: frozenset
) -> float:
    """Largest stable RK4 physics step (s) of the drive (`ship.step_bound.drive_stable_step`)."""
    j = hull.roll_inertia("added_inertia" in eff)
    return drive_stable_step(drive, gyro, j, hull.roll_stiffness, ship.roll_damping, n, eff)


def default_physics_dt(machine: Any, tau_s: float, control_dt: Any, dt_max: float) -> float:
    """Kinematic servo: min(0.05, tau); torque drives: min(control_dt, RK4 limit) / 2. A drive so
    stiff against its gimbal that this step needs more than `MAX_SUBSTEPS` per control step (or
    is below 1e-6 s) is refused naming the drive's arguments, not the physics_dt nobody gave."""
    cdt = check_range("control_dt", control_dt, 1e-9, 60.0)
    if machine is None:
        return min(0.05, tau_s)
    if cdt < 2 * MIN_DT:  # the default step, control_dt / 2, would be below MIN_DT
        raise ValueError(
            f"control_dt: must be >= {2 * MIN_DT:g} s with a torque drive (its default "
            f"physics_dt is control_dt / 2, at least {MIN_DT:g} s), got {control_dt!r}"
        )
    if dt_max < 2e-6 or cdt / (0.5 * min(cdt, dt_max)) > MAX_SUBSTEPS:
        raise ValueError(
            f"gimbal_damping, gimbal_stiffness, gimbal_loop_gain, drive_bandwidth, ship_inertia, "
            f"gimbal_inertia, rotor_inertia, rotor_speed, max_precession_rate, design_roll_rate "
            f"(the unit's cushions): this drive needs physics steps below {dt_max:.3g} s (RK4 "
            f"limit, `step_bound.stable_physics_dt`), more than {MAX_SUBSTEPS} per control step; "
            "soften the drive or enlarge the inertias"
        )
    return 0.5 * min(cdt, dt_max)


def check_step(physics_dt: float, dt_max: float) -> None:
    """ValueError naming physics_dt for a step beyond the drive's RK4 stability limit (the
    substep count is bounded by `MFEnv`, naming control_dt/physics_dt)."""
    if physics_dt > dt_max:
        raise ValueError(
            f"physics_dt: {physics_dt:.4g} s is beyond the RK4 stability limit {dt_max:.4g} s "
            "of this gimbal drive (`step_bound.stable_physics_dt`); pass physics_dt <= that, or "
            "a control_dt it divides"
        )


def build_coupling(coupling: Any, hull: Any) -> SwayRollYaw | None:
    """The sway-roll-yaw coefficients: None/True give MSS's with hull "mss_naval_vessel" (off
    for other hulls, which have no published coupling data), False off, or a `SwayRollYaw`."""
    if coupling is None or coupling is True:
        return SwayRollYaw.mss_naval_vessel() if hull == "mss_naval_vessel" else None
    if coupling is False:
        return None
    if not isinstance(coupling, SwayRollYaw):
        raise ValueError(f"coupling: expected a SwayRollYaw, True/False or None, got {coupling!r}")
    return coupling


def capacity(scene: Scene) -> float:
    """M0 / (n H w sin(max_gimbal_angle)) of the scene's regular wave (docs/design.md bound)."""
    return capacity_ratio(
        scene.wave_moment_amplitude,
        scene.gyro.angular_momentum,
        2.0 * math.pi / scene.wave_period,
        scene.n_gyros,
        scene.max_gimbal_angle,
    )
