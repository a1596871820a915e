"""The ship with one or two gyros on the general multibody engine (ch. 3 Eqs. 98-122).

Kinematic tree (Fig. 3-7)::

    inertial --Spherical (or Free with `translation`)--> ship (1)
      ship --Revolute e_2 at (0,  h2, h3),  phi --> gimbal (2) --Revolute e_3,  psi --> rotor (3)
      ship --Revolute e_2 at (0, -h2, h3), -phi --> gimbal (4) --Revolute e_3, -psi --> rotor (5)

The engine (`mf_envs.physics.multibody`) assembles B(t) (Eq. 120), M (Eq. 121), D (Eq. 122) and
solves Eq. 74 for the hull's free velocities with the gimbal and rotor prescribed (Eq. 115), or
with a free gimbal driven by a torque. Rotors turn about their gimbal's e_3 (the seed's Eqs.
106-107 write R_2). This is the general model the fast paths of `ship.kernels` are checked
against; it is slower (Python per step) and used by tests and benchmarks, not by the env.

Loads: the engine holds applied wrenches constant over a step, so the time-dependent wave moment
is evaluated at the step midpoint (second order) and the state-dependent hydrostatic/damping
moments at the step start (first order in dt).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable

import numpy as np
from numpy.typing import NDArray

from mf_envs.effects import resolve_effects
from mf_envs.frames.so3 import rot_x
from mf_envs.physics.multibody import Body, Free, MBState, Multibody, Revolute, Spherical
from mf_envs.physics.ship import kernels as K
from mf_envs.physics.ship.layout import Slot as S
from mf_envs.physics.ship.model import (
    SEED_EFFECTS,
    SHIP_EFFECTS,
    GimbalDrive,
    ShipRun,
    WaveLoad,
    pack_params,
    pitch_angle,
    roll_angle,
)
from mf_envs.physics.ship.params import GyroParams, ShipParams


def gimbal_prescription(drive: GimbalDrive, sign: float = 1.0) -> Callable[[float], tuple]:
    """phi(t), phi', phi'' of Eq. 119 (sinusoidal) or Eq. 118 (continuous), times `sign`."""
    if drive.mode == "sinusoidal":
        om = 2.0 * math.pi * drive.frequency
        a = sign * drive.amplitude

        def f(t: float) -> tuple[float, float, float]:
            arg = om * t - drive.phase
            return a * math.sin(arg), a * om * math.cos(arg), -a * om * om * math.sin(arg)

        return f
    if drive.mode == "continuous":
        rate = sign * 4.0 * drive.amplitude * drive.frequency
        return lambda t: (rate * t, rate, 0.0)
    raise ValueError(
        f"drive: the engine prescribes only 'sinusoidal'/'continuous', got {drive.mode!r}"
    )


def build_ship_multibody(
    ship: ShipParams,
    gyro: GyroParams,
    n_gyros: int = 2,
    effects: Iterable[str] | str | None = None,
    drive: GimbalDrive | None = None,
    gyro_mass: float = 0.0,
    offset: tuple[float, float] = (0.0, 0.0),
) -> Multibody:
    """The ship + gyros as a `Multibody`; `drive=None` leaves the gimbals free (no torque).

    The engine's tree has no gear constraint phi^(4) = -phi^(2); two free gimbals started
    mirrored stay mirrored while the hull only rolls (w2 = w3 = 0), which is the case checked.

    gyro_mass: mass of each gimbal + rotor unit (kg), split equally; offset: (h2, h3) in m (Eqs.
    100-101). The hull inertia given to the engine is `ship.inertia` (+A44 with added_inertia)
    minus the units' parallel-axis terms, and its mass `ship.mass` minus the units', so that the
    whole ship has `ship.mass` and `ship.inertia` (about the hull frame origin).
    """
    eff = resolve_effects(effects, SHIP_EFFECTS, SEED_EFFECTS)
    h2, h3 = offset
    offsets = [(0.0, h2, h3), (0.0, -h2, h3)][:n_gyros]
    J = np.diag(np.asarray(ship.inertia, dtype=float))
    if "added_inertia" in eff:
        J[0, 0] += ship.added_roll_inertia
    for s in offsets:
        sv = np.asarray(s)
        J -= gyro_mass * (sv @ sv * np.eye(3) - np.outer(sv, sv))
    jg = gyro.gimbal_inertia if "gimbal_inertia" in eff else 0.0
    spin = gyro.rotor_speed if "gyroscopic" in eff else 0.0
    hull_joint = Free() if "translation" in eff else Spherical()
    hull_mass = ship.mass - n_gyros * gyro_mass
    if hull_mass <= 0.0:
        raise ValueError(f"gyro_mass: {n_gyros} x {gyro_mass} kg exceeds the ship mass {ship.mass}")
    bodies = [Body("ship", hull_mass, J, hull_joint)]
    for k, s in enumerate(offsets):
        sign = 1.0 if k == 0 else -1.0
        g, r = f"gimbal{k + 1}", f"rotor{k + 1}"
        pres = None if drive is None else gimbal_prescription(drive, sign)
        bodies.append(
            Body(
                g,
                0.5 * gyro_mass,
                (jg, jg, jg),
                Revolute((0.0, 1.0, 0.0), offset=s),
                parent="ship",
                prescribed=pres,
            )
        )
        bodies.append(
            Body(
                r,
                0.5 * gyro_mass,
                (gyro.rotor_j1, gyro.rotor_j1, gyro.rotor_inertia),
                Revolute((0.0, 0.0, 1.0)),
                parent=g,
                prescribed=_spin(sign * spin),
            )
        )
    return Multibody(bodies)


