"""GyroStabilizer-v0's wiring to the ship physics (`mf_envs.physics.ship`): the hull, the gimbal
drive and its physics-step bound from the public arguments, the packed parameter vector and the
irregular-sea tables. Every hull field reaches the physics (`ship.hulls.Hull`); the drive is a
`ship.drive.DriveParams` machine (or the v0 kinematic servo); seas are met at the env's heading
and speed (`ship.seas`).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable
from typing import Any

import numpy as np

from mf_envs._validate import check_nonnegative, check_positive
from mf_envs.effects import resolve_effects
from mf_envs.physics.ship.coupling import SwayRollYaw
from mf_envs.physics.ship.drive import DriveParams, RollGimbal, electric_drive, stable_physics_dt
from mf_envs.physics.ship.hulls import Hull
from mf_envs.physics.ship.model import SHIP_EFFECTS, WaveLoad, pack_params
from mf_envs.physics.ship.params import ShipParams
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
        base = dataclasses.replace(Hull.yacht(), **hull)
    else:
        raise ValueError(f"hull: expected a Hull, a preset name or a dict, got {hull!r}")
    over: dict[str, Any] = {}
    if ship_inertia is not None:
        inertia = np.ravel(check_positive("ship_inertia", ship_inertia))
        if inertia.shape != (3,):
            raise ValueError(f"ship_inertia: expected 3 principal inertias, got {ship_inertia!r}")
        over["inertia"] = tuple(float(v) for v in inertia)
    for name, value in (
        ("roll_stiffness", roll_stiffness),
        ("roll_damping", roll_damping),
        ("effective_slope", effective_slope),
    ):
        if value is not None:
            over[name] = float(check_nonnegative(name, value))
    return dataclasses.replace(base, **over) if over else base


def build_ship_params(hull: Hull, speed: float) -> ShipParams:
    """The kernels' `ShipParams` of the hull at ship speed U (m/s): B44 + K_|u|p |U|."""
    sp = hull.ship_params()
    if hull.roll_damping_speed > 0.0 and speed > 0.0:
        sp = dataclasses.replace(sp, roll_damping=sp.roll_damping + hull.roll_damping_speed * speed)
    return sp


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
    """The `DriveParams` of `gimbal_drive` (None for the kinematic servo), env doc defaults."""
    if kind == "kinematic":
        return None
    gyro, hull, n = env.gyro, env.hull, env.n_gyros
    jg = gyro.gimbal_inertia + gyro.rotor_j1
    j = hull.inertia[0] + hull.added_roll_inertia + n * jg
    wn = math.sqrt(hull.roll_stiffness / j) if hull.roll_stiffness > 0 else 2 * math.pi / 10.0
    if loop_gain is not None:  # v0 name: the proportional gain K_p = 2 w_b J_g (zeta = 1)
        bandwidth = float(check_positive("gimbal_loop_gain", loop_gain)) / (2.0 * jg)
    kw: dict[str, Any] = {
        "max_rate": env.max_precession_rate,
        "max_angle": env.max_gimbal_angle,
        "max_power": float(check_positive("max_drive_power", max_power)),
        "bandwidth": float(check_positive("drive_bandwidth", bandwidth)),
    }
    if max_torque is not None:
        kw["max_torque"] = float(check_positive("max_gimbal_torque", max_torque))
    if kind in ("electric", "brake"):
        kw["damping"] = float(check_nonnegative("gimbal_damping", damping or 0.0))
        return dataclasses.replace(electric_drive(gyro.angular_momentum, **kw), kind=kind)
    h = gyro.angular_momentum
    stiff = math.sqrt(max(hull.roll_stiffness, 1.0) * j)
    c = n * h * h / stiff if damping is None else damping  # gyro roll damping ratio 0.5
    k = jg * wn * wn if stiffness is None else stiffness  # gimbal pendulum tuned to the roll
    kw["damping"] = float(check_nonnegative("gimbal_damping", c))
    kw["stiffness"] = float(check_nonnegative("gimbal_stiffness", k if kind != "damper" else 0.0))
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
    h = env.gyro.angular_momentum if "gyroscopic" in eff else 0.0
    c44 = hull.roll_stiffness if "hydrostatic_restoring" in eff else 0.0
    b44 = env.ship.roll_damping if "roll_damping" in eff else 0.0
    D = env.drive.machine.pack(jg)
    return stable_physics_dt(D, RollGimbal(jg, j + env.n_gyros * jg, h, env.n_gyros, c44, b44))


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
    heave = regular_heave_force(
        env.wave_moment_amplitude,
        env.wave_period,
        hull.roll_stiffness,
        hull.heave_stiffness,
        env.effective_slope,
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
