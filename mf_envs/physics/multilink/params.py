"""`ChainParams` of the planar n-link chain (module doc of `mf_envs.physics.multilink`) and its
construction from a beam (`chain_from_beam`, the half-link rule) and from a curvature."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import (
    check_choice,
    check_finite,
    check_int,
    check_nonnegative,
    check_shape,
    finite_scalar,
    nonnegative_scalar,
    positive_scalar,
)

BASES = ("clamped", "free")


@dataclass(frozen=True, eq=False)
class ChainParams:
    """Parameters of the planar n-link chain (SI units).

    n_links: number of links n (>= 1; >= 2 for "free").
    link_length: l, m.
    link_mass: m, kg (per link).
    link_inertia: J_c, kg m^2, about the link centre.
    joint_stiffness: (n_joints,) N m/rad; n_joints = n ("clamped", joint 0 at the clamp) or n - 1.
    joint_damping: N m s/rad on every elastic joint rate (0 = conservative).
    base: "clamped" or "free".
    base_position: (2,) m, the clamp point (clamped only).
    base_angle: psi_0, rad, the clamp direction (clamped only).
    gravity: (2,) m/s^2, inertial gravity vector, e.g. (0, -9.81); zeros = off.
    """

    n_links: int
    link_length: float
    link_mass: float
    link_inertia: float
    joint_stiffness: NDArray[np.float64]
    joint_damping: float = 0.0
    base: str = "clamped"
    base_position: NDArray[np.float64] = field(default_factory=lambda: np.zeros(2))
    base_angle: float = 0.0
    gravity: NDArray[np.float64] = field(default_factory=lambda: np.zeros(2))

    def __post_init__(self) -> None:
        check_choice("base", self.base, BASES)
        n = check_int("n_links", self.n_links, low=2 if self.base == "free" else 1)
        set_ = object.__setattr__
        set_(self, "n_links", n)
        set_(self, "link_length", positive_scalar("link_length", self.link_length))
        set_(self, "link_mass", positive_scalar("link_mass", self.link_mass))
        set_(self, "link_inertia", nonnegative_scalar("link_inertia", self.link_inertia))
        set_(self, "joint_damping", nonnegative_scalar("joint_damping", self.joint_damping))
        set_(self, "base_angle", finite_scalar("base_angle", self.base_angle))
        k = check_nonnegative("joint_stiffness", np.atleast_1d(self.joint_stiffness))
        k = check_shape("joint_stiffness", k, (self.n_joints,)).copy()
        for name, arr in (
            ("joint_stiffness", k),
            ("base_position", check_shape("base_position", self.base_position, (2,)).copy()),
            ("gravity", check_shape("gravity", self.gravity, (2,)).copy()),
        ):
            arr.setflags(write=False)
            set_(self, name, arr)

    @property
    def n_joints(self) -> int:
        """Number of spring joints: n (clamped) or n - 1 (free)."""
        return self.n_links if self.base == "clamped" else self.n_links - 1

    @property
    def n_dof(self) -> int:
        """Number of essential coordinates: n (clamped) or n + 2 (free, Eq. 14)."""
        return self.n_links if self.base == "clamped" else self.n_links + 2

    @property
    def n_trans(self) -> int:
        """Leading translational dofs in q: 0 (clamped) or 2 (free)."""
        return 0 if self.base == "clamped" else 2

    @property
    def length(self) -> float:
        """Total length n l, m."""
        return self.n_links * self.link_length


def chain_from_beam(
    length: float,
    EI: float,
    mass_per_length: float,
    n_links: int,
    rotary_inertia_per_length: float = 0.0,
    base: str = "clamped",
    joint_damping: float = 0.0,
    gravity: ArrayLike = (0.0, 0.0),
) -> ChainParams:
    """Chain equivalent of a uniform beam (module docstring): k = EI/l inside, 2 EI/l at a clamp.

    length: L, m; EI: N m^2; mass_per_length: kg/m; rotary_inertia_per_length: J_3, kg m (per
    unit length, e.g. rho I); link inertia J_c = m l^2 / 12 + J_3 l.
    """
    L = positive_scalar("length", length)
    EI = positive_scalar("EI", EI)
    rho = positive_scalar("mass_per_length", mass_per_length)
    J3 = nonnegative_scalar("rotary_inertia_per_length", rotary_inertia_per_length)
    n = check_int("n_links", n_links, low=1)
    l = L / n
    check_choice("base", base, BASES)
    k = np.full(n if base == "clamped" else n - 1, EI / l)
    if base == "clamped":
        k[0] = 2.0 * EI / l
    m = rho * l
    return ChainParams(n, l, m, m * l * l / 12.0 + J3 * l, k, joint_damping, base, gravity=gravity)


def actuation_from_curvature(params: ChainParams, kappa_sharp: ArrayLike) -> NDArray[np.float64]:
    """theta#_j = integral of kappa#(S) over the span of joint j (module docstring rule).

    kappa_sharp: scalar (uniform, 1/m) or (n_links,) values at the link centres (piecewise
    linear between centres). Returns (n_joints,) rad.
    """
    kap = np.broadcast_to(check_finite("kappa_sharp", kappa_sharp), (params.n_links,))
    l = params.link_length
    interior = 0.5 * l * (kap[:-1] + kap[1:])  # trapezoid between link centres
    if params.base == "free":
        return interior
    return np.concatenate(([0.5 * l * kap[0]], interior))


# --- kinematics ----------------------------------------------------------------------------
