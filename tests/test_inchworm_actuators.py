"""Actuator dynamics and friction feet of the inchworm (issue 16; the curvature actuator and the
feet live in `mf_envs.physics.actuators` and `mf_envs.physics.beam.contact`).

Independent truth: the analytic first-order response u + (k0 - u) exp(-t / tau) and a tight
scipy ODE solution of the rate-saturated lag; the hand computation of the holding limit
mu m_A g L / 2 of a symmetric body; the energy balance W_act = Delta U - W_gravity - W_friction
(a second formulation of the actuation work int P dt)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from mf_envs.physics.actuators.curvature import (
    ActuatorParams,
    RateLimitedLag,
    actuation_power,
    increment_work,
    rate_limited_lag,
)
from mf_envs.physics.beam import static
from mf_envs.physics.beam.contact import stick_slip as ss
from mf_envs.physics.beam.contact.feet import FrictionFeet, grip_response
from mf_envs.physics.beam.contact.friction import FORWARD, FrictionParams
from mf_envs.physics.inchworm import Inchworm, InchwormParams, run_gait, seed_uniform_kappa
from mf_envs.physics.inchworm.drive import DrivenInchworm
from mf_envs.physics.inchworm.open_loop import cosine_gait, grip_for, run_open_loop, square_gait

TAU, RATE = 0.3, 13.0
P = InchwormParams(n_elements=12)
WEIGHT = P.mass_per_length * P.gravity * P.length  # m_A g L [N]


# ---------------------------------------------------------------- actuator dynamics
def test_lag_matches_the_analytic_first_order_response():
    """Unsaturated (|u - k0| < r tau): exactly k(t) = u + (k0 - u) exp(-t/tau), at any dt and
    whether advanced in one step or many."""
    k0, u = np.array([0.0, -1.0, 2.0]), np.array([-3.0, 1.5, 0.5])  # gaps 3, 2.5, 1.5 < 3.9
    t = np.array([0.0, 0.01, 0.3, 1.0, 7.0])
    exact = u + (k0 - u) * np.exp(-t[:, None] / TAU)
    assert np.allclose(rate_limited_lag(k0, u, t[:, None], TAU, RATE), exact, rtol=0, atol=1e-13)
    lag = RateLimitedLag(ActuatorParams(TAU, RATE), 3)
    lag.reset(k0)
    for _ in range(100):
        lag.advance(u, 0.01)
    assert np.allclose(lag.kappa, exact[3], atol=1e-12)


@pytest.mark.parametrize("dt", [1e-3, 0.05, 0.1, 0.37, 2.0])
def test_lag_matches_the_saturated_ode(dt):
    """Large gaps saturate the rate: the exact discretisation equals a tight ODE solution of
    dk/dt = clip((u - k)/tau, -r, r) at the end of every step, whatever dt."""
    rng = np.random.default_rng(1)
    lag = RateLimitedLag(ActuatorParams(TAU, RATE), 2)
    k = np.zeros(2)
    for _ in range(12):
        u = rng.uniform(-13.0, 0.0, 2)
        sol = solve_ivp(
            lambda t, y, u=u: np.clip((u - y) / TAU, -RATE, RATE),
            (0, dt),
            k,
            rtol=1e-11,
            atol=1e-12,
        )
        k = sol.y[:, -1]
        assert np.allclose(lag.advance(u, dt), k, atol=1e-8)


def test_bang_bang_commands_never_exceed_the_rate_limit_or_overshoot():
    rng = np.random.default_rng(7)
    lag = RateLimitedLag(ActuatorParams(TAU, RATE), 5)
    worst = 0.0
    for _ in range(2000):
        u = np.where(rng.random(5) < 0.5, -13.0, 0.0)  # bang-bang between the range ends
        dt = float(rng.choice([1e-4, 0.01, 0.1, 0.5, 3.0]))
        before = lag.kappa.copy()
        after = lag.advance(u, dt)
        worst = max(worst, float(np.max(np.abs(after - before) / dt)))
        lo, hi = np.minimum(before, u), np.maximum(before, u)
        assert np.all((after >= lo) & (after <= hi))  # monotone towards u: no overshoot
        assert np.all(np.abs(lag.rate()) <= RATE)
    assert worst <= RATE * (1 + 1e-9)  # round-off of the difference at dt = 1e-4
    assert worst > 0.99 * RATE  # the limit is actually reached (the test can fail)


def test_fastest_cycle_is_set_by_rate_and_bandwidth():
    act = ActuatorParams(TAU, RATE)
    assert act.fastest_cycle(13.0) == pytest.approx(np.pi)  # pi kappa0 / r = pi s
    assert ActuatorParams(2.0, RATE).fastest_cycle(13.0) == pytest.approx(4 * np.pi)
    assert act.corner_frequency == pytest.approx(1 / (2 * np.pi * TAU))
    with pytest.raises(ValueError, match="actuator_rate_limit"):
        ActuatorParams(TAU, 0.0)
    with pytest.raises(ValueError, match="actuator_time_constant"):
        ActuatorParams(-1.0, RATE)


# ---------------------------------------------------------------- actuation power and energy
def _curl_with_anchor(n_inc: int):
    """Curl the seed's body (gravity, head held kinematically) 0 -> -13 1/m in n_inc increments:
    returns (work by trapezoids of (A2), Delta U, gravity work, the sim)."""
    sim = Inchworm(P, effects=frozenset({"gravity", "shear_deformation", "anchor_switching"}))
    m = sim.model
    d0, k0, u0 = sim.state.d.copy(), sim.kappa.copy(), sim.elastic_energy()
    work = 0.0
    for i in range(1, n_inc + 1):
        d_a, k_a = sim.state.d.copy(), sim.kappa.copy()
        sim.actuate(np.full(m.gauss_S.shape, -13.0 * i / n_inc), anchor="head")
        work += increment_work(m, d_a, sim.state.d, k_a, sim.kappa)
    w_grav = float(sim.f_ext @ (sim.state.d - d0))
    del k0
    return work, sim.elastic_energy() - u0, w_grav, sim


def test_actuation_energy_equals_the_energy_balance():
    """int P dt (trapezoids of -int M dk#) -> Delta U - W_gravity (kinematic anchors and sliding
    supports do no work) with second-order convergence in the increment size."""
    errs = []
    for n in (20, 40, 80):
        work, du, w_grav, _ = _curl_with_anchor(n)
        errs.append(abs(work - (du - w_grav)))
    assert work > 0.0 and du - w_grav > 0.0  # curling against gravity costs energy
    assert errs[-1] < 1e-3 * abs(work)
    assert errs[0] / errs[1] > 3.0 and errs[1] / errs[2] > 3.0, errs


def test_power_is_the_rate_of_actuation_work():
    """(A2) at the mid-point equals the finite-difference rate of the increment work."""
    _, _, _, sim = _curl_with_anchor(10)
    m = sim.model
    d_a, k_a = sim.state.d.copy(), sim.kappa.copy()
    rate, h = np.full(k_a.shape, 2.0), 1e-4  # uncurl at 2 1/(m s) for h seconds
    sim.actuate(k_a + rate * h, anchor="tail")
    w = increment_work(m, d_a, sim.state.d, k_a, sim.kappa)
    p_mid = actuation_power(m, sim.state.d, sim.kappa, rate)
    assert w / h == pytest.approx(p_mid, rel=1e-3)
    assert p_mid < 0.0  # uncurling under gravity: the body does work on the actuator


# ---------------------------------------------------------------- feet
def test_grip_rates_never_exceed_the_time_constant_limit():
    fp = FrictionParams(engage_time=0.2, release_time=0.05)
    rng = np.random.default_rng(3)
    g = np.array([0.0, 1.0])
    worst = 0.0
    for _ in range(1000):
        cmd = (rng.random(2) < 0.5).astype(float)
        dt = float(rng.choice([1e-4, 0.01, 0.1, 1.0]))
        g1 = grip_response(g, cmd, dt, fp)
        tau = np.where(cmd > g, 0.2, 0.05)
        ratio = np.abs(g1 - g) / dt * tau  # realised rate / (1 / tau)
        worst = max(worst, float(ratio.max()))
        assert np.all((g1 >= 0.0) & (g1 <= 1.0))
        g = g1
    assert worst <= 1.0 + 1e-12
    assert worst > 0.99


def test_holding_limit_is_mu_times_the_weight_share():
    fp = FrictionParams(grip_forward=0.6, grip_backward=1.0, slide_forward=0.1)
    n = WEIGHT / 2.0  # hand computation: 0.278 * 9.81 * 0.3 / 2 = 0.409077 N
    assert n == pytest.approx(0.409077, rel=1e-5)
    assert fp.holding_limit(1.0, FORWARD, n) == pytest.approx(0.6 * 0.409077, rel=1e-5)
    assert fp.holding_limit(0.0, FORWARD, n) == pytest.approx(0.1 * 0.409077, rel=1e-5)
    assert fp.holding_limit(0.5, -1, n) == pytest.approx(0.575 * 0.409077, rel=1e-5)
    assert fp.holding_limit(1.0, FORWARD, -3.0) == 0.0  # a lifted foot holds nothing


def _feet_scene(fp: FrictionParams, g=(0.0, 1.0), k_start: float = 0.0):
    """Both feet down, settled under gravity with the head held and kappa# = k_start (uniform)."""
    sim = Inchworm(P, effects=frozenset({"gravity", "shear_deformation", "anchor_switching"}))
    if k_start:
        sim.actuate(np.full(sim.model.gauss_S.shape, k_start), anchor="head")
    feet = FrictionFeet(sim.model, fp)
    feet.reset(g)
    return sim, feet


