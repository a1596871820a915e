"""Active C1 beam (ch. 4 §4.3-4.9) against independent truth: finite differences of the residual,
the seed's closed-form mass matrix, the linear Timoshenko solution, the exact circle under an end
moment, the elastica (scipy solve_bvp), and the cantilever's first natural frequency."""

from __future__ import annotations

import numpy as np
import pytest

from mf_envs.physics.beam import (
    BeamModel,
    BeamParams,
    NewmarkState,
    banded,
    clamp_dofs,
    fields,
    initial_acceleration,
    newmark_step,
    solve_cantilever,
    solve_static_path,
    timoshenko_cantilever_uniform,
)
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.reference import SEED_CANTILEVER, elastica_tip, seed_rigidities


def _fd_tangent(model, d, kap, h=1e-6):
    k = np.zeros((model.n_dof, model.n_dof))
    for j in range(model.n_dof):
        dp, dm = d.copy(), d.copy()
        dp[j] += h
        dm[j] -= h
        k[:, j] = (model.internal(dp, kap, False)[0] - model.internal(dm, kap, False)[0]) / (2 * h)
    return k


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_tangent_matches_finite_differences(seed):
    """Consistent tangent (material + geometric) vs central differences of P: 1e-6 relative."""
    rng = np.random.default_rng(seed)
    model = BeamModel(BeamParams(1.3, 2e4, 7e3, 2.0, 3))
    # a strongly deformed state: big rotations, stretch and shear, plus actuation
    d = model.straight() + 0.3 * rng.standard_normal(model.n_dof)
    kap = rng.standard_normal((3, el.N_GAUSS))
    _, ab = model.internal(d, kap)
    k = banded.band_to_dense(ab)
    k_fd = _fd_tangent(model, d, kap)
    assert np.max(np.abs(k - k_fd)) / np.max(np.abs(k)) < 1e-6
    assert np.allclose(k, k.T, rtol=0, atol=1e-10 * np.max(np.abs(k)))  # conservative: symmetric


def test_internal_force_is_gradient_of_energy():
    rng = np.random.default_rng(3)
    model = BeamModel(BeamParams(1.0, 5e3, 2e3, 1.5, 2))
    d = model.straight() + 0.2 * rng.standard_normal(model.n_dof)
    kap = rng.standard_normal((2, 4))
    p, _ = model.internal(d, kap, False)
    h = 1e-6
    for j in range(0, model.n_dof, 3):
        dp, dm = d.copy(), d.copy()
        dp[j] += h
        dm[j] -= h
        g = (model.elastic_energy(dp, kap) - model.elastic_energy(dm, kap)) / (2 * h)
        assert g == pytest.approx(p[j], rel=1e-6, abs=1e-6 * np.max(np.abs(p)))


def test_forces_at_dofs_equal_the_assembled_force():
    """element.forces_at_into (only the elements holding the asked dofs are evaluated) gives
    the bits of the full assembly there, on a mesh of unequal elements (the shape tables
    refill): end nodes, a node two elements share, mid-node psi dofs; kappa_at gives the
    curvature of evaluate_fields."""
    rng = np.random.default_rng(4)
    le = np.array([0.3, 0.3, 0.5, 0.2, 0.2])
    nd = el.n_dof(le.size)
    d = 0.2 * rng.standard_normal(nd)
    d[0::6] += np.append(0.0, np.cumsum(le))
    kap = rng.standard_normal((le.size, el.N_GAUSS))
    qxi, qw, stiff = el.quadrature("sri", 0.3, 2e4, 7e3, 2.0)
    p, ab = np.empty(nd), np.empty((el.N_BAND, nd))
    el.assemble_into(d, le, kap, qxi, qw, stiff, False, p, ab)
    dofs = np.array([0, 2, 9, 11, 17, nd - 3, nd - 5])
    out = np.empty(dofs.size)
    el.forces_at_into(d, le, kap, qxi, qw, stiff, dofs, out)
    assert np.array_equal(out, p[dofs])
    assert np.all(out != 0.0)
    xis = np.array([0.0, 0.37, 1.0])
    kap_fields = fields.evaluate_fields(d, le, xis)[2]
    for e in range(le.size):
        for q, xi in enumerate(xis):
            assert el.kappa_at(d, 6 * e, le[e], xi) == kap_fields[e, q]


