"""Planar geometrically exact active beam (Rios 2017, ch. 4 §4.3-4.9): public entry points.

::

     z2
     ^        kappa#(S, t): actuation curvature          tip force (dead), tip moment
     |   ___,---------------------.___                    |
     |==/ clamp (z, psi fixed)         `--.__             v  <- M (counter-clockwise +)
     +--------------------------------------> z1

The beam: curve of centroids r_C(S) = e^I z_C(S) and frame angle psi(S) (Eqs. 31, 33),
strains gamma = R(psi)^T z_C', kappa = psi' (Eq. 36), active law M3 = EI (kappa - kappa#)
(Eq. 53). The three-node C1 element lives in `element` (elements "seed" and the locking-free
"sri"), the Newton / load-stepping machinery in `solver`, the time schemes ("energy_momentum",
"generalized_alpha", "newmark") in `dynamics` and `algorithmic`, `simulate_cantilever` in
`simulate`; this module re-exports them and adds `solve_cantilever` (docs/api.md), the
boundary-condition helpers (clamp, Eq. 100 sliding support, Eq. 102 anchor) and the linear
Timoshenko reference solution (Eqs. 65-67) used for verification.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from mf_envs._validate import check_int, check_positive, check_shape
from mf_envs.physics.beam.dynamics import (
    SCHEMES,
    NewmarkState,
    TimeScheme,
    initial_acceleration,
    newmark_step,
    time_step,
)
from mf_envs.physics.beam.element import ELEMENTS, GAUSS_W, GAUSS_XI, N_GAUSS, n_dof
from mf_envs.physics.beam.simulate import CantileverHistory, simulate_cantilever
from mf_envs.physics.beam.solver import (
    BeamModel,
    BeamParams,
    NewtonDivergence,
    NewtonSettings,
    PathStats,
    newton,
    solve_static_path,
)

__all__ = [
    "ELEMENTS",
    "SCHEMES",
    "GAUSS_W",
    "GAUSS_XI",
    "N_GAUSS",
    "BeamModel",
    "BeamParams",
    "CantileverHistory",
    "CantileverSolution",
    "NewmarkState",
    "NewtonDivergence",
    "NewtonSettings",
    "PathStats",
    "TimeScheme",
    "anchor_dofs",
    "clamp_dofs",
    "initial_acceleration",
    "n_dof",
    "newmark_step",
    "newton",
    "solve_cantilever",
    "simulate_cantilever",
    "solve_static_path",
    "support_dofs",
    "time_step",
    "timoshenko_cantilever_uniform",
]


def clamp_dofs(model: BeamModel, node: int) -> list[int]:
    """Clamp: position z_C and frame angle psi of `node` prescribed (Eq. 63); z_C' stays free
    (shear strain at a clamp is not zero in a Timoshenko beam)."""
    return [model.dof(node, "z1"), model.dof(node, "z2"), model.dof(node, "psi")]


def support_dofs(model: BeamModel, node: int) -> list[int]:
    """Simple support with sliding (Eq. 100a): height z2 of `node` prescribed; x, psi free, so
    N along the ground and M3 vanish there (Eq. 100b, read as N2 = M3 = 0 in the plane)."""
    return [model.dof(node, "z2")]


def anchor_dofs(model: BeamModel, node: int) -> list[int]:
    """Anchored (gripping) node of Eq. 102: its x-velocity is zero, i.e. z1 held at its value."""
    return [model.dof(node, "z1")]


@dataclass
class CantileverSolution:
    """Static cantilever solution: tip_position (2,) [m], tip_angle [rad] (unwrapped psi at the
    tip), centerline (N, 2) [m]; plus the dofs, model and path statistics."""

    tip_position: np.ndarray
    tip_angle: float
    centerline: np.ndarray
    d: np.ndarray
    model: BeamModel
    stats: PathStats


def solve_cantilever(
    length: float,
    EA: float,
    GAs: float,
    EI: float,
    n_elements: int,
    tip_force: tuple[float, float] = (0.0, 0.0),
    tip_moment: float = 0.0,
    distributed_load: tuple[float, float] = (0.0, 0.0),
    *,
    kappa_sharp: float = 0.0,
    settings: NewtonSettings | None = None,
    first_step: float = 1.0,
    max_step: float = 1.0,
    element: str = "sri",
) -> CantileverSolution:
    """Geometrically exact static cantilever clamped at the origin along +x (docs/api.md).

    tip_force (2,) [N] and distributed_load (2,) [N/m] are dead loads in the inertial frame,
    tip_moment [N m] counter-clockwise positive; kappa_sharp [1/m] a uniform actuation curvature
    (Eq. 53). Loads and actuation are applied proportionally, lam = 0 -> 1, with step halving.
    element: "sri" (locking-free, default) or "seed" (the seed's element, for its figures).
    """
    for name, val in (("length", length), ("EA", EA), ("GAs", GAs), ("EI", EI)):
        check_positive(name, val)
    check_int("n_elements", n_elements, low=1, high=10_000)
    tip_f = check_shape("tip_force", tip_force, (2,))
    q = check_shape("distributed_load", distributed_load, (2,))
    check_shape("tip_moment", tip_moment, ())
    check_shape("kappa_sharp", kappa_sharp, ())
    params = BeamParams(float(length), float(EA), float(GAs), float(EI), n_elements)
    model = BeamModel(replace(params, element=element))
    f = model.uniform_load(q)
    f[model.dof(-1, "z1")] += tip_f[0]
    f[model.dof(-1, "z2")] += tip_f[1]
    f[model.dof(-1, "psi")] += float(tip_moment)
    kap = np.full(model.gauss_S.shape, float(kappa_sharp))
    fixed = np.zeros(model.n_dof, bool)
    fixed[clamp_dofs(model, 0)] = True
    stats = PathStats()
    d = solve_static_path(
        model,
        model.straight(),
        lambda lam: (lam * kap, lam * f),
        fixed,
        settings or NewtonSettings(),
        first_step=first_step,
        max_step=max_step,
        stats=stats,
    )
    tip = np.array([d[model.dof(-1, "z1")], d[model.dof(-1, "z2")]])
    return CantileverSolution(
        tip_position=tip,
        tip_angle=float(d[model.dof(-1, "psi")]),
        centerline=model.centerline(d),
        d=d,
        model=model,
        stats=stats,
    )


def timoshenko_cantilever_uniform(
    S: np.ndarray, length: float, EI: float, GAs: float, q0: float, kappa0: float = 0.0
) -> tuple[np.ndarray, np.ndarray]:
    """Linear active Timoshenko cantilever under n2 = -q0 [N/m] plus uniform actuation kappa0
    [1/m] (Eqs. 65e-f, 66e-f, 67 with alpha = 1): transverse deflection v(S) [m], psi(S) [rad]."""
    S = np.asarray(S, float)
    L = length
    v = -q0 / (6 * EI) * ((S - L) ** 4 / 4 + L**3 * S - L**4 / 4) + q0 / (2 * GAs) * (
        (S - L) ** 2 - L**2
    )
    psi = -q0 / (6 * EI) * ((S - L) ** 3 + L**3)
    return v + 0.5 * kappa0 * S**2, psi + kappa0 * S
