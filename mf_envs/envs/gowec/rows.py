"""GOWEC-v0's compiled step and reset, written once: `step_rows` advances rows of a `Rows` batch
(the gimbal by `physics.gowec`'s kernel, then the observation `observe`, the reward and the info
values) and `reset_row` starts one. The single env is row 0 of a batch of one; the native vector
env runs the same functions on N rows (`reset_rows`: its resets from pre-drawn doubles)."""

from __future__ import annotations

import math
from collections import namedtuple

import numba
import numpy as np

from mf_envs.envs.gowec.spec import MAX_BUOY_RATE, OBS
from mf_envs.physics.gowec import Waves, buoy_rates_into
from mf_envs.physics.gowec.kernels import fast_step_into

Rows = namedtuple(
    "Rows",
    "t x Mg dt n_sub psid amp om eps k w eta steps cdt scale obs ok overspeed energy reward",
)
Rows.__doc__ = """The arrays of N rows: t (N,) s the time after the last step; x (N, 2) gimbal
angle phi (rad) and rate phi' (rad/s); Mg (N,) N m the generator torque of the step; dt (N,) s
and n_sub (N,) int64 each row's physics step and substeps; psid (N,) rad/s rotor speed; amp, om,
eps, k (N, M) the wave components (`physics.gowec.Waves`); w (N, 3) rad/s buoy rates and eta (N,)
m wave elevation at t; steps (N,) int64; cdt (N,) s control step; scale (N,) the reward's
1 / (J per step); obs (N, 6) float32; ok (N,) the state is finite; overspeed (N,) |phi'| above
the trip; energy (N,) J harvested in the step; reward (N,) energy x scale."""
Site = namedtuple("Site", "inert cth sth two_d max_rate")
Site.__doc__ = """What every row shares: inert (5,) = (Ja, Jt, Jg1, Jg2, Jg3) kg m^2; cth, sth,
two_d as `physics.gowec.Waves`; max_rate (rad/s) the overspeed trip."""


def alloc_rows(n: int, m: int) -> Rows:
    """Zeroed `Rows` of n rows with m wave components each."""
    z = [np.zeros(n) for _ in range(Rows._fields.index("amp"))]
    z[Rows._fields.index("x")] = np.zeros((n, 2))
    z[Rows._fields.index("n_sub")] = np.zeros(n, dtype=np.int64)
    return Rows(
        *z, np.zeros((n, m)), np.zeros((n, m)), np.zeros((n, m)), np.zeros((n, m)),
        np.zeros((n, 3)), np.zeros(n), np.zeros(n, dtype=np.int64), np.zeros(n), np.zeros(n),
        np.zeros((n, OBS.size), dtype=np.float32), np.ones(n, dtype=bool),
        np.zeros(n, dtype=bool), np.zeros(n), np.zeros(n),
    )  # fmt: skip


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


@numba.njit(cache=True, nogil=True)
def step_rows(lo, hi, active, b, site):
    """One control step of the active rows lo <= i < hi of `Rows` b with their torques b.Mg held
    (releases the GIL: blocks of rows on threads, `envs._rows.RowBlocks`): n_sub RK4 substeps of
    the gimbal (`physics.gowec.fast_step_into`, Rios 2017 ch. 3 Eqs. 77-81, 89-93) from t =
    steps x cdt, then the observation, the flags, the energy and the reward of each row. A row
    whose state is not finite keeps its last observation in b.obs (b.ok False)."""
    work = np.empty((6, 2))  # one scratch for the block's rows
    for i in range(lo, hi):
        if not active[i]:
            continue
        waves = Waves(b.amp[i], b.om[i], b.eps[i], b.k[i], site.cth, site.sth, site.two_d)
        t0 = b.steps[i] * b.cdt[i]
        p, v, e, w1, w2, w3, z = fast_step_into(
            t0, b.x[i, 0], b.x[i, 1], b.Mg[i], b.dt[i], b.n_sub[i], site.inert, b.psid[i],
            waves, work,
        )  # fmt: skip
        b.x[i, 0], b.x[i, 1], b.energy[i] = p, v, e
        b.w[i, 0], b.w[i, 1], b.w[i, 2], b.eta[i] = w1, w2, w3, z
        b.steps[i] += 1
        b.t[i] = b.steps[i] * b.cdt[i]
        b.reward[i] = e * b.scale[i]
        b.ok[i], b.overspeed[i] = observe(p, v, e, w1, w2, w3, site.max_rate, b.obs[i])


@numba.njit(cache=True)
def reset_row(i, phi, phid, eta, b, site):
    """Row i of `Rows` b at its start (its waves already in place): gimbal angle phi (rad) and
    rate phid (rad/s), t = 0, steps = 0, the buoy rates at t = 0, the wave elevation eta (m) and
    the observation."""
    wv, wd = np.empty(3), np.empty(3)
    b.x[i, 0], b.x[i, 1], b.t[i], b.steps[i] = phi, phid, 0.0, 0
    buoy_rates_into(0.0, b.amp[i], b.om[i], b.eps[i], b.k[i], site.cth, site.sth, site.two_d,
                    wv, wd)  # fmt: skip
    b.w[i, 0], b.w[i, 1], b.w[i, 2] = wv[0], wv[1], wv[2]
    b.eta[i] = eta
    observe(phi, phid, 0.0, wv[0], wv[1], wv[2], site.max_rate, b.obs[i])


PHI0, PHASE0 = (-0.1, 0.1), (0.0, 2.0 * math.pi)  # GOWECEnv.reset's U(low, high) draws


@numba.njit(cache=True)
def reset_rows(idx, draws, ptr, b, site):
    """GOWECEnv.reset() (regular wave, no options) for the rows idx, from pre-drawn doubles:
    draws (N, 2K) next_double()s of each row's generator, ptr (N,) the next unused one (the
    caller refills rows with ptr == 2K first). phi ~ U(PHI0), phi' = 0, the phase eps[:, 0] ~
    U(PHASE0), then `reset_row` with the elevation a cos(eps)."""
    for j in range(idx.shape[0]):
        i = idx[j]
        p = ptr[i]
        phi = PHI0[0] + (PHI0[1] - PHI0[0]) * draws[i, p]
        b.eps[i, 0] = PHASE0[0] + (PHASE0[1] - PHASE0[0]) * draws[i, p + 1]
        ptr[i] = p + 2
        reset_row(i, phi, 0.0, b.amp[i, 0] * math.cos(b.eps[i, 0]), b, site)
