"""`simulate` of the torque-free rigid body over the five METHODS (module doc of
`mf_envs.physics.rigid_body`; step kernels in `rigid_body.kernels`), trajectory and invariants."""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import (
    check_finite,
    check_int,
    check_positive,
    check_shape,
    finite_scalar,
    positive_scalar,
)
from mf_envs.effects import resolve_effects
from mf_envs.physics.constants import G as G_EARTH
from mf_envs.physics.rigid_body import kernels as _k

METHODS: tuple[str, ...] = (
    "rk4_rodrigues",
    "rk4_magnus4",
    "rk4_magnus4_proj",
    "splitting2",
    "splitting4",
)
_METHOD_CODE = {name: code for code, name in enumerate(METHODS)}

EFFECTS: dict[str, str] = {
    "ballistic": "centre-of-mass flight under gravity, m dv/dt = -m g e3^I (ch. 2 Eq. 3)",
}


@dataclass(frozen=True)
class RigidBodyTrajectory:
    """Result of `simulate`. t: (N,) s; omega: (N, 3) rad/s and H: (N, 3) kg m^2/s, body
    components; R: (N, 3, 3) body-to-inertial attitude (e = e^I R, Eq. 4); x: (N, 3) m centre of
    mass in the inertial frame, or None when the "ballistic" effect is off; J: (3,) kg m^2."""

    t: NDArray[np.float64]
    omega: NDArray[np.float64]
    H: NDArray[np.float64]
    R: NDArray[np.float64]
    J: NDArray[np.float64]
    method: str
    dt: float
    x: NDArray[np.float64] | None = None

    @property
    def H_inertial(self) -> NDArray[np.float64]:
        """(N, 3) inertial components R H of the angular momentum (constant exactly, Eq. 18)."""
        return np.einsum("nij,nj->ni", self.R, self.H)

    @property
    def energy(self) -> NDArray[np.float64]:
        """(N,) rotational kinetic energy in J (Eq. 14a)."""
        return kinetic_energy(self.J, self.omega)

    @property
    def momentum_norm(self) -> NDArray[np.float64]:
        """(N,) |H| in kg m^2/s (Eq. 19b)."""
        return np.linalg.norm(self.H, axis=1)


def kinetic_energy(J: ArrayLike, omega: ArrayLike) -> NDArray[np.float64]:
    """Rotational kinetic energy 0.5 omega . J omega in J (Eq. 14a); omega (..., 3) rad/s."""
    w = np.asarray(omega, dtype=np.float64)
    return 0.5 * np.sum(np.asarray(J, dtype=np.float64) * w * w, axis=-1)


def cuboid_inertia(mass: float, a: float, b: float, c: float) -> NDArray[np.float64]:
    """Principal inertias (3,) kg m^2 of a homogeneous cuboid with edges a, b, c (m) along
    s1, s2, s3 (Eq. 21): J1 = m (b^2 + c^2)/12, J2 = m (c^2 + a^2)/12, J3 = m (a^2 + b^2)/12."""
    m = positive_scalar("mass", mass)
    a, b, c = (positive_scalar(n, v) for n, v in (("a", a), ("b", b), ("c", c)))
    return m / 12.0 * np.array([b * b + c * c, c * c + a * a, a * a + b * b])


def flight_time(v0_vertical: float, g: float = G_EARTH) -> float:
    """Time in s from toss to catch at the same height: 2 v0 / g (ch. 2 §2.1.7)."""
    return 2.0 * positive_scalar("v0", v0_vertical) / positive_scalar("g", g)


def ballistic_position(
    t: ArrayLike,
    x0: ArrayLike = (0.0, 0.0, 0.0),
    v0: ArrayLike = (0.0, 0.0, 0.0),
    g: float = G_EARTH,
) -> NDArray[np.float64]:
    """Centre-of-mass path (N, 3) in m, inertial frame, solving m x'' = -m g e3^I (Eq. 3b)
    exactly: x(t) = x0 + v0 t - g t^2/2 e3 (the mass cancels). g = 0 in orbit (Dzhanibekov)."""
    t = np.atleast_1d(check_finite("t", t))
    x0 = check_shape("x0", x0, (3,))
    v0 = check_shape("v0", v0, (3,))
    g = finite_scalar("g", g)
    x = x0 + t[:, None] * v0
    x[:, 2] -= 0.5 * g * t * t
    return x


