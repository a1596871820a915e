"""The one Lie-group kernel: SO(3) hat/vee/exp/log/dexp/dexp^-1 (the RK4 / RKMK4 steppers:
`mf_envs.frames.steppers`).

Every model that integrates an attitude or a state with Runge-Kutta calls these (numba,
`cache=True`); nothing else in the package defines them (a test greps for copies).

Conventions (Rios 2017 ch. 2): a frame e(t) = e^I R(t) has body angular velocity omega with
hat(omega) = R^T R' (Eq. 24); Rodrigues' formula R = exp(hat(theta)) = I + a W + b W^2 (Eq. 29),
a = sin(x)/x, b = (1 - cos x)/x^2, x = |theta|.

dexp and its inverse (x = |theta|, c(x) = (1 - (x/2) cot(x/2)) / x^2 = 1/12 + x^2/720 + ...):

    right (body-frame update R = R0 exp(hat(theta)), R^T R' = hat(omega)):
        omega  = theta' - b theta x theta' + (1 - a)/x^2 theta x (theta x theta')   (dexp_r)
        theta' = omega + 1/2 theta x omega + c theta x (theta x omega)             (dexpinv_r)
    left  (spatial update R = exp(hat(theta)) R0, R' R^T = hat(omega_s)): theta x -> -theta x,
        theta' = omega_s - 1/2 theta x omega_s + c theta x (theta x omega_s)      (dexpinv_l)

The RK4 / RKMK4 steppers built on these live in `mf_envs.frames.steppers`.
"""

from __future__ import annotations

import math

import numba
import numpy as np

# Below x^2 = 0.01 (x < 0.1) the Taylor series of a, b and c to x^8 are used: their truncation is
# < 3e-18, as accurate as libm sin/cos/tan and free of the cancellation of the closed forms.
_SERIES_X2 = 0.01
_R9, _R10 = 1.0 / 362880.0, 1.0 / 3628800.0  # 1/9!, 1/10! (multiplied: see rodrigues_coeffs)
SINCOS_NEAR = 0.1  # |x - x0| below which `sincos_near` uses its series (truncation < 3e-17)


@numba.njit(cache=True)
def hat(w: np.ndarray) -> np.ndarray:
    """Skew matrix (3, 3) of w (3,): hat(w) v = w x v (ch. 3 Eq. 11)."""
    W = np.zeros((3, 3))
    W[0, 1], W[0, 2], W[1, 2] = -w[2], w[1], -w[0]
    W[1, 0], W[2, 0], W[2, 1] = w[2], -w[1], w[0]
    return W


@numba.njit(cache=True)
def vee(W: np.ndarray) -> np.ndarray:
    """Inverse of hat on the skew part of W (3, 3) -> (3,)."""
    return 0.5 * np.array([W[2, 1] - W[1, 2], W[0, 2] - W[2, 0], W[1, 0] - W[0, 1]])


@numba.njit(cache=True)
def hat_batch(w: np.ndarray) -> np.ndarray:
    """hat over rows: w (n, 3) -> (n, 3, 3)."""
    out = np.empty((w.shape[0], 3, 3))
    for i in range(w.shape[0]):
        out[i] = hat(w[i])
    return out


@numba.njit(cache=True)
def vee_batch(W: np.ndarray) -> np.ndarray:
    """vee over a stack: W (n, 3, 3) -> (n, 3)."""
    out = np.empty((W.shape[0], 3))
    for i in range(W.shape[0]):
        out[i] = vee(W[i])
    return out


