"""SO(3): hat/vee, the Rodrigues exponential (Rios 2017 ch. 2 Eq. 29) and its inverse.

Conventions (as in the source): a frame e(t) = e^I R(t) has body angular velocity
omega with hat(omega) = R^T dR/dt (ch. 2 Eq. 24, ch. 3 Eq. 11). Arrays are float64.
The scalar kernels are numba-compiled so that integrator loops can call them.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numpy.typing import ArrayLike, NDArray

# Below this rotation angle the Taylor series of sin(x)/x and (1-cos x)/x^2 are used:
# at x = 1e-4 the truncation error of the 3-term series is ~x^6/5040 ~ 2e-28, far below eps.
_SMALL_ANGLE = 1e-4


@numba.njit(cache=True, fastmath=False)
def _rodrigues_coeffs(theta: float) -> tuple[float, float]:
    """a = sin(theta)/theta, b = (1 - cos(theta))/theta^2 with a safe small-angle branch."""
    if theta < _SMALL_ANGLE:
        t2 = theta * theta
        a = 1.0 - t2 / 6.0 + t2 * t2 / 120.0
        b = 0.5 - t2 / 24.0 + t2 * t2 / 720.0
    else:
        a = math.sin(theta) / theta
        # 1 - cos(theta) = 2 sin^2(theta/2) avoids cancellation for small theta
        s = math.sin(0.5 * theta)
        b = 2.0 * s * s / (theta * theta)
    return a, b


@numba.njit(cache=True)
def exp_so3_nb(w: np.ndarray) -> np.ndarray:
    """exp(hat(w)) for a 3-vector w (the rotation vector), numba kernel of Eq. 29."""
    theta = math.sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2])
    a, b = _rodrigues_coeffs(theta)
    x, y, z = w[0], w[1], w[2]
    R = np.empty((3, 3))
    # I + a*W + b*W^2 with W = hat(w); W^2 = w w^T - |w|^2 I
    R[0, 0] = 1.0 + b * (x * x - theta * theta)
    R[1, 1] = 1.0 + b * (y * y - theta * theta)
    R[2, 2] = 1.0 + b * (z * z - theta * theta)
    R[0, 1] = -a * z + b * x * y
    R[1, 0] = a * z + b * x * y
    R[0, 2] = a * y + b * x * z
    R[2, 0] = -a * y + b * x * z
    R[1, 2] = -a * x + b * y * z
    R[2, 1] = a * x + b * y * z
    return R


def hat(w: ArrayLike) -> NDArray[np.float64]:
    """Skew matrix of w (..., 3) -> (..., 3, 3), hat(w) @ v = w x v (ch. 3 Eq. 11)."""
    w = np.asarray(w, dtype=np.float64)
    if w.shape[-1] != 3:
        raise ValueError(f"w: expected last dimension 3, got shape {w.shape}")
    W = np.zeros(w.shape + (3,), dtype=np.float64)
    W[..., 0, 1] = -w[..., 2]
    W[..., 0, 2] = w[..., 1]
    W[..., 1, 0] = w[..., 2]
    W[..., 1, 2] = -w[..., 0]
    W[..., 2, 0] = -w[..., 1]
    W[..., 2, 1] = w[..., 0]
    return W


def vee(W: ArrayLike) -> NDArray[np.float64]:
    """Inverse of hat: (..., 3, 3) skew matrix -> (..., 3). Uses the skew part of W."""
    W = np.asarray(W, dtype=np.float64)
    if W.shape[-2:] != (3, 3):
        raise ValueError(f"W: expected trailing shape (3, 3), got {W.shape}")
    return 0.5 * np.stack(
        [W[..., 2, 1] - W[..., 1, 2], W[..., 0, 2] - W[..., 2, 0], W[..., 1, 0] - W[..., 0, 1]],
        axis=-1,
    )


def exp_so3(w: ArrayLike) -> NDArray[np.float64]:
    """Rodrigues formula exp(hat(w)) from Cayley-Hamilton (ch. 2 Eq. 29), batched over (..., 3).

    R = I + sin(t)/t W + (1 - cos t)/t^2 W^2, t = |w|, with Taylor series for t < 1e-4.
    """
    w = np.asarray(w, dtype=np.float64)
    if w.shape[-1] != 3:
        raise ValueError(f"w: expected last dimension 3, got shape {w.shape}")
    theta = np.linalg.norm(w, axis=-1)
    small = theta < _SMALL_ANGLE
    t2 = theta * theta
    safe = np.where(small, 1.0, theta)
    a = np.where(small, 1.0 - t2 / 6.0 + t2 * t2 / 120.0, np.sin(safe) / safe)
    b = np.where(small, 0.5 - t2 / 24.0 + t2 * t2 / 720.0, 2.0 * np.sin(0.5 * safe) ** 2 / safe**2)
    W = hat(w)
    W2 = W @ W
    eye = np.broadcast_to(np.eye(3), W.shape)
    return eye + a[..., None, None] * W + b[..., None, None] * W2


def log_so3(R: ArrayLike) -> NDArray[np.float64]:
    """Rotation vector w with exp_so3(w) = R, |w| in [0, pi]; batched over (..., 3, 3).

    Near theta = 0 uses the series of theta/sin(theta); near theta = pi reads the axis
    from the symmetric part R + R^T = 2 cos(t) I + 2 (1 - cos t) u u^T (the skew part vanishes).
    """
    R = np.asarray(R, dtype=np.float64)
    if R.shape[-2:] != (3, 3):
        raise ValueError(f"R: expected trailing shape (3, 3), got {R.shape}")
    batch = R.shape[:-2]
    Rf = R.reshape(-1, 3, 3)
    out = np.empty((Rf.shape[0], 3))
    for i, Ri in enumerate(Rf):
        cos_t = np.clip(0.5 * (np.trace(Ri) - 1.0), -1.0, 1.0)
        s = vee(Ri - Ri.T) * 0.5  # = sin(theta) u
        sin_t = np.linalg.norm(s)
        theta = math.atan2(sin_t, cos_t)
        if theta < 1e-6:
            out[i] = s * (1.0 + theta * theta / 6.0)
        elif theta < math.pi - 1e-4:
            out[i] = s * (theta / sin_t)
        else:
            # near pi: u u^T = (R + R^T - 2 cos t I) / (2 (1 - cos t)); take the largest column
            B = (0.5 * (Ri + Ri.T) - cos_t * np.eye(3)) / (1.0 - cos_t)
            k = int(np.argmax(np.diag(B)))
            u = B[:, k] / math.sqrt(max(B[k, k], 1e-300))
            if np.dot(u, s) < 0.0:  # fix the sign from the (small) skew part when available
                u = -u
            out[i] = theta * u / np.linalg.norm(u)
    return out.reshape(batch + (3,))


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
