"""Nonlinear solution of the active C1 beam: Newton-Raphson, load stepping, Newmark (ch. 4 §4.9).

* `BeamModel`: mesh, dof maps, the constant consistent mass (Eqs. 104-106) and named field
  evaluations (centerline, psi, curvature, strains) on top of the element kernels;
* `newton`: Newton-Raphson on the residual E = F - P - M a (Eqs. 88-98) with the consistent tangent
  (material + geometric), banded solves (scipy.linalg.solve_banded), the seed's two-part
  convergence test (Eq. 93: ||E||_inf < eps1 and ||Delta d||_inf < eps2, both made dimensionless);
* `solve_static_path`: load/actuation stepping lambda: 0 -> 1 with automatic halving of the step
  when Newton does not converge within a few iterations, and a secant predictor (warm start);
* time stepping (Newmark, generalized-alpha, energy-momentum) lives in `dynamics.py` and uses
  `newton` with its `dyn` data and, for the algorithmic forces, its `internal` hook.

Constraints are prescribed dofs (bool mask): their values stay as given in the start vector
(clamp, simple support with sliding Eq. 100a, an anchored node Eq. 102); the rows and columns
are replaced by the identity so the band structure is kept.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy.linalg import get_lapack_funcs

from mf_envs._validate import check_int, check_nonnegative, check_positive
from mf_envs.physics.beam import banded, fields
from mf_envs.physics.beam import element as el

DOF_NAMES = ("z1", "dz1", "z2", "dz2", "psi")

# extra (configuration-dependent) loads: f(d, v) -> (F (n_dof,), dF/dd banded or None,
# dF/dv banded or None), e.g. terrain contact
ExtraLoad = Callable[
    [np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray | None, np.ndarray | None]
]


class NewtonDivergence(RuntimeError):
    """Newton-Raphson failed even after the allowed number of step halvings."""


@dataclass(frozen=True)
class BeamParams:
    """Planar active beam (SI). Rigidities EA [N], GAs [N] (A_s shear area), EI [N m^2]."""

    length: float  # reference length L [m]
    EA: float  # axial rigidity [N]
    GAs: float  # shear rigidity [N]
    EI: float  # bending rigidity [N m^2]
    n_elements: int  # number of three-node C1 elements
    mass_per_length: float = 0.0  # m_A [kg/m]
    rotary_inertia: float = 0.0  # J_3C, rotary inertia per length [kg m]
    element: str = "sri"  # "seed" (Eq. 80b, locks when slender) or "sri" (element.quadrature)

    def __post_init__(self) -> None:
        if self.element not in el.ELEMENTS:
            raise ValueError(f"element: must be one of {el.ELEMENTS}, got {self.element!r}")
        for name in ("length", "EA", "GAs", "EI"):
            check_positive(name, getattr(self, name))
        check_int("n_elements", self.n_elements, low=1, high=10_000)
        check_nonnegative("mass_per_length", self.mass_per_length)
        check_nonnegative("rotary_inertia", self.rotary_inertia)


@dataclass(frozen=True)
class NewtonSettings:
    """eps1 (rtol, residual relative to EI/L + load scale), eps2 (dtol, increment / L), max_iter
    per attempt ("a few", the seed aims at < 5), max_halvings of the load/time step."""

    rtol: float = 1e-10
    dtol: float = 1e-10
    max_iter: int = 8
    max_halvings: int = 14


@dataclass
class NewtonResult:
    d: np.ndarray
    converged: bool
    iterations: int
    residual: float  # final scaled residual


@dataclass
class PathStats:
    steps: int = 0  # accepted load/time increments
    halvings: int = 0
    iterations: int = 0  # total Newton iterations
    iterations_per_step: list[int] = field(default_factory=list)


class BeamModel:
    """Mesh + dof maps + constant matrices of a uniform straight beam of `params.n_elements`."""

    def __init__(self, params: BeamParams) -> None:
        self.params = params
        ne = params.n_elements
        self.n_elements = ne
        self.n_dof = el.n_dof(ne)
        self.le = np.full(ne, params.length / ne)
        self.node_S = np.linspace(0.0, params.length, ne + 1)
        self.gauss_S = self.node_S[:-1, None] + el.GAUSS_XI[None, :] * self.le[:, None]
        # dof scaling for dimensionless convergence checks: z dofs are lengths
        self.u_scale = np.ones(self.n_dof)
        for j in range(ne + 1):
            self.u_scale[[6 * j, 6 * j + 2]] = params.length
        self._mass: np.ndarray | None = None
        self.quad = el.quadrature(
            params.element, params.length / ne, params.EA, params.GAs, params.EI
        )

    # ---------------------------------------------------------------- dofs
    def dof(self, node: int, name: str) -> int:
        """Global index of dof `name` (z1, dz1, z2, dz2, psi) of end node `node` (-1 = last)."""
        if node < 0:
            node += self.n_elements + 1
        return 6 * node + DOF_NAMES.index(name)

    def straight(self) -> np.ndarray:
        """(n_dof,) dofs of the straight reference configuration along +x (Eq. 30)."""
        d = np.zeros(self.n_dof)
        d[0::6] = self.node_S  # z1 at the end nodes
        d[1::6] = 1.0  # z1' = 1
        return d

    @property
    def mass(self) -> np.ndarray:
        """Consistent mass matrix, banded (21, n_dof) (Eqs. 104-106)."""
        if self._mass is None:
            p = self.params
            self._mass = fields.assemble_mass(self.le, p.mass_per_length, p.rotary_inertia)
        return self._mass

    # ---------------------------------------------------------------- physics
    def internal(
        self, d: np.ndarray, kappa_sharp: np.ndarray, tangent: bool = True
    ) -> tuple[np.ndarray, np.ndarray]:
        """Internal force P (n_dof,) and banded tangent dP/dd at `d` (Eq. 80b)."""
        f, ab, _ = el.assemble_internal(d, self.le, kappa_sharp, *self.quad, tangent)
        return f, ab

    def elastic_energy(self, d: np.ndarray, kappa_sharp: np.ndarray) -> float:
        """Stored energy [J]: int (N1 (g1-1) + N2 g2 + M3 (k - k#)) / 2 dS."""
        return float(el.assemble_internal(d, self.le, kappa_sharp, *self.quad, False)[2])

    def distributed(self, n_gp: np.ndarray, m_gp: np.ndarray | None = None) -> np.ndarray:
        """Nodal force (n_dof,) of a line force n_gp (n_el, 4, 2) [N/m, inertial frame] and line
        couple m_gp (n_el, 4) [N] at the Gauss points (Eq. 81b)."""
        if m_gp is None:
            m_gp = np.zeros(self.gauss_S.shape)
        return fields.assemble_distributed(self.le, np.ascontiguousarray(n_gp, float), m_gp)

    def uniform_load(self, q: tuple[float, float] | np.ndarray) -> np.ndarray:
        """Nodal force (n_dof,) of a uniform dead line load q = (q1, q2) [N/m]."""
        n_gp = np.broadcast_to(np.asarray(q, float), (*self.gauss_S.shape, 2)).copy()
        return self.distributed(n_gp)

    def fields(self, d: np.ndarray, per_element: int = 8) -> dict[str, np.ndarray]:
        """Fields sampled along S: S, position (N, 2), psi, kappa, gamma1, gamma2 (N,)."""
        xis = np.linspace(0.0, 1.0, per_element + 1)[:-1]
        pos, psi, kap, g1, g2 = fields.evaluate_fields(d, self.le, xis)
        s = (self.node_S[:-1, None] + xis[None, :] * self.le[:, None]).ravel()
        out = {"S": np.append(s, self.params.length)}
        # the last element at xi = 1 (the last node)
        last = fields.evaluate_fields(d[-11:], self.le[-1:], np.array([1.0]))
        out["position"] = np.vstack([pos.reshape(-1, 2), last[0].reshape(1, 2)])
        for name, arr, tail in (("psi", psi, last[1]), ("kappa", kap, last[2])):
            out[name] = np.append(arr.ravel(), tail.ravel())
        out["gamma1"] = np.append(g1.ravel(), last[3].ravel())
        out["gamma2"] = np.append(g2.ravel(), last[4].ravel())
        return out

    def centerline(self, d: np.ndarray, per_element: int = 8) -> np.ndarray:
        """(N, 2) points of the curve of centroids [m], N = per_element * n_el + 1."""
        return self.fields(d, per_element)["position"]

    def gauss_fields(self, d: np.ndarray) -> dict[str, np.ndarray]:
        """At the Gauss points: position (n_el, 4, 2); psi, kappa, gamma1, gamma2 (n_el, 4)."""
        pos, psi, kap, g1, g2 = fields.evaluate_fields(d, self.le, el.GAUSS_XI)
        return {"position": pos, "psi": psi, "kappa": kap, "gamma1": g1, "gamma2": g2}

    def node_positions(self, d: np.ndarray) -> np.ndarray:
        """(n_el + 1, 2) end-node positions [m]."""
        return np.column_stack([d[0::6][: self.n_elements + 1], d[2::6][: self.n_elements + 1]])


_GBSV = get_lapack_funcs(("gbsv",), (np.zeros((1, 1)),))[0]  # LAPACK dgbsv


def _solve(ab: np.ndarray, r: np.ndarray) -> np.ndarray:
    """x with A x = r, A banded (ab (2 HALF_BW + 1, n), LAPACK layout): the dgbsv call of
    scipy.linalg.solve_banded made directly (same routine, same result, without its input
    validation, which cost as much as the solve in the Newton loop)."""
    hb = el.HALF_BW
    a2 = np.zeros((3 * hb + 1, ab.shape[1]))
    a2[hb:] = ab
    _, _, x, info = _GBSV(hb, hb, a2, r, overwrite_ab=True, overwrite_b=False)
    if info > 0:
        raise np.linalg.LinAlgError("singular matrix")
    if info < 0:
        raise ValueError(f"illegal value in argument {-info} of dgbsv")
    return x


@dataclass
class Dynamics:
    """Newmark data for one step: a = c_a (d - d_pred), v = v_pred + c_v (d - d_pred)."""

    c_a: float  # 1 / (beta dt^2)
    c_v: float  # gamma / (beta dt)
    d_pred: np.ndarray
    v_pred: np.ndarray


def _tolerance(
    model: BeamModel, d: np.ndarray, f_ext: np.ndarray, settings: NewtonSettings, dyn: Any
) -> tuple[float, float]:
    """(f_ref, eps1): the force scale of the scaled residual and its tolerance, floored at the
    round-off level of the axial/shear force terms: the strain z' = sum N_i' z_i of nodes at
    distance |z| from the origin carries eps |z| / l_e, so the floor grows with max(L, |z|)
    (callers far from the origin should use local coordinates)."""
    p = model.params
    f_ref = p.EI / p.length + float(np.max(np.abs(f_ext * model.u_scale)))
    eps = np.finfo(float).eps
    reach = max(1.0, float(np.max(np.abs(d[0::6]), initial=0.0)) / p.length)
    reach = max(reach, float(np.max(np.abs(d[2::6]), initial=0.0)) / p.length)
    tol_r = max(settings.rtol, 256 * eps * max(p.EA, p.GAs) * p.length * reach / f_ref)
    if dyn is not None:  # a = c_a (d - d_pred) loses digits in the difference
        md = banded.band_matvec(model.mass, np.abs(d) + np.abs(dyn.d_pred))
        tol_r = max(tol_r, 256 * eps * dyn.c_a * float(np.max(np.abs(md * model.u_scale))) / f_ref)
    return f_ref, tol_r


def _residual(model, d, kappa_sharp, f_ext, dyn, extra, internal) -> tuple[np.ndarray, np.ndarray]:
    """(residual F - P(d) - M a(d) + extra, banded tangent) at d (before the constraints)."""
    f_int, ab = model.internal(d, kappa_sharp) if internal is None else internal(d)
    r = f_ext - f_int
    if dyn is not None:
        acc = dyn.c_a * (d - dyn.d_pred)
        r -= banded.band_matvec(model.mass, acc)
        ab += dyn.c_a * model.mass
    if extra is not None:
        vel = dyn.v_pred + dyn.c_v * (d - dyn.d_pred) if dyn is not None else np.zeros_like(d)
        fx, dfdd, dfdv = extra(d, vel)
        r += fx
        if dfdd is not None:
            ab -= dfdd
        if dfdv is not None and dyn is not None:
            ab -= dyn.c_v * dfdv
    return r, ab


def newton(
    model: BeamModel,
    d_start: np.ndarray,
    kappa_sharp: np.ndarray,
    f_ext: np.ndarray,
    fixed: np.ndarray,
    settings: NewtonSettings = NewtonSettings(),
    dyn: Dynamics | None = None,
    extra: ExtraLoad | None = None,
    internal: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]] | None = None,
) -> NewtonResult:
    """Newton-Raphson for E(d) = F - P(d) - M a(d) = 0 on the free dofs (Eqs. 92-98).

    d_start: (n_dof,) start (prescribed dofs already at their values); kappa_sharp (n_el, 4) [1/m];
    f_ext: (n_dof,) dead nodal loads; fixed: bool (n_dof,) prescribed dofs; internal: d ->
    (force, banded tangent) replacing model.internal (the time schemes' algorithmic forces).
    """
    d = d_start.copy()
    f_ref, tol_r = _tolerance(model, d, f_ext, settings, dyn)
    res = np.inf
    for it in range(1, settings.max_iter + 1):
        r, ab = _residual(model, d, kappa_sharp, f_ext, dyn, extra, internal)
        banded.constrain_band(ab, r, fixed)
        res = float(np.max(np.abs(r * model.u_scale))) / f_ref
        if it == 1:
            res_first = res
        if not np.isfinite(res) or (it >= 3 and res > 1e3 * max(res_first, tol_r)):
            return NewtonResult(d, False, it, res)  # non-finite or clearly diverging
        try:
            delta = _solve(ab, r)
        except np.linalg.LinAlgError:  # singular tangent (e.g. a body losing all support)
            return NewtonResult(d, False, it, res)
        d += delta
        step = float(np.max(np.abs(delta / model.u_scale)))
        if not np.isfinite(step):
            return NewtonResult(d, False, it, res)
        # eps2 test, or a residual so far below eps1 that the increment is round-off noise
        if res < tol_r and (step < settings.dtol or res < 1e-2 * tol_r):
            return NewtonResult(d, True, it, res)
    return NewtonResult(d, False, settings.max_iter, res)


