"""Poinsot geometry (ch. 2 Eqs. 32-40) against its defining equations and the exact motion."""

import numpy as np
import pytest

from mf_envs.physics.rigid_body import elliptic_solution, simulate
from mf_envs.physics.rigid_body import polhode as polhode

J = np.array([2.0, 1.0, 0.5])  # Fig. 2-5: J1/J2 = 2, J3/J2 = 0.5


@pytest.mark.parametrize("d", [0.5, 0.65, 0.95, 0.999999, 1.0, 1.000001, 1.5, 1.95, 2.0])
def test_polhodes_lie_on_ellipsoid_and_sphere(d):
    for curve in polhode.polhode(J, d, 300):
        ellipsoid = (
            (J[1] / J[0]) * curve[:, 0] ** 2 + curve[:, 1] ** 2 + (J[1] / J[2]) * curve[:, 2] ** 2
        )
        assert np.allclose(ellipsoid, 1.0, atol=1e-13)  # Eq. 36
        assert np.allclose(np.sum(curve**2, axis=1), d, atol=1e-13)  # Eq. 37a


def test_polhode_circles_the_right_axis():
    above = polhode.polhode(J, 1.3)
    below = polhode.polhode(J, 0.8)
    assert all(np.all(np.sign(c[:, 0]) == np.sign(c[0, 0])) for c in above)  # h1 never 0
    assert all(np.all(np.sign(c[:, 2]) == np.sign(c[0, 2])) for c in below)  # h3 never 0


def test_separatrix_planes_match_eq_40a():
    k = polhode.separatrix_slope(J)
    for curve in polhode.separatrices(J):
        assert np.allclose(np.abs(curve[:, 2]), k * np.abs(curve[:, 0]), atol=1e-14)
        # Eq. 40a with d = 1: -(1 - J2/J1) h1^2 + (J2/J3 - 1) h3^2 = 0
        lhs = -(1 - J[1] / J[0]) * curve[:, 0] ** 2 + (J[1] / J[2] - 1) * curve[:, 2] ** 2
        assert np.allclose(lhs, 0.0, atol=1e-14)
        assert np.allclose(polhode.d_bar(J, curve), 1.0, atol=1e-13)


def test_numerical_trajectory_stays_on_its_polhode():
    """The seed's scheme traces the exact curve (Fig. 2-5 overlay): every point satisfies both
    invariants of its starting point, and its d is the one of the polhode it started on."""
    start = polhode.polhode(J, 1.2)[0][10]
    sol = elliptic_solution(J, start / J)
    tr = simulate(J, start / J, sol.period, sol.period / 400)
    assert np.allclose(polhode.d_bar(J, tr.H), 1.2, atol=1e-7)
    assert np.allclose(polhode.energy(J, tr.H), 0.5, atol=1e-7)
    assert np.all(polhode.separatrix_side(J, tr.H) == 1)


def test_side_and_nondimensional():
    H = np.array([0.3, 1.0, 0.2])
    K0 = float(polhode.energy(J, H))
    h = polhode.nondimensional(J, H, K0)
    assert (J[1] / J[0]) * h[0] ** 2 + h[1] ** 2 + (J[1] / J[2]) * h[2] ** 2 == pytest.approx(1.0)
    d = polhode.d_bar(J, H)
    assert polhode.separatrix_side(J, H) == np.sign(d - 1)
    mesh = polhode.energy_ellipsoid(J, 10)
    vals = (J[1] / J[0]) * mesh[0] ** 2 + mesh[1] ** 2 + (J[1] / J[2]) * mesh[2] ** 2
    assert np.allclose(vals, 1.0)
    sphere = polhode.momentum_sphere(1.44, 10)
    assert np.allclose(sum(c**2 for c in sphere), 1.44)


def test_sort_axes_and_errors():
    Js, perm = polhode.sort_axes([1.0, 3.0, 2.0])
    assert np.array_equal(Js, [3.0, 2.0, 1.0]) and np.array_equal(perm, [1, 2, 0])
    with pytest.raises(ValueError, match="J"):
        polhode.polhode([1.0, 3.0, 2.0], 1.1)
    with pytest.raises(ValueError, match="J"):
        polhode.separatrices([2.0, 2.0, 1.0])
    with pytest.raises(ValueError, match="J"):
        polhode.sort_axes([1.0, -3.0, 2.0])
    with pytest.raises(ValueError, match="d"):
        polhode.polhode(J, 2.5)  # outside Eq. 37b
