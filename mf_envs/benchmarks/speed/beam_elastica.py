"""The active C1 beam side by side with PyElastica 1.0, plus Inchworm-v0 throughput.

Rows (`steps_per_s` = solves or env steps per wall second; `ratio` = ours / reference):
- `static_cantilever`: a clamped rod (L = 1 m, r = 2 cm, E = 1 MPa, G = E/3, rho = 1000 kg/m^3)
  under a dead tip load at alpha = P L^2 / EI = 2, same EA, alpha_c G A (alpha_c = 27/28, as
  PyElastica uses) and EI in both codes. Reference tip: our beam with 64 elements (the two codes
  agree as PyElastica is refined: its error halves with each doubling of n, first order, towards
  our value). Ours: Newton + load stepping with the fewest elements whose tip is within 1e-4 L.
  PyElastica: PositionVerlet with AnalyticalLinearDamper (uniform constant 2 omega_1), load ramped
  over a quarter period, integrated in chunks of 1/omega_1 until the tip moves < 1e-8 m per chunk
  (its static state); wall time after numba warm-up. PyElastica at n = 50..200 stalls at 1e-2..
  3e-3 L (first order), so two comparisons are given: at equal accuracy (our cheapest mesh that
  matches PyElastica's finest error) and at 1e-4 L, where the PyElastica time is EXTRAPOLATED
  from its measured error and time-vs-n slopes (marked in `variant`).
- `inchworm_vs_pendulum`: Inchworm-v0 steps/s (default effects) with the seed_uniform gait and
  with uniform random actions (big curvature jumps: more increments per step) against Gymnasium
  Pendulum-v1 steps/s with random actions, run back to back.
- `beam_step_vs_elements`: one quasi-static actuation increment of the inchworm beam
  (kappa# -13 -> -12.8 1/m, Newton from the previous state) vs n_elements; reference n = 4.
  Banded assembly and solve: the cost is expected linear in n (see the PNG's fitted slope).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from mf_envs._files import save_figure
from mf_envs.benchmarks._io import timed
from mf_envs.envs.inchworm.task import DECLARATION
from mf_envs.physics.beam import solve_cantilever

ENV_ID = DECLARATION.env_id

L, R, E, RHO, ALPHA = 1.0, 0.02, 1e6, 1000.0, 2.0
G = E / 3.0
AREA, INERTIA = np.pi * R**2, np.pi * R**4 / 4
EA, GAS, EI = E * AREA, 27 / 28 * G * AREA, E * INERTIA
P = ALPHA * EI / L**2
TOL = 1e-4


def _ours(n: int) -> tuple[np.ndarray, float]:
    def go():
        return solve_cantilever(L, EA, GAS, EI, n, tip_force=(0.0, -P))

    tip = go().tip_position
    return tip, timed(go, repeat=5)[1]


def _elastica(n: int) -> tuple[np.ndarray, float]:
    """PyElastica damped to rest; returns the static tip and the wall time."""
    import elastica as ea

    class Sim(ea.BaseSystemCollection, ea.Constraints, ea.Forcing, ea.Damping):
        pass

    sim = Sim()
    rod = ea.CosseratRod.straight_rod(
        n,
        np.zeros(3),
        np.array([1.0, 0, 0]),
        np.array([0, 1.0, 0]),
        L,
        R,
        RHO,
        youngs_modulus=E,
        shear_modulus=G,
    )
    sim.append(rod)
    dt = 0.2 * (L / n) * np.sqrt(RHO / E)
    omega1 = 3.516 * np.sqrt(EI / (RHO * AREA * L**4))
    sim.dampen(rod).using(
        ea.AnalyticalLinearDamper, uniform_damping_constant=2 * omega1, time_step=dt
    )
    sim.constrain(rod).using(
        ea.OneEndFixedBC, constrained_position_idx=(0,), constrained_director_idx=(0,)
    )
    sim.add_forcing_to(rod).using(
        ea.EndpointForces, np.zeros(3), np.array([0.0, -P, 0.0]), ramp_up_time=0.5 * np.pi / omega1
    )
    sim.finalize()
    stepper, t, chunk = ea.PositionVerlet(), 0.0, 1.0 / omega1
    prev = np.full(2, np.inf)
    t0 = time.perf_counter()
    for _ in range(400):
        t = ea.integrate(
            stepper, sim, chunk, int(round(chunk / dt)), restart_time=t, progress_bar=False
        )
        tip = rod.position_collection[:2, -1].copy()
        if np.linalg.norm(tip - prev) < 1e-8:
            break
        prev = tip
    return tip, time.perf_counter() - t0


def _row(case, variant, sps, ref, ref_sps, **extra):
    sps, ref_sps = float(sps), float(ref_sps)
    return {
        "case": case,
        "variant": variant,
        "steps_per_s": sps,
        "reference": ref,
        "reference_steps_per_s": ref_sps,
        "ratio": sps / ref_sps,
        **extra,
    }


def _static(quick: bool) -> list[dict]:
    import contextlib
    import io

    ref = solve_cantilever(L, EA, GAS, EI, 64, tip_force=(0.0, -P)).tip_position
    ours = {}
    for n in (2, 4, 6, 8, 12, 16, 24, 32):
        tip, sec = _ours(n)
        ours[n] = (float(np.linalg.norm(tip - ref)) / L, sec)
    with contextlib.redirect_stdout(io.StringIO()):  # PyElastica prints per integrate call
        _elastica(8)  # numba warm-up
        pe = {n: _elastica(n) for n in ((25, 50) if quick else (50, 100, 200))}
    pe = {n: (float(np.linalg.norm(tip - ref)) / L, sec) for n, (tip, sec) in pe.items()}
    n_tol = min(n for n, (err, _) in ours.items() if err <= TOL)
    n_pe = max(pe)
    err_pe, sec_pe = pe[n_pe]
    n_eq = min(n for n, (err, _) in ours.items() if err <= err_pe)

    def row(case: str, n: int, ref: str, ref_sec: float, ref_err: float) -> dict:
        """Our beam of n elements against a reference run of ref_sec s and error ref_err."""
        err, sec = ours[n]
        variant = f"mf_envs C1 beam n_el={n} (err {err:.1e} L)"
        return _row(
            case, variant, 1 / sec, ref, 1 / ref_sec, our_error=err, reference_error=ref_err
        )

    rows = []
    for n, (err, sec) in sorted(pe.items()):
        ref = f"PyElastica n={n} damped to rest (err {err:.1e} L)"
        rows.append(row("static_cantilever", n_tol, ref, sec, err))
    ref = f"PyElastica n={n_pe} (err {err_pe:.1e} L)"
    rows.append(row("static_cantilever_equal_accuracy", n_eq, ref, sec_pe, err_pe))
    ns = np.array(sorted(pe))
    order = -np.polyfit(np.log(ns), np.log([pe[n][0] for n in ns]), 1)[0]
    cost = np.polyfit(np.log(ns), np.log([pe[n][1] for n in ns]), 1)[0]
    n_need = n_pe * (err_pe / TOL) ** (1 / order)
    sec_need = sec_pe * (n_need / n_pe) ** cost
    ref = (
        f"PyElastica EXTRAPOLATED n~{n_need:.0f} (order {order:.2f}, time ~ n^{cost:.2f}) to 1e-4 L"
    )
    rows.append(row("static_cantilever_1e-4", n_tol, ref, sec_need, TOL))
    return rows


def _inchworm_vs_pendulum(quick: bool) -> list[dict]:
    import gymnasium as gym

    import mf_envs  # noqa: F401
    from mf_envs.controllers import make_baseline

    n = 80 if quick else 400
    env = gym.make(ENV_ID)
    ctrl = make_baseline(env)
    obs, _ = env.reset(seed=0)
    env.step(ctrl.predict(obs)[0])
    t0 = time.perf_counter()
    for _ in range(n):
        obs, *_ = env.step(ctrl.predict(obs)[0])
    ours = n / (time.perf_counter() - t0)
    rng = np.random.default_rng(0)
    rand = rng.uniform(-1, 1, (n,) + env.action_space.shape).astype(np.float32)
    t0 = time.perf_counter()
    for a in rand:
        _, _, term, trunc, _ = env.step(a)
        if term or trunc:
            env.reset()
    ours_random = n / (time.perf_counter() - t0)
    pend = gym.make("Pendulum-v1")
    pend.reset(seed=0)
    rng = np.random.default_rng(0)
    acts = rng.uniform(-2, 2, (20 * n, 1)).astype(np.float32)
    t0 = time.perf_counter()
    for a in acts:
        _, _, term, trunc, _ = pend.step(a)
        if term or trunc:
            pend.reset()
    ref = 20 * n / (time.perf_counter() - t0)
    pend_ref = "Pendulum-v1 (random actions)"
    return [
        _row("inchworm_vs_pendulum", "Inchworm-v0 seed_uniform gait", ours, pend_ref, ref),
        _row("inchworm_vs_pendulum", "Inchworm-v0 random actions", ours_random, pend_ref, ref),
    ]


def _step_vs_elements(quick: bool) -> list[dict]:
    from mf_envs.physics.inchworm import Inchworm, InchwormParams

    rates = {}
    for n in (4, 8, 16, 32) if quick else (4, 8, 16, 32, 64, 128):
        sim = Inchworm(
            InchwormParams(n_elements=n), frozenset({"anchor_switching"}), increment_factor=10.0
        )
        sim.actuate(np.full(sim.kappa.shape, -13.0), anchor="head")
        base = sim.state

        def one(sim=sim, base=base):
            sim.state, sim.kappa = base, np.full(sim.kappa.shape, -13.0)
            sim.actuate(np.full(sim.kappa.shape, -12.8), anchor="head")

        rates[n] = 1.0 / timed(one, repeat=20)[1]
    return [
        _row("beam_step_vs_elements", f"n_elements={n}", r, "n_elements=4", rates[4], elements=n)
        for n, r in rates.items()
    ]


def rows(quick: bool) -> list[dict]:
    """All cases; without PyElastica (`compare` extra) the static case is skipped with a note."""
    import importlib.util
    import sys

    if importlib.util.find_spec("elastica") is None:
        print(
            "bench speed: skipping static_cantilever (needs PyElastica: "
            'pip install "mf-envs[compare]")',
            file=sys.stderr,
        )
        static = []
    else:
        static = _static(quick)
    return static + _inchworm_vs_pendulum(quick) + _step_vs_elements(quick)


def plot(out: Path, rows_: list[dict]) -> list[Path]:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    sub = [r for r in rows_ if r["case"] == "beam_step_vs_elements"]
    if not sub:
        return []
    n = np.array([r["elements"] for r in sub], float)
    ms = 1e3 / np.array([r["steps_per_s"] for r in sub])
    slope = np.polyfit(np.log(n), np.log(ms), 1)[0]
    fig, ax = plt.subplots(figsize=(5, 4))
    ax.loglog(n, ms, "o-", label=f"one actuation increment (slope {slope:.2f})")
    ax.set(xlabel="beam elements", ylabel="ms per increment", title="C1 beam step cost")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    path = out / "speed_beam_step_vs_elements.png"
    fig.tight_layout()
    save_figure(fig, path, dpi=110)
    return [path]
