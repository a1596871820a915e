"""Work-precision of the free rigid body (Rios 2017 ch. 2): error vs wall seconds per method.

Scenes: `rigid_body_racket` (the seed's tennis racket, 5 s flight, one flip) and
`rigid_body_cuboid` (a 0.1 x 0.2 x 0.3 m cuboid spun near its intermediate axis, 20 s).
Every method of `mf_envs.physics.rigid_body.METHODS` runs over a ladder of dt; scipy's DOP853
runs over a ladder of rtol on the 12 states (H, R) as the outside reference. Errors (max over a
common 0.04 s grid): `quantity="omega"` = max |omega - omega_exact| / max |omega_exact|
against the Jacobi-elliptic solution; `quantity="R"` = max |R - R_ref| entrywise against DOP853 at
rtol 1e-13 (there is no closed form for R here). `seconds` = best of 3 wall times (numba warmed).

What the observed orders show (slopes in dt, see the PNG legend):
- omega: 4 for all three RK4 variants (RK4 on Eq. 22 decides omega; the projection does not
  change the order), 2 for splitting2, 4 for splitting4.
- R: 2 for rk4_rodrigues. The midpoint Rodrigues step (Eqs. 30-31) drops the commutator
  dt^2/12 omega0 x omega1 of the Magnus series, a local error O(dt^3), so the seed's scheme is
  second order in R however accurate H is. rk4_magnus4 adds that term and the Hermite
  correction of the quadrature and gets 4 - for the same right-hand-side evaluations (~500x
  smaller R error at dt = 0.01 s on the racket).
- Near the separatrix round-off is amplified ~4e7 during a flip (racket): no double-precision
  method goes below ~3e-8 relative there, so the finest rungs flatten (DOP853 too).
- DOP853's "order" is in rtol (param = "rtol"), roughly 1: error tracks the tolerance until
  the same floor (racket: from rtol ~1e-8 on).
- Scene `rigid_body_racket_1e4_periods` (full run only): energy / |H| drift and orthonormality
  over 67 679 s. RK4 drifts (5e-4 at dt = 0.01), the splittings keep |H| to ~1e-12 with a
  bounded O(dt^2) / O(dt^4) energy error, rk4_magnus4_proj keeps both at ~4e-16.
"""

from __future__ import annotations

import time
from functools import partial

import numpy as np
from scipy.integrate import solve_ivp

from mf_envs.benchmarks._io import timed
from mf_envs.frames import hat, orthonormality_error
from mf_envs.physics.rigid_body import (
    METHODS,
    analytic_omega,
    cuboid_inertia,
    elliptic_solution,
    simulate,
)

ORDER = 10
GRID = 0.04  # s, common comparison grid: every dt of the ladders divides it

SCENES = {
    "rigid_body_racket": (np.array([0.0185, 0.0164, 0.00121]), np.array([0.001, 5.0, 0.001]), 5.0),
    "rigid_body_cuboid": (cuboid_inertia(1.0, 0.1, 0.2, 0.3), np.array([0.01, 2.0, 0.01]), 20.0),
}


def _rhs(J: np.ndarray):
    def f(_t: float, y: np.ndarray) -> np.ndarray:
        H, R = y[:3], y[3:].reshape(3, 3)
        w = H / J
        return np.concatenate([np.cross(H, w), (R @ hat(w)).ravel()])

    return f


def dop853(J: np.ndarray, w0: np.ndarray, t: np.ndarray, rtol: float) -> tuple[np.ndarray, ...]:
    """omega (N, 3) and R (N, 3, 3) on the grid t from DOP853 at `rtol` (atol scaled to |H|)."""
    y0 = np.concatenate([J * w0, np.eye(3).ravel()])
    atol = rtol * 1e-2 * np.linalg.norm(J * w0)
    sol = solve_ivp(_rhs(J), (0, t[-1]), y0, method="DOP853", rtol=rtol, atol=atol, t_eval=t)
    return sol.y[:3].T / J, sol.y[3:].T.reshape(-1, 3, 3)


def _scene_rows(scene: str, dts: list[float], rtols: list[float]) -> list[dict]:
    J, w0, t_end = SCENES[scene]
    t = np.arange(round(t_end / GRID) + 1) * GRID
    w_exact = analytic_omega(J, w0, t)
    scale = np.max(np.abs(w_exact))
    _, R_ref = dop853(J, w0, t, 1e-13)
    rows: list[dict] = []

    def add(method, dt, param, secs, w, R):
        err_w = float(np.max(np.abs(w - w_exact)) / scale)
        err_R = float(np.max(np.abs(R - R_ref)))
        for q, e in (("omega", err_w), ("R", err_R)):
            rows.append(dict(scene=scene, method=method, dt=dt, error=e, seconds=secs,
                             quantity=q, param=param, t_end=t_end))  # fmt: skip

    for method in METHODS:
        simulate(J, w0, GRID, GRID, method)  # compile / load the numba cache outside the timing
        for dt in dts:
            k = round(GRID / dt)
            run = partial(simulate, J, w0, t_end, dt, method, save_every=k)
            tr, secs = timed(run, repeat=3)
            add(method, dt, "dt", secs, tr.omega, tr.R)
    for rtol in rtols:
        (w, R), secs = timed(dop853, J, w0, t, rtol)
        add("scipy_DOP853", rtol, "rtol", secs, w, R)
    return rows


def _drift_rows(dts: list[float], n_periods: float = 1e4) -> list[dict]:
    """Scene `rigid_body_racket_1e4_periods` (docs/design.md hard case): max relative drift of the
    energy and of |H|, and the orthonormality error of R, over 1e4 racket periods (67 679 s)."""
    J, w0, _ = SCENES["rigid_body_racket"]
    t_end = n_periods * elliptic_solution(J, w0).period
    out: list[dict] = []
    for method in METHODS:
        for dt in dts:
            t0 = time.perf_counter()
            tr = simulate(J, w0, t_end, dt, method, save_every=1000)
            secs = time.perf_counter() - t0
            e, n = tr.energy, tr.momentum_norm
            errs = {
                "energy_drift": np.max(np.abs(e / e[0] - 1)),
                "H_norm_drift": np.max(np.abs(n / n[0] - 1)),
                "R_orthonormality": orthonormality_error(tr.R),
            }
            for q, err in errs.items():
                out.append(dict(scene="rigid_body_racket_1e4_periods", method=method, dt=dt,
                                error=float(err), seconds=secs, quantity=q, param="dt",
                                t_end=t_end))  # fmt: skip
    return out


def rows(quick: bool) -> list[dict]:
    """Rows `scene, method, dt, error, seconds, quantity, param, t_end` for both scenes (and,
    without --quick, the 1e4-period drift scene: about 2 minutes more)."""
    # not finer than 5e-3: below it the RK4 variants reach the round-off floor (~3e-8 on the
    # racket, ~1e-10 on the cuboid) and flat rungs would bias the fitted order
    dts = [0.04, 0.02, 0.01, 0.005]
    if quick:
        rtols = [1e-5, 1e-7, 1e-9]
    else:
        rtols = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11]
    out: list[dict] = []
    for scene in SCENES:
        out.extend(_scene_rows(scene, dts, rtols))
    if not quick:
        out.extend(_drift_rows([0.02, 0.01]))
    return out
