"""SE(3) frame connection matrices (Rios 2017 ch. 3 Eqs. 1-11).

A frame connection matrix E = [[R, x], [0, 1]] (4x4) maps the inertial frame (e^I, 0) to a
body frame (e, r_C): (e r_C) = (e^I 0) E (Eq. 2). Relative connections compose by matrix
product, E^(a+1) = E^(a) E^(a+1/a) (Eq. 7). The time-rate connection Omega = E^-1 dE/dt
(Eq. 9) holds hat(omega) (body angular velocity) and R^T dx/dt (body-frame velocity of the
origin) (Eq. 10).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs.frames.so3 import hat, vee


def frame_connection(R: ArrayLike, x: ArrayLike) -> NDArray[np.float64]:
    """E = [[R, x], [0^T, 1]] (ch. 3 Eq. 2); R (..., 3, 3), x (..., 3) -> (..., 4, 4)."""
    R = np.asarray(R, dtype=np.float64)
    x = np.asarray(x, dtype=np.float64)
    if R.shape[-2:] != (3, 3):
        raise ValueError(f"R: expected trailing shape (3, 3), got {R.shape}")
    if x.shape[-1] != 3:
        raise ValueError(f"x: expected last dimension 3, got {x.shape}")
    batch = np.broadcast_shapes(R.shape[:-2], x.shape[:-1])
    E = np.zeros(batch + (4, 4))
    E[..., :3, :3] = R
    E[..., :3, 3] = x
    E[..., 3, 3] = 1.0
    return E


def frame_inverse(E: ArrayLike) -> NDArray[np.float64]:
    """E^-1 = [[R^T, -R^T x], [0^T, 1]] (ch. 3 Eq. 4), without a general matrix inverse."""
    E = np.asarray(E, dtype=np.float64)
    R = E[..., :3, :3]
    x = E[..., :3, 3]
    Rt = np.swapaxes(R, -1, -2)
    return frame_connection(Rt, -np.einsum("...ij,...j->...i", Rt, x))


def relative_connection(E_parent: ArrayLike, E_child: ArrayLike) -> NDArray[np.float64]:
    """E^(child/parent) = (E^(parent))^-1 E^(child): the child seen from the parent (Eq. 6)."""
    return frame_inverse(E_parent) @ np.asarray(E_child, dtype=np.float64)


def compose(*connections: ArrayLike) -> NDArray[np.float64]:
    """E^(1) E^(2/1) ... E^(n/n-1) = E^(n) (ch. 3 Eq. 7): chain relative connections."""
    if not connections:
        raise ValueError("connections: need at least one frame connection matrix")
    out = np.asarray(connections[0], dtype=np.float64)
    for E in connections[1:]:
        out = out @ np.asarray(E, dtype=np.float64)
    return out


def time_rate_connection(E: ArrayLike, E_dot: ArrayLike) -> NDArray[np.float64]:
    """Omega = E^-1 dE/dt (ch. 3 Eq. 9): [[hat(omega), R^T x_dot], [0^T, 0]] (Eq. 10)."""
    Om = frame_inverse(E) @ np.asarray(E_dot, dtype=np.float64)
    # the exact structure: skew upper-left block, zero last row
    Om[..., :3, :3] = hat(vee(Om[..., :3, :3]))
    Om[..., 3, :] = 0.0
    return Om


def twist_from_time_rate(Omega: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(omega, v) from Omega (Eq. 10): body angular velocity and body-frame origin velocity."""
    Omega = np.asarray(Omega, dtype=np.float64)
    return vee(Omega[..., :3, :3]), Omega[..., :3, 3].copy()
