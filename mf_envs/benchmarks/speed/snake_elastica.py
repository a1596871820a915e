"""The serpentine beam side by side with PyElastica 1.0's continuum snake.

PyElastica: `examples/ContinuumSnakeCase/continuum_snake.py` with its parameters (L = 0.35 m,
r = 0.011 L, E = 1 MPa, G = E / 1.5 (the example's `E / (poisson + 1)`), rho = 1000 kg/m^3,
gravity normal to the plane (the example's 9.80665 m/s^2; we run both codes at the project's
g = 9.81, `physics.constants.G`: the friction force mu m g = m L / (T^2 Fr) does not depend on g,
and nothing else does), muscle torques from the spline coefficients
(3.4, 3.3, 4.2, 2.6, 3.6, 3.5) e-3 N m, wavelength 1.0 L, period 2 s, ramp over one period,
kinetic mu (forward, backward, lateral) = (1, 1.5, 2) L / (T^2 g Fr), Fr = 0.1, static mu 0,
slip tolerance 1e-8 m/s, plane contact k = 1, nu = 1e-6, AnalyticalLinearDamper with
damping_constant 2e-3 at its time step, PositionVerlet), 11.01 periods; the friction is 1.0's
`RodPlaneContactWithAnisotropicFriction` against an `ea.Plane` (the `Contact` mixin).

Ours (`mf_envs.physics.serpentine`): the same rod as a planar C1 beam (EA, 27/28 G A, EI,
m_A, J_3C), the same muscles as kappa# = tau / EI (`gait.elastica_muscles`), the same friction
coefficients (regularised below `slip_speed`), and optionally the damper's equivalent loads
(drag nu_v = 2e-3 1/s on every velocity, line couple -c m_A psi_dot: the deprecated protocol
multiplies omega by exp(-c dt m_e / J_e) per step, a couple -c m_e omega per element).

The env through gym.make (`preset="pyelastica"`, driven by its `elastica_muscles` baseline) is
a row of its own: CPU seconds of its episode loop against PyElastica's (`time.process_time`).

Figure: mean forward speed over periods 5-11, |com(11 T) - com(4 T)| / 7 T, and PyElastica's own
post-processing (`compute_projected_velocity`: the centre-of-mass velocity projected on the
mean heading, averaged from t = 2 T). Wall time: the time loop only, numba warm.

    python -m mf_envs.benchmarks.speed.snake_elastica [--quick]
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from mf_envs.physics.beam.solver import BeamModel
from mf_envs.physics.constants import G
from mf_envs.physics.serpentine import BellyFriction, Serpentine, elastica_muscles, rod_params

L, PERIOD, N_PERIODS = 0.35, 2.0, 11.01
RADIUS, E, RHO, FROUDE = 0.011 * L, 1e6, 1000.0, 0.1
SHEAR = E / 1.5
COEFFS = np.array([3.4e-3, 3.3e-3, 4.2e-3, 2.6e-3, 3.6e-3, 3.5e-3])
WAVELENGTH = 1.0
DAMPING = 2e-3
SAMPLE = 0.02  # s between stored centre-of-mass samples


def forward_speed(t: np.ndarray, com: np.ndarray, first: int = 5, last: int = 11) -> float:
    """|com(last T) - com((first - 1) T)| / ((last - first + 1) T) [m/s], nearest samples."""
    i = int(np.argmin(np.abs(t - (first - 1) * PERIOD)))
    j = int(np.argmin(np.abs(t - last * PERIOD)))
    return float(np.linalg.norm(com[j] - com[i]) / (t[j] - t[i]))


def elastica_projected_speed(t: np.ndarray, com: np.ndarray) -> float:
    """PyElastica's `compute_projected_velocity` average forward speed, with the centre-of-mass
    velocity by central differences of the stored samples."""
    vel = np.gradient(com, t, axis=0)
    step = int(round(PERIOD / (t[1] - t[0])))
    n_per = len(t) // step
    disp = [
        np.mean(com[(i + 1) * step : (i + 2) * step] - com[i * step : (i + 1) * step], 0)
        for i in range(1, n_per - 1)
    ]
    heading = np.mean(disp, axis=0)
    heading /= np.linalg.norm(heading)
    return float(np.mean(vel[2 * step :] @ heading))


def _mu(g: float) -> float:
    """The example's kinetic mu = L / (T^2 g Fr)."""
    return L / (PERIOD**2 * g * FROUDE)