def test_actuation_load_is_the_derivative_of_the_force_in_kappa_sharp():
    """element.actuation_load_into = dP/dkappa# . dk, against the difference of two assembled
    forces (P is affine in kappa#: exact up to round-off for any step), at a deformed state."""
    rng = np.random.default_rng(5)
    model = BeamModel(BeamParams(1.3, 2e4, 7e3, 2.0, 4))
    d = model.straight() + 0.2 * rng.standard_normal(model.n_dof)
    kap = rng.standard_normal((4, el.N_GAUSS))
    dk = rng.standard_normal((4, el.N_GAUSS))
    p1, _ = model.internal(d, kap + dk, False)
    p0, _ = model.internal(d, kap, False)
    load = np.empty(model.n_dof)
    qxi, qw, stiff = model.quad
    el.actuation_load_into(model.le, qxi, qw, stiff, dk, load)
    assert np.max(np.abs(load - (p1 - p0))) < 1e-12 * np.max(np.abs(p1))
    psi = np.zeros(model.n_dof, bool)
    psi[4::6], psi[5::6] = True, True
    assert np.all(load[~psi] == 0.0) and np.max(np.abs(load[psi])) > 0.1


def test_rigid_motion_is_stress_free():
    """Objectivity: a rotated, translated straight beam has zero internal force."""
    model = BeamModel(BeamParams(2.0, 1e5, 4e4, 3.0, 4))
    d = model.straight()
    th = 2.1
    c, s = np.cos(th), np.sin(th)
    x, y = d[0::6].copy(), np.zeros(5)
    d[0::6], d[2::6] = 0.3 + c * x - s * y, -1.0 + s * x + c * y
    d[1::6], d[3::6] = c, s
    d[4::6] = th  # end-node psi
    d[5::6] = th  # mid-node psi
    p, _ = model.internal(d, np.zeros((4, 4)), False)
    assert np.max(np.abs(p)) < 1e-9


def test_mass_matrix_matches_seed_appendix():
    """Gauss-integrated consistent mass vs the closed forms of Eqs. 105-106."""
    le, m_a, j3 = 0.7, 2.0, 0.3
    model = BeamModel(BeamParams(le, 1.0, 1.0, 1.0, 1, mass_per_length=m_a, rotary_inertia=j3))
    m = banded.band_to_dense(model.mass)
    loc = el.element_dofs(1)[0]
    me = m[np.ix_(loc, loc)]
    L = le
    m11 = (
        m_a
        * L
        * np.array(
            [
                [13 / 35, 11 * L / 210, 9 / 70, -13 * L / 420],
                [11 * L / 210, L**2 / 105, 13 * L / 420, -(L**2) / 140],
                [9 / 70, 13 * L / 420, 13 / 35, -11 * L / 210],
                [-13 * L / 420, -(L**2) / 140, -11 * L / 210, L**2 / 105],
            ]
        )
    )
    m33 = j3 * L * np.array([[2, -1 / 2, 1], [-1 / 2, 2, 1], [1, 1, 8]]) / 15
    assert np.allclose(me[:4, :4], m11, rtol=1e-12)
    assert np.allclose(me[4:8, 4:8], m11, rtol=1e-12)
    assert np.allclose(me[8:, 8:], m33, rtol=1e-12)
    assert np.allclose(me[:4, 4:], 0)


