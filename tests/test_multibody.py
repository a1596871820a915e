"""The general multibody engine (ch. 3 Eqs. 48-75) against independent truth."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from mf_envs.frames import exp_so3, hat, orthonormality_error, rot_x, rot_y, vee
from mf_envs.physics.multibody import (
    Body,
    Fixed,
    Free,
    Multibody,
    Prismatic,
    Revolute,
    Spherical,
    constant_rate,
    harmonic,
)
from mf_envs.physics.multibody import kernels as K


def _rock(t: float):
    """Prescribed buoy attitude R = rot_x(b1) rot_y(b2) with its exact body rates."""
    b1, b1d, b1dd = 0.2 * np.sin(1.3 * t), 0.26 * np.cos(1.3 * t), -0.338 * np.sin(1.3 * t)
    b2, b2d, b2dd = 0.1 * np.cos(0.7 * t), -0.07 * np.sin(0.7 * t), -0.049 * np.cos(0.7 * t)
    Ry = rot_y(b2)
    w = Ry.T @ np.array([b1d, 0, 0]) + np.array([0, b2d, 0])
    # d/dt (Ry^T e1 b1d) = -hat(e2 b2d) Ry^T e1 b1d + Ry^T e1 b1dd
    wd = -np.cross([0, b2d, 0], Ry.T @ [b1d, 0, 0]) + Ry.T @ [b1dd, 0, 0] + [0, b2dd, 0]
    return rot_x(b1) @ Ry, w, wd


def gowec_like(prescribe_buoy: bool = True) -> Multibody:
    """Buoy (free or prescribed), gimbal with offsets, thick rotor with an offset axis."""
    return Multibody(
        [
            Body(
                "buoy",
                800.0,
                (900.0, 700.0, 500.0),
                Free() if not prescribe_buoy else Spherical(),
                prescribed=_rock if prescribe_buoy else None,
            ),
            Body(
                "gimbal",
                30.0,
                (3.0, 2.0, 2.5),
                Revolute((0, 1, 0), offset=(0.2, -0.1, 0.4), child_offset=(0.0, 0.0, 0.05)),
                parent="buoy",
            ),
            Body(
                "rotor",
                60.0,
                (4.0, 4.5, 7.0),
                Revolute((0, 0, 1), child_offset=(0.01, 0, 0)),
                parent="gimbal",
                prescribed=constant_rate(80.0),
            ),
            Body(
                "slider",
                5.0,
                (0.1, 0.2, 0.3),
                Prismatic((1, 0, 0), offset=(0, 0.5, 0)),
                parent="buoy",
            ),
            Body(
                "pendulum",
                2.0,
                (0.05, 0.05, 0.01),
                Spherical(child_offset=(0, 0, -0.3), offset=(0, 0, 0.2), rotation=rot_x(0.4)),
                parent="slider",
            ),
            Body("weld", 1.0, (0.01, 0.02, 0.03), Fixed(offset=(0.3, 0, 0)), parent="gimbal"),
        ],
        gravity=(0, 0, -9.81),
    )


def random_state(m: Multibody, rng: np.random.Generator, t: float = 0.3):
    q = {
        "gimbal": rng.uniform(-3, 3),
        "slider": rng.uniform(-0.5, 0.5),
        "pendulum": exp_so3(rng.normal(size=3)),
    }
    u = {"gimbal": rng.normal(), "slider": rng.normal(), "pendulum": rng.normal(size=3)}
    if "buoy" in q or m.bodies[0].prescribed is None:
        q["buoy"] = (exp_so3(rng.normal(size=3)), rng.normal(size=3))
        u["buoy"] = rng.normal(size=6)
    return m.initial_state(t=t, q=q, u=u)


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_reduced_mass_matrix_symmetric_positive_definite(seed):
    m = gowec_like(prescribe_buoy=False)
    s = random_state(m, np.random.default_rng(seed))
    Ms, Ns, Fs = m.matrices(s)
    assert Ms.shape == (m.nu, m.nu) == (12, 12)
    np.testing.assert_allclose(Ms, Ms.T, atol=1e-10 * np.abs(Ms).max())
    assert np.linalg.eigvalsh(Ms).min() > 0
    # M*' along the motion (finite difference) vs N*: with D skew (Eq. 65) the exact identity is
    # N* + N*^T = M*' + B^T (D M - M D) B, and u . N* u = 1/2 u . M*' u (N* does no net work)
    eps = 1e-6
    free_all = np.ones(len(m.bodies), dtype=np.bool_)
    a = m._arrays
    sp = s.copy()
    sm = s.copy()
    sp.q = K.retract(s.q, eps * s.u, a["jtype"], a["qoff"], a["uoff"], free_all)
    sm.q = K.retract(s.q, -eps * s.u, a["jtype"], a["qoff"], a["uoff"], free_all)
    Msd = (m.matrices(sp)[0] - m.matrices(sm)[0]) / (2 * eps)
    _, _, B, _, om = m.kinematics(s)
    D = np.zeros((6 * len(m.bodies),) * 2)
    for b in range(len(m.bodies)):
        D[6 * b + 3 : 6 * b + 6, 6 * b + 3 : 6 * b + 6] = hat(om[b])
    M = m.mass_matrix_blocks()
    np.testing.assert_allclose(
        Ns + Ns.T, Msd + B.T @ (D @ M - M @ D) @ B, atol=1e-6 * np.abs(Msd).max()
    )
    assert s.u @ Ns @ s.u == pytest.approx(0.5 * s.u @ Msd @ s.u, rel=1e-6)


@pytest.mark.parametrize("seed", [3, 4])
def test_B_and_Bdot_against_finite_differences_of_body_poses(seed):
    m = gowec_like(prescribe_buoy=False)
    s = random_state(m, np.random.default_rng(seed))
    R, x, B, Bd, om = m.kinematics(s)
    a = m._arrays
    free_all = np.ones(len(m.bodies), dtype=np.bool_)
    eps = 1e-6

    def at(e):
        q = K.retract(s.q, e * s.u, a["jtype"], a["qoff"], a["uoff"], free_all)
        st = s.copy()
        st.q = q
        return m.kinematics(st)

    Rp, xp, Bp, *_ = at(eps)
    Rm, xm, Bm, *_ = at(-eps)
    Xd = B @ s.u
    for b in range(len(m.bodies)):
        v_fd = (xp[b] - xm[b]) / (2 * eps)
        w_fd = vee(R[b].T @ (Rp[b] - Rm[b]) / (2 * eps))
        np.testing.assert_allclose(Xd[6 * b : 6 * b + 3], v_fd, atol=1e-6)
        np.testing.assert_allclose(Xd[6 * b + 3 : 6 * b + 6], w_fd, atol=1e-6)
        np.testing.assert_allclose(om[b], w_fd, atol=1e-6)
    np.testing.assert_allclose(Bd, (Bp - Bm) / (2 * eps), atol=1e-5)


@pytest.mark.slow
def test_energy_balance_with_prescribed_buoy_rotor_and_generator_torque():
    """d/dt (K + U) = power of the applied torque + power of the prescribing actuators."""
    m = gowec_like(prescribe_buoy=True)
    s = m.initial_state(q={"gimbal": 0.3, "pendulum": rot_x(0.5)}, u={"gimbal": 0.5})
    tau = m.joint_forces(gimbal=-2.0, slider=3.0)
    wrench = np.zeros((len(m.bodies), 6))
    wrench[4] = [1.0, 0.0, 0.5, 0.1, -0.2, 0.0]
    dt, n = 2e-3, 1000
    E0 = m.kinetic_energy(s) + m.potential_energy(s)
    P = [m.power(s, wrench, tau)]
    for _ in range(n):
        s = m.step(s, dt, wrench, tau)
        P.append(m.power(s, wrench, tau))
    E1 = m.kinetic_energy(s) + m.potential_energy(s)
    P = np.asarray(P)
    # Simpson's rule over the sampled power
    work = dt / 3 * (P[0] + P[-1] + 4 * P[1:-1:2].sum() + 2 * P[2:-1:2].sum())
    scale = np.abs(P).max() * n * dt
    assert abs((E1 - E0) - work) < 1e-7 * scale, (E1 - E0, work, scale)
    assert orthonormality_error(m.poses(s)[0]) < 1e-12


def test_free_rigid_body_matches_euler_equations():
    J = np.array([2.0, 3.0, 4.0])
    m = Multibody([Body("b", 1.0, J, Free())])
    w0 = np.array([0.3, 2.0, 0.1])
    v0 = np.array([1.0, -0.5, 0.2])
    s = m.initial_state(u={"b": (v0, w0)})
    dt, n = 1e-2, 500
    for _ in range(n):
        s = m.step(s, dt)

    def euler(t, y):
        w = y[:3]
        R = y[3:].reshape(3, 3)
        return np.concatenate([-np.cross(w, J * w) / J, (R @ hat(w)).ravel()])

    sol = solve_ivp(
        euler,
        (0, n * dt),
        np.concatenate([w0, np.eye(3).ravel()]),
        rtol=1e-12,
        atol=1e-12,
        method="DOP853",
    )
    R, x = m.coordinate(s, "b")
    np.testing.assert_allclose(m.velocity(s, "b")[3:], sol.y[:3, -1], atol=1e-6)
    np.testing.assert_allclose(R, sol.y[3:, -1].reshape(3, 3), atol=1e-6)
    np.testing.assert_allclose(x, v0 * n * dt, atol=1e-12)


def test_axisymmetric_free_body_closed_form():
    """J1 = J2: omega3 constant, (omega1, omega2) turns at lambda = (J3 - J1) omega3 / J1 in the
    body frame; H is constant in the inertial frame (both closed form)."""
    J1, J3 = 2.0, 3.5
    w0 = np.array([0.4, -0.3, 2.0])
    m = Multibody([Body("b", 1.0, (J1, J1, J3), Spherical())])
    s = m.initial_state(u={"b": w0})
    H0 = np.array([J1, J1, J3]) * w0
    dt, n = 5e-3, 800
    for _ in range(n):
        s = m.step(s, dt)
    t = n * dt
    lam = (J3 - J1) * w0[2] / J1
    c, sn = np.cos(lam * t), np.sin(lam * t)
    exact = np.array([c * w0[0] - sn * w0[1], sn * w0[0] + c * w0[1], w0[2]])
    np.testing.assert_allclose(m.velocity(s, "b"), exact, atol=1e-9)
    R = m.coordinate(s, "b")
    np.testing.assert_allclose(R @ (np.array([J1, J1, J3]) * m.velocity(s, "b")), H0, atol=1e-9)


def test_heavy_top_matches_euler_poisson_equations():
    """Spherical joint with the centre of mass off the pivot vs J w' = -w x Jw + m g l x Gamma."""
    J = np.array([0.02, 0.02, 0.01])  # about the centre of mass
    mass, l, g = 1.0, 0.1, 9.81
    top = Multibody([Body("top", mass, J, Spherical(child_offset=(0, 0, l)))], gravity=(0, 0, -g))
    R0, w0 = rot_x(0.3), np.array([0.5, 0.0, 40.0])
    s = top.initial_state(q={"top": R0}, u={"top": w0})
    E0 = top.kinetic_energy(s) + top.potential_energy(s)
    dt, n = 1e-3, 1000
    for _ in range(n):
        s = top.step(s, dt)
    Jp = J + mass * l**2 * np.array([1, 1, 0])  # about the pivot (parallel axes)
    r = np.array([0, 0, l])

    def ep(t, y):
        w, R = y[:3], y[3:].reshape(3, 3)
        torque = np.cross(r, R.T @ np.array([0, 0, -mass * g]))
        return np.concatenate([(torque - np.cross(w, Jp * w)) / Jp, (R @ hat(w)).ravel()])

    sol = solve_ivp(
        ep, (0, n * dt), np.concatenate([w0, R0.ravel()]), rtol=1e-12, atol=1e-12, method="DOP853"
    )
    np.testing.assert_allclose(top.velocity(s, "top"), sol.y[:3, -1], atol=1e-6)
    np.testing.assert_allclose(top.coordinate(s, "top"), sol.y[3:, -1].reshape(3, 3), atol=1e-6)
    E1 = top.kinetic_energy(s) + top.potential_energy(s)
    assert abs(E1 - E0) < 1e-9 * E0


