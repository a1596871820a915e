"""Absorbed-power bounds of the FloatingGOWEC-v0 hull (issue 29) against analytic results:
the radiation bound of an axisymmetric body in pitch is lambda J / pi (Budal & Falnes 1975,
Newman 1976), and a tilt limit theta_max caps the power of a regular wave at
1/2 |X| a w theta_max (Evans 1981; Falnes 2002 ch. 6)."""

import math

import numpy as np
import pytest

from mf_envs.physics.gowec.hydro import load_hull
from mf_envs.physics.gowec.hydro.model import (
    motion_limited_bound,
    radiation_bound,
    wave_power_flux,
)
from mf_envs.physics.waves import IrregularSea, jonswap_spectrum, regular_wave


@pytest.fixture(scope="module")
def hull():
    return load_hull()


def _lambda_over_pi(hull, wave, w):
    return wave_power_flux(wave, hull.rho, hull.g) * 2.0 * math.pi * hull.g / w**2 / math.pi


def test_radiation_bound_is_lambda_over_pi_on_the_table(hull):
    # at the BEM frequencies in 0.3-3 rad/s (this is the Haskind relation of the table)
    for w in hull.omega[(hull.omega >= 0.3) & (hull.omega <= 3.0)]:
        wave = regular_wave(0.5, 2.0 * math.pi / w)
        assert radiation_bound(hull, wave) == pytest.approx(
            _lambda_over_pi(hull, wave, w), rel=0.02
        )


@pytest.mark.parametrize("period", [3.0, 4.0, 5.0, 6.0, 7.0, 9.0])
def test_radiation_bound_is_lambda_over_pi(hull, period):
    # between table frequencies `at` interpolates B and X linearly: within 3 % for 3-9 s; at
    # longer periods B ~ w^7 is convex on the 0.072 rad/s grid and the bound drops (-9 % at 16 s)
    wave = regular_wave(0.5, period)
    w = 2.0 * math.pi / period
    assert radiation_bound(hull, wave) == pytest.approx(_lambda_over_pi(hull, wave, w), rel=0.03)


def _constrained_optimum(F: complex, B: float, umax: float) -> float:
    """max over complex u, |u| <= umax, of 1/2 Re(F conj(u)) - 1/2 B |u|^2, numerically (SLSQP
    from a grid of starting points; no use of the closed form)."""
    from scipy.optimize import minimize

    def power(x):
        return 0.5 * (F.real * x[0] + F.imag * x[1]) - 0.5 * B * (x[0] ** 2 + x[1] ** 2)

    cons = [{"type": "ineq", "fun": lambda x: 1.0 - (x[0] ** 2 + x[1] ** 2) / umax**2}]
    best = 0.0
    for ph in np.linspace(-math.pi, math.pi, 8, endpoint=False):
        x0 = 0.5 * umax * np.array([math.cos(ph), math.sin(ph)])
        r = minimize(lambda x: -power(x) / (abs(F) * umax), x0, method="SLSQP",
                     constraints=cons, options=dict(ftol=1e-14, maxiter=500))  # fmt: skip
        if np.hypot(*r.x) <= umax * (1 + 1e-9):
            best = max(best, power(r.x))
    return best


@pytest.mark.parametrize("theta_max", [0.002, 0.02, 0.1, 1.0])
def test_motion_limited_bound_regular(hull, theta_max):
    a, T = 0.5, 5.5
    wave = regular_wave(a, T)
    w = 2.0 * math.pi / T
    _, B, X = hull.at(w)
    bound = motion_limited_bound(hull, wave, theta_max)
    best = _constrained_optimum(X * a, B, w * theta_max)
    assert best <= bound * (1.0 + 1e-9)
    radiation = radiation_bound(hull, wave)
    if 0.5 * abs(X) * a / B > w * theta_max:  # the limit binds: the bound is 1/2 |X| a w theta_max
        assert bound == pytest.approx(0.5 * abs(X) * a * w * theta_max, rel=1e-12)
        # and exceeds the exact constrained optimum by the radiated 1/2 B (w theta_max)^2
        assert bound - best == pytest.approx(0.5 * B * (w * theta_max) ** 2, rel=1e-3, abs=1e-9)
    else:  # the unconstrained optimum is reachable: the radiation bound
        assert bound == radiation and best == pytest.approx(radiation, rel=1e-5)


def test_motion_limited_bound_irregular_and_bad_input(hull):
    sea = IrregularSea(jonswap_spectrum, 1.5, 6.0, 64, np.random.default_rng(0))
    small = motion_limited_bound(hull, sea, 0.01)
    assert 0.0 < small < radiation_bound(hull, sea)
    assert motion_limited_bound(hull, sea, 0.02) == pytest.approx(2.0 * small, rel=1e-12)
    for bad in (0.0, -0.1, math.inf, math.nan):
        with pytest.raises(ValueError, match="theta_max"):
            motion_limited_bound(hull, sea, bad)
