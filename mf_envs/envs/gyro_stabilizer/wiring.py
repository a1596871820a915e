"""GyroStabilizer-v0's wiring to the ship physics (`mf_envs.physics.ship`): the hull, the gimbal
drive and its physics-step bound from the public arguments, the packed parameter vector and the
irregular-sea tables. Every hull field reaches the physics (`ship.hulls.Hull`); the drive is a
`ship.drive.DriveParams` machine (or the v0 kinematic servo); seas are met at the env's heading
and speed (`ship.seas`).

Arguments of `GyroStabilizerEnv` handled here (SI units):

| Argument | default | meaning |
|---|---|---|
| hull | None | `Hull`, "yacht" (default), "mss_naval_vessel" or a dict of Hull fields |
| coupling | None | `ship.coupling.SwayRollYaw`; None/True: MSS's navalvessel.m coefficients
with hull "mss_naval_vessel", off for other hulls; False: off |
| gimbal_drive | "electric" | electric, brake, damper, pendulous, spring, kinematic ("servo" =
kinematic, "torque" = electric: the v0 names) |
| gimbal_loop_gain | None | K_p of the rate loop, N m s/rad (sets drive_bandwidth) |
| max_gimbal_torque | None | drive torque limit, N m (None: 0.1 H) |
| max_drive_power | 1000 | motoring power limit, W |
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
from collections.abc import Iterable
from typing import Any

import numpy as np

from mf_envs._validate import (
    check_range,
    check_shape,
)
from mf_envs.effects import resolve_effects
from mf_envs.envs.base import MAX_SUBSTEPS
from mf_envs.physics.ship.coupling import SwayRollYaw
from mf_envs.physics.ship.drive import DriveParams, RollGimbal, electric_drive, stable_physics_dt
from mf_envs.physics.ship.hulls import Hull
from mf_envs.physics.ship.model import SHIP_EFFECTS, WaveLoad, pack_params
from mf_envs.physics.ship.params import ShipParams, capacity_ratio
from mf_envs.physics.ship.seas import G, excitation_table, jonswap_sea, regular_roll_moment, sinc
from mf_envs.physics.ship.waves import regular_heave_force

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
) -> Hull:
    """The `Hull`: a `Hull`, a preset name, or a dict of field overrides on the yacht; the v0
    kwargs ship_inertia, roll_stiffness, roll_damping, effective_slope override it last."""
    if hull is None:
        base = Hull.yacht()
    elif isinstance(hull, Hull):
        base = hull
    elif isinstance(hull, str):
        if hull not in HULL_PRESETS:
            raise ValueError(f"hull: must be one of {sorted(HULL_PRESETS)}, got {hull!r}")
        base = HULL_PRESETS[hull]()
    elif isinstance(hull, dict):
        bad = sorted(set(hull) - {f.name for f in dataclasses.fields(Hull)})
        if bad:
            raise ValueError(f"hull: unknown fields {bad}")
        try:
            base = dataclasses.replace(Hull.yacht(), **hull)
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
    env: Any,
    loop_gain: float | None,
    max_torque: float | None,
    max_power: float,
    bandwidth: float,
    damping: float | None,
    stiffness: float | None,
) -> DriveParams | None:
    """The `DriveParams` of `gimbal_drive` (None for the kinematic servo), env doc defaults.
    Every drive kwarg is validated whichever drive is chosen (a bad value is an error even
    where the drive ignores it)."""
    loop_gain = _optional("gimbal_loop_gain", loop_gain, MAX_DRIVE_GAIN, positive=True)
    max_torque = _optional("max_gimbal_torque", max_torque, MAX_DRIVE_GAIN, positive=True)
    max_power = _positive("max_drive_power", max_power, MAX_DRIVE_GAIN)
    bandwidth = _positive("drive_bandwidth", bandwidth, MAX_BANDWIDTH)
    damping = _optional("gimbal_damping", damping, MAX_DRIVE_GAIN)
    stiffness = _optional("gimbal_stiffness", stiffness, MAX_DRIVE_GAIN)
    if kind == "kinematic":
        return None
    gyro, hull, n = env.gyro, env.hull, env.n_gyros
    jg = gyro.gimbal_inertia + gyro.rotor_j1
    j = hull.inertia[0] + hull.added_roll_inertia + n * jg
    wn = math.sqrt(hull.roll_stiffness / j) if hull.roll_stiffness > 0 else 2 * math.pi / 10.0
    if loop_gain is not None:  # v0 name: the proportional gain K_p = 2 w_b J_g (zeta = 1)
        bandwidth = loop_gain / (2.0 * jg)
    kw: dict[str, Any] = {
        "max_rate": env.max_precession_rate,
        "max_angle": env.max_gimbal_angle,
        "max_power": max_power,
        "bandwidth": bandwidth,
    }
    if max_torque is not None:
        kw["max_torque"] = max_torque
    elif gyro.angular_momentum == 0.0:  # rotor stopped: enough to reach max_rate in 1/w_b
        kw["max_torque"] = jg * kw["bandwidth"] * kw["max_rate"]
    if kind in ("electric", "brake"):
        kw["damping"] = damping or 0.0
        return dataclasses.replace(electric_drive(abs(gyro.angular_momentum), **kw), kind=kind)
    h = abs(gyro.angular_momentum)
    stiff = math.sqrt(max(hull.roll_stiffness, 1.0) * j)
    c = n * h * h / stiff if damping is None else damping  # gyro roll damping ratio 0.5
    k = jg * wn * wn if stiffness is None else stiffness  # gimbal pendulum tuned to the roll
    kw["damping"] = c  # validated above when given, >= 0 by construction otherwise
    kw["stiffness"] = k if kind != "damper" else 0.0
    return DriveParams(kind, **kw)


def stable_step(env: Any, effects: Any) -> float:
    """Largest stable RK4 physics step (s) of the env's drive on its roll-gimbal linearisation
    (`ship.drive.stable_physics_dt`); the kinematic servo: 2.78 tau (RK4 on -1/tau)."""
    eff = resolve_effects(effects, SHIP_EFFECTS, env.DEFAULT_EFFECTS)
    if env.drive.machine is None:
        return 2.785 * env.drive.servo_time_constant
    jg = env.gyro.gimbal_inertia + env.gyro.rotor_j1
    hull = env.hull
    j = hull.inertia[0] + (hull.added_roll_inertia if "added_inertia" in eff else 0.0)
    h = abs(env.gyro.angular_momentum) if "gyroscopic" in eff else 0.0
    c44 = hull.roll_stiffness if "hydrostatic_restoring" in eff else 0.0
    b44 = env.ship.roll_damping if "roll_damping" in eff else 0.0
    D = env.drive.machine.pack(jg)
    return stable_physics_dt(D, RollGimbal(jg, j + env.n_gyros * jg, h, env.n_gyros, c44, b44))


def default_physics_dt(machine: Any, tau_s: float, control_dt: Any, dt_max: float) -> float:
    """Kinematic servo: min(0.05, tau); torque drives: min(control_dt, RK4 limit) / 2. A drive so
    stiff against its gimbal that this step needs more than `MAX_SUBSTEPS` per control step (or
    is below 1e-6 s) is refused naming the drive's arguments, not the physics_dt nobody gave."""
    cdt = check_range("control_dt", control_dt, 1e-9, 60.0)
    if machine is None:
        return min(0.05, tau_s)
    if dt_max < 2e-6 or cdt / (0.5 * min(cdt, dt_max)) > MAX_SUBSTEPS:
        raise ValueError(
            f"gimbal_damping, gimbal_stiffness, gimbal_loop_gain, drive_bandwidth, ship_inertia, "
            f"gimbal_inertia: this drive needs physics steps below {dt_max:.3g} s (RK4 limit, "
            f"`ship.drive.stable_physics_dt`), more than {MAX_SUBSTEPS} per control step; "
            "soften the drive or enlarge the inertias"
        )
    return 0.5 * min(cdt, dt_max)


