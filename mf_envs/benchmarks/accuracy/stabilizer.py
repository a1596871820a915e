"""Gyro stabilizer accuracy vs cost: fast paths vs the multibody engine, dt ladders, rotor speed.

Scenes (error = max over the run of |x - x_ref| / max |x_ref|):
- `stabilizer_seed_pair`: seed hull (1e6, 1e9, 1e10 kg m^2), two gyros, 8050 rpm, sinusoidal
  gimbal a = pi/3.6, M_e = 1e5 cos(2 pi t / 10) (Fig. 3-11), 20 s. Methods: `fast_exact` (numba,
  angular-momentum balance), `fast_seed` (Eqs. 123-125 as printed: frozen roll inertia), `engine`
  (general multibody model). Reference: the engine at dt = 1.25e-3 and 2.5e-3 s, Richardson-
  extrapolated (its midpoint-held wave moment makes it 2nd order). `fast_seed` levels off at the
  model difference (Eq. 123's frozen roll inertia: 1.2e-5 here), the others converge.
- `stabilizer_single`: one gyro on a 3.7e5 / 2.2e6 / 2.9e6 kg m^2 hull, same drive, roll and yaw
  rates; `fast_seed` (Eqs. 126-128 as printed, with their 2 J2^(2) slip) levels off.
- `stabilizer_yacht`: the env's yacht (restoring with wall-sided GZ, damping, wave moment, added
  inertia), 20 s; reference `fast_exact` at dt = 5e-4 s. The engine applies state-dependent loads
  held over a step (first order), the fast path evaluates them at every RK stage.
- `stabilizer_rotor_speed`: the stiff case. One FREE gimbal (passive, no torque) on the seed hull,
  hull released at 0.005 rad/s roll rate; rotor 1000 ... 10000 rpm; the nutation frequency
  H / sqrt(J_gimbal J_roll) grows with the speed (0.9 rad/s at 1000 rpm, 8.9 rad/s at 10 000);
  methods `engine_<rpm>rpm` and `fast_<rpm>rpm` (the torque drive of `ship.kernels` with zero
  torque), reference the engine at dt_min / 4 for each speed.
Extra columns: `rpm`, `form`.
"""

from __future__ import annotations

import math

import numpy as np

from mf_envs.benchmarks._io import timed
from mf_envs.physics.ship import (
    RPM,
    SEED_EFFECTS,
    GimbalDrive,
    GyroParams,
    ShipParams,
    WaveLoad,
    initial_state,
    pack_params,
    seed_test_hull,
    simulate,
    simulate_engine,
    small_yacht,
)
from mf_envs.physics.ship.engine import simulate_free_gimbal

ORDER = 30
T = 10.0
DRIVE = GimbalDrive("sinusoidal", amplitude=math.pi / 3.6, frequency=1.0 / T)
WAVE = WaveLoad(1.0e5, T)
EFF = SEED_EFFECTS + ("wave_moment",)


def _err(x: np.ndarray, ref: np.ndarray, t: np.ndarray, t_ref: np.ndarray) -> float:
    xr = np.interp(t, t_ref, ref)
    return float(np.abs(x - xr).max() / np.abs(ref).max())


def _model_scene(
    scene: str,
    ship: ShipParams,
    gyro: GyroParams,
    n: int,
    dts,
    t_end: float,
    quantities: dict[str, int],
) -> list[dict]:
    ref = simulate_engine(ship, gyro, n, EFF, DRIVE, t_end, 1.25e-3, WAVE)
    coarse = simulate_engine(ship, gyro, n, EFF, DRIVE, t_end, 2.5e-3, WAVE)
    # Richardson: the engine's held (midpoint) load makes it 2nd order; remove the h^2 term
    ref.omega[::2] += (ref.omega[::2] - coarse.omega) / 3.0
    ref.t, ref.omega = ref.t[::2], ref.omega[::2]
    rows = []
    for dt in dts:
        runs = {}
        for form in ("exact", "seed"):
            P = pack_params(ship, gyro, n, EFF, DRIVE, WAVE, form=form)
            simulate(P, dt, dt)  # compile / warm up
            runs[f"fast_{form}"] = timed(simulate, P, t_end, dt)
        runs["engine"] = timed(simulate_engine, ship, gyro, n, EFF, DRIVE, t_end, dt, WAVE)
        for method, (r, sec) in runs.items():
            for q, k in quantities.items():
                rows.append(
                    dict(
                        scene=scene,
                        method=method,
                        dt=dt,
                        param="dt",
                        quantity=q,
                        error=_err(r.omega[:, k], ref.omega[:, k], r.t, ref.t),
                        seconds=sec,
                        rpm=gyro.rotor_speed / RPM,
                    )
                )
    return rows


