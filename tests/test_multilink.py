"""n-link chain (ch. 4 §4.2): kinematics vs frame recursion, M*, N*, energy, statics vs beams."""

from __future__ import annotations

import numpy as np
import pytest

from mf_envs.physics import multilink as ml
from mf_envs.physics.multilink.elastica import elastica_cantilever
from mf_envs.physics.multilink.loads import gauss_points, lump_line_load
from mf_envs.physics.multilink.solve import (
    accelerations,
    accelerations_reference,
    simulate,
    solve_static,
    total_energy,
)

RNG = np.random.default_rng(7)


def _chain(base: str, n: int = 5, gravity=(0.0, -9.81)) -> ml.ChainParams:
    k = RNG.uniform(2.0, 5.0, n if base == "clamped" else n - 1)
    return ml.ChainParams(n, 0.3, 0.7, 0.02, k, base=base, gravity=gravity, base_angle=0.2)


def _poses_from_frames(p: ml.ChainParams, q: np.ndarray) -> np.ndarray:
    """X (3n,) = (x_c, z_c, psi) per link read off the frame recursion E^(a+1) = E^(a) E^(a+1/a)."""
    E = ml.link_frames(p, q)
    psi = np.arctan2(E[:, 1, 0], E[:, 0, 0])
    return np.column_stack([E[:, 0, 3], E[:, 1, 3], np.unwrap(psi)]).ravel()


def _random_q(p: ml.ChainParams) -> np.ndarray:
    return RNG.normal(0.0, 0.8, p.n_dof)


@pytest.mark.parametrize("base", ["clamped", "free"])
def test_link_centers_and_b_matrix_match_the_frame_recursion(base):
    p = _chain(base)
    q = _random_q(p)
    X = _poses_from_frames(p, q)
    assert np.allclose(X.reshape(-1, 3)[:, :2], ml.link_centers(p, q), atol=1e-13)
    h = 1e-6
    B_fd = np.column_stack(
        [
            (_poses_from_frames(p, q + h * e) - _poses_from_frames(p, q - h * e)) / (2 * h)
            for e in np.eye(p.n_dof)
        ]
    )
    assert np.max(np.abs(ml.b_matrix(p, q) - B_fd)) < 1e-8
    # dB/dt along qdot
    qd = RNG.normal(size=p.n_dof)
    Bd_fd = (ml.b_matrix(p, q + h * qd) - ml.b_matrix(p, q - h * qd)) / (2 * h)
    assert np.max(np.abs(ml.b_matrix_rate(p, q, qd) - Bd_fd)) < 1e-8


@pytest.mark.parametrize("base", ["clamped", "free"])
def test_mass_matrix_is_btmb_symmetric_positive_definite(base):
    p = _chain(base, n=7)
    for _ in range(5):
        q, qd = _random_q(p), RNG.normal(size=p.n_dof)
        B, M = ml.b_matrix(p, q), np.diag(ml.mass_diagonal(p))
        Ms = ml.mass_matrix(p, q)
        assert np.allclose(Ms, B.T @ M @ B, atol=1e-13)
        assert np.array_equal(Ms, Ms.T)
        assert np.linalg.eigvalsh(Ms).min() > 0.0
        Nq = B.T @ M @ ml.b_matrix_rate(p, q, qd) @ qd  # Eq. 28c
        assert np.allclose(ml.velocity_forces(p, q, qd), Nq, atol=1e-12)


