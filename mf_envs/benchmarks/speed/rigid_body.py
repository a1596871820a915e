"""Throughput of the free-rigid-body integrators against a plain-numpy loop of the seed's scheme.

Case `rigid_body_racket`: the tennis racket (ch. 2), 20 000 steps of dt = 2.5e-4 s (5 s flight).
Reference: the same seed scheme (RK4 on H, Eq. 22; midpoint Rodrigues, Eqs. 29-31) written as
an ordinary Python loop over numpy arrays (np.cross, mf_envs.frames.exp_so3), run in the same
process right before. `ratio` = numba steps/s over the reference's steps/s (>= 10
for the seed scheme). Every other method is listed against the same reference.
"""

from __future__ import annotations

import time

import numpy as np

from mf_envs.frames import exp_so3
from mf_envs.physics.rigid_body import METHODS, simulate

ORDER = 10
J = np.array([0.0185, 0.0164, 0.00121])
W0 = np.array([0.001, 5.0, 0.001])
N_STEPS = 20_000
DT = 5.0 / N_STEPS


def numpy_seed_scheme(J: np.ndarray, w0: np.ndarray, dt: float, n_steps: int):
    """The seed's scheme as a plain numpy loop: H (n+1, 3), R (n+1, 3, 3)."""
    Jinv = 1.0 / J

    def f(H):
        return np.cross(H, Jinv * H)

    H = np.empty((n_steps + 1, 3))
    R = np.empty((n_steps + 1, 3, 3))
    H[0], R[0] = J * w0, np.eye(3)
    for n in range(n_steps):
        h = H[n]
        k1 = f(h)
        k2 = f(h + 0.5 * dt * k1)
        k3 = f(h + 0.5 * dt * k2)
        k4 = f(h + dt * k3)
        H[n + 1] = h + dt / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4)
        R[n + 1] = R[n] @ exp_so3(0.5 * dt * Jinv * (h + H[n + 1]))
    return H, R


def rows(quick: bool) -> list[dict]:
    """One row per method: numba steps/s vs the plain-numpy seed scheme, side by side."""
    n_ref = N_STEPS  # the acceptance figure is at 20 000 steps, --quick included (~4 s)
    t0 = time.perf_counter()
    H_ref, R_ref = numpy_seed_scheme(J, W0, DT, n_ref)
    ref_rate = n_ref / (time.perf_counter() - t0)
    out = []
    for method in METHODS:
        simulate(J, W0, DT, DT, method)  # compile / load the cache outside the timing
        best = np.inf
        for _ in range(3):
            t0 = time.perf_counter()
            tr = simulate(J, W0, N_STEPS * DT, DT, method)
            best = min(best, time.perf_counter() - t0)
        if method == "rk4_rodrigues":  # same scheme: the two loops agree to round-off
            assert np.allclose(tr.R[n_ref], R_ref[-1], atol=1e-9), "numba and numpy loops differ"
            assert np.allclose(tr.H[n_ref], H_ref[-1], rtol=0, atol=1e-12)
        rate = N_STEPS / best
        out.append(dict(case="rigid_body_racket", variant=f"numba {method}", steps_per_s=rate,
                        reference="plain numpy loop (rk4_rodrigues)",
                        reference_steps_per_s=ref_rate, ratio=rate / ref_rate,
                        steps=N_STEPS))  # fmt: skip
    return out
