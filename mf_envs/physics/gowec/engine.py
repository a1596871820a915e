"""The GOWEC in the general multibody engine (ch. 3 Eqs. 21-75), to check the fast path.

Buoy (1): spherical joint to the inertial frame, attitude prescribed by the wave slope
(`WaveField.buoy_motion`, Eqs. 77-78, 90-93). Gimbal (2): revolute about e2^(1) at the offset
s_c^(2/1) (Eq. 28-32), free, loaded by the generator torque -M_g. Rotor (3): revolute about e3^(2)
(Eq. 39-41), prescribed psi = psi' t; its motor torque is `Multibody.reactions`.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from mf_envs.frames.so3 import rot_x
from mf_envs.physics.constants import G
from mf_envs.physics.gowec import GOWECParams
from mf_envs.physics.multibody import Body, MBState, Multibody, Revolute, Spherical, constant_rate
from mf_envs.physics.waves import WaveField

TorqueLaw = Callable[[float, float, float], float]


def build_engine_model(
    params: GOWECParams,
    wave: WaveField,
    effects: frozenset[str],
    offset: tuple[float, float, float] = (0.3, 0.0, 0.5),
    masses: tuple[float, float, float] = (2000.0, 40.0, 300.0),
) -> Multibody:
    """Multibody model of one gyroscope of the GOWEC with the same effects as `GimbalModel`."""
    Ja = params.rotor_inertia
    if "gimbal_inertia" in effects:
        Jt, Jg = params.transverse, params.gimbal_inertia
    else:
        Jt, Jg = 0.5 * Ja, (0.0, 0.0, 0.0)
    rock = "buoy_rocking" in effects
    two_d = "wave_2d" in effects

    def buoy(t: float):
        if not rock:
            return np.eye(3), np.zeros(3), np.zeros(3)
        if two_d:
            return wave.buoy_motion(t)
        (b1, b1d, b1dd), _ = wave.slope_angles(t)
        return rot_x(float(b1)), np.array([b1d, 0.0, 0.0]), np.array([b1dd, 0.0, 0.0])

    psid = params.rotor_speed if "gyroscopic" in effects else 0.0
    return Multibody(
        [
            Body("buoy", masses[0], (1e4, 1e4, 1e4), Spherical(), prescribed=buoy),
            Body("gimbal", masses[1], Jg, Revolute((0, 1, 0), offset=offset), parent="buoy"),
            Body(
                "rotor",
                masses[2],
                (Jt, Jt, Ja),
                Revolute((0, 0, 1)),
                parent="gimbal",
                prescribed=constant_rate(psid),
            ),
        ],
        gravity=(0.0, 0.0, -G),
    )


def simulate_engine(
    model: Multibody,
    phi0: float,
    phid0: float,
    t_end: float,
    dt: float,
    torque: TorqueLaw | None = None,
    motor: bool = False,
    hold: float | None = None,
) -> dict[str, NDArray[np.float64]]:
    """Integrate the engine model; torque(t, phi, phi') -> M_g (N m), held for `hold` seconds
    (a multiple of dt; default one step), as a digital controller would.

    Returns t, phi, phid, Mg (N m) and, with motor=True, motor (the rotor motor torque that
    keeps psi' constant, from `Multibody.reactions`, N m).
    """
    s: MBState = model.initial_state(q={"gimbal": phi0}, u={"gimbal": phid0})
    n = int(round(t_end / dt))
    every = _hold_steps(hold, dt)
    out = {k: np.zeros(n + 1) for k in ("t", "phi", "phid", "Mg", "motor")}
    Mg = 0.0
    for i in range(n + 1):
        phi, phid = model.coordinate(s, "gimbal"), model.velocity(s, "gimbal")
        if torque is not None and i % every == 0:
            Mg = float(torque(s.t, phi, phid))
        tau = model.joint_forces(gimbal=-Mg)
        out["t"][i], out["phi"][i], out["phid"][i], out["Mg"][i] = s.t, phi, phid, Mg
        if motor:
            out["motor"][i] = model.reactions(s, tau=tau)["rotor"]
        if i < n:
            s = model.step(s, dt, tau=tau)
    return out


def _hold_steps(hold: float | None, dt: float) -> int:
    if hold is None:
        return 1
    k = int(round(hold / dt))
    if k < 1 or abs(k * dt - hold) > 1e-9 * hold:
        raise ValueError(f"hold: must be a multiple of dt={dt}, got {hold}")
    return k


def simulate_fast(
    gm,
    phi0: float,
    phid0: float,
    t_end: float,
    dt: float,
    torque: TorqueLaw | None = None,
    hold: float | None = None,
) -> dict[str, NDArray[np.float64]]:
    """The same run with the fast path `GimbalModel` gm (same torque hold as simulate_engine)."""
    n = int(round(t_end / dt))
    every = _hold_steps(hold, dt)
    out = {k: np.zeros(n + 1) for k in ("t", "phi", "phid", "Mg")}
    t, phi, phid = 0.0, float(phi0), float(phid0)
    Mg = 0.0
    for i in range(n + 1):
        if torque is not None and i % every == 0:
            Mg = float(torque(t, phi, phid))
        out["t"][i], out["phi"][i], out["phid"][i], out["Mg"][i] = t, phi, phid, Mg
        if i < n:
            phi, phid = gm.step(t, phi, phid, Mg, dt, 1)[:2]
            t = (i + 1) * dt
    return out


def locking_torque(params: GOWECParams, omega: float, stiffness: float | None = None) -> TorqueLaw:
    """A torque law that locks phi to omega t (feed-forward of the gyroscopic drive is not used:
    a PD on (phi - omega t) and (phi' - omega)), for comparison runs (N m)."""
    J = 0.5 * params.rotor_inertia
    kp = stiffness if stiffness is not None else J * (3.0 * omega) ** 2
    kd = 2.0 * math.sqrt(kp * J)
    return lambda t, phi, phid: kp * (phi - omega * t) + kd * (phid - omega)