def _elastica_snake(n_elem: int, dt: float, g: float):
    """PyElastica's simulator and rod of the example (module docstring), not finalized."""
    import elastica as ea

    class Sim(
        ea.BaseSystemCollection, ea.Constraints, ea.Forcing, ea.Damping, ea.Contact, ea.CallBacks
    ):
        pass

    sim = Sim()
    normal = np.array([0.0, 1.0, 0.0])
    rod = ea.CosseratRod.straight_rod(
        n_elem,
        np.zeros(3),
        np.array([0.0, 0.0, 1.0]),
        normal,
        L,
        RADIUS,
        RHO,
        youngs_modulus=E,
        shear_modulus=SHEAR,
    )
    sim.append(rod)
    sim.add_forcing_to(rod).using(ea.GravityForces, acc_gravity=np.array([0.0, -g, 0.0]))
    sim.add_forcing_to(rod).using(
        ea.MuscleTorques,
        base_length=L,
        b_coeff=COEFFS,
        period=PERIOD,
        wave_number=2.0 * np.pi / WAVELENGTH,
        phase_shift=0.0,
        rest_lengths=rod.rest_lengths,
        ramp_up_time=PERIOD,
        direction=normal,
        with_spline=True,
    )
    plane = ea.Plane(plane_origin=np.array([0.0, -RADIUS, 0.0]), plane_normal=normal)
    sim.append(plane)
    sim.detect_contact_between(rod, plane).using(
        ea.RodPlaneContactWithAnisotropicFriction,
        k=1.0,
        nu=1e-6,
        slip_velocity_tol=1e-8,
        static_mu_array=np.zeros(3),
        kinetic_mu_array=_mu(g) * np.array([1.0, 1.5, 2.0]),
    )
    sim.dampen(rod).using(ea.AnalyticalLinearDamper, damping_constant=DAMPING, time_step=dt)
    return sim, rod


def run_elastica(
    n_elem: int = 50, dt: float = 1e-4, t_end: float = N_PERIODS * PERIOD, g: float = G
):
    """PyElastica's continuum snake (module docstring) -> (t, com (N, 2) in the ground plane,
    wall seconds of the time loop)."""
    import elastica as ea

    sim, rod = _elastica_snake(n_elem, dt, g)
    rec: dict[str, list] = {"t": [], "com": []}
    every = max(1, int(round(SAMPLE / dt)))

    class Cb(ea.CallBackBaseClass):
        def make_callback(self, system, time, current_step):
            if current_step % every == 0:
                rec["t"].append(time)
                rec["com"].append(system.compute_position_center_of_mass().copy())

    sim.collect_diagnostics(rod).using(Cb)
    sim.finalize()
    stepper = ea.PositionVerlet()
    n_steps = int(t_end / dt)
    t0 = time.perf_counter()
    ea.integrate(stepper, sim, t_end, n_steps, progress_bar=False)
    wall = time.perf_counter() - t0
    com = np.array(rec["com"])
    return np.array(rec["t"]), com[:, [2, 0]], wall  # (z, x) of PyElastica = the ground plane


def snake(
    n_el: int = 10, slip_speed: float = 1e-4, damper: bool = True, g: float = G
) -> Serpentine:
    """Our serpentine beam with PyElastica's snake's parameters (module docstring)."""
    p = rod_params(L, RADIUS, E, SHEAR, RHO, n_el)
    drag, couple = (DAMPING, DAMPING * p.mass_per_length) if damper else (0.0, 0.0)
    ground = BellyFriction(
        _mu(g),
        1.5 * _mu(g),
        2.0 * _mu(g),
        slip_speed=slip_speed,
        drag_rate=drag,
        couple_damping=couple,
    )
    gauss_s = BeamModel(p).gauss_S
    gait = elastica_muscles(gauss_s, L, p.EI, COEFFS, WAVELENGTH, PERIOD, PERIOD)
    return Serpentine(p, ground, gait, gravity=g)


