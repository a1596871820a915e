"""The gimbal (precession) drive of a gyro roll stabilizer as a machine.

The gimbal of each gyro turns about the ship's e_2 under the torque of its drive, the gyroscopic
torque H w_g1 of the spinning rotor and, for a pendulous gimbal, gravity (the phi-row of ch. 3
Eq. 74, solved in `kernels.ship_accel`). This module gives that drive torque (N m, on gyro 1's
gimbal axis; gyro 2 of a pair gets the mirror torque) for five drives:

| kind        | machine                                                                      |
|-------------|------------------------------------------------------------------------------|
| electric    | servo motor + gearbox, four-quadrant (the default active drive)              |
| brake       | controlled hydraulic brake: the same loop, torques restricted to tau phi' <= 0 |
| damper      | passive braked gimbal: tau = -c phi' (a constant brake valve setting)         |
| pendulous   | Schlick (1904/1906): gimbal CG a distance l below the axis + brake: gravity   |
|             | torque m g l (cos phi R31 - sin phi R33) - c phi' (see `pendulum_torque`)     |
| spring      | spring-restored gimbal: tau = -k phi - c phi'                                |

Which machine, and where the numbers come from. Seakeeper, the gyro of the default yacht,
controls precession with a hydraulic *brake*: "The hydraulic brake circuit is a 'closed' circuit
with no pump or reservoir" (Seakeeper Model 7000 Gyro Operation Manual, doc. 90021 rev. 4,
2009, §4.2); it can only dissipate (`brake`). Active yacht gyros (VEEM) drive precession with a
powered actuator; the seed excites the gimbal "by either a hydraulic system, or servo" (ch. 3
§3.3.2). The default here is an active electric servo drive, because a precession-rate action
needs a drive that can also supply power. Seakeeper publishes no gimbal-drive rating, so its
limits are sized, not quoted (`electric_drive`): the rate limit 2.0 rad/s (the seed
env's precession-rate limit; H x 2 rad/s = 18 kN m of roll moment for the Seakeeper 9); the
torque limit 0.1 H holds the precession against the gyroscopic torque H w1 up to a roll rate of
0.1 rad/s (the yacht rolling 3.4 deg at its 3.7 s period; larger rolls overpower the drive
and the gimbal runs to its stops, as on a real gyro); the motoring power limit 1 kW. Braking is
limited by the torque only (a brake resistor or relief valve takes the heat). A damping law
phi' = k w1 needs braking, not motoring: the roll drives the gimbal and the drive holds it back
(the power tau phi' = -H k w1^2 < 0), which is why a brake suffices for Seakeeper.

Inner rate loop (active drives): the action stays a precession-rate command u (rad/s). The
command is clipped to +-max_rate and to the end-stop envelope |phi'| <= (phi_max - |phi|) / t_stop,
then a PI loop with feedforward of the gyroscopic torque gives

    tau_c = K_p (u - phi') + K_i z - f H w_g1,    z' = (u - phi') + (tau - tau_c) / (K_i T_t),

saturated to the machine envelope: |tau| <= tau_max; motoring (tau phi' > 0) also
|tau phi'| <= P_max and fading to zero between max_rate and 1.1 max_rate (the no-load speed);
`brake`: tau phi' <= 0. z is integrated with the ship (one state), the loop is evaluated at
every Runge-Kutta stage (so it is a continuous-time machine, not a zero-order hold on the
physics step), and back-calculation (tracking time T_t = K_p / K_i) keeps z bounded while
saturated. K_p = 2 zeta w_b J_g, K_i = w_b^2 J_g put the loop poles at -w_b (zeta = 1) for
the gimbal inertia J_g = J2^(2) + J1^(3).

End stops (all drives): an inelastic hard stop at +-phi_max (`end_stop`): a gimbal reaching it
is put on the stop with its outward rate removed, and the hull takes the reaction so that the
total angular momentum is kept (`end_stop` returns the rate jump). There is no stop spring, so
the stops add no stiffness to the step-size limit.

Step size: `step_bound.stable_physics_dt` returns the largest RK4 step for which every
eigenvalue of the linearised roll-gimbal-loop system lies in RK4's stability region; envs
refuse a larger physics_dt.
Hand-written (numba, no library): these run inside the ship kernel's RK stages.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numba
import numpy as np
from numpy.typing import NDArray

from mf_envs._jit import kernel
from mf_envs._validate import (
    check_choice,
    check_fields,
    nonnegative_scalar,
    positive_scalar,
)
from mf_envs.physics.end_stops import cushion_torque as stop_law

DRIVE_KINDS = ("electric", "brake", "damper", "pendulous", "spring")
KIND_ELECTRIC, KIND_BRAKE, KIND_DAMPER, KIND_PENDULOUS, KIND_SPRING = 1, 2, 3, 4, 5
# packed drive vector D (the last five: the Seakeeper unit's rate cap and cushioned stops)
DKIND, DTMAX, DRMAX, DPMAX, DKP, DKI, DFF, DC, DK, DPHIMAX, DTSTOP = range(11)
DRCAP, DTCAP, DASTOP, DKS, DCS = range(11, 16)
N_DRIVE = 16
RATE_FADE = 0.1  # motoring torque fades to 0 between max_rate and (1 + RATE_FADE) max_rate


@dataclass(frozen=True)
class DriveParams:
    """A gimbal drive (module doc). SI units.

    kind: one of DRIVE_KINDS.
    max_torque: tau_max, N m (active drives); max_rate: rate-command limit and rated speed,
    rad/s; max_power: motoring power limit P_max, W (active drives).
    bandwidth: w_b of the PI rate loop, rad/s; damping_ratio: zeta of the loop;
    feedforward: 1 cancels the gyroscopic torque H w_g1 in the command (within the limits), 0 off.
    damping: c, N m s/rad (brake valve of `damper`/`pendulous`/`spring`; bearing friction of the
    active drives); stiffness: k = m g l (pendulous) or the spring rate (spring), N m/rad.
    max_angle: end stops +-phi_max, rad; stop_time: t_stop of the active drives' stop
    envelope, s.
    rate_cap: the unit's precession-rate cap r_cap, rad/s (0: none; `cap_rate`); cap_torque:
    the largest torque the cap may apply, N m (the relief valve; 0: none);
    stop_stiffness k_s (N m/rad), stop_damping c_s (N m s/rad): cushioned stops engaging at
    +-max_angle (`cushion_torque`; k_s = 0: the inelastic hard stop `end_stop`).
    """

    kind: str = "electric"
    max_torque: float = 900.0
    max_rate: float = 2.0
    max_power: float = 1000.0
    bandwidth: float = 20.0
    damping_ratio: float = 1.0
    feedforward: float = 1.0
    damping: float = 0.0
    stiffness: float = 0.0
    max_angle: float = math.pi / 3
    stop_time: float = 0.1
    rate_cap: float = 0.0
    cap_torque: float = 0.0
    stop_stiffness: float = 0.0
    stop_damping: float = 0.0

    def __post_init__(self) -> None:
        check_choice("kind", self.kind, DRIVE_KINDS)
        limits = ("max_torque", "max_rate", "max_power", "max_angle", "stop_time")
        check_fields(self, positive=(*limits, "bandwidth", "damping_ratio"))
        cap_and_stops = ("rate_cap", "cap_torque", "stop_stiffness", "stop_damping")
        check_fields(self, nonnegative=(*cap_and_stops, "feedforward", "damping", "stiffness"))
        if self.feedforward > 1.0:
            raise ValueError(f"feedforward: must be in [0, 1], got {self.feedforward!r}")

    @property
    def active(self) -> bool:
        """True for drives that follow the rate command (electric, brake)."""
        return self.kind in ("electric", "brake")

    def gains(self, gimbal_inertia: float) -> tuple[float, float]:
        """(K_p in N m s/rad, K_i in N m/rad) of the PI loop for J_g = gimbal_inertia (kg m^2)."""
        if not self.active:
            return 0.0, 0.0
        jg = positive_scalar("gimbal_inertia", gimbal_inertia)
        return 2.0 * self.damping_ratio * self.bandwidth * jg, self.bandwidth**2 * jg

    def pack(self, gimbal_inertia: float) -> NDArray[np.float64]:
        """The packed float64 vector D (N_DRIVE,) read by the numba functions below."""
        D = np.zeros(N_DRIVE)
        D[DKIND] = DRIVE_KINDS.index(self.kind) + 1
        D[DTMAX], D[DRMAX], D[DPMAX] = self.max_torque, self.max_rate, self.max_power
        D[DKP], D[DKI] = self.gains(gimbal_inertia)
        D[DFF] = self.feedforward if self.active else 0.0
        D[DC], D[DK] = self.damping, self.stiffness
        D[DPHIMAX], D[DTSTOP] = self.max_angle, self.stop_time
        D[DRCAP], D[DTCAP] = self.rate_cap, self.cap_torque
        D[DASTOP], D[DKS], D[DCS] = self.max_angle, self.stop_stiffness, self.stop_damping
        return D


def electric_drive(angular_momentum: float, **over: float) -> DriveParams:
    """The default electric drive sized for a rotor of angular momentum H (N m s), module doc:
    tau_max = 0.1 H (holds the precession up to a roll rate of 0.1 rad/s), 2 rad/s, 1 kW."""
    h = nonnegative_scalar("angular_momentum", angular_momentum)
    kw = {"max_torque": 0.1 * h, "max_rate": 2.0, "max_power": 1000.0}
    kw.update(over)
    return DriveParams("electric", **kw)


@kernel(forceinline=True)
def _clip(x: float, lo: float, hi: float) -> float:
    return min(max(x, lo), hi)


@kernel(forceinline=True, error_model="numpy")
def stop_envelope(u: float, phi: float, phi_max: float, stop_time: float) -> float:
    """The end-stop envelope, the one definition (the servo's, the machine drives' and the
    controllers'): a precession rate u (rad/s) clipped to (-phi_max - phi) / stop_time <= u <=
    (phi_max - phi) / stop_time, so the gimbal reaches +-phi_max no sooner than stop_time."""
    lo = (-phi_max - phi) / stop_time
    return _clip(u, lo, (phi_max - phi) / stop_time)


@kernel(forceinline=True)
def rate_command(u: float, phi: float, D: np.ndarray, o: int = 0) -> float:
    """The command u (rad/s) clipped to +-max_rate and the end-stop envelope (module doc).
    D[o:] is the packed drive vector (o > 0: read in place from a longer vector, no slice)."""
    ue = _clip(u, -D[o + DRMAX], D[o + DRMAX])
    return stop_envelope(ue, phi, D[o + DPHIMAX], D[o + DTSTOP])


@kernel(forceinline=True, error_model="numpy")
def machine_limit(tau: float, phid: float, D: np.ndarray, o: int = 0) -> float:
    """tau (N m) saturated to the machine envelope at gimbal rate phid (rad/s), module doc;
    D[o:] the packed drive vector."""
    t = _clip(tau, -D[o + DTMAX], D[o + DTMAX])
    if t * phid > 0.0:  # motoring
        if int(D[o + DKIND]) == KIND_BRAKE:
            return 0.0
        a = abs(phid)
        lim = min(D[o + DTMAX], D[o + DPMAX] / a)
        lim *= _clip((1.0 + RATE_FADE - a / D[o + DRMAX]) / RATE_FADE, 0.0, 1.0)
        t = _clip(t, -lim, lim)
    return t


@kernel(forceinline=True)
def pendulum_torque(phi: float, r20: float, r22: float, mgl: float, n_gyros: int) -> float:
    """Gravity torque (N m) on a gimbal whose CG lies l below its axis, mgl = m g l (N m).

    Ship attitude third row (R31, R33) = (r20, r22) gives gravity in the ship frame; the CG at
    R_2(phi) (0, 0, -l) feels m g l (cos phi R31 - sin phi R33) about e_2 (level ship:
    -m g l sin phi, Schlick's restoring pendulum). For the mirrored pair (gyro 2 at -phi) the
    torque on the common coordinate is the half difference, -m g l sin(phi) R33.
    """
    if n_gyros == 2:
        return -mgl * math.sin(phi) * r22
    return mgl * (math.cos(phi) * r20 - math.sin(phi) * r22)


@kernel(forceinline=True)
def drive_torque(phi, phid, z, u, gyro_torque, r20, r22, n_gyros, D, o=0):
    """(tau in N m, z' in rad/s) of the drive on gyro 1's gimbal (module doc).

    phi, phid: gimbal angle (rad) and rate (rad/s); z: rate-loop integral (rad); u: rate command
    (rad/s); gyro_torque: H w_g1 (N m), the gyroscopic torque on the gimbal the feedforward
    cancels; r20, r22: R31, R33 of the ship attitude (pendulous gimbal); D[o:] the packed drive
    vector (the kernels read it in place from their parameter vector: no slice per stage).
    """
    kind = int(D[o + DKIND])
    tau = -D[o + DC] * phid
    if kind == KIND_PENDULOUS:
        tau += pendulum_torque(phi, r20, r22, D[o + DK], n_gyros)
    elif kind == KIND_SPRING:
        tau -= D[o + DK] * phi
    if kind != KIND_ELECTRIC and kind != KIND_BRAKE:
        return tau, 0.0
    tau_m, dz = active_torque(phi, phid, z, u, gyro_torque, D, o)
    return tau + tau_m, dz


@kernel(forceinline=True, error_model="numpy")
def active_torque(phi, phid, z, u, gyro_torque, D, o=0):
    """(machine torque tau_m in N m, z' in rad/s) of the active drives' PI rate loop (module
    doc), `drive_torque` without the bearing friction; division by zero gives inf/NaN (numpy's
    error model: no exception path; the env's numerical-failure path catches them)."""
    e = rate_command(u, phi, D, o) - phid
    tau_c = D[o + DKP] * e + D[o + DKI] * z - D[o + DFF] * gyro_torque
    tau_m = machine_limit(tau_c, phid, D, o)
    dz = e + (tau_m - tau_c) / D[o + DKP] if D[o + DKI] > 0.0 else 0.0
    return tau_m, dz


@numba.njit(cache=True)
def end_stop(phi: float, phid: float, phi_max: float):
    """Inelastic hard stop: (phi, phi', rate jump dphi' in rad/s) after clamping phi to
    +-phi_max and removing an outward rate (the hull takes -J_g dphi' of momentum)."""
    if phi > phi_max:
        return phi_max, min(phid, 0.0), min(phid, 0.0) - phid
    if phi < -phi_max:
        return -phi_max, max(phid, 0.0), max(phid, 0.0) - phid
    return phi, phid, 0.0


@kernel(forceinline=True)
def cushion_torque(phi: float, phid: float, D: np.ndarray, o: int = 0) -> float:
    """Torque (N m) of the cushioned end stops on the gimbal at angle phi (rad), rate phid
    (rad/s): a spring-damper engaging at +-a_s that only pushes (`end_stops.cushion_torque`),
    -sign(phi) max(0, k_s d + c_s d'), d = |phi| - a_s > 0; 0 without cushions (k_s = 0)."""
    ks = D[o + DKS]
    if ks <= 0.0:
        return 0.0
    return stop_law(phi, phid, D[o + DASTOP], ks, D[o + DCS])


@kernel(forceinline=True)
def cap_rate(phid: float, dt: float, jg: float, D: np.ndarray, o: int = 0):
    """(phi', rate jump in rad/s) after the unit's precession-rate cap over a physics step dt
    (s) on a gimbal of inertia jg (kg m^2): |phi'| above r_cap is brought back to r_cap by a
    torque of at most cap_torque (N m), so the jump is at most cap_torque dt / jg. This is the
    flow-limiting valve of the hydraulic brake as a rate constraint (the stiff valve law of
    `brake.brake_torque` would need steps of ~1e-4 s; docs/stabilizer_physics.md §4)."""
    r = D[o + DRCAP]
    a = abs(phid)
    if r <= 0.0 or a <= r:
        return phid, 0.0
    jump = min(a - r, D[o + DTCAP] * dt / jg) if D[o + DTCAP] > 0.0 else a - r
    if phid > 0.0:
        return phid - jump, -jump
    return phid + jump, jump


def drive_machine(
    kind: str,
    gyro: Any,
    hull: Any,
    n: int,
    max_rate: float,
    max_angle: float,
    loop_gain: float | None,
    max_torque: float | None,
    max_power: float,
    bandwidth: float,
    damping: float | None,
    stiffness: float | None,
) -> DriveParams:
    """The `DriveParams` of a drive `kind` (not "kinematic") for `n` gyros `gyro`
    (`ship.params.GyroParams`) on `hull` (`ship.hulls.Hull`), from validated values; None
    values take the documented defaults: the torque limit 0.1 H (`electric_drive`; a stopped
    rotor: J_g w_b max_rate), `loop_gain` K_p = 2 w_b J_g setting the bandwidth, the passive
    brake c = n H^2 / sqrt(C44 J) and the pendulum/spring k = J_g w_n^2 tuned to the roll."""
    jg = gyro.gimbal_inertia + gyro.rotor_j1
    j = hull.roll_inertia() + n * jg
    wn = math.sqrt(hull.roll_stiffness / j) if hull.roll_stiffness > 0 else 2 * math.pi / 10.0
    if loop_gain is not None:  # v0 name: the proportional gain K_p = 2 w_b J_g (zeta = 1)
        bandwidth = loop_gain / (2.0 * jg)
    kw = {"max_rate": max_rate, "max_angle": max_angle, "max_power": max_power,
          "bandwidth": bandwidth}  # fmt: skip
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
