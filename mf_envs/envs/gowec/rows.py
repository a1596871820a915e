"""GOWEC-v0's compiled step: the observation kernel `observe`, shared by the single env and the
native vector env (`observe_rows`), so both give the same bits, and the vector env's compiled
resets `reset_rows` (the physics step itself is `physics.gowec`'s kernel)."""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs.envs.gowec.spec import MAX_BUOY_RATE
from mf_envs.physics.gowec import buoy_rates_into


@numba.njit(cache=True)
def observe(phi, phid, energy, w1, w2, w3, max_rate, out):
    """The observation (OBS order) into the float32 row `out`, rates clipped to their bounds;
    returns (state finite, overspeed |phi'| > max_rate). `out` is untouched if not finite."""
    if not (math.isfinite(phi) and math.isfinite(phid) and math.isfinite(energy)):
        return False, False
    b = MAX_BUOY_RATE
    out[0] = math.sin(phi)
    out[1] = math.cos(phi)
    out[2] = min(max(phid, -max_rate), max_rate)
    out[3] = min(max(w1, -b), b)
    out[4] = min(max(w2, -b), b)
    out[5] = min(max(w3, -b), b)
    return True, abs(phid) > max_rate


@numba.njit(cache=True)
def observe_rows(active, phi, phid, energy, w, max_rate, out, ok, overspeed):
    """`observe` for every active row i (arrays (N,), w (N, 3), out (N, 6)); ok/overspeed (N,)."""
    for i in range(phi.shape[0]):
        if active[i]:
            ok[i], overspeed[i] = observe(
                phi[i], phid[i], energy[i], w[i, 0], w[i, 1], w[i, 2], max_rate, out[i]
            )


PHI0, PHASE0 = (-0.1, 0.1), (0.0, 2.0 * math.pi)  # GOWECEnv.reset's U(low, high) draws


@numba.njit(cache=True)
def reset_rows(idx, draws, ptr, phi, phid, t, steps, amp, om, eps, k, cth, sth, two_d, w, eta,
               max_rate, obs):  # fmt: skip
    """GOWECEnv.reset() (regular wave, no options) for the rows idx, from pre-drawn doubles.

    draws (N, 2K) next_double()s of each row's generator, ptr (N,) the next unused one (the
    caller refills rows with ptr == 2K first). Writes phi ~ U(-0.1, 0.1) rad, phi' = 0, the
    phase eps[:, 0] ~ U(0, 2 pi), t = 0, steps = 0, the buoy rates w (N, 3) at t = 0, eta (N,)
    m and the float32 observation rows, with the single env's own kernels and expressions.
    """
    wv = np.empty(3)
    wd = np.empty(3)
    for j in range(idx.shape[0]):
        i = idx[j]
        p = ptr[i]
        phi[i] = PHI0[0] + (PHI0[1] - PHI0[0]) * draws[i, p]
        eps[i, 0] = PHASE0[0] + (PHASE0[1] - PHASE0[0]) * draws[i, p + 1]
        ptr[i] = p + 2
        phid[i], t[i], steps[i] = 0.0, 0.0, 0
        buoy_rates_into(0.0, amp[i], om[i], eps[i], k[i], cth, sth, two_d, wv, wd)
        w[i, 0], w[i, 1], w[i, 2] = wv[0], wv[1], wv[2]
        eta[i] = amp[i, 0] * math.cos(eps[i, 0])
        observe(phi[i], 0.0, 0.0, wv[0], wv[1], wv[2], max_rate, obs[i])