@pytest.mark.parametrize("mu_slide", [0.1, 0.3])
def test_foot_slips_exactly_when_the_pull_exceeds_mu_n(mu_slide):
    """Curling with both feet down: the ground pulls on the feet with equal and opposite forces
    H that grow with kappa#; the released tail (mu_slide forward) must hold while H <= mu N with
    N = m_A g L / 2 (symmetric body), slip from the increment where H reaches it, and then be
    held back by exactly mu N while the gripping head stays put. (Start pre-curled at -1 1/m:
    from the gravity sag the first curling straightens the body and pushes the feet apart.)"""
    fp = FrictionParams(slide_forward=mu_slide, grip_backward=1.0)
    sim, feet = _feet_scene(fp, k_start=-1.0)
    m, f = sim.model, sim.f_ext
    limit = mu_slide * WEIGHT / 2.0
    d, k = sim.state.d.copy(), sim.kappa.copy()
    x_head0, slipped = d[m.dof(-1, "z1")], False
    for _ in range(60):
        k1 = k - 0.002  # small increments: H grows through the limit
        ds, rep = feet.step(d, [k, k1], f, np.array([0.0, 1.0]), 0.01)
        h = rep.ground_x[0]  # ground force on the tail (backward: negative)
        assert abs(rep.ground_x[0] + rep.ground_x[1]) < 1e-7  # equal, opposite (Newton tol)
        assert np.allclose(rep.normal, WEIGHT / 2.0, rtol=1e-6)  # symmetric weight share
        if not slipped:
            if rep.slipping[0] == 0:
                assert -h <= limit * (1 + 1e-9) and abs(ds[-1][0] - d[0]) < 1e-15
            else:
                slipped = True
                assert len(rep.onsets) == 1 and 0.0 <= rep.onsets[0] <= 1.0
        if slipped:
            assert rep.slipping[0] == FORWARD and rep.slip[0] > 0.0
            assert -h == pytest.approx(limit, rel=1e-9)
        d, k = ds[-1], k1
    assert slipped
    assert d[m.dof(-1, "z1")] == pytest.approx(x_head0, abs=1e-15)  # the head held


