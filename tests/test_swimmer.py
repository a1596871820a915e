"""The swimmer's physics (mf_envs.physics.swimmer) against independent truth: Taylor's drag of a
towed rigid body (exact), the consistent tangents against central differences, a coasting body
against the closed-form solution of its own ODE (second order in dt), the momentum of body plus
entrained water, the small-amplitude travelling wave's speed (slender-body theory of the linear
law) and Lighthill's mean thrust of a prescribed wave."""

from __future__ import annotations

import numpy as np
import pytest

from mf_envs.physics.beam.banded import band_to_dense
from mf_envs.physics.beam.solver import BeamModel
from mf_envs.physics.serpentine import rod_params, serpenoid
from mf_envs.physics.serpentine.stepping import Body
from mf_envs.physics.swimmer import Swimmer, Water
from mf_envs.physics.swimmer.fluid import added_momentum, assemble_water
from mf_envs.physics.swimmer.theory import (
    coasting_distance,
    coasting_speed,
    lighthill_thrust,
    taylor_small_amplitude_speed,
)

L, D = 0.2, 0.012  # m: the eel's length and diameter


def _swimmer(water=None, n_el=6, gait=None, e=1e6, density=1000.0):
    p = rod_params(L, D / 2, e, e / 1.5, density, n_el)
    return Swimmer(p, water or Water(diameter=D), gait)


def _rigid(sw, heading, velocity):
    """Straight body along `heading` [rad] through the origin, rigid velocity (2,) [m/s]."""
    m = sw.model
    d = m.straight()
    c, s = np.cos(heading), np.sin(heading)
    d[0::6], d[2::6] = c * m.node_S, s * m.node_S
    d[1::6], d[3::6], d[4::6] = c, s, heading
    d[5::6] = heading
    v = np.zeros(m.n_dof)
    v[0::6], v[2::6] = velocity
    return d, v


@pytest.mark.parametrize("heading", [0.0, 0.7, -2.4])
@pytest.mark.parametrize("angle", [0.0, np.pi, np.pi / 2, np.pi / 4, -3 * np.pi / 4, 2.0])
@pytest.mark.parametrize("linear", [False, True])
def test_towed_rigid_body_feels_taylors_drag(heading, angle, linear):
    """Resistive only: the resultant of the nodal forces is -L (g_t(v_t) t + g_n(v_n) n) with
    Taylor's coefficients, to 1e-10 relative, whatever the heading and direction of tow."""
    water = Water(diameter=D, linear=linear, linear_normal=3.0, linear_tangential=0.4,
                  reactive=False)  # fmt: skip
    sw = _swimmer(water)
    speed = 0.37
    t = np.array([np.cos(heading), np.sin(heading)])
    n = np.array([-t[1], t[0]])
    u = speed * (np.cos(angle) * t + np.sin(angle) * n)
    d, v = _rigid(sw, heading, u)
    f, power = sw.water_force(d, v)
    vt, vn = u @ t, u @ n
    if linear:
        gt, gn = 0.4 * vt, 3.0 * vn
    else:
        rho = 1000.0
        gt = 0.5 * rho * np.pi * D * 0.0055 * abs(vt) * vt
        gn = 0.5 * rho * D * 1.1 * abs(vn) * vn
    want = -L * (gt * t + gn * n)
    got = np.array([f[0::6].sum(), f[2::6].sum()])  # nodal z1, z2 forces (slopes carry none)
    assert np.linalg.norm(got - want) <= 1e-10 * np.linalg.norm(want)
    assert power == pytest.approx(want @ u, rel=1e-10)


def _random_state(sw, rng):
    d, v = _rigid(sw, 0.3, (0.2, -0.1))
    d = d + 0.02 * rng.standard_normal(d.size)
    v = v + 0.3 * rng.standard_normal(v.size)
    return d, v