def _spin(rate: float) -> Callable[[float], tuple[float, float, float]]:
    # the rotor angle is kept modulo 2 pi: at 8050 rpm it would otherwise grow without bound
    return lambda t: (math.fmod(rate * t, 2.0 * math.pi), rate, 0.0)


def simulate_engine(
    ship: ShipParams,
    gyro: GyroParams,
    n_gyros: int,
    effects: Iterable[str] | str | None,
    drive: GimbalDrive,
    t_end: float,
    dt: float,
    wave: WaveLoad | None = None,
    roll0: float = 0.0,
    omega0: Iterable[float] = (0.0, 0.0, 0.0),
    gyro_mass: float = 0.0,
    offset: tuple[float, float] = (0.0, 0.0),
    heave0: float = 0.0,
) -> ShipRun:
    """Run the engine model with a prescribed gimbal; returns the same `ShipRun` as the fast path.

    heave0: initial hull CM height (m, `translation` only).

    External moments are those of the fast path (`ship.loads.external_moment`, the same packed
    parameters), applied to the hull as a body-frame moment.
    """
    eff = resolve_effects(effects, SHIP_EFFECTS, SEED_EFFECTS)
    m = build_ship_multibody(ship, gyro, n_gyros, eff, drive, gyro_mass, offset)
    P = pack_params(ship, gyro, n_gyros, eff - {"irregular_waves"}, drive, wave)
    tab = np.zeros((1, 2))
    R0 = rot_x(roll0)
    w0 = np.asarray(tuple(omega0), dtype=float)
    trans = "translation" in eff
    # the fast path's x is the composite CM, fixed in the hull at s_cm: start it at rest
    s_cm = _composite_cm_offset(ship, n_gyros, gyro_mass, offset)
    x0 = np.array([0.0, 0.0, heave0]) - R0 @ s_cm
    v0 = -R0 @ np.cross(w0, s_cm)
    q0 = (R0, x0) if trans else R0
    u0 = (v0, w0) if trans else w0
    st = m.initial_state(q={"ship": q0}, u={"ship": u0})
    n = int(round(t_end / dt))
    out = _Recorder(n + 1)
    wrench = np.zeros((len(m.bodies), 6))
    for k in range(n + 1):
        out.record(m, st, P, n_gyros, gyro, trans, s_cm)
        if k == n:
            break
        wrench[0, 3:6] = _hull_moment(m, st, P, tab, dt, trans)
        if trans:
            wrench[0, 0:3] = _hull_force(m, st, P, dt, s_cm)
        st = m.step(st, dt, wrench)
    return out.result()


def _hull_rates(m: Multibody, st: MBState, trans: bool) -> tuple[NDArray, NDArray]:
    R = m.coordinate(st, "ship")
    if trans:
        R = R[0]
    u = m.velocity(st, "ship")
    w = u[3:6] if trans else u
    return R, w