@pytest.mark.parametrize("base", ["clamped", "free"])
def test_compiled_kernel_matches_the_term_by_term_equations(base):
    p = ml.ChainParams(
        6,
        0.2,
        0.5,
        0.01,
        RNG.uniform(1, 2, 6 if base == "clamped" else 5),
        joint_damping=0.3,
        base=base,
        gravity=(0.3, -3.0),
        base_angle=0.4,
    )
    q, v, ts = _random_q(p), RNG.normal(size=p.n_dof), RNG.normal(size=p.n_joints)
    loads = {
        "link_forces": RNG.normal(size=(6, 2)),
        "link_moments": RNG.normal(size=6),
        "tip_force": (1.0, 2.0),
        "tip_moment": 0.3,
    }
    ref = accelerations_reference(p, q, v, ts, loads)
    assert np.allclose(accelerations(p, q, v, ts, loads), ref, rtol=1e-12, atol=1e-12)
    assert np.allclose(accelerations(p, q, v), accelerations_reference(p, q, v), atol=1e-12)


def test_stiffness_and_actuation_forces_follow_eq_17():
    p = _chain("free", n=5, gravity=(0.0, 0.0))
    ts = RNG.normal(size=p.n_joints)
    q = _random_q(p)
    # delta U = dq^T (K* q - F#) (Eq. 17a): compare with the gradient of Eq. 16a
    h = 1e-6
    grad = [
        (ml.spring_energy(p, q + h * e, ts) - ml.spring_energy(p, q - h * e, ts)) / (2 * h)
        for e in np.eye(p.n_dof)
    ]
    assert np.allclose(ml.stiffness_matrix(p) @ q - ml.actuation_forces(p, ts), grad, atol=1e-7)
    k = p.joint_stiffness  # Eq. 17c written out
    expected = np.concatenate(
        [[0, 0, -k[0] * ts[0]], k[:-1] * ts[:-1] - k[1:] * ts[1:], [k[-1] * ts[-1]]]
    )
    assert np.allclose(ml.actuation_forces(p, ts), expected)


def test_two_link_clamped_matches_hand_derived_lagrange_equations():
    m, l, J, g = 0.7, 0.3, 0.02, 9.81
    k0, k1, t0, t1 = 3.0, 2.0, 0.1, -0.3
    p = ml.ChainParams(2, l, m, J, [k0, k1], gravity=(0.0, -g))
    for _ in range(5):
        (a, b), (da, db) = RNG.normal(size=2), RNG.normal(size=2)
        # link 1 centre l/2 e(a), link 2 centre l e(a) + l/2 e(b); Lagrange by hand:
        M = np.array(
            [
                [m * l**2 * 1.25 + J, m * l**2 / 2 * np.cos(a - b)],
                [m * l**2 / 2 * np.cos(a - b), m * l**2 / 4 + J],
            ]
        )
        rhs = np.array(
            [
                -m * l**2 / 2 * np.sin(a - b) * db**2
                - k0 * (a - t0)
                + k1 * (b - a - t1)
                - 1.5 * m * g * l * np.cos(a),
                -m * l**2 / 2 * np.sin(b - a) * da**2
                - k1 * (b - a - t1)
                - 0.5 * m * g * l * np.cos(b),
            ]
        )
        acc = accelerations(p, [a, b], [da, db], theta_sharp=[t0, t1])
        assert np.allclose(acc, np.linalg.solve(M, rhs), rtol=1e-12, atol=1e-12)


def test_two_link_free_matches_hand_derived_lagrange_equations():
    m, l, J, g, k, ts = 0.7, 0.3, 0.02, 9.81, 2.5, 0.4
    p = ml.ChainParams(2, l, m, J, [k], base="free", gravity=(0.0, -g))
    x, z, a, b = RNG.normal(size=4)
    v = RNG.normal(size=4)
    da, db = v[2], v[3]
    e1p, e2p = np.array([-np.sin(a), np.cos(a)]), np.array([-np.sin(b), np.cos(b)])
    M = np.zeros((4, 4))
    M[:2, :2] = 2 * m * np.eye(2)
    M[:2, 2], M[:2, 3] = m * l / 2 * e1p, m * l / 2 * e2p
    M[2, :2], M[3, :2] = M[:2, 2], M[:2, 3]
    M[2, 2] = M[3, 3] = m * l**2 / 4 + J
    M[2, 3] = M[3, 2] = m * l**2 / 4 * np.cos(a - b)
    gv = np.array([0.0, -g])
    rhs = np.concatenate(
        [
            m
            * l
            / 2
            * (np.array([np.cos(a), np.sin(a)]) * da**2 + np.array([np.cos(b), np.sin(b)]) * db**2)
            + 2 * m * gv,
            [
                -m * l**2 / 4 * np.sin(a - b) * db**2 + k * (b - a - ts) + m * l / 2 * gv @ e1p,
                -m * l**2 / 4 * np.sin(b - a) * da**2 - k * (b - a - ts) + m * l / 2 * gv @ e2p,
            ],
        ]
    )
    acc = accelerations(p, [x, z, a, b], v, theta_sharp=[ts])
    assert np.allclose(acc, np.linalg.solve(M, rhs), rtol=1e-12, atol=1e-12)