@pytest.mark.parametrize("linear", [False, True])
def test_water_tangent_matches_central_differences(linear):
    """dF/dd and dF/dv of the resistive + end forces (trailing edge and form drag,
    `assemble_water`) and dp/dd, dp/dv of the entrained water's momentum (`added_momentum`)
    against central differences."""
    sw = _swimmer(Water(diameter=D, linear=linear, linear_normal=3.0, linear_tangential=0.4,
                        form_drag=True, end_speed=0.05))  # fmt: skip
    rng = np.random.default_rng(3)
    d, v = _random_state(sw, rng)
    nzt, npt, law = sw.packed
    le, nd = sw.model.le, sw.model.n_dof
    m_a = sw.water.added_mass

    def force(dd, vv):
        f = np.zeros(nd)
        assemble_water(dd, vv, le, nzt, npt, law, f, np.zeros((21, nd)), 0.0, 0.0)
        return f

    def momentum(dd, vv):
        p = np.zeros(nd)
        added_momentum(dd, vv, le, nzt, npt, m_a, p, np.zeros((21, nd)), 0.0, 0.0)
        return p

    for fun, assemble in ((force, "water"), (momentum, "momentum")):
        for wrt in ("d", "v"):
            ab = np.zeros((21, nd))
            cd, cv = (1.0, 0.0) if wrt == "d" else (0.0, 1.0)
            if assemble == "water":
                assemble_water(d, v, le, nzt, npt, law, np.zeros(nd), ab, cd, cv)
            else:
                added_momentum(d, v, le, nzt, npt, m_a, np.zeros(nd), ab, cd, cv)
            k = band_to_dense(ab)
            fd = np.zeros((nd, nd))
            h = 1e-6
            for j in range(nd):
                e = np.zeros(nd)
                e[j] = h
                if wrt == "d":
                    fd[:, j] = (fun(d + e, v) - fun(d - e, v)) / (2 * h)
                else:
                    fd[:, j] = (fun(d, v + e) - fun(d, v - e)) / (2 * h)
            scale = np.max(np.abs(fd))
            assert scale > 0.0
            assert np.max(np.abs(k - fd)) < 1e-7 * scale, (assemble, wrt)


@pytest.mark.parametrize("backwards", [False, True])
def test_form_drag_of_a_towed_straight_body(backwards):
    """Resistive + form drag, towed along its axis head first (or tail first): the resultant
    is -(k_t L + k_f) |u| u t exactly (the leading end carries k_f), with the blend's weights
    summing to one; the tangential speed 0.3 m/s is far above the blend's width."""
    water = Water(diameter=D, reactive=False, form_drag=True)
    sw = _swimmer(water)
    u = -0.3 if backwards else 0.3
    d, v = _rigid(sw, 0.4, (u * np.cos(0.4), u * np.sin(0.4)))
    f, power = sw.water_force(d, v)
    k = water.k_tangential * L + water.k_form
    t = np.array([np.cos(0.4), np.sin(0.4)])
    want = -k * abs(u) * u * t
    got = np.array([f[0::6].sum(), f[2::6].sum()])
    assert np.linalg.norm(got - want) <= 1e-10 * np.linalg.norm(want)
    assert water.k_form == pytest.approx(0.5 * 1000.0 * 0.19 * np.pi * D**2 / 4, rel=1e-12)
    end = f[-5] * t[0] + f[-3] * t[1] if not backwards else f[0] * t[0] + f[2] * t[1]
    skin = -water.k_tangential * L * abs(u) * u  # the leading node carries the form drag
    assert abs(end - (-water.k_form * abs(u) * u)) < 0.3 * abs(skin)


@pytest.mark.parametrize("c_form", [0.13, 0.19, 0.24])
def test_coasting_distance_with_form_drag(c_form):
    """A straight body launched head first at 0.3 m/s, resistive + form drag (the cited range of
    the form-drag coefficient, docs/eel.md): the distance it coasts while slowing to the speed
    it has after 3 s is `theory.coasting_distance` of M dV/dt = -(k_t L + k_f) V^2 (M the body
    mass: no added mass along the axis), to 1e-4; the speed is `theory.coasting_speed`."""
    water = Water(diameter=D, reactive=False, form_drag=True, c_form=c_form)
    sw = _swimmer(water)
    v0, t_end, dt = 0.3, 3.0, 0.01
    d, v = _rigid(sw, 0.0, (v0, 0.0))
    h = sw.simulate(t_end, dt, every=int(round(t_end / dt)), d0=d, v0=v)
    mass = sw.model.params.mass_per_length * L
    b = water.k_tangential * L + water.k_form
    v_end = coasting_speed(v0, t_end, b, mass)
    com_v = h.momentum()[0][-1][0] / mass
    assert com_v == pytest.approx(v_end, rel=1e-4)
    moved = h.com()[-1][0] - h.com()[0][0]
    assert moved == pytest.approx(coasting_distance(v0, v_end, mass, 0.0, b), rel=1e-4)


