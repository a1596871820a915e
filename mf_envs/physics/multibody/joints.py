"""Joints, bodies, state and prescriptions of the multibody engine (see `multibody`).

A joint's relative frame connection is E^(b/p)(q) = E_pre . E_joint(q) . E_post (ch. 3 Eq. 6):
E_pre = [[rotation, offset], [0, 1]] places the joint frame in the parent body frame (offset in
m, parent coordinates), E_post = [[child_rotation, child_offset], [0, 1]] places the child's
centre-of-mass frame in the joint frame after the joint motion.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from mf_envs._validate import check_shape
from mf_envs.physics.multibody import kernels as K

Prescription = Callable[[float], tuple[Any, Any, Any]]


@dataclass(frozen=True, kw_only=True)
class Joint:
    """Common joint geometry: E_pre = [[rotation, offset]], E_post = [[child_rotation,
    child_offset]] (offsets in m, in the parent frame and the joint frame respectively)."""

    offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    child_offset: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotation: Any = None
    child_rotation: Any = None
    kind = K.FIXED

    def axis_vector(self) -> NDArray[np.float64]:
        return np.zeros(3)


@dataclass(frozen=True)
class Fixed(Joint):
    """Weld: 0 degrees of freedom."""


@dataclass(frozen=True)
class Revolute(Joint):
    """Rotation q (rad) about the unit `axis` of the joint frame; velocity q' (rad/s)."""

    axis: Any = (0.0, 0.0, 1.0)
    kind = K.REVOLUTE

    def axis_vector(self) -> NDArray[np.float64]:
        a = check_shape("axis", self.axis, (3,))
        n = np.linalg.norm(a)
        if n == 0:
            raise ValueError("axis: must be nonzero")
        return a / n


@dataclass(frozen=True)
class Prismatic(Revolute):
    """Translation q (m) along the unit `axis` of the joint frame; velocity q' (m/s)."""

    kind = K.PRISMATIC


@dataclass(frozen=True)
class Spherical(Joint):
    """Free rotation: configuration R (3,3), velocity omega (3,) in the child joint frame."""

    kind = K.SPHERICAL


@dataclass(frozen=True)
class Free(Joint):
    """6 DOF: configuration (R, x), velocity (v, omega); v = x' in the pre-frame (m/s)."""

    kind = K.FREE


@dataclass(frozen=True)
class Body:
    """A rigid body: mass (kg), inertia about its centre of mass in its body frame (kg m^2;
    (3,) principal values or (3,3)), the joint to `parent` (None = inertial frame)."""

    name: str
    mass: float
    inertia: Any
    joint: Joint = field(default_factory=Fixed)
    parent: str | None = None
    prescribed: Prescription | None = None


@dataclass
class MBState:
    """Time t (s), configuration q (nq,) and essential velocities u (nu,) (see module doc)."""

    t: float
    q: NDArray[np.float64]
    u: NDArray[np.float64]

    def copy(self) -> MBState:
        return MBState(self.t, self.q.copy(), self.u.copy())


def constant_rate(rate: float, q0: float = 0.0) -> Prescription:
    """Prescription q = q0 + rate t (e.g. a rotor spun at `rate` rad/s about its axis)."""
    return lambda t: (q0 + rate * t, rate, 0.0)


def harmonic(amplitude: float, omega: float, phase: float = 0.0) -> Prescription:
    """Prescription q = amplitude sin(omega t + phase) for a scalar joint."""

    def f(t: float) -> tuple[float, float, float]:
        th = omega * t + phase
        return (
            amplitude * np.sin(th),
            amplitude * omega * np.cos(th),
            -amplitude * omega**2 * np.sin(th),
        )

    return f
