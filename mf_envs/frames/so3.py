"""SO(3): hat/vee, the Rodrigues exponential (Rios 2017 ch. 2 Eq. 29) and its inverse.

Conventions (as in the source): a frame e(t) = e^I R(t) has body angular velocity
omega with hat(omega) = R^T dR/dt (ch. 2 Eq. 24, ch. 3 Eq. 11). Arrays are float64.
The numba kernels integrator loops call are in `mf_envs.frames.kernels`; these are the numpy
faces (batched, validated).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs.frames import kernels as _k


def _rows(batch: Any, x: ArrayLike, name: str, trail_in: tuple, trail_out: tuple) -> Any:
    """Numba kernel `batch` (over a contiguous (n, *trail_in) stack) applied to x (..., *trail_in)
    -> (..., *trail_out); ValueError naming `name` for any other trailing shape."""
    x = np.asarray(x, dtype=np.float64)
    k = len(trail_in)
    if x.shape[x.ndim - k :] != trail_in:
        raise ValueError(f"{name}: expected trailing shape {trail_in}, got shape {x.shape}")
    lead = x.shape[: x.ndim - k]
    return batch(np.ascontiguousarray(x.reshape((-1, *trail_in)))).reshape(lead + trail_out)


def hat(w: ArrayLike) -> NDArray[np.float64]:
    """Skew matrix of w (..., 3) -> (..., 3, 3), hat(w) @ v = w x v (ch. 3 Eq. 11)."""
    return _rows(_k.hat_batch, w, "w", (3,), (3, 3))


def vee(W: ArrayLike) -> NDArray[np.float64]:
    """Inverse of hat: (..., 3, 3) skew matrix -> (..., 3). Uses the skew part of W."""
    return _rows(_k.vee_batch, W, "W", (3, 3), (3,))


def exp_so3(w: ArrayLike) -> NDArray[np.float64]:
    """Rodrigues formula exp(hat(w)) (ch. 2 Eq. 29) of rotation vectors w (..., 3) -> (..., 3, 3);
    the numba kernel `mf_envs.frames.kernels.exp_so3` (series for small angles) over the batch."""
    return _rows(_k.exp_so3_batch, w, "w", (3,), (3, 3))


def log_so3(R: ArrayLike) -> NDArray[np.float64]:
    """Rotation vector w with exp_so3(w) = R, |w| in [0, pi]; batched over (..., 3, 3)
    (the numba kernel `mf_envs.frames.kernels.log_so3`, safe near 0 and pi)."""
    return _rows(_k.log_so3_batch, R, "R", (3, 3), (3,))


def rot_x(angle: float) -> NDArray[np.float64]:
    """Rotation by `angle` (rad) about e_1."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(angle: float) -> NDArray[np.float64]:
    """Rotation by `angle` (rad) about e_2."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def rot_z(angle: float) -> NDArray[np.float64]:
    """Rotation by `angle` (rad) about e_3."""
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def project_to_so3(R: ArrayLike) -> NDArray[np.float64]:
    """Nearest rotation matrix (polar decomposition via SVD), batched over (..., 3, 3)."""
    U, _, Vt = np.linalg.svd(np.asarray(R, dtype=np.float64))
    d = np.sign(np.linalg.det(U @ Vt))
    U = U.copy()
    U[..., :, 2] *= d[..., None]
    return U @ Vt


def orthonormality_error(R: ArrayLike) -> float:
    """max over the batch of ||R^T R - I||_max (0 for an exact rotation)."""
    R = np.asarray(R, dtype=np.float64)
    RtR = np.swapaxes(R, -1, -2) @ R
    return float(np.max(np.abs(RtR - np.eye(3))))
