"""The anguilliform swimmer of Rios 2017 §4.5 I on the active C1 beam: a planar, neutrally
buoyant beam swimming in the horizontal plane (x, y) of still water, Taylor's resistive and
Lighthill's reactive forces of `fluid` as its distributed load n_hat(S, t) (Eq. 40, m_hat_3 = 0),
muscles as an active curvature kappa#(S, t) (`serpentine.gait`), stepped by `kernels`.

::

    y
    |   tail S = 0  ~~~~~~~~~~~~~~~~~~~~>  head S = L     (straight reference along +x)
    +---- x        water: f = -(g_t(v_t) t + g_n(v_n) n) - d/dt (m_a w n), F_tail at S = 0

`Swimmer.simulate` returns a `serpentine.SnakeHistory` (the same fields: centre of mass, momenta,
energies) with the muscles' work in `extras`.
"""

from __future__ import annotations

import numpy as np

from mf_envs._validate import check_positive, check_range
from mf_envs.physics.beam.banded import HALF_BW
from mf_envs.physics.beam.fused import quadrature_tables
from mf_envs.physics.beam.solver import BeamModel, BeamParams
from mf_envs.physics.serpentine.gait import WaveGait, gait_for
from mf_envs.physics.serpentine.model import SnakeHistory, run_history
from mf_envs.physics.serpentine.stepping import Body
from mf_envs.physics.swimmer import kernels
from mf_envs.physics.swimmer.fluid import Water, added_momentum, assemble_water, shape_tables


class Swimmer:
    """A swimming beam (module docstring): beam params, the water, the gait (None: passive)."""

    def __init__(self, params: BeamParams, water: Water | None = None,
                 gait: WaveGait | None = None) -> None:  # fmt: skip
        if params.mass_per_length <= 0.0:
            raise ValueError("mass_per_length: a swimming body needs mass, got 0")
        self.model = BeamModel(params)
        self.water = water if water is not None else Water()
        self.gait = gait_for(gait, self.model.gauss_S.shape)
        self.tables = shape_tables(self.model.le)
        qxi, qw, stiff = self.model.quad
        tab = quadrature_tables(self.model.le, qxi)
        self.quad = (qw, stiff, self.model.u_scale, tab)  # the kernels' `quad`

    @property
    def packed(self) -> tuple:
        """(N_z table, N_psi table, packed law): the kernels' `water` argument."""
        return (*self.tables, self.water.packed())

    def water_force(self, d: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, float]:
        """Nodal resistive + tail force (n_dof,) at (d, v) [N] and its power [W]."""
        f = np.zeros(self.model.n_dof)
        ab = np.zeros((2 * HALF_BW + 1, self.model.n_dof))
        nzt, npt, law = self.packed
        power = assemble_water(d, v, self.model.le, nzt, npt, law, f, ab, 0.0, 0.0)
        return f, float(power)

    def water_momentum(self, d: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, float]:
        """Nodal momentum of the entrained water (n_dof,) [kg m/s] and its kinetic energy [J]."""
        p = np.zeros(self.model.n_dof)
        ab = np.zeros((2 * HALF_BW + 1, self.model.n_dof))
        nzt, npt, _ = self.tables + (None,)
        m_a = self.water.added_mass
        energy = added_momentum(d, v, self.model.le, nzt, npt, m_a, p, ab, 0.0, 0.0)
        return p, float(energy)

    def simulate(self, t_end: float, dt: float, every: int = 1, theta: float = 0.5,
                 d0: np.ndarray | None = None, v0: np.ndarray | None = None, tol: float = 1e-10,
                 max_iter: int = 12, max_halvings: int = 6,
                 stress_theta: float = 0.5) -> SnakeHistory:  # fmt: skip
        """Step from (d0, v0) (default: straight along +x at rest) at t = 0 to t_end [s] with
        steps dt [s]; theta in [1/2, 1] is where the resistive force is taken, stress_theta in
        [1/2, 1] where the stresses are (`kernels`)."""
        th = (
            check_range("theta", theta, 0.5, 1.0),
            check_range("stress_theta", stress_theta, 0.5, 1.0),
        )
        m, tol = self.model, float(check_positive("tol", tol))
        body = Body(m.mass, m.le, self.quad, self.packed, tuple(map(float, th)), tol,
                    int(max_iter), int(max_halvings), m.params.EI, 0.0)  # fmt: skip
        return run_history(kernels, m, body, self.gait, (d0, v0), (t_end, dt, every))
