"""The RK4 and RKMK4 steppers on `mf_envs.frames.kernels` (numba), specialised per model.

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

from collections.abc import Callable

import numba
import numpy as np

from mf_envs._jit import specialise
from mf_envs.frames.kernels import _rodrigues_entries, dexpinv_right3, rodrigues_coeffs

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


@numba.njit(cache=True, inline="always")
def times_exp_row2_into(out: np.ndarray, R: np.ndarray, theta) -> None:
    """Row 2 of R exp(hat(theta)) only (out's rows 0 and 1 untouched): the RKMK4 stage attitude
    of a right-hand side that reads only R's third row r (`make_rkmk4`). By Rodrigues on the
    row, r exp(hat(theta)) = r - a theta x r + b theta x (theta x r) (exp(hat(theta))^T =
    exp(-hat(theta))): the cross products need no a, b, so they run beside their series
    (`times_exp_into` forms the 9 entries first; this is its row to round-off)."""
    x, y, z = theta[0], theta[1], theta[2]
    a, b = rodrigues_coeffs(x * x + y * y + z * z)
    out[2, 0], out[2, 1], out[2, 2] = row_times_exp(R[2, 0], R[2, 1], R[2, 2], x, y, z, a, b)


@numba.njit(cache=True, inline="always")
def row_times_exp(r0, r1, r2, x, y, z, a, b):
    """The row (r0, r1, r2) times exp(hat((x, y, z))) given its Rodrigues coefficients a, b
    (`times_exp_row2_into`)."""
    c0, c1, c2 = y * r2 - z * r1, z * r0 - x * r2, x * r1 - y * r0
    d0, d1, d2 = y * c2 - z * c1, z * c0 - x * c2, x * c1 - y * c0
    return r0 - a * c0 + b * d0, r1 - a * c1 + b * d1, r2 - a * c2 + b * d2


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
    i1 = _inputs(t + dt, args)  # noqa: F821
    _stages(t, x, dt, args, work, _inputs(t, args), _inputs(t + h, args), i1)  # noqa: F821
    return i1


def _rk4_given_template(t, x, dt, args, work, i0, ih, i1):
    """`_rk4_template`'s step with the stage inputs given by the caller: i0, ih, i1 at t,
    t + dt/2, t + dt (a model that forms them more cheaply together than one at a time, e.g.
    wave components advanced by rotation); the increment into work[0]."""
    h = 0.5 * dt
    k1, k2, k3, k4, xs = work[0], work[1], work[2], work[3], work[4]
    _rhs(t, x, i0, args, k1)  # noqa: F821
    _rhs(t + h, _stage_point(xs, x, h, k1), ih, args, k2)  # noqa: F821
    _rhs(t + h, _stage_point(xs, x, h, k2), ih, args, k3)  # noqa: F821
    _rhs(t + dt, _stage_point(xs, x, dt, k3), i1, args, k4)  # noqa: F821
    _rk4_combine(dt, k1, k2, k3, k4)


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
    _stage_exp(Rs, R, th)  # noqa: F821
    q2 = dexpinv_right3(th, _rhs(t + h, _stage_point(ys, y, h, k1), Rs, ih, args, k2))  # noqa: F821
    th = _scale3(h, q2)
    _stage_exp(Rs, R, th)  # noqa: F821
    q3 = dexpinv_right3(th, _rhs(t + h, _stage_point(ys, y, h, k2), Rs, ih, args, k3))  # noqa: F821
    th = _scale3(dt, q3)
    _stage_exp(Rs, R, th)  # noqa: F821
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


def _specialise(
    template: Callable, rhs, inputs, prefix: str, inline: bool = False, **extra: Callable
):
    """Compile `template` with `_rhs`/`_inputs` bound to the model's jitted functions (module doc;
    `mf_envs._jit.specialise`); inline=True makes it a kernel that LLVM inlines into its callers
    (`forceinline`; numba's IR inlining, `inline="always"`, cost minutes of compilation here),
    None a small piece spliced into its one caller (numba IR inlining)."""
    return specialise(template, rhs, prefix, inline, _rhs=rhs, _inputs=inputs, **extra)


def make_rk4(rhs, inputs, inline: bool = False):
    """The RK4 step `step(t, x, dt, args, work) -> inputs(t + dt)` for one model (numba); the
    increment dx is left in work[0].

    rhs(t, x, inp, args, out) (writes x' (n,) into out) and inputs(t, args) -> inp must be
    `numba.njit` functions;
    `step` is itself jitted and callable from the model's kernels; inline=True makes it a
    kernel that LLVM inlines into them (`_specialise`)."""
    stages = _specialise(_rk4_given_template, rhs, None, "rk4s", True if inline else None)
    return _specialise(_rk4_template, rhs, inputs, "rk4", inline, _stages=stages)


def make_rk4_given(rhs, inline: bool = False):
    """The RK4 step `step(t, x, dt, args, work, i0, ih, i1)` with the stage inputs at t,
    t + dt/2, t + dt given (`_rk4_given_template`); rhs and inline as `make_rk4`."""
    return _specialise(_rk4_given_template, rhs, None, "rk4g", inline)


def make_rkmk4(rhs, inputs, inline: bool = False, third_row: bool = False):
    """The RKMK4 step `step(t, y, R, dt, args, work, Rwork) -> inputs(t + dt)`, the increment dy
    left in work[0] and the new attitude in Rwork[1]; rhs(t, y, R, inp, args, out) -> omega and
    inputs(t, args) jitted (see `_rkmk4_template`); inline as `make_rk4`. third_row: the rhs
    reads only R[2] (the ship's gravity direction), so the stage attitudes form only that row
    (`times_exp_row2_into`; the new attitude is formed whole)."""
    stage_exp = times_exp_row2_into if third_row else times_exp_into
    prefix = "rkmk4r" if third_row else "rkmk4"
    return _specialise(_rkmk4_template, rhs, inputs, prefix, inline, _stage_exp=stage_exp)