@pytest.mark.parametrize("base", ["clamped", "free"])
def test_energy_is_conserved_without_damping(base):
    p = _chain(base, n=4)
    q0, v0 = 0.5 * _random_q(p), RNG.normal(size=p.n_dof)
    tr = simulate(p, q0, v0, 2.0, rtol=1e-11, atol=1e-12, t_eval=np.linspace(0, 2, 41))
    E = tr.energy()
    swing = np.ptp([ml.kinetic_energy(p, q, v) for q, v in zip(tr.q, tr.qdot)])
    assert swing > 0.1 * abs(E[0])  # energy really moves between kinetic and potential
    assert np.max(np.abs(E - E[0])) < 1e-8 * max(abs(E[0]), swing)


def test_free_chain_conserves_momentum_and_angular_momentum():
    p = _chain("free", n=4, gravity=(0.0, 0.0))
    q0, v0 = _random_q(p), RNG.normal(size=p.n_dof)
    tr = simulate(p, q0, v0, 1.5, rtol=1e-11, atol=1e-12, t_eval=[0.0, 0.7, 1.5])
    mom = []
    for q, v in zip(tr.q, tr.qdot):
        X = (ml.b_matrix(p, q) @ v).reshape(-1, 3)
        xc = ml.link_centers(p, q)
        lin = p.link_mass * X[:, :2].sum(axis=0)
        ang = np.sum(
            p.link_mass * (xc[:, 0] * X[:, 1] - xc[:, 1] * X[:, 0]) + p.link_inertia * X[:, 2]
        )
        mom.append([*lin, ang])
    assert np.allclose(mom, mom[0], atol=1e-9)


@pytest.mark.slow
def test_damped_dynamics_settle_on_the_static_solution():
    # two independent routes to the sagging cantilever: Newton on the potential, and the damped
    # dynamics (stiff: implicit LSODA) released from straight
    p = ml.chain_from_beam(1.0, 2.0, 0.5, 4, joint_damping=2.0, gravity=(0.0, -9.81))
    tr = simulate(p, np.zeros(4), np.zeros(4), 8.0, method="LSODA", rtol=1e-9, atol=1e-11)
    st = solve_static(p)
    assert np.max(np.abs(st.psi)) > 0.1
    assert np.max(np.abs(tr.q[-1] - st.psi)) < 1e-8
    assert np.max(np.abs(tr.qdot[-1])) < 1e-8


@pytest.mark.parametrize("n", [2, 3, 8, 50])
def test_small_tip_load_matches_the_hand_derived_chain_deflection(n):
    # the chain's joints carry exactly the beam moment P (L - S_j); k = EI/l inside and 2 EI/l
    # at the clamp give psi_i = P/EI (L S_i - S_i^2/2) + P l^2 / (8 EI) at the link centres S_i, so
    # w_n = sum l psi_i = P L^3 / (3 EI) (1 + 1 / (2 n^2)) (midpoint rule + the clamp offset)
    L, EI, P = 1.3, 4.0, 1e-7
    st = solve_static(ml.chain_from_beam(L, EI, 1.0, n), tip_force=(0.0, -P))
    w_beam = P * L**3 / (3 * EI)  # Euler-Bernoulli cantilever
    assert -st.tip_position[1] == pytest.approx(w_beam * (1 + 0.5 / n**2), rel=1e-6)