def _steps(t_end: float, dt: float) -> tuple[int, float]:
    """n steps of a uniform size <= dt reaching t_end exactly (dt kept if t_end/dt is whole)."""
    ratio = t_end / dt
    n = max(1, round(ratio))
    if abs(n - ratio) > 1e-9 * max(1.0, ratio):
        n = math.ceil(ratio)
    return n, t_end / n


def simulate(
    J: ArrayLike,
    omega0: ArrayLike,
    t_end: float,
    dt: float,
    method: str = "rk4_rodrigues",
    *,
    R0: ArrayLike | None = None,
    save_every: int = 1,
    effects: str | Iterable[str] | None = None,
    x0: ArrayLike = (0.0, 0.0, 0.0),
    v0: ArrayLike = (0.0, 0.0, 0.0),
    g: float = G_EARTH,
) -> RigidBodyTrajectory:
    """Integrate the torque-free rigid body from omega0 over [0, t_end] with fixed steps.

    J: (3,) principal inertias kg m^2 (> 0, any order). omega0: (3,) body angular velocity rad/s.
    t_end, dt: s (> 0); if t_end is not a whole number of dt, the step shrinks to
    t_end / ceil(t_end / dt) (reported as `.dt`). method: one of METHODS (module docstring).
    R0: (3, 3) initial attitude (default I: the seed's e^I = e(0)); must be a rotation.
    save_every: keep every k-th step (memory for long runs; samples at t = i k dt, so the last
    one is t_end only if k divides the step count). effects: () or ("ballistic",), which adds
    the centre-of-mass path `.x` from x0 (m) and v0 (m/s) under gravity g in m/s^2 (Eq. 3; x0,
    v0, g are used only then). A state that turns non-finite (explicit RK4 beyond its stability
    limit) raises ValueError naming dt instead of returning NaN.
    """
    Jv = check_shape("J", check_positive("J", J), (3,))
    w0 = check_shape("omega0", omega0, (3,))
    t_end = positive_scalar("t_end", t_end)
    dt = positive_scalar("dt", dt)
    if method not in _METHOD_CODE:
        raise ValueError(f"method: must be one of {METHODS}, got {method!r}")
    save_every = check_int("save_every", save_every, low=1)
    chosen = resolve_effects(effects, EFFECTS, default=())
    R_init = np.eye(3) if R0 is None else check_shape("R0", R0, (3, 3))
    if np.max(np.abs(R_init.T @ R_init - np.eye(3))) > 1e-9 or np.linalg.det(R_init) < 0:
        raise ValueError("R0: must be a rotation matrix (orthonormal, det +1)")
    n_steps, dt_used = _steps(t_end, dt)
    Jinv = 1.0 / Jv
    order3 = np.argsort(-Jv, kind="stable").astype(np.int64)  # (big, mid, small): small in middle
    H, R = _k.integrate(
        Jv * w0, np.ascontiguousarray(R_init), Jinv, dt_used, n_steps, save_every,
        _METHOD_CODE[method], order3,
    )  # fmt: skip
    t = np.arange(H.shape[0]) * (dt_used * save_every)
    bad = ~(np.all(np.isfinite(H), axis=1) & np.all(np.isfinite(R), axis=(1, 2)))
    if bad.any():  # explicit RK4 is unstable once (wobble frequency) * dt > ~2.8 (docs/design.md)
        raise ValueError(
            f"dt: {dt_used:g} s is too large for {method!r} here: the state became non-finite "
            f"by t = {t[np.argmax(bad)]:g} s; use a smaller dt"
        )
    x = ballistic_position(t, x0, v0, g) if "ballistic" in chosen else None
    return RigidBodyTrajectory(t, H * Jinv, H, R, Jv, method, dt_used, x)
