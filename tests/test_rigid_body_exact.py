"""The exact (Jacobi elliptic) solution of ch. 2 against independent truth: mpmath's elliptic
functions, a tight DOP853 integration of Euler's equations, and the conserved quantities."""

import math

import numpy as np
import pytest
import scipy.special as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from mf_envs.physics.rigid_body.exact import (
    analytic_omega,
    complete_k,
    elliptic_solution,
    jacobi_sn_cn_dn,
)

RACKET_J = (0.0185, 0.0164, 0.00121)
RACKET_W0 = (0.001, 5.0, 0.001)


def euler_reference(J, w0, t, rtol=1e-13):
    J = np.asarray(J, float)

    def f(_, w):
        return np.cross(J * w, w) / J

    sol = solve_ivp(f, (0.0, t[-1]), w0, method="DOP853", rtol=rtol, atol=1e-15, t_eval=t)
    return sol.y.T


@pytest.mark.parametrize("m1", [0.9, 0.5, 1e-3, 1e-8, 1e-11, 1e-13, 1e-20])
def test_jacobi_agm_matches_mpmath(m1):
    mpmath = pytest.importorskip("mpmath", reason="needs the dev extra: pip install -e '.[dev]'")
    mpmath.mp.dps = 40
    u = np.array([-3.0, 0.3, 5.0, 17.0, 40.0, 123.4])
    sn, cn, dn = jacobi_sn_cn_dn(u, m1)
    m = 1 - mpmath.mpf(m1)
    for x, a, b, c in zip(u, sn, cn, dn):
        tru = [float(mpmath.ellipfun(k, mpmath.mpf(x), m=m)) for k in ("sn", "cn", "dn")]
        assert abs(a - tru[0]) < 1e-13 and abs(b - tru[1]) < 1e-13 and abs(c - tru[2]) < 1e-13


def test_jacobi_agm_where_scipy_ellipj_fails():
    """scipy issue #8480: ellipj is wrong for 1 - m < 1e-9 and u > K. Truth without mpmath:
    the m -> 1 expansion (Abramowitz & Stegun 16.15) at u = 5, carried past K by the half-period
    shift sn(u + 2K) = -sn(u), cn(u + 2K) = -cn(u), dn(u + 2K) = dn(u), K from Carlson's R_F."""
    m1, u = 1e-11, 5.0
    q = 0.25 * m1 * (math.sinh(u) * math.cosh(u) - u)
    p = 0.25 * m1 * (math.sinh(u) * math.cosh(u) + u)
    sech, tanh = 1 / math.cosh(u), math.tanh(u)
    truth = (tanh + q * sech**2, sech - q * tanh * sech, sech + p * tanh * sech)
    two_k = 2 * complete_k(m1)
    assert u + two_k > complete_k(m1)
    sn, cn, dn = jacobi_sn_cn_dn(np.array([u, u + two_k, u - two_k]), m1)
    for got, sign in ((0, 1), (1, -1), (2, -1)):
        assert abs(sn[got] - sign * truth[0]) < 1e-13
        assert abs(cn[got] - sign * truth[1]) < 1e-13
        assert abs(dn[got] - truth[2]) < 1e-13


def test_jacobi_separatrix_limit_is_continuous():
    u = np.linspace(-6, 6, 25)
    lim = jacobi_sn_cn_dn(u, 0.0)
    assert np.allclose(lim[0], np.tanh(u)) and np.allclose(lim[1], 1 / np.cosh(u))
    near = jacobi_sn_cn_dn(u, 1e-14)
    for a, b in zip(lim, near):
        assert np.max(np.abs(a - b)) < 1e-11


def test_complete_k_matches_scipy():
    for m1 in (0.7, 0.1, 1e-4):
        assert complete_k(m1) == pytest.approx(sp.ellipk(1 - m1), rel=1e-14)
    assert complete_k(1e-30) == pytest.approx(0.5 * math.log(16 / 1e-30), rel=1e-12)


