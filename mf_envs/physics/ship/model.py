"""Ship + gyro roll stabilizer model: effects, packing, simulation and named quantities.

The equations are in `ship.kernels` (module doc there: total angular-momentum balance, which is
the B-matrix result of ch. 3 Eqs. 74-75 with prescribed gimbal and rotor, and the seed's Eqs.
123-128 as the `form="seed"` fast path). `ship_engine` builds the same ship on the general
multibody engine (`mf_envs.physics.multibody`) for cross-checks.

Effects (names from `mf_envs.effects`; all off costs nothing: a zero coefficient is skipped):

| effect                 | term                                                             |
|------------------------|------------------------------------------------------------------|
| gyroscopic             | rotor spin psi' (off: rotor stopped, gimbal still moves)         |
| gimbal_inertia         | gimbal frame inertia J^(2) (off: J^(2) = 0)                      |
| added_inertia          | A44 added to the roll inertia                                    |
| hydrostatic_restoring  | -C44 r (or wall-sided GZ if BM/GM > 0), -C55 pitch               |
| roll_damping           | -B44 w1, -B55 w2, -B66 w3 (linear)                               |
| quadratic_roll_damping | -B44q abs(w1) w1 (MSS's K_abs(p)p; Ikeda's eddy/viscous part)    |
| wave_moment            | regular M0 cos(2 pi t / T + phase)                               |
| irregular_waves        | roll moment from an irregular sea (`ship.seas`), replaces regular |
| gimbal_limits          | precession-rate limit and end stops on the servo                 |
| gimbal_damping         | bearing friction c phi' of an active torque drive (passive drives |
|                        | always brake with their own c)                                   |
| translation            | hull surge/sway/heave (heave restoring, damping, wave heave force)|
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from mf_envs._validate import (
    check_choice,
    check_fields,
    check_finite,
    check_int,
    check_nonnegative,
    check_positive,
    finite_scalar,
)
from mf_envs.effects import EFFECT_NAMES, resolve_effects
from mf_envs.frames.so3 import rot_x
from mf_envs.physics.ship import kernels as K
from mf_envs.physics.ship.coupling import SwayRollYaw
from mf_envs.physics.ship.drive import DCS, DKS, DPHIMAX, DRCAP, DriveParams
from mf_envs.physics.ship.kernels import gyro_roll_moment  # noqa: F401 (public name)
from mf_envs.physics.ship.layout import KernelParams
from mf_envs.physics.ship.params import GyroParams, ShipParams

SHIP_EFFECTS: dict[str, str] = {
    "gimbal_damping": "bearing friction c phi' of an active gimbal drive (torque drive)",
    # what the controller sees (GyroStabilizer-v0's observation; no physics term)
    "sensor_noise": "IMU and gimbal-encoder noise on the observation (GyroStabilizer-v0)",
    "sensor_delay": "observation delayed by whole control steps (GyroStabilizer-v0)",
    "quadratic_roll_damping": "quadratic roll damping -B44q |p| p (MSS K_|p|p)",
}
SHIP_EFFECTS.update(
    {
        name: EFFECT_NAMES[name]
        for name in (
            "gyroscopic",
            "gimbal_inertia",
            "added_inertia",
            "hydrostatic_restoring",
            "roll_damping",
            "wave_moment",
            "irregular_waves",
            "gimbal_limits",
            "translation",
        )
    }
)
SEED_EFFECTS = ("gyroscopic", "gimbal_inertia")  # the seed's simplified model (§3.3.4)
FORMS = ("exact", "seed")


@dataclass(frozen=True)
class GimbalDrive:
    """How gyro 1's gimbal moves (gyro 2 mirrors it).

    mode: "servo" (rate servo following a precession-rate command u, rad/s),
          "sinusoidal" (Eq. 119: phi = a sin(2 pi f t - phase)),
          "continuous" (Eq. 118: phi = 4 a f t),
          "torque" (the gimbal is a degree of freedom driven by the machine `machine`, a
          `ship.drive.DriveParams`: electric/brake rate loop, passive damper, pendulous or
          spring gimbal; None: a free gimbal, no torque; inelastic end stops at max_angle with
          `gimbal_limits`).
    amplitude a (rad), frequency f (Hz), phase (rad): Eqs. 118-119.
    servo_time_constant: first-order lag of the servo, s.
    max_rate: precession-rate limit, rad/s; max_angle: end stops, rad; stop_time: s, the end-stop
    envelope |phi'| <= (max_angle - |phi|) / stop_time (both only with `gimbal_limits`).
    machine: the torque drive (its own max_angle/stop_time/max_rate are used by it).
    """

    mode: str = "servo"
    amplitude: float = 0.0
    frequency: float = 0.0
    phase: float = 0.0
    servo_time_constant: float = 0.05
    max_rate: float = 2.0
    max_angle: float = math.pi / 3
    stop_time: float = 0.1
    machine: DriveParams | None = None

    def __post_init__(self) -> None:
        check_choice("mode", self.mode, ("servo", "sinusoidal", "continuous", "torque"))
        check_fields(self, finite=("amplitude", "frequency", "phase"))
        check_fields(self, positive=("servo_time_constant", "max_rate", "max_angle", "stop_time"))


@dataclass(frozen=True)
class WaveLoad:
    """Regular wave roll moment M0 cos(2 pi t / period + phase) (N m, s, rad); heave force
    amplitude heave_force (N, used with `translation`, in quadrature with the moment)."""

    moment_amplitude: float = 0.0
    period: float = 10.0
    phase: float = 0.0
    heave_force: float = 0.0

    def __post_init__(self) -> None:
        check_fields(self, finite=("moment_amplitude", "phase", "heave_force"))
        check_positive("period", self.period)


def pack_params(
    ship: ShipParams,
    gyro: GyroParams,
    n_gyros: int,
    effects: Iterable[str] | str | None,
    drive: GimbalDrive,
    wave: WaveLoad | None = None,
    form: str = "exact",
    table_dt: float = 0.0,
    ship_gz_cubic: float = 0.0,
    coupling: SwayRollYaw | None = None,
    speed: float = 0.0,
    units: int = 1,
    rotor_power: float = 0.0,
) -> NDArray[np.float64]:
    """The packed float64 parameter vector P of `ship.kernels` for this scene.

    `irregular_waves` needs a moment table (see `ship.seas.wave_table`) passed to the kernels
    with its sampling step `table_dt` (s). ship_gz_cubic: the cubic GZ term over GM (1/rad^2,
    `ship.hulls.Hull.gz_cubic`). coupling: sway-roll-yaw coefficients (`ship.coupling`): with
    them the sway equation and the coupling terms are on, at ship speed `speed` (m/s); they
    exist only for hulls with published coupling data, so this is a switch on the hull's data,
    not a named effect every hull could turn on. units: identical units lumped in each gyro
    (`gyro` is their sum; only the reported mount moment per unit uses it); rotor_power: the
    rotors' running power, W (reported in `kernels.advance`'s out[5]).
    """
    n = check_int("n_gyros", n_gyros, 1, 2)
    check_choice("form", form, FORMS)
    eff = resolve_effects(effects, SHIP_EFFECTS, SEED_EFFECTS)
    gs = _gyro_slots(gyro, n, eff, form)
    kp = {
        **_hull_slots(ship, eff),
        **gs,
        **_drive_slots(drive, eff, gs["d2"]),
        **_wave_slots(wave, eff, table_dt),
        "gz3": ship_gz_cubic if "hydrostatic_restoring" in eff else 0.0,
        "speed": check_nonnegative("speed", speed),
        "units": float(check_int("units", units, 1, 64)),
        "protor": check_nonnegative("rotor_power", rotor_power),
    }
    if coupling is not None:
        kp.update(cplon=1.0, coupling=tuple(map(float, coupling.pack())))
    return KernelParams(**kp).pack()


def _hull_slots(ship: ShipParams, eff: frozenset[str]) -> dict[str, float]:
    """Hull inertia, hydrostatics, damping and translation slots of `KernelParams`."""
    kp = dict(zip(("j1", "j2", "j3"), map(float, ship.inertia)))
    if "added_inertia" in eff:
        kp["j1"] += ship.added_roll_inertia
    if "hydrostatic_restoring" in eff:
        kp.update(k44=ship.roll_stiffness, gzr=ship.gz_bm_over_gm, k55=ship.pitch_stiffness)
    if "roll_damping" in eff:
        kp.update(b44=ship.roll_damping, b55=ship.pitch_damping, b66=ship.yaw_damping)
    if "quadratic_roll_damping" in eff:
        kp["b44q"] = ship.roll_damping_quadratic
    if "translation" in eff:
        kp.update(trans=1.0, mass=ship.mass, kh=ship.heave_stiffness, ch=ship.heave_damping)
        kp.update(css=ship.surge_sway_damping)
    return kp


def _gyro_slots(gyro: GyroParams, n: int, eff: frozenset[str], form: str) -> dict[str, float]:
    """Gimbal + rotor inertias, spin rate, count and equation form."""
    jg = gyro.gimbal_inertia if "gimbal_inertia" in eff else 0.0
    return dict(
        d1=jg + gyro.rotor_j1,
        d2=jg + gyro.rotor_j1,
        d3=jg + gyro.rotor_inertia,
        jr3=gyro.rotor_inertia,
        jg2=jg,
        psid=gyro.rotor_speed if "gyroscopic" in eff else 0.0,
        ngyro=float(n),
        form=float(K.FORM_SEED if form == "seed" else K.FORM_EXACT),
    )


_GMODES = {
    "servo": K.GIMBAL_SERVO,
    "sinusoidal": K.GIMBAL_SINUSOIDAL,
    "continuous": K.GIMBAL_CONTINUOUS,
    "torque": K.GIMBAL_TORQUE,
}


def _drive_slots(drive: GimbalDrive, eff: frozenset[str], d2: float) -> dict[str, Any]:
    """Gimbal drive: mode, prescribed motion, servo, limits and the torque drive's block
    (`ship.drive.DriveParams.pack` at gimbal inertia d2, kg m^2)."""
    kp: dict[str, Any] = {}
    if drive.mode == "torque" and drive.machine is not None:
        m = drive.machine
        if m.active and "gimbal_damping" not in eff:  # bearing friction of an active drive
            m = dataclasses.replace(m, damping=0.0)
        D = m.pack(d2)
        if "gimbal_limits" not in eff:  # no end stops: the drive's stop envelope is off too,
            D[DPHIMAX] = math.inf  # and so are the unit's rate cap and cushions
            D[DRCAP] = D[DKS] = D[DCS] = 0.0
        kp["drive"] = tuple(map(float, D))
    return dict(
        kp,
        gmode=float(_GMODES[drive.mode]),
        gamp=drive.amplitude,
        gfreq=drive.frequency,
        gphase=drive.phase,
        tau=drive.servo_time_constant,
        ratemax=drive.max_rate,
        phimax=drive.max_angle,
        tstop=drive.stop_time,
        limits=1.0 if "gimbal_limits" in eff else 0.0,
    )


def _wave_slots(wave: WaveLoad | None, eff: frozenset[str], table_dt: float) -> dict[str, float]:
    """Wave moment (and heave force): none, regular, or a table sampled every table_dt s."""
    if "irregular_waves" in eff:
        if table_dt <= 0.0:
            raise ValueError("table_dt: irregular_waves needs a wave table and its step (s)")
        return dict(wmode=float(K.WAVE_TABLE), tabdt=table_dt)
    if "wave_moment" in eff and wave is not None:
        return dict(
            wmode=float(K.WAVE_REGULAR),
            wm0=wave.moment_amplitude,
            womega=2.0 * math.pi / wave.period,
            wphase=wave.phase,
            wf0=wave.heave_force,
        )
    return {}


def initial_state(
    roll: float = 0.0,
    omega: Iterable[float] = (0.0, 0.0, 0.0),
    gimbal_angle: float = 0.0,
    gimbal_rate: float = 0.0,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(y, R): state vector (see `ship.kernels`) and attitude rot_x(roll) (inertial <- ship)."""
    y = np.zeros(K.N_STATE)
    y[0:3] = check_finite("omega", omega)
    y[3] = finite_scalar("gimbal_angle", gimbal_angle)
    y[4] = finite_scalar("gimbal_rate", gimbal_rate)
    return y, rot_x(roll)