def test_onset_is_located_inside_the_increment():
    """One big increment across the onset: the located lambda* reproduces, by a stuck solve to
    lambda*, a ground force equal to the holding limit."""
    sim, feet = _feet_scene(FrictionParams(slide_forward=0.2), k_start=-1.0)
    f = sim.f_ext
    k0 = sim.kappa.copy()
    k1 = k0 - 0.2
    ds, rep = feet.step(sim.state.d, [k0, k1], f, np.array([0.0, 1.0]), 0.01)
    (lam,) = rep.onsets
    assert 0.0 < lam < 1.0
    strong = FrictionParams(slide_forward=10.0, grip_backward=10.0)  # never slips: stuck solve
    probe, probe_feet = _feet_scene(strong, k_start=-1.0)
    _, rep2 = probe_feet.step(probe.state.d, [k0, k0 + lam * (k1 - k0)], f, np.ones(2), 0.01)
    assert rep2.slipping[0] == 0
    assert -rep2.ground_x[0] == pytest.approx(0.2 * WEIGHT / 2, rel=1e-6)


def test_bordered_onset_agrees_with_the_bracketing_search():
    """The onset by Newton on (d, lambda) together converges on its own (no fallback) to the
    lambda* and configuration of regula falsi on stuck solves, in fewer iterations, and the
    foot's ground force there equals its holding limit."""
    sim, feet = _feet_scene(FrictionParams(slide_forward=0.2), k_start=-1.0)
    m, f = sim.model, sim.f_ext
    k0 = sim.kappa.copy()
    k1 = k0 - 0.2
    xd, zd, mu4 = feet.kernel_args()[:3]
    bc = static.constants(m, feet.settings)
    both = np.zeros(m.n_dof, bool)
    both[xd], both[zd] = True, True
    d0 = sim.state.d.copy()
    d1, _, _ = static.solve_linear_path(m, d0, k0, k1, f, both, feet.settings)
    sc = ss.scratch(m.n_elements)
    rx, nz = np.empty(2), np.empty(2)
    ss._ground(d1, k1, f, xd, zd, bc, sc, rx, nz)
    g = feet.g.copy()
    e1 = -FORWARD * rx[0] - feet.params.holding_limit(g[0], FORWARD, nz[0])
    assert e1 > 0.0  # the released tail, pulled forward, exceeds its limit at the end
    inc = ss.Increment(k0, k1, f, g, g, xd, zd, mu4, bc, sc)
    args = (d0, d1, 0, FORWARD, e1, 0, both, inc)
    lam_r, ok_r, it_r = ss._onset(*args, True)
    d_r = sc.vec[ss.ROW_STAR].copy()
    lam_b, ok_b, it_b = ss._onset(*args)
    d_b = sc.vec[ss.ROW_STAR].copy()
    assert ok_r and ok_b and 0.0 < lam_b < 1.0
    assert lam_b == pytest.approx(lam_r, abs=1e-8)
    assert np.max(np.abs(d_b - d_r)) < 1e-10  # m, rad
    assert it_b < it_r
    guess = d0 + lam_r * (d1 - d0)  # the bordered Newton alone, from near the answer
    lam_d, ok_d, _ = ss._onset_bordered(lam_r, guess, 0, FORWARD, both, inc)
    assert ok_d and lam_d == pytest.approx(lam_r, abs=1e-8)
    ss._ground(d_b, k0 + lam_b * (k1 - k0), f, xd, zd, bc, sc, rx, nz)
    assert -rx[0] == pytest.approx(0.2 * nz[0], rel=1e-8)