def test_uniform_load_converges_to_euler_bernoulli_at_second_order():
    L, EI, q = 1.0, 1.0, 1e-6
    errs = []
    for n in (8, 16, 32):
        st = solve_static(ml.chain_from_beam(L, EI, 1.0, n), distributed_load=(0.0, -q))
        errs.append(abs(-st.tip_position[1] / (q * L**4 / (8 * EI)) - 1))
    assert errs[-1] < 1e-3
    assert np.log2(errs[0] / errs[1]) == pytest.approx(2.0, abs=0.05)
    assert np.log2(errs[1] / errs[2]) == pytest.approx(2.0, abs=0.05)


@pytest.mark.parametrize("alpha", [1.0, 5.0])
def test_large_deflection_converges_to_the_elastica(alpha):
    ref = elastica_cantilever(1.0, 1.0, tip_force=(0.0, -alpha))
    errs = [
        np.linalg.norm(
            solve_static(ml.chain_from_beam(1.0, 1.0, 1.0, n), tip_force=(0.0, -alpha)).tip_position
            - ref.tip_position
        )
        for n in (16, 32, 64)
    ]
    assert errs[-1] < 2e-4
    rates = np.log2(np.array(errs[:-1]) / errs[1:])
    assert np.all(np.abs(rates - 2.0) < 0.1)


def test_uniform_actuation_bends_the_chain_into_the_circle():
    L, kap = 1.0, 3.0
    exact = np.array([np.sin(kap * L), 1 - np.cos(kap * L)]) / kap
    errs = []
    for n in (8, 16, 32):
        p = ml.chain_from_beam(L, 1.0, 1.0, n)
        ts = ml.actuation_from_curvature(p, kap)
        st = solve_static(p, theta_sharp=ts)
        assert np.allclose(ml.joint_angles(p, st.psi), ts, atol=1e-12)  # stress free
        errs.append(np.linalg.norm(st.tip_position - exact))
    assert np.log2(errs[0] / errs[1]) == pytest.approx(2.0, abs=0.1)


def test_roll_up_under_end_moment_closes_the_circle():
    p = ml.chain_from_beam(1.0, 1.0, 1.0, 32)
    st = solve_static(p, tip_moment=2 * np.pi)
    assert np.linalg.norm(st.tip_position) < 1e-12
    # psi_n is the beam angle at the last link centre S = L - l/2
    assert st.tip_angle == pytest.approx(2 * np.pi * (1 - 0.5 / 32), rel=1e-12)


def test_lumped_line_load_does_the_same_virtual_work():
    p = _chain("free", n=4)
    q, qd = _random_q(p), RNG.normal(size=p.n_dof)
    pos, vel, w = gauss_points(p, q, qd, n_gauss=3)
    h = 1e-6
    pos_p, pos_m = gauss_points(p, q + h * qd)[0], gauss_points(p, q - h * qd)[0]
    assert np.allclose(vel, (pos_p - pos_m) / (2 * h), atol=1e-8)
    f = np.stack([np.sin(pos[..., 0]) + pos[..., 1], 2.0 - pos[..., 0] ** 2], axis=-1)
    F, Mo = lump_line_load(p, q, f, w)
    work = np.einsum("g,ngk,ngk->", w, f, vel)  # power of the line load along qdot
    Q = ml.generalized_loads(p, q, link_forces=F, link_moments=Mo) - ml.generalized_loads(p, q)
    assert Q @ qd == pytest.approx(work, rel=1e-12)