def run_ours(
    n_el: int = 10,
    dt: float = 0.01,
    slip_speed: float = 1e-4,
    damper: bool = True,
    theta: float = 1.0,
    t_end: float = N_PERIODS * PERIOD,
    g: float = G,
):
    """-> (t, com (N, 2), wall seconds, Newton iterations)."""
    s = snake(n_el, slip_speed, damper, g)
    s.simulate(4 * dt, dt)  # compile / warm
    t0 = time.perf_counter()
    h = s.simulate(t_end, dt, every=max(1, int(round(SAMPLE / dt))), theta=theta)
    wall = time.perf_counter() - t0
    return h.t, h.com(), wall, h.iterations


def run_env_preset(t_end: float = N_PERIODS * PERIOD):
    """`gym.make("Serpentine-v0", preset="pyelastica")` driven by its `elastica_muscles`
    baseline from rest, straight along +x -> (t, com (N, 2), CPU seconds of the episode's loop:
    env steps and controller, numba warm)."""
    import gymnasium as gym

    from mf_envs.controllers.serpentine import ElasticaMuscles

    env = gym.make("Serpentine-v0", preset="pyelastica", episode_seconds=t_end)
    ctrl = ElasticaMuscles(env)

    def episode():
        opts = {"heading": 0.0, "kappa": np.zeros(env.unwrapped.n_ctrl)}
        obs, info = env.reset(seed=0, options=opts)
        ctrl.reset()
        t, com, done = [0.0], [(info["x"], info["y"])], False
        while not done:
            obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
            t.append(info["time"])
            com.append((info["x"], info["y"]))
            done = term or trunc
        return np.array(t), np.array(com)

    episode()  # compile / warm
    c0 = time.process_time()
    t, com = episode()
    return t, com, time.process_time() - c0


def _row(name, t, com, wall):
    v5, vp = forward_speed(t, com), elastica_projected_speed(t, com)
    print(
        f"{name:38s} v(5-11) {1e3 * v5:7.3f} mm/s  projected {1e3 * vp:7.3f} mm/s  "
        f"wall {wall:7.3f} s"
    )
    return v5, wall


# our converged run (the speed moves < 1e-4 relative beyond it: `accuracy.serpentine`)
CONVERGED = (40, 0.0025)
# ours as benched: the cheapest settings whose speed is within 1e-3 of the converged run
BENCHED = ((10, 0.01), (6, 0.02))


