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
- `beam_locking_rollup`, `beam_locking_tipload`: both elements ("seed", "sri") at slenderness
  EA L^2 / EI = 1e2, 1e4, 1e6, 1e8 (GA_s = EA): end moment 2 pi EI/L (error = max(tip gap / L,
  tip angle error [rad]), exact circle) and tip load alpha = 3 (error = |tip - Reissner BVP| / L,
  reference.reissner_tip); param h = L / n_el.
- `beam_period`: slender strip (L = 0.3 m, 20 mm x 0.5 mm, EA L^2/EI = 4.3e6, 10 elements)
  released in its first linear mode (tip 1e-4 L): relative error of the first period against
  Euler-Bernoulli, per time scheme; param dt [s].
- `beam_energy`: the same strip released from its alpha = 0.5 tip-load shape (tip 0.16 L),
  error = max |E / E0 - 1| over N periods (N = 100, quick 10), per scheme; param dt [s]. A
  scheme whose Newton fails gets a row with failed = True (the trapezoidal rule's energy
  instability on the nonlinear beam: "newmark", "generalized_alpha" at rho_inf = 1).
- `inchworm_gait`: advance per cycle of the two seed gaits (kappa0# = 13, gravity off) against the
  stress-free chord (L - chord, a quadrature), param h = L / n_el.
- `inchworm_terrain`: tail advance per cycle [L] of the seed_uniform gait (one cycle of 2 s in 40
  control steps) on dry sand (`terrain`, quasi-static) against 64 elements (quick: 32); param h.
- `inchworm_inertia`: the same gait with `inertia` (energy-momentum, rho_inf 0.8, 12 elements)
  against 256 Newmark steps per control step (quick: 64); param dt [s]. The first bending mode
  (~150 Hz) is resolved only below dt ~ 1 ms: accuracy costs time here too.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from mf_envs.benchmarks._io import accuracy_row, timed
from mf_envs.physics.beam import (
    BeamModel,
    BeamParams,
    NewmarkState,
    NewtonDivergence,
    NewtonSettings,
    TimeScheme,
    clamp_dofs,
    initial_acceleration,
    newmark_step,
    simulate_cantilever,
    solve_cantilever,
    timoshenko_cantilever_uniform,
)
from mf_envs.physics.beam.reference import (
    SEED_CANTILEVER,
    elastica_tip,
    reissner_tip,
    seed_rigidities,
)
from mf_envs.physics.beam.simulate import linear_modes, simulate_clamped
from mf_envs.physics.inchworm import (
    Inchworm,
    InchwormParams,
    chord_of_stress_free_shape,
    run_gait,
    seed_linear_kappa,
    seed_uniform_kappa,
)

ORDER = 40


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
                accuracy_row(
                    "beam_timoshenko", f"alpha={alpha:g}", c["L"] / n, err, sec, "h", elements=n
                )
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
                accuracy_row(
                    "beam_rollup", "sri element", 1.0 / n, err, sec, "h", quantity=q, elements=n
                )
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
                accuracy_row(
                    "beam_elastica", f"alpha={alpha:g}", 1.0 / n, err, sec, "h", elements=n
                )
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
                    accuracy_row(
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
            rows.append(
                accuracy_row("beam_newmark", name, float(dt), float(err), sec, "dt", failed=False)
            )
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
        rows.append(accuracy_row("beam_newton_tol", "Newton eps1 = eps2", tol, err, sec, "tol"))
    return rows


def _locking(quick: bool) -> list[dict]:
    rows = []
    for s_ in (1e2, 1e4, 1e6, 1e8):
        ref = np.array(reissner_tip(3.0, s_, s_)[:2])
        for element in ("seed", "sri"):
            for n in (5, 10, 20) if quick else (5, 10, 20, 40):
                name = f"{element} EA L^2/EI = {s_:.0e}"
                sol, sec = timed(
                    lambda n=n, e=element, s_=s_: solve_cantilever(
                        1.0, s_, s_, 1.0, n, tip_moment=2 * np.pi, element=e
                    ),
                    repeat=3,
                )
                err = max(np.linalg.norm(sol.tip_position), abs(sol.tip_angle - 2 * np.pi))
                rows.append(accuracy_row("beam_locking_rollup", name, 1 / n, float(err), sec, "h"))
                sol, sec = timed(
                    lambda n=n, e=element, s_=s_: solve_cantilever(
                        1.0, s_, s_, 1.0, n, (0.0, -3.0), element=e
                    ),
                    repeat=3,
                )
                err = float(np.linalg.norm(sol.tip_position - ref))
                rows.append(accuracy_row("beam_locking_tipload", name, 1 / n, err, sec, "h"))
    return rows


def strip(h: float = 0.0005) -> tuple[float, ...]:
    """Strip L = 0.3 m, b = 20 mm, thickness h [m] of the inchworm's material (E = 2.4 GPa,
    G = 0.96 GPa, 1390 kg/m^3): (L, EA, GAs, EI, m_A, J_3C, T1 Euler-Bernoulli [s])."""
    L, b, e, g, rho = 0.3, 0.02, 2.4e9, 0.96e9, 1390.0
    area, inertia = b * h, b * h**3 / 12
    t1 = 2 * np.pi / (1.875104068711961**2 * np.sqrt(e * inertia / (rho * area * L**4)))
    return L, e * area, g * 5 / 6 * area, e * inertia, rho * area, rho * inertia, t1


SCHEME_RUNS = (
    ("energy_momentum", 1.0),
    ("energy_momentum", 0.8),
    ("generalized_alpha", 1.0),
    ("generalized_alpha", 0.8),
    ("newmark", 1.0),
)


def _period(quick: bool) -> list[dict]:
    L, ea, gas, ei, m, j, t1 = strip()
    model = BeamModel(BeamParams(L, ea, gas, ei, 10, m, j))
    _, modes = linear_modes(model)
    d0 = model.straight() + 1e-4 * L * modes[:, 0] / modes[model.dof(-1, "z2"), 0]
    rows = []
    for scheme, rho in SCHEME_RUNS:
        for spp in (25, 50, 100) if quick else (25, 50, 100, 200):
            ts = TimeScheme(scheme, rho)
            hist, sec = timed(
                lambda ts=ts, spp=spp: simulate_clamped(model, d0, 4 * t1, t1 / spp, scheme=ts),
                repeat=1,
            )
            z, t = hist.tip_position[:, 1], hist.t
            i = np.where((z[:-1] < 0) & (z[1:] >= 0))[0]
            tc = t[i] - z[i] * (t[i + 1] - t[i]) / (z[i + 1] - z[i])
            err = abs(float(np.mean(np.diff(tc))) / t1 - 1)
            name = f"{scheme} rho_inf={rho:g}"
            rows.append(
                accuracy_row("beam_period", name, t1 / spp, err, sec, "dt", steps_per_period=spp)
            )
    return rows


def strip_release(n_periods: float, steps: int, scheme: str, rho_inf: float = 1.0):
    """The slender strip (10 elements) released from its alpha = 0.5 tip-load shape, dt = T1 /
    steps, for n_periods first periods T1 (simulate_cantilever)."""
    L, ea, gas, ei, m, j, t1 = strip()
    params, load = BeamParams(L, ea, gas, ei, 10, m, j), (0.0, -0.5 * ei / L**2)
    return simulate_cantilever(
        params, n_periods * t1, t1 / steps, load, scheme=scheme, rho_inf=rho_inf
    )


def _energy(quick: bool) -> list[dict]:
    t1, n_per = strip()[-1], 10 if quick else 100
    rows = []
    for scheme, rho in SCHEME_RUNS:
        name = f"{scheme} rho_inf={rho:g}"
        for spp in (50,) if quick else (50, 100):
            extra = {"periods": n_per, "failed": False}
            try:
                hist, sec = timed(
                    lambda s=scheme, r=rho, spp=spp: strip_release(n_per, spp, s, r), repeat=1
                )
            except NewtonDivergence as exc:
                extra.update(failed=True, note=str(exc)[:120])
                rows.append(
                    accuracy_row("beam_energy", name, t1 / spp, np.nan, np.nan, "dt", **extra)
                )
                continue
            e = hist.total_energy
            err = float(np.max(np.abs(e / e[0] - 1)))
            extra["final_energy_ratio"] = float(e[-1] / e[0])
            rows.append(accuracy_row("beam_energy", name, t1 / spp, err, sec, "dt", **extra))
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
            rows.append(
                accuracy_row("inchworm_gait", name, p.length / n, err, sec, "h", elements=n)
            )
    return rows


SOIL_SCENE = frozenset({"gravity", "terrain", "anchor_switching", "shear_deformation"})
INERTIA_SCENE = frozenset({"gravity", "shear_deformation", "anchor_switching", "inertia"})


def _uniform_cycle(sim: Inchworm, substeps: int = 1) -> float:
    """Tail advance [L] of one seed_uniform cycle (kappa0# = 13 1/m) in 40 control steps of
    0.05 s, each in at least `substeps` increments (Newmark steps with `inertia`)."""
    x0 = sim.x_tail
    for i in range(1, 41):
        kappa = np.full(sim.kappa.shape, seed_uniform_kappa(2 * np.pi * i / 40, 13.0))
        sim.actuate(kappa, 0.05, min_increments=substeps)
    return (sim.x_tail - x0) / sim.params.length


def _inchworm_effects(quick: bool) -> list[dict]:
    """The inchworm's heavier effects, against converged fine runs: `terrain` (Bekker/Janosi
    soil, quasi-static) refined in elements, and `inertia` (energy-momentum Newmark, 12
    elements) refined in the time step (increments left to the step count)."""
    rows = []
    ns, n_ref = ((4, 8, 16), 32) if quick else ((4, 8, 16, 32), 64)
    ref = _uniform_cycle(Inchworm(InchwormParams(n_elements=n_ref), SOIL_SCENE))
    for n in ns:
        sim = Inchworm(InchwormParams(n_elements=n), SOIL_SCENE)
        adv, sec = timed(lambda sim=sim: _uniform_cycle(sim), repeat=1)
        rows.append(accuracy_row("inchworm_terrain", "quasi-static on dry sand", 0.3 / n,
                                 abs(adv - ref), sec, "h", elements=n, reference_elements=n_ref,
                                 advance_per_cycle_L=adv))  # fmt: skip
    ms, m_ref = ((1, 4, 16), 64) if quick else ((1, 4, 16, 64), 256)
    p = InchwormParams(n_elements=12)

    def dynamic(m: int) -> float:
        return _uniform_cycle(Inchworm(p, INERTIA_SCENE, increment_factor=1e3), m)

    ref = dynamic(m_ref)
    for m in ms:
        adv, sec = timed(lambda m=m: dynamic(m), repeat=1)
        rows.append(accuracy_row("inchworm_inertia", "energy-momentum, rho_inf 0.8", 0.05 / m,
                                 abs(adv - ref), sec, "dt", steps_per_control_step=m,
                                 reference_dt=0.05 / m_ref, advance_per_cycle_L=adv))  # fmt: skip
    return rows


def rows(quick: bool) -> list[dict]:
    solve_cantilever(1.0, 1e4, 1e4, 1.0, 2, tip_force=(0, -1.0))  # numba warm-up
    out = []
    parts = (_timoshenko, _rollup, _elastica, _newmark, _newton_tol, _locking, _period, _energy)
    for part in (*parts, _inchworm, _inchworm_effects):
        out.extend(part(quick))
    return out


def plot(out: Path, rows_: list[dict]) -> list[Path]:
    from mf_envs.benchmarks._io import work_precision_plot

    files = []
    for scene in sorted({r["scene"] for r in rows_}):
        sub = [r for r in rows_ if r["scene"] == scene]
        files.append(work_precision_plot(out / f"accuracy_{scene}.png", sub, scene))
    return files