@dataclass
class ShipRun:
    """A simulated trajectory: t (N,) s; omega (N,3) body rates rad/s; phi, phi_rate (N,) gyro-1
    gimbal rad, rad/s; R (N,3,3) attitude; roll, pitch (N,) rad; gyro_moment (N,) N m (roll);
    x (N,3) hull CM position m (translation)."""

    t: NDArray[np.float64]
    omega: NDArray[np.float64]
    phi: NDArray[np.float64]
    phi_rate: NDArray[np.float64]
    R: NDArray[np.float64]
    roll: NDArray[np.float64]
    pitch: NDArray[np.float64]
    gyro_moment: NDArray[np.float64]
    x: NDArray[np.float64]


def simulate(
    P: NDArray[np.float64],
    t_end: float,
    dt: float,
    y0: NDArray[np.float64] | None = None,
    R0: NDArray[np.float64] | None = None,
    table: NDArray[np.float64] | None = None,
) -> ShipRun:
    """Open-loop run of the fast path (prescribed gimbal, or the servo with zero command)."""
    check_positive("t_end", t_end)
    check_positive("dt", dt)
    if y0 is None or R0 is None:
        y0, R0 = initial_state()
    tab = np.zeros((1, 2)) if table is None else np.ascontiguousarray(table, dtype=np.float64)
    t, y, R, mg = K.simulate_kernel(
        np.asarray(y0, float), np.asarray(R0, float), float(t_end), float(dt), P, tab
    )
    return ShipRun(t, y[:, 0:3], y[:, 3], y[:, 4], R, roll_angle(R), pitch_angle(R), mg, y[:, 5:8])