def rows(quick: bool) -> list[dict]:
    """`mf-envs bench speed` rows: 22 s of PyElastica's snake (n = 50, dt = 1e-4, numba warm)
    against ours at `BENCHED`, `steps_per_s` = simulated seconds per wall second (the same 22 s
    in both), `ratio` = ours / PyElastica; each row carries both speeds, their ratio and each
    code's error against its own converged run: ours against `CONVERGED`; PyElastica's from
    its first-order mesh convergence (n = 25 vs 50: error(50) ~ |v50 - v25|; quick: skipped).
    Without PyElastica (the `compare` extra) the scene is skipped with a note."""
    import importlib.util
    import sys

    if importlib.util.find_spec("elastica") is None:
        print(
            "bench speed: skipping snake_elastica (needs PyElastica: "
            'pip install "mf-envs[compare]")',
            file=sys.stderr,
        )
        return []
    t_end = N_PERIODS * PERIOD
    run_elastica(n_elem=50, t_end=0.01)  # numba warm-up
    c0 = time.process_time()
    t, com, wall_e = run_elastica(50, 1e-4)
    cpu_e = time.process_time() - c0
    v_e = forward_speed(t, com)
    err_e = float("nan")
    if not quick:
        t25, com25, _ = run_elastica(25, 1e-4)
        err_e = abs(v_e - forward_speed(t25, com25)) / v_e
    t, com, _, _ = run_ours(*CONVERGED)
    v_conv = forward_speed(t, com)
    out = []
    for n_el, dt in BENCHED:
        t, com, wall, its = run_ours(n_el, dt)
        v = forward_speed(t, com)
        out.append(
            {
                "case": "continuum_snake_22s",
                "variant": f"ours n={n_el} dt={dt:g} vs PyElastica n=50 dt=1e-4",
                "steps_per_s": t_end / wall,
                "reference": "PyElastica 1.0 continuum snake",
                "reference_steps_per_s": t_end / wall_e,
                "ratio": wall_e / wall,
                "wall_s": wall,
                "reference_wall_s": wall_e,
                "speed_mm_s": 1e3 * v,
                "reference_speed_mm_s": 1e3 * v_e,
                "speed_ratio": v / v_e,
                "error_vs_own_converged": abs(v - v_conv) / v_conv,
                "reference_error_vs_own_converged": err_e,
                "newton_per_step": its / (t_end / dt),
            }
        )
    t, com, cpu = run_env_preset(t_end)
    v = forward_speed(t, com)
    out.append(
        {
            "case": "continuum_snake_22s",
            "variant": "gym.make('Serpentine-v0', preset='pyelastica') vs PyElastica n=50 dt=1e-4",
            "steps_per_s": t_end / cpu,
            "reference": "PyElastica 1.0 continuum snake",
            "reference_steps_per_s": t_end / cpu_e,
            "ratio": cpu_e / cpu,
            "cpu_s": cpu,
            "reference_cpu_s": cpu_e,
            "speed_mm_s": 1e3 * v,
            "reference_speed_mm_s": 1e3 * v_e,
            "speed_ratio": v / v_e,
            "error_vs_own_converged": abs(v - v_conv) / v_conv,
            "reference_error_vs_own_converged": err_e,
        }
    )
    return out


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="skip PyElastica's 25-element run")
    ap.add_argument("--no-elastica", action="store_true", help="ours only")
    ap.add_argument("--gravity", type=float, default=G, help="g [m/s^2] of both codes")
    args = ap.parse_args(argv)
    ref = None
    if not args.no_elastica:
        run_elastica(n_elem=50, t_end=0.01, g=args.gravity)  # numba warm-up
        c0 = time.process_time()
        ref = _row("pyelastica n=50 dt=1e-4", *run_elastica(50, 1e-4, g=args.gravity))
        cpu_ref = time.process_time() - c0
        if not args.quick:
            _row("pyelastica n=25 dt=1e-4", *run_elastica(25, 1e-4, g=args.gravity))
    for n_el, dt, v_eps, damper, th in (
        (10, 0.01, 1e-4, True, 1.0),
        (10, 0.005, 1e-4, True, 1.0),
        (20, 0.01, 1e-4, True, 1.0),
        (10, 0.01, 1e-3, True, 1.0),
        (10, 0.01, 1e-4, False, 1.0),
        (10, 0.01, 1e-4, True, 0.5),
        (6, 0.02, 1e-4, True, 1.0),
    ):
        t, com, wall, its = run_ours(n_el, dt, v_eps, damper, th, g=args.gravity)
        name = f"ours n={n_el} dt={dt:g} v_eps={v_eps:g}{'' if damper else ' no-damper'} th={th:g}"
        v5, _ = _row(name, t, com, wall)
        if ref is not None:
            print(
                f"{'':38s} speed / PyElastica {v5 / ref[0]:.4f}  wall ratio {ref[1] / wall:.1f}x"
                f"  Newton its/step {its / (N_PERIODS * PERIOD / dt):.2f}"
            )
    if args.gravity == G:  # the env runs at the project's g
        t, com, cpu = run_env_preset()
        v5, _ = _row("gym.make Serpentine-v0 preset=pyelastica", t, com, cpu)
        if ref is not None:
            print(f"{'':38s} speed / PyElastica {v5 / ref[0]:.4f}  CPU ratio {cpu_ref / cpu:.1f}x "
                  f"({cpu_ref:.2f} s against {cpu:.2f} s of CPU)")  # fmt: skip


if __name__ == "__main__":
    main()
