"""Batched ship + gyro steps: the scalar fast path `ship_kernels.advance` over a batch axis.

One compiled call advances N independent ships (own state, attitude, packed parameters and wave
table each) by n RK4-Munthe-Kaas substeps. No physics is written here: every row calls
`mf_envs.physics.ship.kernels.advance` (as `advance_with`, one stepper scratch for all rows;
Rios 2017 ch. 3 Eqs. 98-128), so a row is bit-identical to a scalar step with the same inputs.
(`mf_envs.envs.gyro_stabilizer.vector.step_rows` does the same inside its one-call env step.)

Note on numba's on-disk cache: a cached function is invalidated only when ITS source file
changes, not when a kernel it calls does; after editing `ship_kernels`, touch this module too
(or clear `__pycache__`), or `batch_advance` keeps running the old kernel (and the vector
env stops matching the single env bit for bit).
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.frames.kernels import rk4_work, rkmk4_rwork
from mf_envs.physics.ship.kernels import N_STATE, advance_with


@numba.njit(cache=True)
def batch_advance(active, t, y, R, u, dt, n_sub, P, tab, out):
    """Advance the rows i with active[i] in place; rows not active are left untouched.

    Shapes: active (N,) bool; t (N,) s, time, updated; y (N, N_STATE) state vectors (see
    `ship.kernels`), R (N, 3, 3) attitudes (inertial <- ship), updated; u (N,) rad/s precession
    command held over the step; dt (s) substep, n_sub substeps; P (N, N_PARAMS) packed
    parameters; tab (N, L, 2) wave tables; out (N, 4) (gyro roll moment, wave moment N m, drive
    torque N m, drive power W). Observations are the env's business
    (`mf_envs.envs.gyro_stabilizer.spec`).
    """
    work, Rwork = rk4_work(N_STATE), rkmk4_rwork()
    for i in range(active.shape[0]):
        if active[i]:
            t[i] = advance_with(
                t[i], y[i], R[i], u[i], dt, n_sub, P[i], tab[i], out[i], work, Rwork
            )


def alloc_batch(n_envs: int, n_state: int, n_params: int, table_shape: tuple[int, int]):
    """Zeroed batch arrays for `batch_advance` (names as its arguments), R = identity."""
    return {
        "t": np.zeros(n_envs),
        "y": np.zeros((n_envs, n_state)),
        "R": np.tile(np.eye(3), (n_envs, 1, 1)),
        "P": np.zeros((n_envs, n_params)),
        "tab": np.zeros((n_envs, *table_shape)),
        "out": np.zeros((n_envs, 4)),
    }
