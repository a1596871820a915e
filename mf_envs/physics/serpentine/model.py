"""The serpentine robot of Rios 2017 §4.5 II on the active C1 beam: a planar beam lying in the
ground plane (x, y), gravity along -z pressing it on the ground with p = m_A g per length, the
belly friction of `friction` as a distributed load, muscles as an active curvature kappa#(S, t)
(`gait`), stepped by the energy-momentum scheme of `kernels`.

::

    y
    |   tail S = 0  ~~~~~~~~~~~~~~~~~~~~>  head S = L     (straight reference along +x)
    +---- x        ground friction f(S) = -p [mu_t (u.t) t + mu_n (u.n) n]

`Serpentine.simulate` returns a `SnakeHistory` (states every `every` steps) with the centre of
mass, linear and angular momentum and the energies computed from the discrete fields.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from mf_envs._validate import check_int, check_positive, check_range
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam import fields
from mf_envs.physics.beam.banded import band_matvec
from mf_envs.physics.beam.solver import BeamModel, BeamParams, NewtonDivergence
from mf_envs.physics.constants import G
from mf_envs.physics.serpentine import kernels
from mf_envs.physics.serpentine.friction import BellyFriction, assemble_ground
from mf_envs.physics.serpentine.gait import WaveGait, gait_for, gait_tables


def rod_params(
    length: float,
    radius: float,
    youngs_modulus: float,
    shear_modulus: float,
    density: float,
    n_elements: int,
    shear_factor: float = 27.0 / 28.0,
) -> BeamParams:
    """BeamParams of a solid circular rod: EA = E A, GA_s = alpha G A, EI = E pi r^4 / 4,
    m_A = rho A, J_3C = rho I (alpha = 27/28 as PyElastica's CosseratRod.straight_rod)."""
    for name, val in (
        ("length", length),
        ("radius", radius),
        ("youngs_modulus", youngs_modulus),
        ("shear_modulus", shear_modulus),
        ("density", density),
        ("shear_factor", shear_factor),
    ):
        check_positive(name, val)
    area = np.pi * radius**2
    inertia = np.pi * radius**4 / 4.0
    return BeamParams(
        length=float(length),
        EA=float(youngs_modulus * area),
        GAs=float(shear_factor * shear_modulus * area),
        EI=float(youngs_modulus * inertia),
        n_elements=check_int("n_elements", n_elements, low=1, high=10_000),
        mass_per_length=float(density * area),
        rotary_inertia=float(density * inertia),
    )


@dataclass
class SnakeHistory:
    """States every `every` steps: t (N,) [s]; d, v (N, n_dof); the model; Newton iterations."""

    t: np.ndarray
    d: np.ndarray
    v: np.ndarray
    model: BeamModel
    iterations: int
    extras: dict = field(default_factory=dict)

    def com(self) -> np.ndarray:
        """(N, 2) centre of mass [m] (uniform m_A: int z dS / L, 4-point Gauss)."""
        return (
            np.array([_integrate(self.model, d, None)[0] for d in self.d])
            / self.model.params.length
        )

    def momentum(self) -> tuple[np.ndarray, np.ndarray]:
        """Linear momentum (N, 2) [kg m/s] and angular momentum about the origin (N,) [kg m^2/s]:
        int m_A z_dot dS, int (m_A z x z_dot + J_3C psi_dot) dS."""
        out = [_integrate(self.model, d, v) for d, v in zip(self.d, self.v)]
        return np.array([o[1] for o in out]), np.array([o[2] for o in out])

    def kinetic_energy(self) -> np.ndarray:
        """(N,) v^T M v / 2 [J]."""
        return np.array([0.5 * v @ band_matvec(self.model.mass, v) for v in self.v])

    def mean_speed(self, t_start: float, t_end: float) -> float:
        """|com(t_end) - com(t_start)| / (t_end - t_start) [m/s] (nearest stored samples)."""
        i, j = (int(np.argmin(np.abs(self.t - x))) for x in (t_start, t_end))
        if j <= i:
            raise ValueError("t_end: must lie after t_start within the history")
        c = self.com()
        return float(np.linalg.norm(c[j] - c[i]) / (self.t[j] - self.t[i]))


def _integrate(model: BeamModel, d: np.ndarray, v: np.ndarray | None):
    """(int z dS, int m_A z_dot dS, int m_A z x z_dot + J psi_dot dS) by 4-point Gauss."""
    pos = fields.evaluate_fields(d, model.le, el.GAUSS_XI)[0]
    w = el.GAUSS_W[None, :] * model.le[:, None]
    zint = np.einsum("eg,egk->k", w, pos)
    if v is None:
        return zint, None, None
    p = model.params
    vel = fields.evaluate_fields(v, model.le, el.GAUSS_XI)[0]  # N_z v (linear in the dofs)
    psi_dot = fields.evaluate_fields(v, model.le, el.GAUSS_XI)[1]
    mom = p.mass_per_length * np.einsum("eg,egk->k", w, vel)
    cross = pos[..., 0] * vel[..., 1] - pos[..., 1] * vel[..., 0]
    ang = float(np.sum(w * (p.mass_per_length * cross + p.rotary_inertia * psi_dot)))
    return zint, mom, ang


class Serpentine:
    """A serpentine beam (module docstring): beam params, ground law, gait (None: passive),
    gravity [m/s^2] normal to the ground, material_damping: the Kelvin-Voigt retardation time
    tau [s] of the body (every strain's stress gains EA tau d(eps)/dt; `kernels`; 0: elastic)."""

    def __init__(
        self,
        params: BeamParams,
        ground: BellyFriction | None = None,
        gait: WaveGait | None = None,
        gravity: float = G,
        material_damping: float = 0.0,
    ) -> None:
        if params.mass_per_length <= 0.0:
            raise ValueError("mass_per_length: a crawling body needs mass, got 0")
        self.model = BeamModel(params)
        self.ground = ground if ground is not None else BellyFriction()
        self.gravity = float(check_range("gravity", gravity, 0.0, 1e3))
        self.material_damping = float(check_range("material_damping", material_damping, 0.0, 10.0))
        self.gait = gait_for(gait, self.model.gauss_S.shape)

    @property
    def normal_load(self) -> float:
        """p = m_A g [N/m]."""
        return self.model.params.mass_per_length * self.gravity

    def ground_force(self, d: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, float]:
        """Nodal force (n_dof,) of the ground at (d, v) and its power [W]."""
        f = np.zeros(self.model.n_dof)
        ab = np.zeros((21, self.model.n_dof))
        m = self.model
        args = (m.le, self.normal_load, m.params.mass_per_length, self.ground.packed())
        power = assemble_ground(d, v, *args, f, ab, 0.0, 0.0)
        return f, float(power)

    def simulate(
        self,
        t_end: float,
        dt: float,
        every: int = 1,
        theta: float = 1.0,
        d0: np.ndarray | None = None,
        v0: np.ndarray | None = None,
        tol: float = 1e-10,
        max_iter: int = 12,
        max_halvings: int = 6,
    ) -> SnakeHistory:
        """Step from (d0, v0) (default: straight along +x at rest) at t = 0 to t_end [s] with
        steps dt [s]; theta in [1/2, 1] is where the ground force is taken (kernels docstring)."""
        check_range("theta", theta, 0.5, 1.0)
        m = self.model
        ground = (self.normal_load, m.params.mass_per_length, self.ground.packed())
        body = kernels.Body(m.mass, m.le, kernels.quad_tables(m), ground, float(theta),
                            float(check_positive("tol", tol)), int(max_iter), int(max_halvings),
                            m.params.EI, self.material_damping)  # fmt: skip
        return run_history(kernels, m, body, self.gait, (d0, v0), (t_end, dt, every))


def run_history(kernels: Any, model: BeamModel, body: Any, gait: WaveGait, start: tuple,
                steps: tuple) -> SnakeHistory:  # fmt: skip
    """`kernels.run` (the serpentine's or the swimmer's compiled run) of the `stepping.Body` body
    under the gait from start = (d0, v0) (None: straight along +x, at rest), steps = (t_end [s],
    dt [s], every): the states and the muscles' work every `every` steps; NewtonDivergence
    naming dt if even 2^max_halvings sub-steps fail."""
    t_end, dt, every = steps
    check_positive("t_end", t_end)
    check_positive("dt", dt)
    every = check_int("every", every, low=1)
    d0, v0 = start
    d = model.straight() if d0 is None else np.array(d0, float)
    v = np.zeros(model.n_dof) if v0 is None else np.array(v0, float)
    for name, arr in (("d0", d), ("v0", v)):
        if arr.shape != (model.n_dof,) or not np.all(np.isfinite(arr)):
            raise ValueError(f"{name}: need {model.n_dof} finite values")
    n_steps = int(round(t_end / dt))
    rows = n_steps // every + 1
    d_out, v_out = np.zeros((rows, model.n_dof)), np.zeros((rows, model.n_dof))
    work_out = np.zeros((rows, 2))
    its, failed = kernels.run(d, v, float(dt), n_steps, every, body, gait_tables(gait),
                              kernels.make_scratch(model.n_dof, model.n_elements), d_out, v_out,
                              work_out)  # fmt: skip
    if failed >= 0:
        raise NewtonDivergence(
            f"dt: Newton failed at step {failed} (t = {failed * dt:.6g} s) even after "
            f"{2**body.max_halvings} sub-steps"
        )
    t_out = np.arange(rows) * every * float(dt)
    return SnakeHistory(t_out, d_out, v_out, model, int(its), {"muscle_work": work_out})