@pytest.mark.parametrize("direction", ["along", "across"])
def test_coasting_body_decays_as_its_own_ode_at_second_order(direction):
    """A straight body launched at V0 along (resistive only) or across (resistive + added mass,
    no tail force) its axis decays as V0 / (1 + k V0 t / M) (theory.coasting_speed). The
    midpoint force (theta = 1/2) is second order: the error falls 4x when dt halves."""
    water = Water(diameter=D, tail=False, reactive=direction == "across")
    sw = _swimmer(water)
    v0 = 0.5
    vel = (v0, 0.0) if direction == "along" else (0.0, v0)
    d, v = _rigid(sw, 0.0, vel)
    t_end = 1.0
    mass = sw.model.params.mass_per_length + water.added_mass
    k = water.k_tangential if direction == "along" else water.k_normal
    want = coasting_speed(v0, t_end, k, mass)
    assert want < 0.7 * v0  # a real decay
    errors = []
    for dt in (0.04, 0.02, 0.01):
        h = sw.simulate(t_end, dt, every=int(round(t_end / dt)), d0=d, v0=v)
        com_v = h.momentum()[0][-1] / (sw.model.params.mass_per_length * L)
        got = com_v[0] if direction == "along" else com_v[1]
        errors.append(abs(got - want) / want)
    assert errors[-1] < 1e-3, errors
    ratios = errors[0] / errors[1], errors[1] / errors[2]
    assert all(3.5 < r < 4.5 for r in ratios), (errors, ratios)


@pytest.mark.parametrize("a, b", [(0.01, 0.05), (0.0, 0.05), (0.01, 0.0)])
def test_coasting_distance_closed_form_matches_the_integrated_ode(a, b):
    """theory.coasting_distance against scipy's integration of M x'' = -a x' - b x'^2 (rtol
    1e-12) to the time the speed falls to V1."""
    from scipy.integrate import solve_ivp

    mass, v0, v1 = 0.02, 0.4, 0.1

    def slow(t, y):
        return y[1] - v1

    sol = solve_ivp(lambda t, y: [y[1], -(a * y[1] + b * y[1] ** 2) / mass], [0.0, 100.0],
                    [0.0, v0], rtol=1e-12, atol=1e-14, events=slow)  # fmt: skip
    want = sol.y_events[0][0][0]
    assert coasting_distance(v0, v1, mass, a, b) == pytest.approx(want, rel=1e-9)


def test_body_and_entrained_water_conserve_momentum():
    """Reactive only (no resistive, no tail): an actuated body's momentum plus its water's
    momentum stays at its start value to the Newton tolerance."""
    water = Water(diameter=D, resistive=False, tail=False)
    model = BeamModel(rod_params(L, D / 2, 1e6, 1e6 / 1.5, 1000.0, 6))
    gait = serpenoid(model.gauss_S, 20.0, L, 0.4, direction=-1, ramp_time=0.4)
    sw = _swimmer(water, gait=gait)
    d, v = _rigid(sw, 0.4, (0.1, 0.05))
    h = sw.simulate(1.0, 0.01, every=10, d0=d, v0=v)
    body = h.momentum()[0]
    total = []
    for dd, vv in zip(h.d, h.v):
        p = sw.water_momentum(dd, vv)[0]
        total.append(body[len(total)] + np.array([p[0::6].sum(), p[2::6].sum()]))
    total = np.array(total)
    scale = np.max(np.abs(total))
    assert np.max(np.abs(total - total[0])) < 1e-8 * scale
    assert np.max(np.abs(body - body[0])) > 1e-2 * scale  # the body's own momentum changes