@numba.njit(cache=True)
def cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a x b for 3-vectors."""
    out = np.empty(3)
    out[0] = a[1] * b[2] - a[2] * b[1]
    out[1] = a[2] * b[0] - a[0] * b[2]
    out[2] = a[0] * b[1] - a[1] * b[0]
    return out


@numba.njit(cache=True)
def matmul3(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """A @ B for 3x3 matrices by loops (no BLAS call overhead)."""
    C = np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            C[i, j] = A[i, 0] * B[0, j] + A[i, 1] * B[1, j] + A[i, 2] * B[2, j]
    return C


@numba.njit(cache=True, inline="always")
def rodrigues_series(x2: float) -> tuple[float, float]:
    """`rodrigues_coeffs` by their Taylor series to x^8 / x^10, for x2 < _SERIES_X2."""
    # constant reciprocals, not x2 / 362880.0: a division by a constant stays a division
    # (~14 cycles on the stage's critical path) unless the constant is a power of two;
    # Estrin's scheme (x^4 beside the low terms), not Horner's: half the dependent chain
    x4 = x2 * x2
    a = (1.0 - x2 * (1.0 / 6.0)) + x4 * ((1.0 / 120.0 - x2 * (1.0 / 5040.0)) + x4 * _R9)
    b = (0.5 - x2 * (1.0 / 24.0)) + x4 * ((1.0 / 720.0 - x2 * (1.0 / 40320.0)) + x4 * _R10)
    return a, b


@numba.njit(cache=True, inline="always")
def rodrigues_coeffs(x2: float) -> tuple[float, float]:
    """a = sin(x)/x, b = (1 - cos x)/x^2 of the angle x = sqrt(x2) (ch. 2 Eq. 29)."""
    if x2 < _SERIES_X2:
        return rodrigues_series(x2)
    x = math.sqrt(x2)
    s = math.sin(0.5 * x)
    return math.sin(x) / x, 2.0 * s * s / x2


@numba.njit(cache=True, inline="always")
def _rodrigues_entries(x: float, y: float, z: float):
    """Rows ((e00, e01, e02), ...) of exp(hat(w)) = I + a W + b W^2, w = (x, y, z) (Eq. 29),
    W^2 = w w^T - |w|^2 I."""
    x2 = x * x + y * y + z * z
    a, b = rodrigues_coeffs(x2)
    return (
        (1.0 + b * (x * x - x2), -a * z + b * x * y, a * y + b * x * z),
        (a * z + b * x * y, 1.0 + b * (y * y - x2), -a * x + b * y * z),
        (-a * y + b * x * z, a * x + b * y * z, 1.0 + b * (z * z - x2)),
    )


@numba.njit(cache=True)
def exp_so3(w: np.ndarray) -> np.ndarray:
    """Rodrigues: exp(hat(w)) (3, 3) of a rotation vector w (3,) in rad (ch. 2 Eq. 29)."""
    E = _rodrigues_entries(w[0], w[1], w[2])
    R = np.empty((3, 3))
    for i in range(3):
        R[i, 0], R[i, 1], R[i, 2] = E[i]
    return R


@numba.njit(cache=True)
def exp_so3_batch(w: np.ndarray) -> np.ndarray:
    """exp_so3 over rows: w (n, 3) -> (n, 3, 3)."""
    out = np.empty((w.shape[0], 3, 3))
    for i in range(w.shape[0]):
        out[i] = exp_so3(w[i])
    return out


@numba.njit(cache=True)
def log_so3(R: np.ndarray) -> np.ndarray:
    """Rotation vector w (3,), |w| in [0, pi], with exp_so3(w) = R (3, 3).

    Near 0 the series of x/sin(x); near pi the axis from the symmetric part
    R + R^T = 2 cos(x) I + 2 (1 - cos x) u u^T (the skew part vanishes there).
    """
    cos_t = min(max(0.5 * (R[0, 0] + R[1, 1] + R[2, 2] - 1.0), -1.0), 1.0)
    s = 0.5 * vee(R - R.T)  # sin(x) u
    sin_t = math.sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2])
    theta = math.atan2(sin_t, cos_t)
    if theta < 1e-6:
        return s * (1.0 + theta * theta / 6.0)
    if theta < math.pi - 1e-4:
        return s * (theta / sin_t)
    B = (0.5 * (R + R.T) - cos_t * np.eye(3)) / (1.0 - cos_t)
    k = int(np.argmax(np.diag(B)))
    u = B[:, k] / math.sqrt(max(B[k, k], 1e-300))
    if u[0] * s[0] + u[1] * s[1] + u[2] * s[2] < 0.0:  # sign from the small skew part
        u = -u
    return theta * u / math.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])


@numba.njit(cache=True)
def log_so3_batch(R: np.ndarray) -> np.ndarray:
    """log_so3 over a stack: R (n, 3, 3) -> (n, 3)."""
    out = np.empty((R.shape[0], 3))
    for i in range(R.shape[0]):
        out[i] = log_so3(R[i])
    return out


@numba.njit(cache=True, inline="always")
def sincos_near(x: float, x0: float, c0: float, s0: float) -> tuple[float, float]:
    """(cos x, sin x) from c0 = cos(x0), s0 = sin(x0) of a nearby angle x0 (rad): the addition
    formulas with the Taylor series of cos d, sin d (d = x - x0) to d^8 / d^9 for |d| < 0.1
    (truncation < 3e-17: libm's accuracy), libm beyond; x == x0 gives (c0, s0) exactly.

    For the stages of a Runge-Kutta step, which sit close to its start: one libm sincos per
    step instead of one per stage (the ship's gimbal angle and wave phase: libm's sin/cos took
    a quarter of its step)."""
    d = x - x0
    if d == 0.0:
        return c0, s0
    if abs(d) < SINCOS_NEAR:
        return sincos_series(d, c0, s0)
    return math.cos(x), math.sin(x)


@numba.njit(cache=True, inline="always")
def sincos_series(d: float, c0: float, s0: float) -> tuple[float, float]:
    """`sincos_near` for 0 < |d| < SINCOS_NEAR, d = x - x0: the addition formulas with the
    Taylor series of cos d, sin d."""
    d2 = d * d
    d4 = d2 * d2  # Estrin's scheme, as `rodrigues_coeffs`
    cd = (1.0 - 0.5 * d2) + d4 * ((1.0 / 24.0 - d2 * (1.0 / 720.0)) + d4 * (1.0 / 40320.0))
    sd = d * ((1.0 - d2 * (1.0 / 6.0)) + d4 * ((1.0 / 120.0 - d2 * (1.0 / 5040.0)) + d4 * _R9))
    return c0 * cd - s0 * sd, s0 * cd + c0 * sd


@numba.njit(cache=True, inline="always")
def _dexpinv_c(x2: float) -> float:
    """c(x) = (1 - (x/2) cot(x/2)) / x^2 of dexp^-1 (module doc), series to x^8 for x < 0.1."""
    if x2 < _SERIES_X2:
        return dexpinv_series(x2)
    x = math.sqrt(x2)
    return (1.0 - 0.5 * x / math.tan(0.5 * x)) / x2


@numba.njit(cache=True, inline="always")
def dexpinv_series(x2: float) -> float:
    """`_dexpinv_c` by its series, for x2 < _SERIES_X2."""
    x4 = x2 * x2  # Estrin's scheme, as `rodrigues_coeffs`
    return (1.0 / 12.0 + x2 * (1.0 / 720.0)) + x4 * (
        (1.0 / 30240.0 + x2 * (1.0 / 1209600.0)) + x4 * (1.0 / 47900160.0)
    )


@numba.njit(cache=True, inline="always")
def _two_term3(t, v, c1: float, c2: float):
    """v + c1 t x v + c2 t x (t x v) for 3-tuples t, v (no allocation)."""
    a0, a1, a2 = t[1] * v[2] - t[2] * v[1], t[2] * v[0] - t[0] * v[2], t[0] * v[1] - t[1] * v[0]
    return (
        v[0] + c1 * a0 + c2 * (t[1] * a2 - t[2] * a1),
        v[1] + c1 * a1 + c2 * (t[2] * a0 - t[0] * a2),
        v[2] + c1 * a2 + c2 * (t[0] * a1 - t[1] * a0),
    )


@numba.njit(cache=True)
def _two_term(theta: np.ndarray, v: np.ndarray, c1: float, c2: float) -> np.ndarray:
    """Array face of `_two_term3`: (3,) in, (3,) out."""
    r = _two_term3((theta[0], theta[1], theta[2]), (v[0], v[1], v[2]), c1, c2)
    return np.array([r[0], r[1], r[2]])


@numba.njit(cache=True, inline="always")
def dexpinv_right3(t, w):
    """`dexpinv_right` on 3-tuples (what the RKMK4 stages use)."""
    return _two_term3(t, w, 0.5, _dexpinv_c(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]))


@numba.njit(cache=True)
def dexpinv_right(theta: np.ndarray, omega: np.ndarray) -> np.ndarray:
    """theta' (3,) of R = R0 exp(hat(theta)) with body rate omega (3,), R^T R' = hat(omega):
    omega + 1/2 theta x omega + 1/12 theta x (theta x omega) + ... (module doc)."""
    r = dexpinv_right3((theta[0], theta[1], theta[2]), (omega[0], omega[1], omega[2]))
    return np.array([r[0], r[1], r[2]])


@numba.njit(cache=True)
def dexpinv_left(theta: np.ndarray, omega_s: np.ndarray) -> np.ndarray:
    """theta' (3,) of R = exp(hat(theta)) R0 with spatial rate omega_s, R' R^T = hat(omega_s)."""
    t = theta
    return _two_term(t, omega_s, -0.5, _dexpinv_c(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]))


@numba.njit(cache=True)
def _dexp_coeffs(x2: float) -> tuple[float, float]:
    """(b, (1 - a)/x^2) of dexp: (1 - cos x)/x^2 and (x - sin x)/x^3."""
    a, b = rodrigues_coeffs(x2)
    if x2 < _SERIES_X2:
        return b, 1.0 / 6.0 - x2 * (1.0 / 120.0 - x2 * (1.0 / 5040.0 - x2 * _R9))
    return b, (1.0 - a) / x2


@numba.njit(cache=True)
def dexp_right(theta: np.ndarray, theta_dot: np.ndarray) -> np.ndarray:
    """Body rate omega (3,) of R = R0 exp(hat(theta)) moving with theta' (inverse of
    dexpinv_right): theta' - b theta x theta' + (1 - a)/x^2 theta x (theta x theta')."""
    b, d = _dexp_coeffs(theta[0] * theta[0] + theta[1] * theta[1] + theta[2] * theta[2])
    return _two_term(theta, theta_dot, -b, d)


@numba.njit(cache=True)
def dexp_left(theta: np.ndarray, theta_dot: np.ndarray) -> np.ndarray:
    """Spatial rate omega_s (3,) of R = exp(hat(theta)) R0 moving with theta'."""
    b, d = _dexp_coeffs(theta[0] * theta[0] + theta[1] * theta[1] + theta[2] * theta[2])
    return _two_term(theta, theta_dot, b, d)