def check_step(physics_dt: float, dt_max: float) -> None:
    """ValueError naming physics_dt for a step beyond the drive's RK4 stability limit (the
    substep count is bounded by `MFEnv`, naming control_dt/physics_dt)."""
    if physics_dt > dt_max:
        raise ValueError(
            f"physics_dt: {physics_dt:.4g} s is beyond the RK4 stability limit {dt_max:.4g} s "
            "of this gimbal drive (`ship.drive.stable_physics_dt`); pass physics_dt <= that, or "
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


def pack(env: Any, phase: float) -> np.ndarray:
    """The packed physics parameters of `env`, its regular wave at `phase` (rad) met at the
    env's heading and speed (`physics.ship.seas.regular_roll_moment`)."""
    hull = env.hull
    m0, we = regular_roll_moment(
        env.wave_moment_amplitude, env.wave_period, env.heading, env.ship_speed, hull.length
    )
    period = 2.0 * math.pi / max(abs(we), 1e-12)
    phase = phase if we >= 0.0 else -phase  # cos(-w t + p) = cos(w t - p)
    k = (2.0 * math.pi / env.wave_period) ** 2 / G
    gain = float(sinc(0.5 * k * hull.length * math.cos(env.heading)))  # heave: length mean
    try:
        heave = regular_heave_force(
            env.wave_moment_amplitude,
            env.wave_period,
            hull.roll_stiffness,
            hull.heave_stiffness,
            env.effective_slope,
        )
    except ZeroDivisionError:
        heave = math.inf
    if not math.isfinite(heave * gain):
        raise ValueError(
            "roll_stiffness, wave_period: the wave of this roll moment would have an infinite "
            f"heave force (C44 = {hull.roll_stiffness:g} N m/rad is too small)"
        )
    wave = WaveLoad(m0, period, phase, heave * gain)
    return pack_params(
        env.ship,
        env.gyro,
        env.n_gyros,
        env.effects,
        env.drive,
        wave,
        env.form,
        env.table_dt,
        hull.gz_cubic,
        env.coupling,
        env.ship_speed,
    )


def irregular_table(env: Any) -> np.ndarray:
    """A new JONSWAP sea (long- or short-crested, `physics.ship.seas`) met at the env's heading
    and speed, drawn from env.np_random: the (N, 2) roll-moment / heave-force table."""
    hull = env.hull
    sea = jonswap_sea(
        env.significant_wave_height,
        env.wave_period,
        env.heading,
        env.np_random,
        64,
        env.wave_spreading,
    )
    return excitation_table(
        sea,
        env.ship_speed,
        hull.roll_stiffness,
        hull.heave_stiffness,
        hull.length,
        hull.beam,
        env.episode_seconds + 1.0,
        env.table_dt,
        env.effective_slope,
    )


def capacity(env: Any) -> float:
    """M0 / (n H w sin(max_gimbal_angle)) of the env's regular wave (docs/design.md bound)."""
    return capacity_ratio(
        env.wave_moment_amplitude,
        env.gyro.angular_momentum,
        2.0 * math.pi / env.wave_period,
        env.n_gyros,
        env.max_gimbal_angle,
    )