@pytest.mark.parametrize("wavelength", [L, 2 * L])
def test_small_amplitude_wave_swims_at_taylors_speed(wavelength):
    """Resistive only, linear law c_t = 10, c_n = 20 N s/m^2 (inertia negligible at T = 2 s):
    a stiff body (the shape is kappa#) under kappa# = a sin(k (L - S) - w t), slope amplitude
    0.05, swims at the slender-body speed (theory.taylor_small_amplitude_speed) within 2 %."""
    period = 2.0
    p = rod_params(L, D / 2, 1e12, 1e12 / 1.5, 1000.0, 16)
    k = 2 * np.pi / wavelength
    a = 0.05 * k
    water = Water(diameter=D, linear=True, linear_tangential=10.0, linear_normal=20.0,
                  reactive=False)  # fmt: skip
    gait = serpenoid(BeamModel(p).gauss_S, a, wavelength, period, direction=1, ramp_time=period)
    h = Swimmer(p, water, gait).simulate(3 * period, 0.02)
    com = h.com()
    i, j = (int(np.argmin(np.abs(h.t - n * period))) for n in (1, 3))
    speed = (com[j, 0] - com[i, 0]) / (h.t[j] - h.t[i])
    want = taylor_small_amplitude_speed(L, k, 2 * np.pi / period, a, 10.0, 20.0)
    assert want < 0.0  # against the wave
    assert speed == pytest.approx(want, rel=0.02)


def test_tail_force_gives_lighthills_mean_thrust():
    """Reactive only, a prescribed small-amplitude wave h = b (S / L) sin(k S + w t) (amplitude
    growing to the tail... here the tail is S = 0, so the envelope grows towards S = 0) on a body
    moving at U along +x: the period mean of the model's reactive force (the water momentum's
    -dp/dt by central differences, plus the tail force) along x equals Lighthill's
    m_a / 2 < h_t^2 - U^2 h_x^2 >_tail within 5 %."""
    water = Water(diameter=D, resistive=False)
    sw = _swimmer(water, n_el=12)
    m = sw.model
    b, lam, period, speed = 0.01, 0.8 * L, 0.4, 0.15
    k, w = 2 * np.pi / lam, 2 * np.pi / period

    def state(t):
        s = m.node_S
        env = b * (1.0 - 0.6 * s / L)  # larger at the tail S = 0
        denv = -0.6 * b / L
        ph = k * s + w * t
        h, h_x = env * np.sin(ph), env * k * np.cos(ph) + denv * np.sin(ph)
        h_t = env * w * np.cos(ph)
        psi = np.arctan(h_x)
        smid = 0.5 * (s[1:] + s[:-1])
        pm = k * smid + w * t
        envm = b * (1.0 - 0.6 * smid / L)
        psi_mid = np.arctan(envm * k * np.cos(pm) - 0.6 * b / L * np.sin(pm))
        d, v = m.straight(), np.zeros(m.n_dof)
        d[0::6], d[1::6], d[2::6], d[3::6], d[4::6] = s + speed * t, 1.0, h, h_x, psi
        d[5::6] = psi_mid
        v[0::6], v[2::6] = speed, h_t
        return d, v, h_t[0], h_x[0]

    n, eps = 64, 1e-5
    thrust, ht, hx = [], [], []
    for i in range(n):
        t = i * period / n
        d, v, a, bb = state(t)
        f = sw.water_force(d, v)[0]
        dp = sw.water_momentum(*state(t + eps)[:2])[0] - sw.water_momentum(*state(t - eps)[:2])[0]
        thrust.append(f[0::6].sum() - dp[0::6].sum() / (2 * eps))
        ht.append(a)
        hx.append(bb)
    want = lighthill_thrust(water.added_mass, np.array(ht), np.array(hx), speed)
    assert want > 0.0
    assert np.mean(thrust) == pytest.approx(want, rel=0.05)


