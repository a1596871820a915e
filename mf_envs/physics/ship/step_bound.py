"""The largest stable RK4 physics step of a gimbal drive (`drive.DriveParams` packed).

`stable_physics_dt` returns the largest RK4 step for which every eigenvalue of the linearised
roll-gimbal-loop system (`roll_gimbal_matrix`: loop closed, and loop saturated; also on a
cushioned stop) lies in RK4's stability region |1 + z + z^2/2 + z^3/6 + z^4/24| <= 1; envs
refuse a larger physics_dt (`drive_stable_step`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from mf_envs._validate import check_fields, check_nonnegative
from mf_envs.physics.ship.drive import (
    DC,
    DCS,
    DFF,
    DK,
    DKI,
    DKIND,
    DKP,
    DKS,
    KIND_PENDULOUS,
    KIND_SPRING,
)


def rk4_amplification(z: complex | NDArray) -> NDArray[np.float64]:
    """|R(z)| = |1 + z + z^2/2 + z^3/6 + z^4/24| of classical RK4 at z = h lambda."""
    z = np.asarray(z, dtype=complex)
    return np.abs(1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6.0 + z / 24.0))))


def _rk4_max_step(lam: complex) -> float:
    """Largest h with |R(h lambda)| <= 1 for a decaying or oscillating mode (bisection on the
    ray h lambda; RK4's region is star-shaped along it near the origin). inf for growth."""
    if lam.real > 1e-12 * abs(lam) or abs(lam) == 0.0:
        return math.inf  # a physically growing (or static) mode: no step makes it decay
    lo, hi = 0.0, 4.0 / abs(lam)  # RK4's region lies inside |z| < 3
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if rk4_amplification(mid * lam) <= 1.0 + 1e-12:
            lo = mid
        else:
            hi = mid
    return lo


@dataclass(frozen=True)
class RollGimbal:
    """The linear roll + gimbal plant a drive is checked on (SI units): gimbal inertia J_g and
    roll inertia J (kg m^2, J incl. added inertia and gyros), one rotor's H (N m s), number of
    gyros, roll stiffness C (N m/rad) and linear roll damping B (N m s/rad)."""

    gimbal_inertia: float
    roll_inertia: float
    angular_momentum: float
    n_gyros: int = 1
    roll_stiffness: float = 0.0
    roll_damping: float = 0.0

    def __post_init__(self) -> None:
        check_fields(self, positive=("gimbal_inertia", "roll_inertia"))
        check_nonnegative("angular_momentum", self.angular_momentum)


def roll_gimbal_matrix(
    D: NDArray[np.float64], plant: RollGimbal, saturated: bool, contact: bool = False
) -> NDArray:
    """A (5, 5) of x = [roll, roll rate, phi, phi', z] linearised about rest (SI units).

    J r'' = -C r - B r' - n H phi';  J_g phi'' = H r' + tau;  tau from `drive_torque` with the
    loop closed (saturated=False) or its output frozen (saturated=True: the passive parts only,
    z' = -(K_i / K_p) z from the back-calculation); `contact`: also on a cushioned stop
    (its spring k_s and damper c_s added).
    """
    J, Jg = plant.roll_inertia, plant.gimbal_inertia
    H, n = plant.angular_momentum, plant.n_gyros
    kp, ki, ff = (0.0, 0.0, 0.0) if saturated else (D[DKP], D[DKI], D[DFF])
    k = D[DK] if int(D[DKIND]) in (KIND_PENDULOUS, KIND_SPRING) else 0.0
    A = np.zeros((5, 5))
    A[0, 1] = A[2, 3] = 1.0
    A[1] = [-plant.roll_stiffness / J, -plant.roll_damping / J, 0.0, -n * H / J, 0.0]
    c = D[DC]
    if contact:
        k, c = k + D[DKS], c + D[DCS]
    A[3] = [0.0, H * (1.0 - ff) / Jg, -k / Jg, -(kp + c) / Jg, ki / Jg]
    A[4, 3] = -1.0 if ki > 0.0 else 0.0
    if saturated and D[DKI] > 0.0:
        A[4, 4] = -D[DKI] / D[DKP]
    return A


def stable_physics_dt(D: NDArray[np.float64], plant: RollGimbal) -> float:
    """Largest RK4 physics step (s) for which the linearised roll-gimbal-drive system is stable
    with the loop closed and with it saturated (module doc), also on a cushioned stop."""
    h = math.inf
    cases = [(False, False), (True, False)]
    if D[DKS] > 0.0:  # on a cushioned stop, loop working or saturated
        cases += [(False, True), (True, True)]
    for sat, contact in cases:
        for lam in np.linalg.eigvals(roll_gimbal_matrix(D, plant, sat, contact)):
            h = min(h, _rk4_max_step(complex(lam)))
    return h


def drive_stable_step(
    drive: Any,
    gyro: Any,
    roll_inertia: float,
    roll_stiffness: float,
    roll_damping: float,
    n: int,
    eff: Any,
) -> float:
    """Largest stable RK4 physics step (s) of a `model.GimbalDrive` on its roll-gimbal
    linearisation (`stable_physics_dt`) with the effects `eff` and the hull's roll inertia
    (`Hull.roll_inertia`, with A44 per the effects); the kinematic servo: 2.78 tau (RK4 on
    -1/tau)."""
    if drive.machine is None:
        return 2.785 * drive.servo_time_constant
    jg = gyro.gimbal_inertia + gyro.rotor_j1
    j = roll_inertia
    h = abs(gyro.angular_momentum) if "gyroscopic" in eff else 0.0
    c44 = roll_stiffness if "hydrostatic_restoring" in eff else 0.0
    b44 = roll_damping if "roll_damping" in eff else 0.0
    D = drive.machine.pack(jg)
    return stable_physics_dt(D, RollGimbal(jg, j + n * jg, h, n, c44, b44))
