"""Work-precision of the active C1 beam (Rios 2017 ch. 4): error vs wall seconds.

Scenes (the `dt` column is the refinement parameter named in `param`):
- `beam_timoshenko`: the seed's cantilever (E = 30e6 psi, G = 12e6 psi, q0 = 200 lb/in; our
  L = 100 in, b = 1 in, h = 10 in) under uniform load, actuation alpha = 0 and 1 (Eqs. 65-67);
  error = |v_tip - v_Eq65| / |v_passive tip|, param h = L / n_el. The geometrically exact model
  differs from the linear theory by ~1e-4 (rotations ~0.013 rad): the curve floors there.
- `beam_rollup`: end moment 2 pi EI / L, exact circle: quantity "tip position / L" and
  "tip angle [rad]"; param h.
- `beam_elastica`: tip-load cantilever at alpha = P L^2 / EI = 1, 2, 5, 10 against the elastica
  by scipy solve_bvp (tol 1e-10; agrees with Mattiasson 1981's table to its 5 digits); param h.
- `beam_newmark`: free vibration of a clamped beam released from rest in its first linear mode
  at tip amplitude 0.2 L (nonlinear), Newmark beta = 1/4, gamma = 1/2 (8 elements); error =
  max |tip z - reference| over 2 periods / 0.2 L against dt/16 of the finest step; param dt
  (order 2 expected: the trapezoidal rule's period error is (omega dt)^2 / 12).
- `beam_newton_tol`: Newton eps1 = eps2 = tol on the alpha = 5 elastica (24 elements), error against
  the tol = 1e-12 solution; param tol.
- `inchworm_gait`: advance per cycle of the two seed gaits (kappa0# = 13, gravity off) against the
  stress-free chord (L - chord, a quadrature), param h = L / n_el.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mf_envs.benchmarks._io import timed
from mf_envs.physics.beam import (
    BeamModel,
    BeamParams,
    NewmarkState,
    NewtonDivergence,
    NewtonSettings,
    clamp_dofs,
    initial_acceleration,
    newmark_step,
    solve_cantilever,
    timoshenko_cantilever_uniform,
)
from mf_envs.physics.beam.reference import SEED_CANTILEVER, elastica_tip, seed_rigidities
from mf_envs.physics.inchworm import (
    Inchworm,
    InchwormParams,
    chord_of_stress_free_shape,
    run_gait,
    seed_linear_kappa,
    seed_uniform_kappa,
)

ORDER = 40


def _row(scene, method, h, err, sec, param, **extra):
    return {
        "scene": scene,
        "method": method,
        "dt": h,
        "error": err,
        "seconds": sec,
        "param": param,
        **extra,
    }


def _timoshenko(quick: bool) -> list[dict]:
    ea, gas, ei = seed_rigidities()
    c = SEED_CANTILEVER
    v_p = timoshenko_cantilever_uniform(np.array([c["L"]]), c["L"], ei, gas, c["q0"])[0][0]
    rows = []
    for alpha in (0.0, 1.0):
        v_ref = timoshenko_cantilever_uniform(
            np.array([c["L"]]), c["L"], ei, gas, c["q0"], alpha * c["kappa0"]
        )[0][0]
        for n in (1, 2, 4) if quick else (1, 2, 4, 8, 16):
            sol, sec = timed(
                lambda n=n, alpha=alpha: solve_cantilever(
                    c["L"],
                    ea,
                    gas,
                    ei,
                    n,
                    distributed_load=(0, -c["q0"]),
                    kappa_sharp=alpha * c["kappa0"],
                ),
                repeat=2,
            )
            err = abs(sol.tip_position[1] - v_ref) / abs(v_p)
            rows.append(
                _row("beam_timoshenko", f"alpha={alpha:g}", c["L"] / n, err, sec, "h", elements=n)
            )
    return rows


def _rollup(quick: bool) -> list[dict]:
    rows = []
    for n in (4, 8, 16) if quick else (4, 8, 16, 32, 64):
        sol, sec = timed(
            lambda n=n: solve_cantilever(1.0, 1e4, 1e4, 1.0, n, tip_moment=2 * np.pi), repeat=2
        )
        for q, err in (
            ("tip position / L", np.linalg.norm(sol.tip_position)),
            ("tip angle [rad]", abs(sol.tip_angle - 2 * np.pi)),
        ):
            rows.append(
                _row("beam_rollup", "C1 element", 1.0 / n, err, sec, "h", quantity=q, elements=n)
            )
    return rows


def _elastica(quick: bool) -> list[dict]:
    rows = []
    for alpha in (1.0, 2.0, 5.0, 10.0):
        x, y, _ = elastica_tip(alpha)
        for n in (4, 8, 16) if quick else (4, 8, 16, 32, 64):
            sol, sec = timed(
                lambda n=n, a=alpha: solve_cantilever(1.0, 1e7, 1e7, 1.0, n, tip_force=(0, -a)),
                repeat=2,
            )
            err = float(np.linalg.norm(sol.tip_position - [x, y]))
            rows.append(
                _row("beam_elastica", f"alpha={alpha:g}", 1.0 / n, err, sec, "h", elements=n)
            )
    return rows


def _vibration(dt: float, t_end: float, gamma: float = 0.5) -> np.ndarray:
    """Tip z(t) of a clamped beam released from rest from its static deflection under a uniform
    load (tip ~0.1 L, close to the first mode and free of axial transients)."""
    p = BeamParams(1.0, 1e4, 1e4, 1.0, 8, mass_per_length=1.0, rotary_inertia=1e-4)
    model = BeamModel(p)
    fixed = np.zeros(model.n_dof, bool)
    fixed[clamp_dofs(model, 0)] = True
    kap, zero = np.zeros(model.gauss_S.shape), np.zeros(model.n_dof)
    d0 = solve_cantilever(1.0, 1e4, 1e4, 1.0, 8, distributed_load=(0, -0.8)).d
    st = NewmarkState(d0, zero.copy(), initial_acceleration(model, d0, kap, zero, fixed))
    out = []
    beta = (gamma + 0.5) ** 2 / 4
    for _ in range(round(t_end / dt)):
        st = newmark_step(model, st, dt, kap, zero, fixed, beta=beta, gamma=gamma)
        out.append(st.d[model.dof(-1, "z2")])
    return np.array(out)


def _newmark(quick: bool) -> list[dict]:
    period = 2 * np.pi / 1.87510407**2
    t_end = 2 * period
    dts = period / np.array([10, 20, 40] if quick else [10, 20, 40, 80, 160])
    rows = []
    for gamma, name in ((0.5, "Newmark 1/4 1/2 (seed)"), (0.6, "Newmark gamma=0.6 (damped)")):
        ref = _vibration(dts[-1] / 16, t_end, gamma)
        for dt in dts:
            try:
                z, sec = timed(lambda dt=dt, gamma=gamma: _vibration(dt, t_end, gamma), repeat=1)
            except NewtonDivergence:  # the energy instability of the trapezoidal rule
                rows.append(
                    _row(
                        "beam_newmark",
                        name,
                        float(dt),
                        float("nan"),
                        float("nan"),
                        "dt",
                        failed=True,
                    )
                )
                continue
            k = int(round(dt / (dts[-1] / 16)))
            err = np.max(np.abs(z - ref[k - 1 :: k][: len(z)])) / 0.1
            rows.append(_row("beam_newmark", name, float(dt), float(err), sec, "dt", failed=False))
    return rows


def _newton_tol(quick: bool) -> list[dict]:
    def solve(tol):
        return solve_cantilever(
            1.0, 1e5, 1e5, 1.0, 24, tip_force=(0, -5.0), settings=NewtonSettings(tol, tol, 8, 14)
        )

    ref = solve(1e-12).tip_position
    rows = []
    for tol in (1e-2, 1e-4, 1e-6) if quick else (1e-2, 1e-3, 1e-4, 1e-6, 1e-8, 1e-10):
        sol, sec = timed(lambda tol=tol: solve(tol), repeat=2)
        err = float(np.linalg.norm(sol.tip_position - ref))
        rows.append(_row("beam_newton_tol", "Newton eps1 = eps2", tol, err, sec, "tol"))
    return rows


def _inchworm(quick: bool) -> list[dict]:
    rows = []
    gaits = {
        "seed_uniform": (
            lambda S, t: np.full(S.shape, seed_uniform_kappa(t, 13.0)),
            lambda s, L: np.full(s.shape, -13.0),
        ),
        "seed_linear": (
            lambda S, t, L=0.3: seed_linear_kappa(S, t, 13.0, L),
            lambda s, L: -13.0 * (0.2 + 0.8 * s / L),
        ),
    }
    for name, (fn, peak) in gaits.items():
        for n in (4, 8, 16) if quick else (4, 8, 16, 32):
            p = InchwormParams(n_elements=n)
            exact = p.length - chord_of_stress_free_shape(
                lambda s, p=p, peak=peak: peak(s, p.length), p.length
            )
            hist, sec = timed(
                lambda p=p, fn=fn: run_gait(
                    Inchworm(p, effects=frozenset({"anchor_switching"})), fn, 1, 40
                ),
                repeat=1,
            )
            err = abs(hist.x_tail[-1] - hist.x_tail[0] - exact) / p.length
            rows.append(_row("inchworm_gait", name, p.length / n, err, sec, "h", elements=n))
    return rows


def rows(quick: bool) -> list[dict]:
    solve_cantilever(1.0, 1e4, 1e4, 1.0, 2, tip_force=(0, -1.0))  # numba warm-up
    out = []
    for part in (_timoshenko, _rollup, _elastica, _newmark, _newton_tol, _inchworm):
        out.extend(part(quick))
    return out


def plot(out: Path, rows_: list[dict]) -> list[Path]:
    from mf_envs.benchmarks._io import work_precision_plot

    files = []
    for scene in sorted({r["scene"] for r in rows_}):
        sub = [r for r in rows_ if r["scene"] == scene]
        files.append(work_precision_plot(out / f"accuracy_{scene}.png", sub, scene))
    return files
