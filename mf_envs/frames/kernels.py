"""The one Lie-group kernel: SO(3) hat/vee/exp/log/dexp/dexp^-1 and the RK4 / RKMK4 steppers.

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

The steppers are templates specialised per model right-hand side (`make_rk4`, `make_rkmk4`):
numba cannot cache a function that receives another jitted function as an argument, so the
template's code object is re-bound to the model's `rhs` and `inputs` as globals and compiled
with `cache=True` under a name derived from the model function (cached in the model's folder).
A step returns the stage inputs at t + dt and leaves its increment in its scratch (`work[0]`,
the RKMK4's new attitude in `Rwork[1]`), so that it returns no array and can be a
`mf_envs._jit.kernel` that LLVM inlines into its caller (`inline=True`, see `_jit`).
Hand-written (no library offers numba-compiled Lie-group Runge-Kutta): the tableau is the
classical RK4 one, the Munthe-Kaas form is Iserles et al., Acta Numerica 9 (2000), Sec. 5.
"""

from __future__ import annotations

import math
import types
import zlib
from collections.abc import Callable

import numba
import numpy as np

from mf_envs._jit import kernel

# Below x^2 = 0.01 (x < 0.1) the Taylor series of a, b and c to x^8 are used: their truncation is
# < 3e-18, as accurate as libm sin/cos/tan and free of the cancellation of the closed forms.
_SERIES_X2 = 0.01
with open(__file__, "rb") as _f:  # stamps the steppers' caches (see `_specialise`)
    _SOURCE_CRC = zlib.crc32(_f.read())


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
def rodrigues_coeffs(x2: float) -> tuple[float, float]:
    """a = sin(x)/x, b = (1 - cos x)/x^2 of the angle x = sqrt(x2) (ch. 2 Eq. 29)."""
    if x2 < _SERIES_X2:
        a = 1.0 - x2 * (1.0 / 6.0 - x2 * (1.0 / 120.0 - x2 * (1.0 / 5040.0 - x2 / 362880.0)))
        b = 0.5 - x2 * (1.0 / 24.0 - x2 * (1.0 / 720.0 - x2 * (1.0 / 40320.0 - x2 / 3628800.0)))
        return a, b
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
    if abs(d) < 0.1:
        d2 = d * d
        cd = 1.0 - d2 * (0.5 - d2 * (1.0 / 24.0 - d2 * (1.0 / 720.0 - d2 * (1.0 / 40320.0))))
        sd = d * (
            1.0
            - d2 * (1.0 / 6.0 - d2 * (1.0 / 120.0 - d2 * (1.0 / 5040.0 - d2 * (1.0 / 362880.0))))
        )
        return c0 * cd - s0 * sd, s0 * cd + c0 * sd
    return math.cos(x), math.sin(x)


@numba.njit(cache=True, inline="always")
def _dexpinv_c(x2: float) -> float:
    """c(x) = (1 - (x/2) cot(x/2)) / x^2 of dexp^-1 (module doc), series to x^8 for x < 0.1."""
    if x2 < _SERIES_X2:
        return 1.0 / 12.0 + x2 * (
            1.0 / 720.0 + x2 * (1.0 / 30240.0 + x2 * (1.0 / 1209600.0 + x2 / 47900160.0))
        )
    x = math.sqrt(x2)
    return (1.0 - 0.5 * x / math.tan(0.5 * x)) / x2


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
        return b, 1.0 / 6.0 - x2 * (1.0 / 120.0 - x2 * (1.0 / 5040.0 - x2 / 362880.0))
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


# ---- the steppers (templates; see the module doc and `make_rk4` / `make_rkmk4`) ----


@numba.njit(cache=True, inline="always")
def _rk4_weight(c: float, a: float, b: float, d: float, e: float) -> float:
    """c (a + 2 b + 2 d + e): the RK4 quadrature of four stage slopes (c = dt / 6)."""
    return c * (a + 2.0 * b + 2.0 * d + e)