@pytest.mark.parametrize("alpha", [0.0, 0.5, 1.0])
def test_timoshenko_uniform_load_with_actuation(alpha):
    """Seed §4.6 numbers (Eqs. 65-67): tip deflection within 0.5% of the passive tip deflection
    (and of the total when alpha = 0), 4 elements."""
    ea, gas, ei = seed_rigidities()
    c = SEED_CANTILEVER
    sol = solve_cantilever(
        c["L"], ea, gas, ei, 4, distributed_load=(0, -c["q0"]), kappa_sharp=alpha * c["kappa0"]
    )
    v_ref, psi_ref = timoshenko_cantilever_uniform(
        np.array([c["L"]]), c["L"], ei, gas, c["q0"], alpha * c["kappa0"]
    )
    v_passive = timoshenko_cantilever_uniform(np.array([c["L"]]), c["L"], ei, gas, c["q0"])[0][0]
    err = abs(sol.tip_position[1] - v_ref[0])
    assert err < 5e-3 * abs(v_passive)
    if alpha == 0.0:
        assert err < 5e-3 * abs(v_ref[0])
    assert abs(sol.tip_angle - psi_ref[0]) < 5e-3 * abs(psi_ref[0] if alpha != 0.5 else 1e-2)


def test_one_element_reproduces_tip_loaded_active_cantilever():
    """§4.7: one element gives the linear active Timoshenko tip-load solution exactly. The only
    error left is geometric nonlinearity, so it must shrink in proportion to the load."""
    ea, gas, ei = seed_rigidities()
    L = SEED_CANTILEVER["L"]
    errs = []
    for p in (1e-3 * ei / L**2, 1e-4 * ei / L**2):
        k0 = 0.1 * p * L / ei  # actuation of the same order as the load
        sol = solve_cantilever(L, ea, gas, ei, 1, tip_force=(0, -p), kappa_sharp=k0)
        v = -p * L**3 / (3 * ei) - p * L / gas + 0.5 * k0 * L**2
        psi = -p * L**2 / (2 * ei) + k0 * L
        errs.append(abs(sol.tip_position[1] - v) / abs(v))
        assert abs(sol.tip_angle - psi) / abs(psi) < 1e-5
    assert errs[0] < 1e-5
    assert errs[1] < 0.2 * errs[0]  # error ~ load: not a discretisation error


def test_roll_up_to_full_circle():
    """End moment 2 pi EI / L rolls the beam into a circle: tip back at the root, psi = 2 pi."""
    L, ei = 1.5, 2.0
    sol = solve_cantilever(L, 1e5, 4e4, ei, 24, tip_moment=2 * np.pi * ei / L)
    assert np.linalg.norm(sol.tip_position) < 1e-3 * L
    assert abs(sol.tip_angle - 2 * np.pi) < 1e-3
    # every point lies on the circle of radius L / (2 pi) centred at (0, R)
    r = L / (2 * np.pi)
    dist = np.linalg.norm(sol.centerline - np.array([0.0, r]), axis=1)
    assert np.max(np.abs(dist - r)) < 1e-3 * L


def test_roll_up_mesh_convergence_rate():
    """The seed's element converges fast once the mesh resolves its locking."""
    errs = []
    for n in (5, 10, 20):
        sol = solve_cantilever(1.0, 1e4, 1e4, 1.0, n, tip_moment=2 * np.pi, element="seed")
        errs.append(np.linalg.norm(sol.tip_position))
    rates = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(rates > 4.0), rates  # observed ~ 5-6


@pytest.mark.parametrize("alpha", [1.0, 2.0, 5.0, 10.0])
def test_tip_load_elastica(alpha):
    """Large-deflection cantilever, alpha = P L^2 / EI: tip within 1e-3 L of the elastica."""
    x, y, th = elastica_tip(alpha)
    sol = solve_cantilever(1.0, 1e7, 1e7, 1.0, 24, tip_force=(0.0, -alpha))
    assert np.linalg.norm(sol.tip_position - [x, y]) < 1e-3
    assert abs(sol.tip_angle - th) < 1e-3