def _yacht_scene(dts, t_end: float) -> list[dict]:
    ship = small_yacht()
    gyro = GyroParams(9.549, 9.549, 9000 * RPM)
    eff = EFF + ("hydrostatic_restoring", "roll_damping", "added_inertia")
    tn = ship.natural_roll_period(True)
    drive = GimbalDrive("sinusoidal", amplitude=0.5, frequency=1.0 / tn)
    wave = WaveLoad(8000.0, tn)
    y0, R0 = initial_state(0.05)
    P = pack_params(ship, gyro, 1, eff, drive, wave)
    ref = simulate(P, t_end, 5e-4, y0, R0)
    rows = []
    for dt in dts:
        simulate(P, dt, dt, y0, R0)
        runs = {
            "fast_exact": timed(simulate, P, t_end, dt, y0, R0),
            "engine": timed(
                simulate_engine, ship, gyro, 1, eff, drive, t_end, dt, wave, roll0=0.05
            ),
        }
        for method, (r, sec) in runs.items():
            rows.append(
                dict(
                    scene="stabilizer_yacht",
                    method=method,
                    dt=dt,
                    param="dt",
                    quantity="roll",
                    error=_err(r.roll, ref.roll, r.t, ref.t),
                    seconds=sec,
                    rpm=9000.0,
                )
            )
    return rows


def _rotor_speed_scene(rpms, dts, t_end: float) -> list[dict]:
    ship, _ = seed_test_hull()
    w0 = (0.005, 0.0, 0.0)
    rows = []
    for rpm in rpms:
        gyro = GyroParams(50.0, 10.0, rpm * RPM)
        ref = simulate_free_gimbal(ship, gyro, t_end, min(dts) / 4, omega0=w0)
        P = pack_params(ship, gyro, 1, SEED_EFFECTS, GimbalDrive("torque"))
        y0, R0 = initial_state(0.0, w0)
        for dt in dts:
            simulate(P, dt, dt, y0, R0)
            runs = {
                f"engine_{rpm}rpm": timed(simulate_free_gimbal, ship, gyro, t_end, dt, w0),
                f"fast_{rpm}rpm": timed(simulate, P, t_end, dt, y0, R0),
            }
            for method, (r, sec) in runs.items():
                for q, x, xr in (
                    ("gimbal_angle", r.phi, ref.phi),
                    ("roll_rate", r.omega[:, 0], ref.omega[:, 0]),
                ):
                    err = _err(x, xr, r.t, ref.t) if np.all(np.isfinite(x)) else math.inf
                    rows.append(
                        dict(
                            scene="stabilizer_rotor_speed",
                            method=method,
                            dt=dt,
                            param="dt",
                            quantity=q,
                            error=err,
                            seconds=sec,
                            rpm=float(rpm),
                        )
                    )
    return rows


def rows(quick: bool) -> list[dict]:
    ship, gyro = seed_test_hull()
    dts = (0.04, 0.02, 0.01) if quick else (0.08, 0.04, 0.02, 0.01, 0.005)
    t_end = 10.0 if quick else 20.0
    out = _model_scene("stabilizer_seed_pair", ship, gyro, 2, dts, t_end, {"roll_rate": 0})
    hull = ShipParams(inertia=(3.7e5, 2.2e6, 2.9e6))
    out += _model_scene(
        "stabilizer_single", hull, gyro, 1, dts, t_end, {"roll_rate": 0, "yaw_rate": 2}
    )
    out += _yacht_scene(dts, t_end)
    rpms = (1000, 8050, 10000) if quick else (1000, 4000, 8050, 10000)
    sdts = (0.1, 0.05, 0.025) if quick else (0.2, 0.1, 0.05, 0.025, 0.0125)
    out += _rotor_speed_scene(rpms, sdts, 5.0 if quick else 10.0)
    return out
