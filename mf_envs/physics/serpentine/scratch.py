"""The scratch arrays of the serpentine beam's compiled time loop (`kernels.advance_linear`,
`kernels.run`: the step allocates nothing) and its quadrature tables."""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.physics.beam import fused
from mf_envs.physics.beam.banded import HALF_BW, N_BAND

MAX_QUAD = 6  # quadrature points per element (`beam.element.quadrature`: 4 seed, 6 sri)


@numba.njit(cache=True)
def _scratch(n_dof, n_elements):
    return (
        np.empty((n_dof, 3 * HALF_BW + 1)),
        np.empty(n_dof, np.int64),
        np.empty((n_elements, 4)),
        np.empty((n_elements, 4)),
        np.empty(n_dof),
        np.empty(n_dof),
        np.empty(n_dof),
        np.empty(n_dof),
        np.empty((5, n_dof)),
        np.empty((4, 11)),
        np.zeros((N_BAND, n_dof)),
        np.empty((n_elements, MAX_QUAD, fused.N_START)),
        np.empty((11, 11)),
        np.empty((5, n_dof)),
        np.zeros((N_BAND, n_dof)),
        np.empty((N_BAND, n_dof)),
        np.zeros(1),
    )


def make_scratch(n_dof: int, n_elements: int) -> tuple:
    """The scratch arrays of `advance_linear` / `run` for a beam of n_elements: the band
    solver's (work, pivots), kappa# at the sub-step ends, states at the sub-step ends, the
    Newton vectors, four element vectors (11,), the tangent's band, the start's strains
    (`beam.fused.start_strains`), an element matrix, the second predictor's Newton vectors
    and band, the band of (2 / dt^2) M, and the predictor's hint (1,) (the last step's choice,
    1.0 for d0 + dt v0: it orders the predictor's work, no result depends on it; the step
    allocates nothing)."""
    return _scratch(int(n_dof), int(n_elements))


def quad_tables(model) -> tuple:
    """The kernels' `quad` of a `BeamModel`: its quadrature (points, weights, rigidities), the
    dof scales of the convergence test and the shape functions tabulated at the quadrature
    points (`beam.fused.quadrature_tables`) and at the 4 Gauss points of the loads
    (`beam.fused.shape_tables`: N_z, N_psi)."""
    qxi = model.quad[0]
    return (*model.quad, model.u_scale, fused.quadrature_tables(model.le, qxi),
            *fused.shape_tables(model.le))  # fmt: skip
