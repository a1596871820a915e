"""Time integration of the active C1 beam (ch. 4 §4.9): one alpha-family step, three schemes.

The semi-discrete equations M a + P(d) = F (Eq. 87; M constant, Eqs. 104-106) are stepped by the
generalized-alpha form (Chung & Hulbert 1993)

    (1 - a_m) M a_{n+1} + a_m M a_n + Pa = (1 - a_f) F_{n+1} + a_f F_n,
    d_{n+1} = d_n + dt v_n + dt^2 ((1/2 - beta) a_n + beta a_{n+1}),
    v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma a_{n+1}),

with three choices of coefficients and of the force Pa (names are the `scheme` argument):

* "newmark" (the seed, Eqs. 90-92): a_m = a_f = 0, Pa = P(d_{n+1}), beta = 1/4, gamma = 1/2 by
  default. Documented instability: on the geometrically nonlinear beam the trapezoidal rule is
  not energy-stable (Simo & Tarnow 1992); a slender strip released at alpha = 0.5 gains ~8 % of
  its energy by period 20 and Newton diverges at period 21 (dt = T1/200). gamma > 1/2 with
  beta = (gamma + 1/2)^2 / 4 damps, but also the first mode (~2 % per period at gamma = 0.6).
* "generalized_alpha": Chung-Hulbert a_m = (2 rho - 1)/(rho + 1), a_f = rho/(rho + 1),
  gamma = 1/2 - a_m + a_f, beta = (1 - a_m + a_f)^2 / 4 from the spectral radius rho_inf at
  infinite frequency; Pa = (1 - a_f) P(d_{n+1}) + a_f P(d_n). Second order, controllable
  high-frequency damping, but at rho_inf = 1 it is the trapezoidal rule again.
* "energy_momentum" (default): the energy-momentum method of Simo & Tarnow (1992) for the
  planar beam, with the algorithmic force Pbar of `algorithmic.py` (an exact discrete gradient
  at the strain level) and trapezoidal kinematics:
      M (v_{n+1} - v_n) / dt = F_mid - Pbar,   d_{n+1} - d_n = dt (v_n + v_{n+1}) / 2,
  (a_m = a_f = 1/2, beta = 1/4, gamma = 1/2 in the form above). With rho_inf = 1 the total
  energy is conserved exactly (to the Newton tolerance) for any step and amplitude. For
  rho_inf < 1 the stresses get a second-difference term, sigma = D (e_mid + chi (De_{n+1} -
  De_n)), De = strain increment of a step, so that (our construction, in the spirit of the
  energy-decaying schemes of Armero & Romero 2001)
      H_{n+1} - H_n = -(chi / 2) int |De_{n+1} - De_n|_D^2 dS <= 0,
      H = kinetic + strain energy + (chi / 2) int |De_n|_D^2 dS,
  exactly, in the nonlinear regime. The term is O(dt^2) on resolved motion (second order, a
  first-mode loss ~ 2 pi chi (omega dt)^3 per period), and on the linear stiff limit the
  amplification roots solve (1/2 + chi) l^2 + (1/2 - 2 chi) l + chi = 0, so
  chi = rho (1 - rho) / (2 (1 + rho)^2) gives spectral radius rho_inf at infinite frequency
  (rho_inf in [1/3, 1]). Two-step: the last increment rate De/dt rides in the state.

Configuration-dependent loads `extra(d, v)` (contact) enter like F: (1 - a_f) at t_{n+1} plus
a_f at t_n. On Newton failure the step is split into halves (actuation and loads interpolated)
up to settings.max_halvings; beyond that NewtonDivergence names the time and the residual.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from mf_envs._validate import check_choice, finite_scalar
from mf_envs.physics.beam import banded
from mf_envs.physics.beam.algorithmic import assemble_algorithmic
from mf_envs.physics.beam.solver import (
    BeamModel,
    Dynamics,
    ExtraLoad,
    NewtonDivergence,
    NewtonSettings,
    PathStats,
    _solve,
    newton,
)

SCHEMES = ("energy_momentum", "generalized_alpha", "newmark")
BETA, GAMMA = 0.25, 0.5  # the seed's average-acceleration Newmark
DEFAULT_SETTINGS = NewtonSettings()


@dataclass
class NewmarkState:
    """Nodal displacements d, velocities v, accelerations a (n_dof,) at time t [s]."""

    d: np.ndarray
    v: np.ndarray
    a: np.ndarray
    t: float = 0.0
    strain_rate: np.ndarray | None = None  # energy_momentum: last De / dt (n_el, nq, 3)

    def copy(self) -> NewmarkState:
        rate = None if self.strain_rate is None else self.strain_rate.copy()
        return NewmarkState(self.d.copy(), self.v.copy(), self.a.copy(), self.t, rate)


@dataclass(frozen=True)
class TimeScheme:
    """A time scheme (module docstring): name in SCHEMES; rho_inf in [0, 1] for the alpha
    schemes; newmark_gamma for "newmark" (beta = (gamma + 1/2)^2 / 4)."""

    name: str = "energy_momentum"
    rho_inf: float = 1.0
    newmark_gamma: float = GAMMA

    def __post_init__(self) -> None:
        check_choice("scheme", self.name, SCHEMES)
        rho = finite_scalar("rho_inf", self.rho_inf)
        low = 1.0 / 3.0 if self.name == "energy_momentum" else 0.0
        if not low - 1e-12 <= rho <= 1.0:
            raise ValueError(f"rho_inf: must be in [{low:.4g}, 1] for {self.name}, got {rho!r}")
        if not finite_scalar("newmark_gamma", self.newmark_gamma) >= 0.5:
            raise ValueError(f"newmark_gamma: must be >= 1/2, got {self.newmark_gamma!r}")

    @property
    def chi(self) -> float:
        """Second-difference stress factor of "energy_momentum" (module docstring)."""
        rho = self.rho_inf
        return rho * (1.0 - rho) / (2.0 * (1.0 + rho) ** 2)

    def coefficients(self) -> tuple[float, float, float, float]:
        """(alpha_m, alpha_f, beta, gamma)."""
        if self.name == "newmark":
            g = self.newmark_gamma
            return 0.0, 0.0, (g + 0.5) ** 2 / 4.0, g
        if self.name == "energy_momentum":
            return 0.5, 0.5, 0.25, 0.5
        rho = self.rho_inf
        am, af = (2.0 * rho - 1.0) / (rho + 1.0), rho / (rho + 1.0)
        return am, af, 0.25 * (1.0 - am + af) ** 2, 0.5 - am + af


def _scaled(extra: ExtraLoad | None, s: float) -> ExtraLoad | None:
    if extra is None or s == 1.0:
        return extra

    def f(d, v):
        fx, dfdd, dfdv = extra(d, v)
        return s * fx, None if dfdd is None else s * dfdd, None if dfdv is None else s * dfdv

    return f


def _algorithmic_force(model, st, scheme, k0, k1, af, dt):
    """d -> (Pa, dPa/dd) of the scheme (module docstring), for Newton."""
    if scheme.name == "energy_momentum":
        chi, q = scheme.chi, model.quad
        shift = np.zeros((model.n_elements, q[0].shape[0], 3))
        if st.strain_rate is not None and chi > 0.0:
            shift = chi * dt * st.strain_rate
        args = (model.le, k0, k1, *q, 0.5 + chi, shift, True, 1.0)
        return lambda d: assemble_algorithmic(st.d, d, *args)[:2]
    if af == 0.0:
        return None  # model.internal at kappa_end

    def pa(d):
        f, ab = model.internal(d, k1)
        return (1.0 - af) * f, (1.0 - af) * ab

    return pa


def _strain_rate(model, st, d, k0, k1, dt):
    zero = np.zeros((model.n_elements, model.quad[0].shape[0], 3))
    args = (model.le, k0, k1, *model.quad, 0.5, zero, False, 1.0)
    return assemble_algorithmic(st.d, d, *args)[2] / dt


def _effective_force(model, state, scheme, extra, k0, f0, f_end) -> np.ndarray:
    """The right-hand side of the alpha form: (1 - a_f) F_{n+1} + a_f F_n - a_m M a_n, minus
    a_f P(d_n) (generalized-alpha) and plus a_f of the extra load at t_n."""
    am, af, _, _ = scheme.coefficients()
    f = f_end
    if af != 0.0 or am != 0.0:
        f = (1.0 - af) * f_end + af * f0 - am * banded.band_matvec(model.mass, state.a)
    if af != 0.0 and scheme.name == "generalized_alpha":
        f = f - af * model.internal(state.d, k0, tangent=False)[0]
    if af != 0.0 and extra is not None:
        f = f + af * extra(state.d, state.v)[0]
    return f


def _accept(model, state, scheme, d, d_pred, v_pred, fixed, k0, kappa_end, dt) -> NewmarkState:
    """The converged step's state: a, v from the Newmark relations (zero on prescribed dofs),
    and with the energy-momentum scheme the strain rate of the step."""
    _, _, beta, gamma = scheme.coefficients()
    a = (d - d_pred) / (beta * dt**2)
    v = v_pred + gamma * dt * a
    a[fixed] = 0.0
    v[fixed] = 0.0
    rate = None
    if scheme.name == "energy_momentum":
        rate = _strain_rate(model, state, d, k0, kappa_end, dt)
    return NewmarkState(d, v, a, state.t + dt, rate)


def time_step(
    model: BeamModel,
    state: NewmarkState,
    dt: float,
    kappa_end: np.ndarray,
    f_end: np.ndarray,
    fixed: np.ndarray,
    settings: NewtonSettings = DEFAULT_SETTINGS,
    extra: ExtraLoad | None = None,
    kappa_start: np.ndarray | None = None,
    f_start: np.ndarray | None = None,
    scheme: TimeScheme = TimeScheme(),
    stats: PathStats | None = None,
    _depth: int = 0,
) -> NewmarkState:
    """One step of length dt [s] from `state` (module docstring). kappa_* (n_el, 4) [1/m] and
    f_* (n_dof,) are the actuation and dead loads at t_n (default: as at t_{n+1}) and t_{n+1};
    prescribed dofs keep their values with zero velocity and acceleration."""
    am, af, beta, gamma = scheme.coefficients()
    k0 = kappa_end if kappa_start is None else kappa_start
    f0 = f_end if f_start is None else f_start
    d_pred = state.d + dt * state.v + dt**2 * (0.5 - beta) * state.a
    v_pred = state.v + (1.0 - gamma) * dt * state.a
    d_pred[fixed] = state.d[fixed]
    v_pred[fixed] = 0.0
    f = _effective_force(model, state, scheme, extra, k0, f0, f_end)
    pa = _algorithmic_force(model, state, scheme, k0, kappa_end, af, dt)
    dyn = Dynamics((1.0 - am) / (beta * dt**2), gamma / (beta * dt), d_pred, v_pred)
    args = (model, d_pred, kappa_end, f, fixed, settings, dyn, _scaled(extra, 1.0 - af), pa)
    res = newton(*args)
    if not res.converged:  # retry from the last converged displacement
        res = newton(model, state.d.copy(), *args[2:])
    if stats is not None:
        stats.iterations += res.iterations
    if res.converged:
        if stats is not None:
            stats.steps += 1
        return _accept(model, state, scheme, res.d, d_pred, v_pred, fixed, k0, kappa_end, dt)
    if _depth >= settings.max_halvings:
        raise NewtonDivergence(
            f"{scheme.name}/Newton failed at t = {state.t:.6g} s (dt = {dt:.3g} s): scaled "
            f"residual {res.residual:.3g} after {res.iterations} iterations"
        )
    if stats is not None:
        stats.halvings += 1
    k_mid, f_mid = 0.5 * (k0 + kappa_end), 0.5 * (f0 + f_end)
    kw = {"scheme": scheme, "stats": stats, "_depth": _depth + 1}
    half = time_step(model, state, dt / 2, k_mid, f_mid, fixed, settings, extra, k0, f0, **kw)
    return time_step(
        model, half, dt / 2, kappa_end, f_end, fixed, settings, extra, k_mid, f_mid, **kw
    )


def newmark_step(
    *args: Any, beta: float = BETA, gamma: float = GAMMA, **kwargs: Any
) -> NewmarkState:
    """One Newmark step (the seed's Eqs. 90-92, beta = 1/4, gamma = 1/2 by default; see the
    module docstring for its instability): `time_step` with `time_step`'s arguments but
    `scheme`. beta must be (gamma + 1/2)^2 / 4."""
    if abs(beta - (gamma + 0.5) ** 2 / 4.0) > 1e-12:
        raise ValueError(f"beta: must be (gamma + 1/2)^2 / 4, got {beta!r}")
    return time_step(*args, scheme=TimeScheme("newmark", newmark_gamma=gamma), **kwargs)


def initial_acceleration(
    model: BeamModel, d: np.ndarray, kappa_sharp: np.ndarray, f_ext: np.ndarray, fixed: np.ndarray
) -> np.ndarray:
    """a0 from M a0 = F - P(d0) on the free dofs (§4.9, after Eq. 87)."""
    f_int, _ = model.internal(d, kappa_sharp, tangent=False)
    r = f_ext - f_int
    m = model.mass.copy()
    banded.constrain_band(m, r, fixed)
    return _solve(m, r)