def test_rkmk4_is_fourth_order():
    m = Multibody([Body("b", 1.0, (1.0, 2.0, 3.0), Spherical())])
    s0 = m.initial_state(u={"b": (1.0, 0.5, -0.7)})

    def run(dt):
        s = s0.copy()
        for _ in range(round(1.0 / dt)):
            s = m.step(s, dt)
        return m.coordinate(s, "b")

    ref = run(1e-3)
    e1, e2 = (np.abs(run(h) - ref).max() for h in (0.1, 0.05))
    assert 3.6 < np.log2(e1 / e2) < 4.6


def test_prescribed_joint_follows_prescription_and_reaction_is_inertial_torque():
    """A rotor driven by harmonic(...) about a fixed axis needs tau = J3 q''."""
    m = Multibody(
        [Body("r", 1.0, (1.0, 1.0, 2.5), Revolute((0, 0, 1)), prescribed=harmonic(0.7, 3.0))]
    )
    s = m.initial_state(t=0.4)
    for _ in range(10):
        s = m.step(s, 0.01)
    q, qd, qdd = harmonic(0.7, 3.0)(s.t)
    assert m.coordinate(s, "r") == pytest.approx(q)
    assert m.velocity(s, "r") == pytest.approx(qd)
    assert m.reactions(s)["r"] == pytest.approx(2.5 * qdd, rel=1e-12)


def test_bad_inputs_raise_value_errors_naming_the_parameter():
    with pytest.raises(ValueError, match="parent"):
        Multibody([Body("a", 1.0, (1, 1, 1), Revolute(), parent="b")])
    with pytest.raises(ValueError, match="a.mass"):
        Multibody([Body("a", -1.0, (1, 1, 1), Revolute())])
    with pytest.raises(ValueError, match="a.inertia"):
        Multibody([Body("a", 1.0, (1, -1, 1), Revolute())])
    with pytest.raises(ValueError, match="axis"):
        Multibody([Body("a", 1.0, (1, 1, 1), Revolute((0, 0, 0)))])
    m = Multibody([Body("a", 1.0, (1, 1, 1), Spherical())])
    with pytest.raises(ValueError, match="a"):
        m.initial_state(q={"a": np.ones((3, 3))})
    with pytest.raises(ValueError, match="name"):
        m.slots("zzz")


def test_module_docstring_example_runs():
    """The worked example the ship model builds on stays valid."""
    import doctest

    from mf_envs.physics import multibody

    res = doctest.testmod(multibody, verbose=False)
    assert res.failed == 0 and res.attempted >= 10
