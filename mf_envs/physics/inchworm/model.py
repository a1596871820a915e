"""The inchworm as an active C1 beam (Rios 2017 §4.10, Eqs. 99-102): its parameters, effects
and the `Inchworm` simulation (quasi-static or dynamic actuation, kinematic anchors of Eq. 102
or Bekker/Janosi terrain, the moving local origin). The package docstring
(`mf_envs.physics.inchworm`) describes the scene and the coordinates.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field, replace

import numpy as np

from mf_envs._validate import check_int, check_positive, finite_scalar
from mf_envs.physics.beam import (
    BeamModel,
    BeamParams,
    NewmarkState,
    NewtonSettings,
    PathStats,
    TimeScheme,
    anchor_dofs,
    initial_acceleration,
    solve_static_path,
    support_dofs,
    time_step,
)
from mf_envs.physics.beam.fields import centerline_into
from mf_envs.physics.beam.static import scratch as static_scratch
from mf_envs.physics.beam.static import solve_linear_path
from mf_envs.physics.constants import G as STANDARD_GRAVITY

INCHWORM_EFFECTS = {
    "gravity": "self weight m_A g (Eq. 99)",
    "inertia": "dynamics, energy-momentum scheme (off = quasi-static, the seed's setting)",
    "shear_deformation": "Timoshenko shear strain (off = shear-rigid, GA_s x 100 penalty)",
    "anchor_switching": "kinematic anchor switching of Eq. 102 (off = head held, fig. 4-8)",
    "terrain": "Bekker/Janosi soil contact (Eqs. 56-57) instead of kinematic supports/anchors",
}
SHEAR_RIGID_FACTOR = 100.0


@dataclass(frozen=True)
class InchwormParams:
    """The seed's section (§4.10); the length is our choice (the seed does not state it):
    L = 0.3 m gives kappa0# L = 3.9 rad at kappa0# = 13 1/m, a deep loop short of self-contact."""

    length: float = 0.3  # L [m]
    width: float = 0.02  # b [m]
    height: float = 0.01  # h [m]
    youngs_modulus: float = 2.4e9  # E [Pa]
    shear_modulus: float = 0.96e9  # G [Pa]
    mass_per_length: float = 0.278  # m_A [kg/m]
    rotary_inertia: float = 0.232e-5  # J_3C [kg m]
    n_elements: int = 16
    gravity: float = STANDARD_GRAVITY  # g [m/s^2]
    shear_correction: float = 5.0 / 6.0  # A_s = k b h

    def __post_init__(self) -> None:
        for name in ("length", "width", "height", "youngs_modulus", "shear_modulus"):
            check_positive(name, getattr(self, name))
        for name in ("mass_per_length", "rotary_inertia", "gravity", "shear_correction"):
            check_positive(name, getattr(self, name))
        check_int("n_elements", self.n_elements, low=1, high=1000)

    @property
    def EI(self) -> float:  # noqa: N802 - the standard symbol
        return self.youngs_modulus * self.width * self.height**3 / 12.0

    @property
    def max_dkappa(self) -> float:
        """The seed's actuation increment 2h/L^2 [1/m] (h/4 mid-span rise per increment)."""
        return 2.0 * self.height / self.length**2

    def beam(self, shear_deformation: bool = True) -> BeamParams:
        area = self.width * self.height
        gas = self.shear_modulus * self.shear_correction * area
        if not shear_deformation:
            gas *= SHEAR_RIGID_FACTOR
        return BeamParams(
            self.length,
            self.youngs_modulus * area,
            gas,
            self.EI,
            self.n_elements,
            self.mass_per_length,
            self.rotary_inertia,
        )


@dataclass
class StepReport:
    increments: int = 0
    iterations: int = 0
    halvings: int = 0