def test_bad_inputs_raise_value_errors_naming_the_parameter():
    with pytest.raises(ValueError, match="n_links"):
        ml.chain_from_beam(1.0, 1.0, 1.0, 0)
    with pytest.raises(ValueError, match="joint_stiffness"):
        ml.ChainParams(3, 0.1, 1.0, 0.0, [1.0, 1.0])
    with pytest.raises(ValueError, match="base"):
        ml.ChainParams(3, 0.1, 1.0, 0.0, [1.0, 1.0, 1.0], base="pinned")
    with pytest.raises(ValueError, match="link_length"):
        ml.ChainParams(3, -0.1, 1.0, 0.0, [1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="tip_force"):
        solve_static(ml.chain_from_beam(1.0, 1.0, 1.0, 3), tip_force=(np.nan, 0.0))
    with pytest.raises(ValueError, match="method"):
        simulate(
            ml.chain_from_beam(1.0, 1.0, 1.0, 3), np.zeros(3), np.zeros(3), 1.0, method="euler"
        )
    with pytest.raises(ValueError, match="params"):
        solve_static(_chain("free"))


def test_total_energy_includes_gravity():
    p = ml.chain_from_beam(1.0, 1.0, 2.0, 4, gravity=(0.0, -9.81))
    q = np.full(4, np.pi / 2)  # standing straight up: centres at 1/8, 3/8, 5/8, 7/8
    assert total_energy(p, q, np.zeros(4)) == pytest.approx(
        2.0 * 9.81 * 0.5 + ml.spring_energy(p, q), rel=1e-12
    )


@pytest.mark.slow
def test_chain_resting_on_sand_sinks_like_a_bekker_plate():
    # terrain + Gauss-point lumping + free-chain dynamics against the closed-form plate sinkage
    from mf_envs.physics import terrain as tr

    L, b, m_A, g = 0.3, 0.02, 0.278, 9.81
    EI = 2.4e9 * b * 0.01**3 / 12
    p = ml.chain_from_beam(L, EI, m_A, 4, base="free", joint_damping=0.5, gravity=(0.0, -g))
    contact = tr.TerrainContact(tr.soil("dry_sand"), width=b, normal_damping=5e3)

    def loads(t, q, v):
        pos, vel, w = gauss_points(p, q, v, 3)
        x = pos[..., 0].ravel()
        out = contact.loads(x, pos[..., 1].ravel(), tr.SlipState.at_rest(x), vel[..., 1].ravel())
        F, M = lump_line_load(p, q, np.stack([out.fx, out.fz], -1).reshape(pos.shape), w)
        return {"link_forces": F, "link_moments": M}

    q0 = np.array([L / 8, 0.0, 0.0, 0.0, 0.0, 0.0])  # lying straight on the surface
    tr_ = simulate(p, q0, np.zeros(6), 0.3, method="LSODA", rtol=1e-8, atol=1e-11, loads=loads)
    sink = tr.plate_sinkage(contact.soil, m_A * g * L, b, L)
    assert -tr_.q[-1][1] == pytest.approx(sink, rel=1e-6)
    assert np.max(np.abs(tr_.q[-1][2:])) < 1e-10  # stays straight


def test_natural_frequencies_converge_to_the_euler_bernoulli_cantilever():
    from scipy.linalg import eigh

    beta_l = np.array([1.8751040687119611, 4.694091132973912, 7.854757438237613])
    errs = []
    for n in (16, 32, 64):
        p = ml.chain_from_beam(1.0, 1.0, 1.0, n)
        w2 = eigh(ml.stiffness_matrix(p), ml.mass_matrix(p, np.zeros(n)), eigvals_only=True)
        errs.append(np.abs(np.sqrt(w2[:3]) / beta_l**2 - 1.0))
    errs = np.array(errs)
    assert np.all(errs[-1] < 1e-3)
    assert np.all(np.abs(np.log2(errs[:-1] / errs[1:]) - 2.0) < 0.1)