@pytest.mark.parametrize(
    "J, w0",
    [
        ((3.0, 2.0, 1.0), (0.3, 1.0, 0.8)),  # D < J2: circles e3
        ((3.0, 2.0, 1.0), (0.9, 1.0, 0.1)),  # D > J2: circles e1
        ((1.0, 3.0, 2.0), (0.3, -1.0, 0.8)),  # unsorted, odd permutation
        ((2.0, 1.0, 3.0), (-0.3, 0.5, -0.8)),  # unsorted, negative components
        ((2.0, 2.0, 1.0), (0.3, 0.5, 0.8)),  # axisymmetric (m = 0)
        ((1.0, 2.0, 2.0), (0.3, 0.5, 0.8)),
        ((3.036e-6, 2.741e-6, 0.699e-6), (1e-8 / 3.036e-6, 2.1252e-5 / 2.741e-6, 1e-8 / 0.699e-6)),
    ],
)
def test_analytic_matches_dop853(J, w0):
    t = np.linspace(0.0, 10.0, 801)
    err = np.max(np.abs(analytic_omega(J, w0, t) - euler_reference(J, w0, t)))
    assert err < 2e-9 * np.linalg.norm(w0)


@settings(max_examples=25, deadline=None)
@given(
    J=st.lists(st.floats(0.2, 5.0), min_size=3, max_size=3),
    w0=st.lists(st.floats(-3.0, 3.0), min_size=3, max_size=3),
)
def test_analytic_random_bodies(J, w0):
    if np.linalg.norm(w0) < 1e-3:
        return
    t = np.linspace(0.0, 4.0, 41)
    ref = euler_reference(J, w0, t, rtol=1e-12)
    assert np.max(np.abs(analytic_omega(J, w0, t) - ref)) < 1e-7 * np.linalg.norm(w0)


@pytest.mark.parametrize(
    "J, w0",
    [((1.0, 2.0, 3.0), (0.0, 1.0, 1.3e-157)), ((3.0, 2.0, 1.0), (1.3e-157, 1.0, 0.0))],
)
def test_intermediate_axis_with_a_subnormal_deviation(J, w0):
    """Hypothesis found these: a deviation of 1e-157 from the permanent rotation about the
    intermediate axis made 1 - m subnormal and the solution NaN; it stays on the axis to
    round-off for t = 0..4 s (the deviation grows as e^{lam t})."""
    t = np.linspace(0.0, 4.0, 41)
    w = analytic_omega(J, w0, t)
    assert np.all(np.isfinite(w)) and np.max(np.abs(w - np.asarray(w0))) < 1e-12


def test_racket_period_and_invariants():
    s = elliptic_solution(RACKET_J, RACKET_W0)
    assert s.period == pytest.approx(6.767881, abs=1e-6)  # docs/design.md
    assert s.axes[1] == 1 and s.side == 1  # intermediate axis e2, D > J2 (circles e1)
    flips = s.flip_times(20.0)
    assert np.allclose(np.diff(flips), s.period / 2, rtol=1e-12)
    t = np.linspace(0, 20, 4001)
    w = analytic_omega(RACKET_J, RACKET_W0, t)
    J = np.asarray(RACKET_J)
    E = np.sum(J * w * w, axis=1)
    H2 = np.sum((J * w) ** 2, axis=1)
    assert np.max(np.abs(E / E[0] - 1)) < 1e-13 and np.max(np.abs(H2 / H2[0] - 1)) < 1e-13
    w_flip = analytic_omega(RACKET_J, RACKET_W0, flips[:3])
    assert np.max(np.abs(w_flip[:, 1])) < 1e-9 * 5.0  # omega_2 = 0 at a flip


def _near_separatrix(J, eps):
    """omega0 with (D - J2)/J2 = eps (any sign): H on a separatrix plane, h3 nudged."""
    J = np.asarray(J, float)
    k = math.sqrt(J[2] * (J[0] - J[1]) / (J[0] * (J[1] - J[2])))
    H = np.array([0.05, 1.0, 0.05 * k])
    for _ in range(50):  # fixed point on H3 so that 2K (D - J2) = eps 2K J2
        two_k = np.sum(H * H / J)
        rhs = H[0] ** 2 * (J[0] - J[1]) / J[0] - eps * two_k * J[1]
        H[2] = math.sqrt(rhs * J[2] / (J[1] - J[2]))
    return H / J


