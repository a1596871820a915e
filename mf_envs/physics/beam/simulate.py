"""`simulate_cantilever`: free and forced large-amplitude dynamics of a clamped planar beam.

::

     clamp at the origin, along +x         released at t = 0 from its static shape
     |==o~~~~~~~~~~~~~~~~~~~~~~~~~~~~o  <- initial_tip_force (dead, before t = 0)
                                     |  tip_force (dead, t > 0)

The beam of `BeamModel` (Eqs. 68-83, 104-106) stepped by `dynamics.time_step`; the default
scheme "energy_momentum" with rho_inf = 1 conserves the total energy, rho_inf < 1 damps the
unresolved high modes (dynamics.py).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from mf_envs._validate import check_choice, check_positive, check_shape
from mf_envs.physics.beam import banded
from mf_envs.physics.beam.dynamics import (
    SCHEMES,
    NewmarkState,
    TimeScheme,
    initial_acceleration,
    time_step,
)
from mf_envs.physics.beam.solver import BeamModel, BeamParams, NewtonSettings, PathStats

DEFAULT_SCHEME = "energy_momentum"


@dataclass
class CantileverHistory:
    """Time series of `simulate_cantilever` (N = steps + 1 samples, t = 0 included):
    t (N,) [s]; tip_position (N, 2) [m]; kinetic_energy, strain_energy (N,) [J];
    load_potential (N,) [J] = -tip_force . (tip - tip(0)); plus the model, the final state and
    the Newton statistics (stats.halvings is always 0: a failed step raises)."""

    t: np.ndarray
    tip_position: np.ndarray
    kinetic_energy: np.ndarray
    strain_energy: np.ndarray
    load_potential: np.ndarray
    model: BeamModel
    final: NewmarkState
    stats: PathStats

    @property
    def total_energy(self) -> np.ndarray:
        """(N,) kinetic + strain energy + potential of the dead tip force [J]."""
        return self.kinetic_energy + self.strain_energy + self.load_potential


def _tip_load(model: BeamModel, force: np.ndarray) -> np.ndarray:
    f = np.zeros(model.n_dof)
    f[model.dof(-1, "z1")], f[model.dof(-1, "z2")] = force
    return f


def simulate_cantilever(
    params: BeamParams,
    t_end: float,
    dt: float,
    initial_tip_force: tuple[float, float] = (0.0, 0.0),
    tip_force: tuple[float, float] = (0.0, 0.0),
    scheme: str = DEFAULT_SCHEME,
    rho_inf: float = 1.0,
    *,
    settings: NewtonSettings | None = None,
) -> CantileverHistory:
    """Clamped beam of `params` (a `BeamParams` with mass: root at the origin, along +x)
    released at t = 0 [s] from its static shape under the dead tip force `initial_tip_force`
    (2,) [N], with the dead `tip_force` (2,) [N] for t > 0, stepped with dt [s] up to t_end [s]
    (ceil(t_end / dt) steps).

    scheme in SCHEMES with rho_inf in [0, 1] (dynamics.py); the element is the params'.
    Raises ValueError naming a bad input, NewtonDivergence (naming the time and the residual)
    if Newton fails at a step (no step halving here: a failure is reported, not hidden).
    """
    if not isinstance(params, BeamParams):
        raise ValueError(f"params: expected a BeamParams, got {type(params).__name__}")
    check_positive("mass_per_length", params.mass_per_length)
    check_positive("rotary_inertia", params.rotary_inertia)
    check_positive("t_end", t_end)
    check_positive("dt", dt)
    check_choice("scheme", scheme, SCHEMES)
    f0 = check_shape("initial_tip_force", initial_tip_force, (2,))
    f1 = check_shape("tip_force", tip_force, (2,))
    ts = TimeScheme(scheme, float(rho_inf))
    from mf_envs.physics.beam import solve_cantilever  # the package imports this module

    p = params
    model = BeamModel(p)
    d0 = solve_cantilever(p.length, p.EA, p.GAs, p.EI, p.n_elements, tuple(f0),
                          element=p.element).d  # fmt: skip
    return simulate_clamped(model, d0, t_end, dt, tuple(f1), ts, settings)


def clamped_root(model: BeamModel) -> np.ndarray:
    """bool (n_dof,): z1, z2, psi of the root node prescribed (the clamp of Eq. 63)."""
    fixed = np.zeros(model.n_dof, bool)
    fixed[[model.dof(0, "z1"), model.dof(0, "z2"), model.dof(0, "psi")]] = True
    return fixed


def simulate_clamped(
    model: BeamModel,
    d0: np.ndarray,
    t_end: float,
    dt: float,
    tip_force: tuple[float, float] = (0.0, 0.0),
    scheme: TimeScheme | None = None,
    settings: NewtonSettings | None = None,
) -> CantileverHistory:
    """Release `model` (clamped at its root) from rest at the dofs d0 (n_dof,) at t = 0 [s],
    with a dead tip force (2,) [N] for t > 0; ceil(t_end / dt) steps of dt [s]."""
    fixed = clamped_root(model)
    kap = np.zeros(model.gauss_S.shape)
    f1 = np.asarray(tip_force, float)
    f = _tip_load(model, f1)
    st = NewmarkState(d0, np.zeros_like(d0), initial_acceleration(model, d0, kap, f, fixed))
    settings = settings or NewtonSettings(1e-10, 1e-10, 12, 0)
    n = int(np.ceil(t_end / dt - 1e-9))
    states, stats = [st], PathStats()
    for _ in range(n):
        st = time_step(
            model, st, dt, kap, f, fixed, settings, scheme=scheme or TimeScheme(), stats=stats
        )
        states.append(st)
    tip = np.array([[s.d[model.dof(-1, "z1")], s.d[model.dof(-1, "z2")]] for s in states])
    ke = np.array([0.5 * s.v @ banded.band_matvec(model.mass, s.v) for s in states])
    se = np.array([model.elastic_energy(s.d, kap) for s in states])
    return CantileverHistory(
        t=dt * np.arange(n + 1),
        tip_position=tip,
        kinetic_energy=ke,
        strain_energy=se,
        load_potential=-(tip - tip[0]) @ f1,
        model=model,
        final=st,
        stats=stats,
    )


def linear_modes(model: BeamModel) -> tuple[np.ndarray, np.ndarray]:
    """Natural angular frequencies (n_free,) [rad/s] and mode shapes (n_dof, n_free) of the
    root-clamped beam linearised about the straight state (scipy.linalg.eigh, dense)."""
    free = ~clamped_root(model)
    k = banded.band_to_dense(model.internal(model.straight(), np.zeros(model.gauss_S.shape))[1])
    m = banded.band_to_dense(model.mass)
    w2, vec = eigh(k[np.ix_(free, free)], m[np.ix_(free, free)])
    modes = np.zeros((model.n_dof, free.sum()))
    modes[free] = vec
    return np.sqrt(np.abs(w2)), modes