LoadPath = Callable[[float], tuple[np.ndarray, np.ndarray]]  # lam -> (kappa_sharp, f_ext)


def solve_static_path(
    model: BeamModel,
    d0: np.ndarray,
    load_at: LoadPath,
    fixed: np.ndarray,
    settings: NewtonSettings = NewtonSettings(),
    first_step: float = 1.0,
    max_step: float = 1.0,
    extra: ExtraLoad | None = None,
    stats: PathStats | None = None,
) -> np.ndarray:
    """Quasi-static path lam = 0 -> 1 with step halving on Newton failure (Eqs. 93-98).

    load_at(lam) gives (kappa_sharp (n_el, 4), f_ext (n_dof,)); d0 is converged at lam = 0 (or
    the reference). A secant predictor extrapolates the previous increment (warm start).
    Raises NewtonDivergence when the step would need more than `settings.max_halvings` halvings.
    """
    stats = stats if stats is not None else PathStats()
    lam, h = 0.0, min(first_step, max_step)
    d, d_prev, h_prev = d0.copy(), None, None
    min_h = min(first_step, max_step) * 0.5**settings.max_halvings
    while lam < 1.0 - 1e-14:
        h = min(h, 1.0 - lam)
        guess = d if d_prev is None else d + (d - d_prev) * (h / h_prev)
        guess[fixed] = d[fixed]
        kap, f = load_at(lam + h)
        res = newton(model, guess, kap, f, fixed, settings, extra=extra)
        if not res.converged and d_prev is not None:  # retry without the predictor
            res = newton(model, d.copy(), kap, f, fixed, settings, extra=extra)
        stats.iterations += res.iterations
        if not res.converged:
            h *= 0.5
            stats.halvings += 1
            if h < min_h:
                raise NewtonDivergence(f"Newton failed at lam = {lam:.6g} (step {2 * h:.3g})")
            continue
        d_prev, h_prev, d = d, h, res.d
        lam += h
        stats.steps += 1
        stats.iterations_per_step.append(res.iterations)
        if res.iterations <= settings.max_iter // 2:
            h = min(2.0 * h, max_step)
    return d