@numba.njit(cache=True, inline="always")
def _rk4_combine(dt: float, k1: np.ndarray, k2, k3, k4) -> np.ndarray:
    """The RK4 increment dt/6 (k1 + 2 k2 + 2 k3 + k4) (n,), written into k1 and returned."""
    c = dt / 6.0
    for i in range(k1.shape[0]):
        k1[i] = _rk4_weight(c, k1[i], k2[i], k3[i], k4[i])
    return k1


@numba.njit(cache=True, inline="always")
def _rk4_combine3(dt: float, q1, q2, q3, q4):
    """`_rk4_combine` for 3-tuples (the Lie-algebra increment of RKMK4)."""
    c = dt / 6.0
    return (
        _rk4_weight(c, q1[0], q2[0], q3[0], q4[0]),
        _rk4_weight(c, q1[1], q2[1], q3[1], q4[1]),
        _rk4_weight(c, q1[2], q2[2], q3[2], q4[2]),
    )


@numba.njit(cache=True, inline="always")
def times_exp_into(out: np.ndarray, R: np.ndarray, theta) -> None:
    """out (3, 3) <- R exp(hat(theta)), theta a 3-tuple (rad); no allocation."""
    E = _rodrigues_entries(theta[0], theta[1], theta[2])
    (e00, e01, e02), (e10, e11, e12), (e20, e21, e22) = E
    for i in range(3):
        r0, r1, r2 = R[i, 0], R[i, 1], R[i, 2]
        out[i, 0] = r0 * e00 + r1 * e10 + r2 * e20
        out[i, 1] = r0 * e01 + r1 * e11 + r2 * e21
        out[i, 2] = r0 * e02 + r1 * e12 + r2 * e22


