"""SO(3)/SE(3) kernel against independent truth: scipy's expm, group identities, FD."""

import math

import numpy as np
import pytest
import scipy.linalg as sla
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from mf_envs.frames import (
    compose,
    exp_so3,
    frame_connection,
    frame_inverse,
    hat,
    log_so3,
    orthonormality_error,
    project_to_so3,
    relative_connection,
    rot_x,
    rot_y,
    rot_z,
    time_rate_connection,
    twist_from_time_rate,
    vee,
)
from mf_envs.frames.kernels import exp_so3 as exp_so3_nb

vec3 = arrays(np.float64, 3, elements=st.floats(-10, 10, allow_nan=False))
small_vec3 = arrays(np.float64, 3, elements=st.floats(-1e-5, 1e-5, allow_nan=False))
# compile (or load) the numba kernels once here, not inside a hypothesis deadline
exp_so3(np.zeros(3)), log_so3(np.eye(3)), hat(np.zeros(3)), vee(np.zeros((3, 3)))


@given(vec3)
def test_exp_is_rotation(w):
    R = exp_so3(w)
    assert orthonormality_error(R) < 1e-13
    assert abs(np.linalg.det(R) - 1.0) < 1e-13


@given(vec3)
def test_exp_matches_scipy_expm_and_numba_kernel(w):
    R = exp_so3(w)
    assert np.allclose(R, sla.expm(hat(w)), atol=1e-12)
    assert np.allclose(exp_so3_nb(w), R, atol=1e-14)


@given(small_vec3)
def test_small_angle_branch_matches_series(w):
    # exp(W) = I + W + W^2/2 + W^3/6 + ... to round-off for |w| < 1e-5
    W = hat(w)
    ref = np.eye(3) + W + W @ W / 2 + W @ W @ W / 6
    assert np.allclose(exp_so3(w), ref, atol=1e-16, rtol=0)


@given(vec3)
def test_hat_vee_cross(w):
    v = np.array([0.3, -1.1, 2.2])
    assert np.allclose(hat(w) @ v, np.cross(w, v))
    assert np.allclose(vee(hat(w)), w)


@given(
    arrays(np.float64, 3, elements=st.floats(-1, 1, allow_nan=False)), st.floats(0.0, np.pi - 1e-9)
)
def test_log_inverts_exp_on_its_domain(axis, angle):
    n = np.linalg.norm(axis)
    if n < 1e-3:
        axis, n = np.array([0.0, 0.0, 1.0]), 1.0
    w = axis / n * angle
    assert np.allclose(log_so3(exp_so3(w)), w, atol=1e-8)
    # R is recovered to round-off everywhere, including near pi
    assert np.allclose(exp_so3(log_so3(exp_so3(w))), exp_so3(w), atol=1e-12)


def test_elementary_rotations_are_exponentials():
    for R, e in ((rot_x, 0), (rot_y, 1), (rot_z, 2)):
        w = np.zeros(3)
        w[e] = 0.7
        assert np.allclose(R(0.7), exp_so3(w), atol=1e-15)


@settings(max_examples=50)
@given(vec3, vec3, vec3, vec3, vec3, vec3)
def test_composition_associative_and_inverse(w1, x1, w2, x2, w3, x3):
    A, B, C = (frame_connection(exp_so3(w), x) for w, x in ((w1, x1), (w2, x2), (w3, x3)))
    assert np.allclose(compose(compose(A, B), C), compose(A, compose(B, C)), atol=1e-10)
    assert np.allclose(frame_inverse(A) @ A, np.eye(4), atol=1e-12)
    assert np.allclose(frame_inverse(A), np.linalg.inv(A), atol=1e-10)
    # relative connection recovers the child from the parent (Eq. 7)
    assert np.allclose(A @ relative_connection(A, B), B, atol=1e-10)


