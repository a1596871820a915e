"""Batched GOWEC gimbal steps: the scalar fast path `gowec.fast_step` over a batch axis.

One compiled call advances N independent gyroscopes (each with its own wave components, time and
gimbal state) by n RK4 substeps each. No physics is written here: every row calls
`mf_envs.physics.gowec.fast_step` (Rios 2017 ch. 3 Eqs. 77-81, 89-93), so a row is bit-identical
to a scalar step with the same inputs. Used by `mf_envs.envs.gowec.vector`.
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.physics.gowec.kernels import fast_step_into


@numba.njit(cache=True, nogil=True)
def batch_fast_step(
    lo, hi, active, t, phi, phid, Mg, dt, n, inert, psid, amp, om, eps, k, cth, sth, two_d,
    energy, w, eta,
):  # fmt: skip
    """Advance the rows i in lo..hi - 1 with active[i] in place; rows not active are left
    untouched. Releases the GIL (blocks of rows on threads: `envs._rows.RowBlocks`).

    Shapes: active (N,) bool; t (N,) s, time at the start of the step; phi (N,) rad, phid (N,)
    rad/s, updated in place; Mg (N,) N m, generator torque held over the step; dt (N,) s
    substep, n (N,) substeps and psid (N,) rad/s of each row (its wave period and rotor speed);
    inert (5,) = (Ja, Jt, Jg1, Jg2, Jg3) kg m^2; amp, om, eps, k (N, M)
    wave components (m, rad/s, rad, rad/m) of each row, k being the slope wavenumbers k F(k r)
    (`WaveField.slope_wavenumbers`); cth, sth direction projections (0 for a still buoy);
    two_d: both slope angles. Outputs: energy (N,) J harvested in the step, w (N, 3) buoy body
    rates rad/s and eta (N,) m wave elevation at the end of the step.
    """
    work = np.empty((6, 2))  # one scratch for the block's rows (fast_step_into)
    for i in range(lo, hi):
        if not active[i]:
            continue
        p, v, e, w1, w2, w3, z = fast_step_into(
            t[i], phi[i], phid[i], Mg[i], dt[i], n[i], inert, psid[i],
            amp[i], om[i], eps[i], k[i], cth, sth, two_d, work,
        )  # fmt: skip
        phi[i], phid[i], energy[i] = p, v, e
        w[i, 0], w[i, 1], w[i, 2], eta[i] = w1, w2, w3, z


def alloc_batch(n_envs: int, n_components: int) -> dict[str, np.ndarray]:
    """Zeroed float64 batch arrays for `batch_fast_step` (names as its arguments)."""
    m = (n_envs, n_components)
    return {
        "t": np.zeros(n_envs),
        "phi": np.zeros(n_envs),
        "phid": np.zeros(n_envs),
        "amp": np.zeros(m),
        "om": np.zeros(m),
        "eps": np.zeros(m),
        "k": np.zeros(m),
        "energy": np.zeros(n_envs),
        "w": np.zeros((n_envs, 3)),
        "eta": np.zeros(n_envs),
    }
