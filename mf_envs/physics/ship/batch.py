"""Batch arrays of N independent ships + gyros (`alloc_batch`), the layout the native vector env
(`mf_envs.envs.gyro_stabilizer.vector`) steps row by row with the scalar kernel
`mf_envs.physics.ship.kernels.advance_with` (Rios 2017 ch. 3 Eqs. 98-128), so a row is
bit-identical to a single env's step with the same inputs.
"""

from __future__ import annotations

import numpy as np


def alloc_batch(n_envs: int, n_state: int, n_params: int, table_shape: tuple[int, int]):
    """Zeroed batch arrays, R = identity: t (N,) s, time; y (N, n_state) state vectors (see
    `ship.kernels`); R (N, 3, 3) attitudes (inertial <- ship); P (N, n_params) packed
    parameters; tab (N, L, 2) wave tables; out (N, 6) (`kernels.N_OUT`: gyro roll moment, wave
    moment N m, drive torque N m, drive power W, mount moment per unit N m, rotor power W)."""
    return {
        "t": np.zeros(n_envs),
        "y": np.zeros((n_envs, n_state)),
        "R": np.tile(np.eye(3), (n_envs, 1, 1)),
        "P": np.zeros((n_envs, n_params)),
        "tab": np.zeros((n_envs, *table_shape)),
        "out": np.zeros((n_envs, 6)),
    }