def _hull_moment(
    m: Multibody, st: MBState, P: NDArray, tab: NDArray, dt: float, trans: bool
) -> NDArray:
    R, w = _hull_rates(m, st, trans)
    m1, m2, m3, mw = K.external_moment(st.t, w, R, P, tab)
    _, _, _, mw_mid = K.external_moment(st.t + 0.5 * dt, w, R, P, tab)
    return np.array([m1 - mw + mw_mid, m2, m3])


def _composite_cm_offset(
    ship: ShipParams, n_gyros: int, gyro_mass: float, offset: tuple[float, float]
) -> NDArray:
    """s_cm (3,), m: the whole ship's CM in the hull frame (gyro units at (0, +-h2, h3))."""
    return np.array([0.0, 0.0, n_gyros * gyro_mass * offset[1] / ship.mass])


def _hull_force(m: Multibody, st: MBState, P: NDArray, dt: float, s_cm: NDArray) -> NDArray:
    """Inertial force on the hull (N) of the `translation` effect, as in `ship.kernels.stage_rhs`
    on the composite CM (regular-wave heave force at the step midpoint; restoring and damping
    at the step start)."""
    (R, x), u = m.coordinate(st, "ship"), m.velocity(st, "ship")
    x = x + R @ s_cm
    v = u[0:3] + R @ np.cross(u[3:6], s_cm)
    fw = 0.0
    if int(P[S.WMODE]) == K.WAVE_REGULAR:
        fw = P[S.WF0] * math.sin(P[S.WOMEGA] * (st.t + 0.5 * dt) + P[S.WPHASE])
    return np.array([-P[S.CSS] * v[0], -P[S.CSS] * v[1], fw - P[S.KH] * x[2] - P[S.CH] * v[2]])


class _Recorder:
    def __init__(self, n: int) -> None:
        self.t, self.w, self.R = np.zeros(n), np.zeros((n, 3)), np.zeros((n, 3, 3))
        self.phi, self.phid, self.mg, self.x = (
            np.zeros(n),
            np.zeros(n),
            np.zeros(n),
            np.zeros((n, 3)),
        )
        self.k = 0

    def record(
        self,
        m: Multibody,
        st: MBState,
        P: NDArray,
        n_gyros: int,
        gyro: GyroParams,
        trans: bool,
        s_cm: NDArray | None = None,
    ) -> None:
        k = self.k
        R, w = _hull_rates(m, st, trans)
        self.t[k], self.w[k], self.R[k] = st.t, w, R
        if trans:  # composite centre of mass (hull origin + R s_cm), m
            self.x[k] = m.coordinate(st, "ship")[1] + R @ s_cm
        self.phi[k] = m.coordinate(st, "gimbal1")
        self.phid[k] = m.velocity(st, "gimbal1")
        H = P[S.JR3] * P[S.PSID]
        self.mg[k] = K.gyro_roll_moment(self.phi[k], self.phid[k], H, n_gyros)
        self.k += 1

    def result(self) -> ShipRun:
        return ShipRun(
            self.t,
            self.w,
            self.phi,
            self.phid,
            self.R,
            roll_angle(self.R),
            pitch_angle(self.R),
            self.mg,
            self.x,
        )


def simulate_free_gimbal(
    ship: ShipParams,
    gyro: GyroParams,
    t_end: float,
    dt: float,
    omega0: Iterable[float] = (0.05, 0.0, 0.0),
    effects: Iterable[str] | str | None = None,
    n_gyros: int = 1,
) -> ShipRun:
    """Gyros whose gimbals are FREE (no torque): a passive stabilizer nutating with the hull.

    No applied loads, so the engine's RKMK4 keeps its full order; the nutation frequency
    H / sqrt(J_gimbal J_roll) grows with the rotor speed (the stiff case of the benchmarks).
    """
    eff = resolve_effects(effects, SHIP_EFFECTS, SEED_EFFECTS)
    m = build_ship_multibody(ship, gyro, n_gyros, eff, None)
    P = pack_params(ship, gyro, n_gyros, eff, GimbalDrive())
    st = m.initial_state(u={"ship": np.asarray(tuple(omega0), dtype=float)})
    n = int(round(t_end / dt))
    out = _Recorder(n + 1)
    for k in range(n + 1):
        out.record(m, st, P, n_gyros, gyro, False)
        if k < n:
            st = m.step(st, dt)
    return out.result()