@numba.njit(cache=True)
def times_exp(R: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """R exp(hat(theta)) (3, 3) for theta (3,) rad."""
    out = np.empty((3, 3))
    times_exp_into(out, R, (theta[0], theta[1], theta[2]))
    return out


@numba.njit(cache=True, inline="always")
def _stage_point(out: np.ndarray, x: np.ndarray, h: float, k: np.ndarray) -> np.ndarray:
    """out <- x + h k (the stage state; the same arithmetic as the array expression)."""
    for i in range(x.shape[0]):
        out[i] = x[i] + h * k[i]
    return out


@numba.njit(cache=True, inline="always")
def _scale3(h: float, v):
    return (h * v[0], h * v[1], h * v[2])


def _rk4_template(t, x, dt, args, work):
    """One classical RK4 step of x' = rhs(t, x, inp(t), args) from t to t + dt.

    x: (n,) state; `rhs(t, x, inp, args, out)` writes x' into out (n,); `inputs(t, args)`
    (exogenous, state-free: waves, prescribed motions) is evaluated once at each of t, t + dt/2,
    t + dt. work: (5, n) scratch (`rk4_work(n)`; reuse it across steps: no allocation).
    Writes the increment dx into work[0] (the caller forms x + dx; the increment itself is
    what energy bookkeeping needs) and returns the inputs at t + dt."""
    h = 0.5 * dt
    i0, ih, i1 = _inputs(t, args), _inputs(t + h, args), _inputs(t + dt, args)  # noqa: F821
    k1, k2, k3, k4, xs = work[0], work[1], work[2], work[3], work[4]
    _rhs(t, x, i0, args, k1)  # noqa: F821
    _rhs(t + h, _stage_point(xs, x, h, k1), ih, args, k2)  # noqa: F821
    _rhs(t + h, _stage_point(xs, x, h, k2), ih, args, k3)  # noqa: F821
    _rhs(t + dt, _stage_point(xs, x, dt, k3), i1, args, k4)  # noqa: F821
    _rk4_combine(dt, k1, k2, k3, k4)
    return i1


def _rkmk4_template(t, y, R, dt, args, work, Rwork):
    """One Runge-Kutta-Munthe-Kaas step (RK4 tableau) of y' = f, R' = R hat(omega) on SO(3) x R^n.

    `rhs(t, y, R, inp, args, out) -> omega` writes y' (n,) into out and returns the body rate
    omega as a 3-tuple (rad/s). The attitude is carried in the Lie algebra: R_s = R exp(hat(
    theta_s)), theta' = dexpinv_right(theta, omega); the new attitude is R exp(hat(theta_new))
    (4th order in y and R, R orthogonal to round-off). work (5, n), Rwork (2, 3, 3): scratch
    (`rk4_work(n)`, `rkmk4_rwork()`; reuse across steps). Writes the increment dy into work[0]
    and the new attitude R_new into Rwork[1]; returns the inputs at t + dt."""
    h = 0.5 * dt
    i0, ih, i1 = _inputs(t, args), _inputs(t + h, args), _inputs(t + dt, args)  # noqa: F821
    k1, k2, k3, k4, ys = work[0], work[1], work[2], work[3], work[4]
    Rs, R1 = Rwork[0], Rwork[1]
    q1 = _rhs(t, y, R, i0, args, k1)  # noqa: F821
    th = _scale3(h, q1)
    times_exp_into(Rs, R, th)
    q2 = dexpinv_right3(th, _rhs(t + h, _stage_point(ys, y, h, k1), Rs, ih, args, k2))  # noqa: F821
    th = _scale3(h, q2)
    times_exp_into(Rs, R, th)
    q3 = dexpinv_right3(th, _rhs(t + h, _stage_point(ys, y, h, k2), Rs, ih, args, k3))  # noqa: F821
    th = _scale3(dt, q3)
    times_exp_into(Rs, R, th)
    q4 = dexpinv_right3(th, _rhs(t + dt, _stage_point(ys, y, dt, k3), Rs, i1, args, k4))  # noqa: F821
    times_exp_into(R1, R, _rk4_combine3(dt, q1, q2, q3, q4))
    _rk4_combine(dt, k1, k2, k3, k4)
    return i1


@numba.njit(cache=True)
def rk4_work(n: int) -> np.ndarray:
    """Scratch (5, n) for the RK4 / RKMK4 steppers (stage slopes and the stage state)."""
    return np.empty((5, n))


@numba.njit(cache=True)
def rkmk4_rwork() -> np.ndarray:
    """Scratch (2, 3, 3) for the RKMK4 stepper (stage attitude, new attitude)."""
    return np.empty((2, 3, 3))


def _specialise(template: Callable, rhs, inputs, prefix: str, inline: bool = False):
    """Compile `template` with `_rhs`/`_inputs` bound to the model's jitted functions (module doc);
    inline=True makes it a `mf_envs._jit.kernel` that LLVM inlines into its callers
    (`forceinline`; numba's IR inlining, `inline="always"`, cost minutes of compilation here).

    The result is cached beside the model's module (its file stamps the cache) under a name that
    also carries a checksum of this file, so editing either invalidates it."""
    py = rhs.py_func
    tag = zlib.crc32(py.__code__.co_code, _SOURCE_CRC) & 0xFFFFFFFF
    name = f"{prefix}_{py.__name__}_{tag:08x}"
    code = template.__code__.replace(
        co_filename=py.__code__.co_filename, co_name=name, co_qualname=name
    )
    glb = dict(template.__globals__, _rhs=rhs, _inputs=inputs)
    fn = types.FunctionType(code, glb, name)
    fn.__module__, fn.__doc__ = py.__module__, template.__doc__
    if inline:
        return kernel(fn, forceinline=True)
    return numba.njit(cache=True)(fn)


def make_rk4(rhs, inputs, inline: bool = False):
    """The RK4 step `step(t, x, dt, args, work) -> inputs(t + dt)` for one model (numba); the
    increment dx is left in work[0].

    rhs(t, x, inp, args, out) (writes x' (n,) into out) and inputs(t, args) -> inp must be
    `numba.njit` functions;
    `step` is itself jitted and callable from the model's kernels; inline=True makes it a
    kernel that LLVM inlines into them (`_specialise`)."""
    return _specialise(_rk4_template, rhs, inputs, "rk4", inline)


def make_rkmk4(rhs, inputs, inline: bool = False):
    """The RKMK4 step `step(t, y, R, dt, args, work, Rwork) -> inputs(t + dt)`, the increment dy
    left in work[0] and the new attitude in Rwork[1]; rhs(t, y, R, inp, args, out) -> omega and
    inputs(t, args) jitted (see `_rkmk4_template`); inline as `make_rk4`."""
    return _specialise(_rkmk4_template, rhs, inputs, "rkmk4", inline)