@pytest.mark.parametrize("linear", [False, True])
def test_fused_newton_residual_equals_the_beam_and_water_assemblies(linear):
    """`kernels._residual` + `fluid.tail_into` (`beam.fused`: the algorithmic force, the
    water's momentum, Taylor's force and the inertia element by element) against
    `beam.algorithmic.assemble_algorithmic`, `fluid.added_momentum`, `fluid.assemble_water` and
    the banded mass on random states: the same -R and tangent to round-off."""
    from mf_envs.physics.beam import fused
    from mf_envs.physics.beam.algorithmic import assemble_algorithmic
    from mf_envs.physics.swimmer import kernels
    from mf_envs.physics.swimmer.fluid import tail_into

    water = Water(diameter=D, linear=linear, linear_normal=3.0, linear_tangential=1.0)
    sw = _swimmer(water, n_el=5)
    m = sw.model
    nd, ne = m.n_dof, m.n_elements
    nzt, npt, law = sw.packed
    tab = sw.quad[3]
    m_a = law[6]
    rng = np.random.default_rng(5)
    for dt, th, th_s in ((0.01, 0.5, 0.6), (0.005, 1.0, 0.5)):
        d0 = m.straight() + 0.03 * rng.standard_normal(nd)
        v0 = 0.05 * rng.standard_normal(nd)
        d = d0 + dt * v0 + 1e-3 * rng.standard_normal(nd)
        k0, k1 = (20 * rng.standard_normal((ne, 4)) for _ in range(2))
        shift = np.zeros((ne, tab.shape[1], 3))
        p_int, ab0, _ = assemble_algorithmic(d0, d, m.le, k0, k1, *m.quad, th_s, shift, True, 1.0)
        x = d - d0 - dt * v0
        v = 2.0 * (d - d0) / dt - v0
        mass = band_to_dense(m.mass)
        p0, p1 = np.zeros(nd), np.zeros(nd)
        added_momentum(d0, v0, m.le, nzt, npt, m_a, p0, ab0, 0.0, 0.0)
        added_momentum(d, v, m.le, nzt, npt, m_a, p1, ab0, 1.0 / dt, 2.0 / dt**2)
        r0 = -p_int - 2.0 / dt**2 * mass @ x - (p1 - p0) / dt
        assemble_water(d0 + th * (d - d0), (1 - th) * v0 + th * v, m.le, nzt, npt, law, r0, ab0,
                       -th, -2.0 * th / dt)  # fmt: skip
        k_dense = band_to_dense(ab0) + 2.0 / dt**2 * mass
        sc = kernels.make_scratch(nd, ne)  # `newton_step` forms the start strains, M, p0 there
        fused.start_strains(d0, m.le, k0, tab, sc[15])
        sc[10][:], sc[16][:] = 2.0 / dt**2 * m.mass, p0
        buf, ab = np.empty((5, nd)), np.empty((21, nd))
        v_out = np.empty(nd)
        body = Body(m.mass, m.le, sw.quad, sw.packed, (th, th_s), 1e-10, 12, 6, m.params.EI, 0.0)
        kernels._residual(d0, v0, d, k0, k1, dt, body, sc, buf, ab, v_out, True)
        r_full = buf[0].copy()
        tail_into(buf[2], buf[3], law, buf[0], ab, -th, -2.0 * th / dt)
        assert np.max(np.abs(buf[0] - r0)) <= 1e-12 * np.max(np.abs(r0))
        assert np.max(np.abs(band_to_dense(ab) - k_dense)) <= 1e-13 * np.max(np.abs(k_dense))
        # the residual alone (the predictor's other candidate): the same bits, no tangent
        ab_before = ab.copy()
        kernels._residual(d0, v0, d, k0, k1, dt, body, sc, buf, ab, v_out, False)
        assert np.array_equal(buf[0], r_full) and np.array_equal(ab, ab_before)


def test_a_reversed_wave_swims_as_the_mirror_of_the_forward_one():
    """Reactive force only, a uniform body: a wave running tail to head is the forward wave seen
    from the other end (S -> L - S), so the body must swim as fast the other way at the same
    muscle power. This holds only if Lighthill's trailing-edge term sits at the end that trails
    (the head, swimming tail first); at the tail alone the reversed wave swam the wrong way."""
    p = rod_params(L, D / 2, 1e6, 1e6 / 1.5, 1000.0, 12)
    lam, period, a = 0.8 * L, 0.5, 15.0
    out = {}
    for direction in (-1, 1):  # -1: head to tail (swims head first), +1: tail to head
        gait = serpenoid(BeamModel(p).gauss_S, a, lam, period, direction=direction,
                         ramp_time=period)  # fmt: skip
        h = Swimmer(p, Water(diameter=D, resistive=False), gait).simulate(6 * period, 0.005)
        i, j = (int(np.argmin(np.abs(h.t - n * period))) for n in (2, 6))
        com, work = h.com(), h.extras["muscle_work"]
        out[direction] = ((com[j, 0] - com[i, 0]) / (h.t[j] - h.t[i]),
                          np.sum(work[j] - work[i]) / (h.t[j] - h.t[i]))  # fmt: skip
    (u_fwd, p_fwd), (u_rev, p_rev) = out[-1], out[1]
    assert u_fwd > 0.2 * L  # swims head first, 0.34 L/s
    assert u_rev == pytest.approx(-u_fwd, rel=1e-6)
    assert p_rev == pytest.approx(p_fwd, rel=1e-6)
    assert abs(u_fwd) / (lam / period) < 1.0  # slower than the wave
