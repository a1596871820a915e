"""SO(3): hat/vee, the Rodrigues exponential (Rios 2017 ch. 2 Eq. 29) and its inverse.

Conventions (as in the source): a frame e(t) = e^I R(t) has body angular velocity
omega with hat(omega) = R^T dR/dt (ch. 2 Eq. 24, ch. 3 Eq. 11). Arrays are float64.
The numba kernels integrator loops call are in `mf_envs.frames.kernels`; these are the numpy
faces (batched, validated).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs.frames import kernels as _k


def hat(w: ArrayLike) -> NDArray[np.float64]:
    """Skew matrix of w (..., 3) -> (..., 3, 3), hat(w) @ v = w x v (ch. 3 Eq. 11)."""
    w = np.asarray(w, dtype=np.float64)
    if w.shape[-1] != 3:
        raise ValueError(f"w: expected last dimension 3, got shape {w.shape}")
    flat = np.ascontiguousarray(w.reshape(-1, 3))
    return _k.hat_batch(flat).reshape(w.shape[:-1] + (3, 3))


def vee(W: ArrayLike) -> NDArray[np.float64]:
    """Inverse of hat: (..., 3, 3) skew matrix -> (..., 3). Uses the skew part of W."""
    W = np.asarray(W, dtype=np.float64)
    if W.shape[-2:] != (3, 3):
        raise ValueError(f"W: expected trailing shape (3, 3), got {W.shape}")
    flat = np.ascontiguousarray(W.reshape(-1, 3, 3))
    return _k.vee_batch(flat).reshape(W.shape[:-2] + (3,))


def exp_so3(w: ArrayLike) -> NDArray[np.float64]:
    """Rodrigues formula exp(hat(w)) (ch. 2 Eq. 29) of rotation vectors w (..., 3) -> (..., 3, 3);
    the numba kernel `mf_envs.frames.kernels.exp_so3` (series for small angles) over the batch."""
    w = np.asarray(w, dtype=np.float64)
    if w.shape[-1] != 3:
        raise ValueError(f"w: expected last dimension 3, got shape {w.shape}")
    flat = np.ascontiguousarray(w.reshape(-1, 3))
    return _k.exp_so3_batch(flat).reshape(w.shape[:-1] + (3, 3))


def log_so3(R: ArrayLike) -> NDArray[np.float64]:
    """Rotation vector w with exp_so3(w) = R, |w| in [0, pi]; batched over (..., 3, 3)
    (the numba kernel `mf_envs.frames.kernels.log_so3`, safe near 0 and pi)."""
    R = np.asarray(R, dtype=np.float64)
    if R.shape[-2:] != (3, 3):
        raise ValueError(f"R: expected trailing shape (3, 3), got {R.shape}")
    flat = np.ascontiguousarray(R.reshape(-1, 3, 3))
    return _k.log_so3_batch(flat).reshape(R.shape[:-2] + (3,))


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