@pytest.mark.parametrize("eps", [1e-6, -1e-6, 1e-12, -1e-12])
def test_analytic_accurate_near_separatrix(eps):
    J = np.array([0.0108333, 0.00833333, 0.00416667])
    w0 = _near_separatrix(J, eps)
    w0 *= 2.0 / np.linalg.norm(w0)
    s = elliptic_solution(J, w0)
    assert s.side == np.sign(eps)
    if abs(eps) < 1e-10:
        assert s.m1 < 1e-10  # the regime where scipy's ellipj breaks
    # (1) against DOP853 through the first flip (before round-off amplification ~ exp(lam t))
    t_flip = s.flip_times(1e3)[0]
    t = np.linspace(0.0, 1.2 * t_flip, 601)
    ref = euler_reference(J, w0, t)
    assert np.max(np.abs(analytic_omega(J, w0, t) - ref)) < 1e-6 * 2.0
    # (2) over several flips: Euler's equations hold (central differences) and invariants exact
    t = np.linspace(0.0, 3.2 * s.period, 4001)
    h = 1e-4
    w, wp, wm = (analytic_omega(J, w0, t + d) for d in (0.0, h, -h))
    resid = J * (wp - wm) / (2 * h) - np.cross(J * w, w)
    assert np.max(np.abs(resid)) < 1e-6 * np.max(np.abs(np.cross(J * w, w)))
    E, H2 = np.sum(J * w * w, axis=1), np.sum((J * w) ** 2, axis=1)
    assert np.max(np.abs(E / E[0] - 1)) < 1e-12 and np.max(np.abs(H2 / H2[0] - 1)) < 1e-12
    circled = 0 if eps > 0 else 2  # the component that never changes sign
    assert np.all(np.sign(w[:, circled]) == np.sign(w0[circled]))


def test_permanent_rotations_and_axis_order():
    J = (3.0, 2.0, 1.0)
    for w0 in ((2.0, 0, 0), (0, -2.0, 0), (0, 0, 2.0)):
        assert np.array_equal(analytic_omega(J, w0, [0.0, 7.0])[1], np.asarray(w0, float))
    # relabelling the axes relabels the solution
    w0 = np.array([0.4, 1.0, -0.7])
    t = np.linspace(0, 9, 50)
    base = analytic_omega(J, w0, t)
    for perm in ([1, 2, 0], [2, 1, 0], [0, 2, 1]):
        permuted = analytic_omega(np.asarray(J)[perm], w0[perm], t)
        sign = 1.0 if perm in ([1, 2, 0],) else -1.0  # odd relabelling reverses time's sense
        if sign > 0:
            assert np.allclose(permuted, base[:, perm], atol=1e-12)
        else:  # a mirror frame: omega' = -omega(-t) ... compare invariants instead
            Jp = np.asarray(J)[perm]
            E = np.sum(Jp * permuted**2, axis=1)
            assert np.allclose(E, E[0], rtol=1e-13)
            ref = euler_reference(Jp, w0[perm], t)
            assert np.allclose(permuted, ref, atol=1e-9)


@pytest.mark.parametrize(
    "J, w0, name",
    [
        ((0.0, 1.0, 2.0), (1, 1, 1), "J"),
        ((-1.0, 1.0, 2.0), (1, 1, 1), "J"),
        ((np.nan, 1.0, 2.0), (1, 1, 1), "J"),
        ((1.0, np.inf, 2.0), (1, 1, 1), "J"),
        ((1.0, 2.0), (1, 1, 1), "J"),
        ((1.0, 2.0, 3.0), (1, np.nan, 1), "omega0"),
        ((1.0, 2.0, 3.0), (1, 1), "omega0"),
    ],
)
def test_bad_inputs(J, w0, name):
    with pytest.raises(ValueError, match=name):
        analytic_omega(J, w0, [0.0, 1.0])
