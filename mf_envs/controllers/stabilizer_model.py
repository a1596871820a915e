"""The stabilizer baselines' model of the env: the roll-gimbal linearisation read from an env
(`RollModel`, `roll_model`) and its python-control systems (`roll_gimbal_nlsys`,
`roll_drive_nlsys`), which `mf_envs.controllers.stabilizer` designs its PID and LQR on."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from mf_envs.physics.ship import gyro_roll_moment


@dataclass(frozen=True)
class RollModel:
    """Roll-gimbal model of the env's defaults: J_eff (kg m^2), C (N m/rad), B (N m s/rad),
    n H (N m s), servo tau (s), rate and angle limits (rad/s, rad), control dt (s), wave period (s),
    the torque drive (`ship.drive.DriveParams`, None: kinematic servo), the gimbal inertia
    J_g = J2^(2) + J1^(3) (kg m^2) and the number of gyros.
    """

    j_eff: float
    c: float
    b: float
    nh: float
    tau: float
    max_rate: float
    max_angle: float
    dt: float
    wave_period: float
    drive: Any = None
    jg: float = 0.0
    n_gyros: int = 1
    stop_time: float = 0.1  # s, the drive's end-stop envelope (`ship.drive.stop_envelope`)

    @property
    def omega_n(self) -> float:
        """Undamped roll frequency (rad/s); the wave frequency when there is no restoring."""
        if self.c > 0.0:
            return math.sqrt(self.c / self.j_eff)
        return 2.0 * math.pi / self.wave_period


def roll_model(env: Any) -> RollModel:
    """The `RollModel` of a (wrapped) GyroStabilizer env, from its parameters and effects."""
    u = env.unwrapped
    eff = u.effects
    j = u.ship.roll_inertia("added_inertia" in eff)
    j += u.n_gyros * (u.gyro.gimbal_inertia + u.gyro.rotor_j1)
    c = u.ship.roll_stiffness if "hydrostatic_restoring" in eff else 0.0
    b = u.ship.roll_damping if "roll_damping" in eff else 0.0
    nh = u.n_gyros * u.angular_momentum
    return RollModel(
        j,
        c,
        b,
        nh,
        u.drive.servo_time_constant,
        u.max_precession_rate,
        u.max_gimbal_angle,
        u.control_dt,
        u.wave_period,
        u.drive.machine,
        u.gyro.gimbal_inertia + u.gyro.rotor_j1,
        u.n_gyros,
        u.drive.stop_time,
    )


def roll_gimbal_nlsys(m: RollModel) -> Any:
    """python-control `nlsys` of the roll-gimbal model: x = [r, r', phi, phi'], u = phi' command.

    J_eff r'' = -C r - B r' - n H phi' cos(phi);  tau phi'' = u - phi'  (the env's servo).
    """
    import control as ct

    def update(t: float, x: np.ndarray, u: np.ndarray, params: dict) -> np.ndarray:
        r, rd, phi, phid = x
        rdd = (-m.c * r - m.b * rd + gyro_roll_moment(phi, phid, m.nh, 1)) / m.j_eff
        return np.array([rd, rdd, phid, (u[0] - phid) / m.tau])

    return ct.nlsys(
        update,
        None,
        inputs=["u"],
        states=["roll", "roll_rate", "phi", "phi_rate"],
        outputs=["roll", "roll_rate", "phi", "phi_rate"],
        name="roll_gimbal",
    )


def roll_drive_nlsys(m: RollModel) -> Any:
    """python-control `nlsys` of roll + gimbal + the torque drive's rate loop (`ship.drive`):
    x = [r, r', phi, phi', z], u = phi' command (rad/s).

    J_eff r'' = -C r - B r' - n H phi' cos(phi);  J_g phi'' = H r' cos(phi) + tau(x, u),
    z' = loop integral, tau and z' from `ship.drive.drive_torque` (limits included; the
    linearisation at rest sees the unsaturated loop).
    """
    import control as ct

    from mf_envs.physics.ship.drive import drive_torque

    D = m.drive.pack(m.jg)
    h = m.nh / m.n_gyros  # one rotor's H; the pair's gimbal equation is per gimbal

    def update(t: float, x: np.ndarray, u: np.ndarray, params: dict) -> np.ndarray:
        r, rd, phi, phid, z = x
        g = h * rd * math.cos(phi)
        tau, dz = drive_torque(phi, phid, z, float(u[0]), g, 0.0, 1.0, 1, D)
        rdd = (-m.c * r - m.b * rd - m.nh * phid * math.cos(phi)) / m.j_eff
        return np.array([rd, rdd, phid, (g + tau) / m.jg, dz])

    return ct.nlsys(
        update,
        None,
        inputs=["u"],
        states=["roll", "roll_rate", "phi", "phi_rate", "z"],
        outputs=["roll", "roll_rate", "phi", "phi_rate", "z"],
        name="roll_gimbal_drive",
    )


# the LQR's Bryson weights tuned on GyroStabilizer-JONSWAP-v0's training seeds 0-7
# (`benchmarks.stabilizer_tuning`, docs/benchmark.md "Tuned baselines"): roll 2.51e-3 rad,
# gimbal 0.374 x max_gimbal_angle, precession rate 0.362 x max_precession_rate