def roll_angle(R: NDArray[np.float64]) -> NDArray[np.float64]:
    """Roll r = atan2(R32, R33) of attitude(s) R (..., 3, 3) (z-y-x Euler angles), rad."""
    R = np.asarray(R)
    return np.arctan2(R[..., 2, 1], R[..., 2, 2])


def pitch_angle(R: NDArray[np.float64]) -> NDArray[np.float64]:
    """Pitch p = -asin(R31) of attitude(s) R (..., 3, 3), rad."""
    R = np.asarray(R)
    return -np.arcsin(np.clip(R[..., 2, 0], -1.0, 1.0))


def roll_inertia(
    phi: float, ship: ShipParams, gyro: GyroParams, n_gyros: int, added: bool = False
) -> float:
    """Exact roll inertia J_xx(phi) = J1 (+A44) + n [(J_g + J_r1) cos^2 phi + (J_g + J_r3) sin^2
    phi] (kg m^2); Eq. 123 uses its phi = 0 value."""
    jg = gyro.gimbal_inertia
    j = ship.roll_inertia(added)
    c2, s2 = math.cos(phi) ** 2, math.sin(phi) ** 2
    return j + n_gyros * ((jg + gyro.rotor_j1) * c2 + (jg + gyro.rotor_inertia) * s2)