def test_time_rate_connection_of_known_motion():
    """Screw motion R = exp(t hat(w)) R0, x = x0 + v t: Omega = [[R^T dR/dt, R^T x'], [0, 0]]."""
    w = np.array([0.2, -0.5, 1.3])
    v = np.array([1.0, 2.0, -0.5])
    R0 = exp_so3([0.4, 0.1, -0.9])
    x0 = np.array([3.0, -1.0, 2.0])
    t, h = 0.8, 1e-6

    def E(s):
        return frame_connection(exp_so3(s * w) @ R0, x0 + s * v)

    Edot = (E(t + h) - E(t - h)) / (2 * h)
    omega, vb = twist_from_time_rate(time_rate_connection(E(t), Edot))
    R = exp_so3(t * w) @ R0
    # spatial angular velocity w -> body omega = R^T w
    assert np.allclose(omega, R.T @ w, atol=1e-8)
    assert np.allclose(vb, R.T @ v, atol=1e-8)


def test_project_to_so3_and_bad_shapes():
    R = exp_so3([0.3, 0.2, 0.1]) + 1e-6 * np.arange(9).reshape(3, 3)
    P = project_to_so3(R)
    assert orthonormality_error(P) < 1e-14
    assert np.linalg.det(P) > 0
    with pytest.raises(ValueError, match="w"):
        exp_so3([1.0, 2.0])
    with pytest.raises(ValueError, match="R"):
        log_so3(np.eye(2))


@settings(deadline=None)
@given(vec3.filter(lambda w: np.linalg.norm(w) < 3.0), vec3)
def test_dexp_right_and_left_match_finite_differences(theta, thd):
    """omega = dexp(theta) theta' against the central difference of R = exp(hat(theta)),
    body (R^T R') and spatial (R' R^T), and dexpinv inverts dexp (frames.kernels module doc)."""
    from mf_envs.frames import kernels as k

    eps = 1e-6
    R = k.exp_so3(theta)
    dR = (k.exp_so3(theta + eps * thd) - k.exp_so3(theta - eps * thd)) / (2 * eps)
    scale = 1.0 + np.linalg.norm(thd)
    assert np.allclose(vee(R.T @ dR), k.dexp_right(theta, thd), atol=1e-7 * scale)
    assert np.allclose(vee(dR @ R.T), k.dexp_left(theta, thd), atol=1e-7 * scale)
    assert np.allclose(k.dexpinv_right(theta, k.dexp_right(theta, thd)), thd, atol=1e-12 * scale)
    assert np.allclose(k.dexpinv_left(theta, k.dexp_left(theta, thd)), thd, atol=1e-12 * scale)


def test_dexpinv_right_series_is_the_body_frame_one():
    """theta' = omega + 1/2 theta x omega + 1/12 theta x (theta x omega) + O(theta^4) for the
    update R exp(hat(theta)) (the sign the ship's copy had wrong, issue 11)."""
    from mf_envs.frames import kernels as k

    th, w = np.array([1e-3, -2e-3, 1.5e-3]), np.array([0.6, 0.8, 0.4])
    series = w + 0.5 * np.cross(th, w) + np.cross(th, np.cross(th, w)) / 12.0
    assert np.allclose(k.dexpinv_right(th, w), series, rtol=0, atol=1e-12)  # next: x^2/720


def test_sincos_near_equals_libm_to_round_off() -> None:
    """sincos_near (addition formulas + Taylor series of the offset) against libm's cos, sin:
    within 4e-16 absolute for offsets up to 0.1 rad on each side of angles across two turns,
    exactly (c0, s0) at a zero offset, and libm's own values beyond 0.1 rad."""
    from mf_envs.frames.kernels import sincos_near

    rng = np.random.default_rng(7)
    worst = 0.0
    for x0 in rng.uniform(-4 * np.pi, 4 * np.pi, 200):
        c0, s0 = math.cos(x0), math.sin(x0)
        assert sincos_near(x0, x0, c0, s0) == (c0, s0)
        for d in np.concatenate([rng.uniform(-0.1, 0.1, 20), [0.0999, -0.0999, 1e-12]]):
            c, s = sincos_near(x0 + d, x0, c0, s0)
            worst = max(worst, abs(c - math.cos(x0 + d)), abs(s - math.sin(x0 + d)))
        for d in (0.12, -0.3, 2.0):
            assert sincos_near(x0 + d, x0, c0, s0) == (math.cos(x0 + d), math.sin(x0 + d))
    assert worst < 4e-16, worst
