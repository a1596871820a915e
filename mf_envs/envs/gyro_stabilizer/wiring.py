"""GyroStabilizer-v0's wiring to the ship physics: the gimbal drive from the public arguments,
the packed parameter vector and the irregular-sea wave tables (`mf_envs.physics.ship`)."""

from __future__ import annotations

from typing import Any

import numpy as np

from mf_envs._validate import check_range
from mf_envs.physics.ship.model import GimbalDrive, WaveLoad, pack_params
from mf_envs.physics.ship.waves import regular_heave_force, wave_table


def gimbal_drive(env: Any, mode, tau_s, loop_gain, max_torque, damping) -> GimbalDrive:
    """The gimbal drive from the public arguments (errors name them)."""
    d2 = env.gyro.gimbal_inertia + env.gyro.rotor_j1
    if loop_gain is None:
        loop_gain = d2 / tau_s if mode == "torque" else 0.0
    loop_gain = check_range("gimbal_loop_gain", loop_gain, 0.0, 1e12)
    if mode == "torque" and loop_gain * env.physics_dt / d2 > 1.5:
        raise ValueError(
            f"physics_dt: the torque drive's loop gain {loop_gain:g} N m s/rad needs "
            f"physics_dt <= {1.5 * d2 / loop_gain:.3g} s (RK4 stability)"
        )
    return GimbalDrive(
        mode,
        servo_time_constant=tau_s,
        max_rate=env.max_precession_rate,
        max_angle=env.max_gimbal_angle,
        loop_gain=loop_gain,
        max_torque=check_range("max_gimbal_torque", max_torque, 0.0, 1e12),
        damping=check_range("gimbal_damping", damping, 0.0, 1e12),
    )


def pack(env: Any, phase: float) -> np.ndarray:
    """The packed physics parameters of `env` with the regular wave at `phase` (rad)."""
    wave = WaveLoad(
        env.wave_moment_amplitude,
        env.wave_period,
        phase,
        regular_heave_force(
            env.wave_moment_amplitude,
            env.wave_period,
            env.ship.roll_stiffness,
            env.ship.heave_stiffness,
            env.effective_slope,
        ),
    )
    return pack_params(
        env.ship,
        env.gyro,
        env.n_gyros,
        env.effects,
        env.drive,
        wave,
        env.form,
        env.table_dt,
    )


def irregular_table(env: Any) -> np.ndarray:
    """A new JONSWAP wave-moment/heave table for one episode, drawn from env.np_random."""
    from mf_envs.physics.waves import IrregularSea, jonswap_spectrum

    sea = IrregularSea(
        jonswap_spectrum, env.significant_wave_height, env.wave_period, 64, env.np_random
    )
    a, w, eps = sea.components
    return wave_table(
        a,
        w,
        eps,
        env.ship.roll_stiffness,
        env.ship.heave_stiffness,
        env.episode_seconds + 1.0,
        env.table_dt,
        env.effective_slope,
    )