def test_anisotropic_feet_ratchet_forward_without_switching():
    """Identical anisotropic feet (mu forward < mu backward), both gripping, no switching:
    curling pulls the feet together, so the tail (pulled forward, lower limit) slips; uncurling
    pushes them apart, so the head (pushed forward) slips: the body walks forward."""
    fp = FrictionParams(grip_forward=0.3, grip_backward=1.0)
    sim, feet = _feet_scene(fp, g=(1.0, 1.0))
    m, f = sim.model, sim.f_ext
    d, k = sim.state.d.copy(), np.zeros(m.gauss_S.shape)
    path = [k + kk for kk in np.linspace(0.0, -8.0, 41)]
    path += path[-2::-1]
    ds, rep = feet.step(d, path, f, np.array([1.0, 1.0]), 2.0)
    x_t, x_h = ds[-1][0], ds[-1][m.dof(-1, "z1")]
    assert x_t > 0.01 and x_h - P.length > 0.01
    assert x_h - x_t == pytest.approx(P.length, rel=1e-6)  # straight again
    assert rep.friction_work < 0.0


def test_frictionless_slide_and_strong_grip_reproduce_the_kinematic_anchors():
    """mu = 0 on the released foot, a strong grip on the other: the seed's kinematic scene."""
    fp = FrictionParams(slide_forward=0.0, slide_backward=0.0, grip_forward=5, grip_backward=5)
    sim, feet = _feet_scene(fp, g=(0.0, 1.0))
    ref = Inchworm(P, effects=frozenset({"gravity", "shear_deformation", "anchor_switching"}))
    m, f = sim.model, sim.f_ext
    d, k = sim.state.d.copy(), np.zeros(m.gauss_S.shape)
    for i in range(1, 21):
        k1 = np.full(k.shape, -13.0 * i / 20)
        ds, _ = feet.step(d, [k, k1], f, np.array([0.0, 1.0]), 0.1)
        ref.actuate(k1, anchor="head")
        d, k = ds[-1], k1
    assert np.allclose(d, ref.state.d, atol=1e-9)