def test_cantilever_first_frequency_newmark():
    """Small free vibration of a slender cantilever (Newmark + consistent mass): the period
    matches Euler-Bernoulli omega_1 = 1.8751^2 sqrt(EI / (m L^4)) within 1%."""
    L, ei, m_a = 1.0, 1.0, 1.0
    p = BeamParams(L, 1e6, 1e6, ei, 8, mass_per_length=m_a, rotary_inertia=1e-8)
    model = BeamModel(p)
    fixed = np.zeros(model.n_dof, bool)
    fixed[clamp_dofs(model, 0)] = True
    tip_load = np.zeros(model.n_dof)
    tip_load[model.dof(-1, "z2")] = -1e-4
    kap = np.zeros(model.gauss_S.shape)
    static = solve_cantilever(L, 1e6, 1e6, ei, 8, tip_force=(0, -1e-4)).d
    zero = np.zeros(model.n_dof)
    st = NewmarkState(static, zero.copy(), initial_acceleration(model, static, kap, zero, fixed))
    omega = 1.87510407**2 * np.sqrt(ei / (m_a * L**4))
    period = 2 * np.pi / omega
    dt = period / 200
    ys, ts = [], []
    for _ in range(500):
        st = newmark_step(model, st, dt, kap, zero, fixed)
        ys.append(st.d[model.dof(-1, "z2")])
        ts.append(st.t)
    ys = np.array(ys)
    up = np.where((ys[:-1] < 0) & (ys[1:] >= 0))[0]
    t_cross = np.array(ts)[up] - ys[up] * dt / (ys[up + 1] - ys[up])
    measured = np.mean(np.diff(t_cross))
    assert measured == pytest.approx(period, rel=1e-2)
    assert np.max(np.abs(ys)) < 1.01 * abs(static[model.dof(-1, "z2")])  # no energy growth


def test_step_halving_reaches_same_solution():
    a = solve_cantilever(1.0, 1e6, 1e6, 1.0, 8, tip_force=(0, -8.0))
    b = solve_cantilever(1.0, 1e6, 1e6, 1.0, 8, tip_force=(0, -8.0), max_step=0.05)
    assert a.stats.halvings > 0  # the full step does not converge in a few iterations
    assert np.allclose(a.tip_position, b.tip_position, atol=1e-9)


@pytest.mark.parametrize("x0", [10.0, 1e3])
def test_static_solution_far_from_origin(x0):
    """The same clamped cantilever (elastica alpha = 2) with its root at x0: Newton converges
    (it failed at 10 m: the tolerance floor ignored the round-off eps |x| / l_e of the strains)
    and the tip displacement equals the one at the origin (translation invariance)."""
    ref = solve_cantilever(1.0, 1e7, 1e7, 1.0, 24, tip_force=(0.0, -2.0))
    model = BeamModel(BeamParams(1.0, 1e7, 1e7, 1.0, 24))
    fixed = np.zeros(model.n_dof, bool)
    fixed[clamp_dofs(model, 0)] = True
    f = np.zeros(model.n_dof)
    f[model.dof(-1, "z2")] = -2.0
    d0 = model.straight()
    d0[0::6] += x0
    kap = np.zeros(model.gauss_S.shape)
    d = solve_static_path(model, d0, lambda lam: (kap, lam * f), fixed)
    tip = model.node_positions(d)[-1] - [x0, 0.0]
    assert np.allclose(tip, ref.tip_position, rtol=0, atol=1e-9)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"n_elements": 0}, "n_elements"),
        ({"EI": -1.0}, "EI"),
        ({"tip_force": (np.nan, 0.0)}, "tip_force"),
        ({"distributed_load": (1.0, 2.0, 3.0)}, "distributed_load"),
    ],
)
def test_bad_input_names_parameter(kwargs, name):
    args = {"length": 1.0, "EA": 1e4, "GAs": 1e4, "EI": 1.0, "n_elements": 2} | kwargs
    with pytest.raises(ValueError, match=name):
        solve_cantilever(**args)