@dataclass
class Inchworm:
    """Mutable simulation state of one inchworm; physics in `actuate`."""

    params: InchwormParams = field(default_factory=InchwormParams)
    effects: frozenset[str] = frozenset({"gravity", "shear_deformation", "anchor_switching"})
    settings: NewtonSettings = field(default_factory=lambda: NewtonSettings(1e-9, 1e-9, 8, 12))
    increment_factor: float = 1.0  # increments up to increment_factor * 2h/L^2
    soil: str = "dry_sand"  # terrain effect: a preset of mf_envs.physics.terrain.SOILS
    # inertia: time scheme of mf_envs.physics.beam.dynamics. Default "energy_momentum" with
    # rho_inf = 0.8: energy-stable on the nonlinear beam, < 0.02 % per period off a resolved
    # mode, and it damps the unresolved axial/contact modes that abrupt actuation and anchor
    # switches excite. (The seed's Newmark needs gamma > 1/2 there, which also damps the first
    # mode ~2 % per period; still available as scheme="newmark" with newmark_gamma.)
    scheme: str = "energy_momentum"
    rho_inf: float = 0.8
    newmark_gamma: float = 0.6
    element: str = "sri"  # beam element: "sri" (locking-free) or "seed" (the seed's figures)

    def __post_init__(self) -> None:
        unknown = set(self.effects) - set(INCHWORM_EFFECTS)
        if unknown:
            raise ValueError(f"effects: unknown {sorted(unknown)}; available {INCHWORM_EFFECTS}")
        check_positive("increment_factor", self.increment_factor)
        self.time_scheme = TimeScheme(self.scheme, self.rho_inf, self.newmark_gamma)
        beam = self.params.beam("shear_deformation" in self.effects)
        self.model = BeamModel(replace(beam, element=self.element))
        self._scratch = static_scratch(self.model.n_elements)
        p = self.params
        self.f_ext = np.zeros(self.model.n_dof)
        if "gravity" in self.effects or "terrain" in self.effects:  # no contact without weight
            self.f_ext = self.model.uniform_load((0.0, -p.mass_per_length * p.gravity))
        self.head, self.tail = self.model.n_elements, 0
        self.terrain = None
        if "terrain" in self.effects:
            from mf_envs.physics.beam.contact.terrain import BeamTerrain

            self.terrain = BeamTerrain(self.model, p.height, p.width, self.soil)
        self.reset()

    # ------------------------------------------------------------------ state
    def reset(self, x_tail: float = 0.0) -> None:
        """Straight, unactuated, at rest, tail at x_tail [m]; head anchored (loading first)."""
        self.x_origin = finite_scalar("x_tail", x_tail)  # local x = 0 at the tail
        d = self.model.straight()
        if self.terrain is not None:  # bottom surface on the ground; settling finds the sinkage
            from mf_envs.physics.terrain import plate_sinkage

            p = self.params
            sink = plate_sinkage(
                self.terrain.grip.soil, p.mass_per_length * p.gravity * p.length, p.width, p.length
            )
            d[2::6] = 0.5 * p.height - sink
            self.terrain.reset(d)
            self.terrain.anchor = "head" if "anchor_switching" in self.effects else None
        self.kappa = np.zeros(self.model.gauss_S.shape)
        self.anchor = "head"
        self.state = NewmarkState(d, np.zeros_like(d), np.zeros_like(d), 0.0)
        self._dyn_fixed: np.ndarray | None = None
        self._settle()

    def _settle(self) -> None:
        """Static equilibrium under the current loads (gravity sag) with the current anchor."""
        d = self._path(self.state.d, self.kappa, self.kappa, self.fixed_mask(), PathStats())
        if self.terrain is not None:
            self.terrain.commit(d)
        self.state = NewmarkState(d, np.zeros_like(d), np.zeros_like(d), self.state.t)

    def fixed_mask(self, anchor: str | None = None) -> np.ndarray:
        """Prescribed dofs: z2 = 0 at tail and head (Eq. 100a) + x of the anchored node (102)."""
        anchor = anchor or self.anchor
        fixed = np.zeros(self.model.n_dof, bool)
        if self.terrain is not None:  # the soil carries and holds the body
            return fixed
        fixed[support_dofs(self.model, self.tail) + support_dofs(self.model, self.head)] = True
        if "anchor_switching" not in self.effects:
            anchor = "head"  # fig. 4-8: the head stays put
        fixed[anchor_dofs(self.model, self.head if anchor == "head" else self.tail)] = True
        return fixed

    # ------------------------------------------------------------------ physics
    def actuate(
        self,
        kappa_target: np.ndarray,
        dt: float = 1.0,
        anchor: str | None = None,
        min_increments: int = 1,
    ) -> StepReport:
        """Move kappa# at the Gauss points (n_el, 4) [1/m] to `kappa_target` over dt [s].

        anchor: "head"/"tail"; None = Eq. 102 from the sign of the mean change (<= 0: head).
        Quasi-static: increments of at most increment_factor * 2h/L^2 (and at least
        min_increments), each solved by Newton with step halving. Inertia: the same number of
        time steps of dt / n (`scheme`).
        Raises NewtonDivergence when halving cannot rescue Newton.
        """
        kappa_target = np.asarray(kappa_target, float).reshape(self.kappa.shape)
        dk = kappa_target - self.kappa
        if anchor is None:
            anchor = "head" if float(np.mean(dk)) <= 0.0 else "tail"
        if anchor not in ("head", "tail"):
            raise ValueError(f"anchor: must be 'head' or 'tail', got {anchor!r}")
        self.anchor = anchor
        if self.terrain is not None and "anchor_switching" in self.effects:
            if anchor != self.terrain.anchor:  # the feet re-plant: slip history starts afresh
                self.terrain.reset(self.state.d)
            self.terrain.anchor = anchor
        fixed = self.fixed_mask()
        limit = self.increment_factor * self.params.max_dkappa
        n_inc = max(min_increments, int(np.ceil(np.max(np.abs(dk)) / limit - 1e-12)))
        k0, report = self.kappa.copy(), StepReport(increments=n_inc)
        if "inertia" in self.effects:
            self._dynamic(k0, kappa_target, dt, n_inc, fixed, report)
        else:
            stats, d = PathStats(), self.state.d
            for i in range(n_inc):  # slip history committed after every increment
                ka = k0 + dk * (i / n_inc)
                d = self._path(d, ka, ka + dk / n_inc, fixed, stats)
                if self.terrain is not None:
                    self.terrain.commit(d)
            self.state = NewmarkState(d, np.zeros_like(d), np.zeros_like(d), self.state.t + dt)
            report.iterations, report.halvings = stats.iterations, stats.halvings
        self.kappa = kappa_target
        self._recenter()
        return report

    def _recenter(self) -> None:
        """Move the local origin to the tail once it is more than a body length away (a
        translation of the nodal x dofs and of the soil's slip references; exact physics)."""
        shift = float(self.state.d[self.model.dof(self.tail, "z1")])
        if not abs(shift) > self.params.length:  # also skips a non-finite state
            return
        d = self.state.d.copy()  # never mutate an array a caller may hold
        d[0::6] -= shift
        st = self.state
        self.state = NewmarkState(d, st.v, st.a, st.t, st.strain_rate)
        self.x_origin += shift
        if self.terrain is not None:
            self.terrain.translate(-shift)

    def _dynamic(self, k0, k1, dt, n_sub, fixed, report) -> None:
        st = self.state.copy()
        if not np.array_equal(fixed, self._dyn_fixed):  # new anchor: impulsive stop, fresh a0
            st.v[fixed] = 0.0
            st.a = initial_acceleration(self.model, st.d, k0, self.f_ext, fixed)
            self._dyn_fixed = fixed
        h = dt / n_sub
        for i in range(1, n_sub + 1):
            k_end = k0 + (k1 - k0) * (i / n_sub)
            k_start = k0 + (k1 - k0) * ((i - 1) / n_sub)
            st = time_step(
                self.model,
                st,
                h,
                k_end,
                self.f_ext,
                fixed,
                self.settings,
                self._extra(),
                k_start,
                scheme=self.time_scheme,
            )
            if self.terrain is not None:
                self.terrain.commit(st.d)
        self.state = st
        report.iterations = n_sub

    def _path(self, d, ka, kb, fixed, stats: PathStats) -> np.ndarray:
        """Quasi-static path kappa# ka -> kb from d: the compiled linear path
        (`beam.static`), or with `terrain` the general one with the soil's loads."""
        if self.terrain is None:
            d, its, halvings = solve_linear_path(
                self.model, d, ka, kb, self.f_ext, fixed, self.settings, self._scratch
            )
            stats.iterations += its
            stats.halvings += halvings
            return d
        dk = kb - ka
        return solve_static_path(
            self.model,
            d,
            lambda lam: (ka + lam * dk, self.f_ext),
            fixed,
            self.settings,
            stats=stats,
            extra=self._extra(),
        )

    def _extra(self):
        return None if self.terrain is None else self.terrain.loads

    # ------------------------------------------------------------------ named quantities
    @property
    def x_head(self) -> float:
        """x of the head node (S = L) [m]."""
        return self.x_origin + float(self.state.d[self.model.dof(self.head, "z1")])

    @property
    def x_tail(self) -> float:
        """x of the tail node (S = 0) [m]."""
        return self.x_origin + float(self.state.d[self.model.dof(self.tail, "z1")])

    def centerline(self, per_element: int = 8) -> np.ndarray:
        """(N, 2) curve of centroids (x, z) [m], inertial frame."""
        xis = _sample_xis(per_element)
        line = np.empty((per_element * self.model.n_elements + 1, 2))
        centerline_into(self.state.d, self.x_origin, self.model.le, xis, line)
        return line

    def end_angles(self) -> tuple[float, float]:
        """Frame angles psi at tail and head [rad] (what an IMU on each foot reads)."""
        d = self.state.d
        return float(d[self.model.dof(self.tail, "psi")]), float(
            d[self.model.dof(self.head, "psi")]
        )

    def curvature_at(self, S: np.ndarray) -> np.ndarray:
        """Curvature kappa = psi' [1/m] at reference arc lengths S (strain-gauge reading)."""
        f = self.model.fields(self.state.d, per_element=16)
        return np.interp(S, f["S"], f["kappa"])

    def support_reactions(self) -> tuple[float, float]:
        """Vertical ground reactions at tail and head [N] (positive up, foot force sensors):
        the residual P - F at the prescribed z2 dofs."""
        if self.terrain is not None:  # soil line loads on each half of the body
            f, _, _ = self.terrain.loads(self.state.d, self.state.v)
            half = self.model.n_dof // 2 // 6 * 6
            fz = f[2::6]
            nodes = np.arange(len(fz)) * 6
            return float(fz[nodes < half].sum()), float(fz[nodes >= half].sum())
        f_int, _ = self.model.internal(self.state.d, self.kappa, tangent=False)
        r = f_int - self.f_ext
        return float(r[self.model.dof(self.tail, "z2")]), float(r[self.model.dof(self.head, "z2")])

    def elastic_energy(self) -> float:
        """Stored elastic energy [J]."""
        return self.model.elastic_energy(self.state.d, self.kappa)


@functools.lru_cache(maxsize=8)
def _sample_xis(per_element: int) -> np.ndarray:
    """Local sample points 0, 1/k, ..., (k - 1)/k of an element (read-only, cached)."""
    xis = np.linspace(0.0, 1.0, per_element + 1)[:-1]
    xis.flags.writeable = False
    return xis