def test_energy_balance_with_friction():
    """W_act (trapezoids of A2) = Delta U - W_gravity - W_friction over a curl/uncurl with
    slipping feet (friction dissipates: W_friction < 0)."""
    fp = FrictionParams(grip_forward=0.3, grip_backward=1.0)
    sim, feet = _feet_scene(fp, g=(1.0, 1.0))
    m, f = sim.model, sim.f_ext
    d0 = sim.state.d.copy()
    u0 = m.elastic_energy(d0, np.zeros(m.gauss_S.shape))
    path = [np.full(m.gauss_S.shape, kk) for kk in np.linspace(0.0, -6.0, 121)]
    ds, rep = feet.step(d0, path, f, np.array([1.0, 1.0]), 1.0)
    work, d_prev = 0.0, d0
    for j, d in enumerate(ds):
        work += increment_work(m, d_prev, d, path[j], path[j + 1])
        d_prev = d
    du = m.elastic_energy(ds[-1], path[-1]) - u0
    w_grav = float(f @ (ds[-1] - d0))
    assert rep.friction_work < 0.0
    assert work == pytest.approx(du - w_grav - rep.friction_work, rel=2e-3)


# ---------------------------------------------------------------- the driven robot
def _driven(actuator=True, friction=True):
    sim = Inchworm(P, effects=frozenset({"gravity", "shear_deformation", "anchor_switching"}))
    S = np.linspace(0.0, P.length, 3)
    act = ActuatorParams(TAU, RATE) if actuator else None
    dr = DrivenInchworm(sim, S, act, FrictionParams() if friction else None)
    dr.reset(np.zeros(3))
    return dr


def test_driven_bang_bang_never_exceeds_kappa_or_grip_rates():
    """Random bang-bang curvature commands and grip flips at every 0.1 s step: the realised
    kappa# at the control points and at every Gauss point of the beam, and the engagements of
    both feet, change no faster than the actuator and the feet allow."""
    dr, rng, dt = _driven(), np.random.default_rng(11), 0.1
    fp = dr.feet.params
    worst_k = worst_g = 0.0
    for _ in range(40):
        u = np.where(rng.random(3) < 0.5, -13.0, 0.0)
        k_ctrl, k_gauss, g = dr.kappa_ctrl.copy(), dr.sim.kappa.copy(), dr.feet.g.copy()
        rep = dr.step(u, "head" if rng.random() < 0.5 else "tail", dt)
        worst_k = max(worst_k, np.max(np.abs(rep.kappa_sharp - k_ctrl)) / dt)
        worst_k = max(worst_k, np.max(np.abs(dr.sim.kappa - k_gauss)) / dt)
        tau = np.where(dr.grip > g, fp.engage_time, fp.release_time)
        worst_g = max(worst_g, float(np.max(np.abs(dr.grip - g) * tau / dt)))
    assert worst_k <= RATE * (1 + 1e-9) and worst_k > 0.9 * RATE
    assert worst_g <= 1.0 + 1e-12 and worst_g > 0.3


def test_driver_without_dynamics_is_the_seed_scene():
    """No actuator dynamics, kinematic anchors: the driver reproduces `run_gait` (Eq. 101,
    40 steps per cycle, Eq. 102 anchors) to solver tolerance."""
    dr = _driven(actuator=False, friction=False)
    ref = Inchworm(P, effects=frozenset({"gravity", "shear_deformation", "anchor_switching"}))
    hist = run_gait(ref, lambda S, t: np.full(S.shape, seed_uniform_kappa(t, 13.0)), 1, 40)
    gait = cosine_gait(13.0, np.ones(3), 4.0)
    for k in range(40):
        c = gait(0.1 * (k + 1))
        dr.step(c, grip_for(dr, c, 0.1), 0.1)
        assert dr.sim.x_tail == pytest.approx(hist.x_tail[k + 1], abs=1e-9)


def test_open_loop_metrics_are_consistent():
    """Speed x period = advance per cycle; cost of transport = energy / (weight x distance)."""
    dr = _driven()
    m = run_open_loop(dr, square_gait(13.0, np.ones(3), 2.0), 2.0, 0.1, 1, 1)
    assert m.speed * 2.0 == pytest.approx(m.advance_per_cycle)
    assert m.cost_of_transport == pytest.approx(m.energy / (WEIGHT * m.distance))
    assert m.distance > 0.05 and 0.0 < m.cost_of_transport < 10.0
