"""Linear waves (ch. 3 Eqs. 12-19, 89-93, 97) against limits, identities and published moments."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad

from mf_envs.frames import vee
from mf_envs.physics import waves as W


def test_dispersion_deep_and_shallow_limits_and_residual():
    w = np.linspace(0.2, 3.0, 50)
    np.testing.assert_allclose(W.wavenumber(w), w**2 / W.G)
    # deep water: kD >> 1 recovers w^2/g; shallow: k = w / sqrt(g D)
    np.testing.assert_allclose(W.wavenumber(w, depth=5000.0), w**2 / W.G, rtol=1e-12)
    D = 0.05
    np.testing.assert_allclose(W.wavenumber(w[:5], depth=D), w[:5] / np.sqrt(W.G * D), rtol=2e-3)
    for depth in (0.5, 3.0, 20.0, 200.0):
        k = W.wavenumber(w, depth)
        np.testing.assert_allclose(W.G * k * np.tanh(k * depth), w**2, rtol=1e-13)


def test_phase_and_group_velocity():
    T = 8.0
    w = 2 * math.pi / T
    assert W.phase_velocity(w) == pytest.approx(W.G * T / (2 * math.pi))  # deep: c_p = gT/2pi
    assert W.group_velocity(w) == pytest.approx(W.G * T / (4 * math.pi))
    assert W.wavelength(T) == pytest.approx(W.G * T**2 / (2 * math.pi))
    # c_g = dw/dk by a finite difference of the dispersion relation at finite depth
    D, h = 12.0, 1e-6
    dk = W.wavenumber(w + h, D) - W.wavenumber(w - h, D)
    assert W.group_velocity(w, D) == pytest.approx(2 * h / dk, rel=1e-8)
    assert W.group_velocity(w, 0.01) == pytest.approx(W.phase_velocity(w, 0.01), rel=1e-3)


def test_energy_and_power_per_metre():
    hs, T = 2.0, 10.0
    a = W.amplitude_from_hs(hs)
    assert W.energy_density(a) == pytest.approx(W.energy_density_hs(hs))  # Eqs. 15-17
    P_deep = W.deep_water_power_per_metre(hs, T)
    assert P_deep == pytest.approx(0.49e3 * hs**2 * T, rel=2e-3)  # "0.49 Hs^2 T kW/m" (rho 1025)
    assert W.power_per_metre(hs, T) == pytest.approx(P_deep, rel=1e-12)
    assert W.power_per_metre(hs, T, depth=1e4) == pytest.approx(P_deep, rel=1e-9)


def test_breaking_limit_eq97():
    assert W.BREAKING_STEEPNESS == pytest.approx(0.01326, abs=5e-6)
    T = 6.0
    a = W.breaking_amplitude(T)
    assert a * W.wavenumber(2 * math.pi / T) == pytest.approx(math.pi / 6)  # 30 deg slope


@pytest.mark.parametrize("gamma", [1.0, 2.0, 3.3, 7.0])
def test_spectra_moments(gamma):
    hs, tp = 3.0, 9.0
    m0, _ = quad(
        lambda w: W.jonswap_spectrum(np.array([w]), hs, tp, gamma)[0], 0, np.inf, limit=400
    )
    assert m0 == pytest.approx(hs**2 / 16, rel=1e-6)
    # the published approximate scaling A_gamma = 1 - 0.287 ln(gamma) (DNV-RP-C205)
    wp = 2 * math.pi / tp
    ratio = W.jonswap_spectrum(np.array([wp]), hs, tp, gamma)[0] / (
        gamma * W.pierson_moskowitz_spectrum(np.array([wp]), hs, tp)[0]
    )
    assert ratio == pytest.approx(1 - 0.287 * math.log(gamma), rel=0.03)
    w = np.linspace(0.3 * wp, 3 * wp, 20001)
    assert w[np.argmax(W.jonswap_spectrum(w, hs, tp, gamma))] == pytest.approx(wp, rel=1e-3)


def test_pierson_moskowitz_m0():
    m0, _ = quad(lambda w: W.pierson_moskowitz_spectrum(np.array([w]), 2.0, 7.0)[0], 0, np.inf)
    assert m0 == pytest.approx(0.25, rel=1e-8)


def test_irregular_sea_is_seeded_and_has_the_spectral_variance():
    def make(seed):
        return W.IrregularSea(W.jonswap_spectrum, 2.0, 8.0, 400, np.random.default_rng(seed))

    s1, s2, s3 = make(1), make(1), make(2)
    np.testing.assert_array_equal(s1.components[2], s2.components[2])
    assert not np.array_equal(s1.components[2], s3.components[2])
    t = np.arange(0.0, 3600.0, 0.25)
    eta = s1.elevation(t)
    # 4 sqrt(m0) = Hs (sample estimate over one hour of a 400-component sea)
    assert 4 * eta.std() == pytest.approx(2.0, rel=0.08)
    assert 4 * math.sqrt(0.5 * np.sum(s1.amplitudes**2)) == pytest.approx(2.0, rel=0.02)
    with pytest.raises(ValueError, match="rng"):
        W.IrregularSea(W.jonswap_spectrum, 2.0, 8.0, 10, 42)


def test_directional_wave_slope_and_buoy_rates_eqs_89_93():
    a, T, theta = 0.8, 5.0, 0.6
    wave = W.regular_wave(a, T, direction=theta)
    k, w = wave.wavenumbers[0], wave.omegas[0]
    t = 1.37
    (b1, b1d, _), (b2, b2d, _) = wave.slope_angles(t)
    assert b1 == pytest.approx(a * k * math.sin(w * t) * math.sin(theta))  # Eq. 90
    assert b1d == pytest.approx(a * k * w * math.cos(w * t) * math.sin(theta))  # Eq. 92
    assert b2d == pytest.approx(-a * k * w * math.cos(w * t) * math.cos(theta))  # Eq. 93 (sign)
    # slopes are the finite-difference gradient of the elevation (Eq. 89)
    h = 1e-5
    d2 = (wave.elevation(t, 0.0, h) - wave.elevation(t, 0.0, -h)) / (2 * h)
    d1 = (wave.elevation(t, h, 0.0) - wave.elevation(t, -h, 0.0)) / (2 * h)
    assert b1 == pytest.approx(d2, rel=1e-7) and b2 == pytest.approx(-d1, rel=1e-7)
    # R e3 is the surface normal to first order; omega = vee(R^T R') by finite differences
    R, om, omd = wave.buoy_motion(t)
    Rp, omp, _ = wave.buoy_motion(t + h)
    Rm, omm, _ = wave.buoy_motion(t - h)
    np.testing.assert_allclose(om, vee(R.T @ (Rp - Rm) / (2 * h)), atol=1e-8)
    np.testing.assert_allclose(omd, (omp - omm) / (2 * h), atol=1e-7)
    n = np.array([-d1, -d2, 1.0]) / math.sqrt(1 + d1**2 + d2**2)
    assert np.linalg.norm(R[:, 2] - n) < 0.02
    # head-on wave (Eq. 78): only omega_1, amplitude A = (2 pi / T)^3 a / g
    R, om, _ = W.regular_wave(a, T).buoy_motion(0.0)
    np.testing.assert_allclose(om, [(2 * math.pi / T) ** 3 * a / W.G, 0, 0], atol=1e-15)


def test_bad_inputs():
    with pytest.raises(ValueError, match="omega"):
        W.wavenumber(-1.0)
    with pytest.raises(ValueError, match="depth"):
        W.wavenumber(1.0, depth=0.0)
    with pytest.raises(ValueError, match="period"):
        W.regular_wave(1.0, float("nan"))


# ---------------------------------------------------------------------- finite buoy (waterplane)
def _disk_mean_slope(a, k, r, phase, n=64):
    """Mean of d eta/d x2 of eta = a cos(k x2 + phase) over the disk |x| <= r, by Gauss-Legendre
    in radius x trapezoid in angle (independent of the Bessel closed form)."""
    xg, wg = np.polynomial.legendre.leggauss(n)
    rho = 0.5 * r * (xg + 1.0)
    th = np.linspace(0.0, 2 * math.pi, 4 * n, endpoint=False)
    x2 = rho[:, None] * np.sin(th)[None, :]
    slope = -a * k * np.sin(k * x2 + phase)
    ring = slope.mean(axis=1)  # periodic trapezoid = spectral accuracy in angle
    return float(np.sum(0.5 * r * wg * rho * ring) * 2.0 / r**2)


@pytest.mark.parametrize("kr", [1e-3, 0.3, 1.0, 2.5, 3.8317, 5.0, 9.0])
def test_disk_average_factor_vs_direct_average_over_the_waterplane(kr):
    a, T, r = 0.9, 6.0, 2.0
    k = kr / r
    F = float(W.disk_average_factor(kr))
    for phase in (0.3, 1.9):  # sin and cos parts of the slope
        assert _disk_mean_slope(a, k, r, phase) == pytest.approx(
            F * (-a * k * math.sin(phase)), rel=1e-9, abs=1e-13
        )
    # the wave field applies it: slope angles of a finite buoy = F x the point buoy's
    T = 2 * math.pi / math.sqrt(W.G * k)  # deep water: k = w^2 / g
    pt, fin = W.regular_wave(a, T), W.regular_wave(a, T, buoy_radius=r)
    np.testing.assert_allclose(
        fin.slope_angles(0.7), F * pt.slope_angles(0.7), rtol=1e-9, atol=1e-13
    )
    np.testing.assert_allclose(fin.slope_response, [F], rtol=1e-9, atol=1e-13)


def test_disk_average_factor_limits():
    assert W.disk_average_factor(0.0) == 1.0
    assert float(W.disk_average_factor(1e-5)) == pytest.approx(1.0, abs=1e-10)
    assert float(W.disk_average_factor(2e-4)) == pytest.approx(1.0 - 0.5e-8, rel=1e-12)
    assert abs(float(W.disk_average_factor(3.8317059702))) < 1e-9  # first zero of J1
    big = np.array([50.0, 200.0])
    assert np.all(np.abs(W.disk_average_factor(big)) < 2.0 * math.sqrt(2 / math.pi) * big**-1.5)
    with pytest.raises(ValueError, match="buoy_radius"):
        W.regular_wave(1.0, 6.0, buoy_radius=-1.0)
    with pytest.raises(ValueError, match="buoy_radius"):
        W.IrregularSea(W.jonswap_spectrum, 2.0, 6.0, 8, np.random.default_rng(0), buoy_radius=-1)


def _rate_moment(hs, tp, r, hi):
    """int S(w) w^2 (k F(k r))^2 dw over [0.2 wp, hi wp]: variance of the head-on buoy rate."""

    def f(w):
        k = w * w / W.G
        return (
            W.jonswap_spectrum(np.array([w]), hs, tp)[0]
            * (w * k * W.disk_average_factor(k * r)) ** 2
        )

    wp = 2 * math.pi / tp
    return quad(f, 0.2 * wp, hi * wp, limit=400)[0]


def test_irregular_sea_buoy_rate_matches_moment_integral_and_converges():
    hs, tp, r = 2 * math.sqrt(2), 6.0, 2.5
    m4 = _rate_moment(hs, tp, r, 4.0)
    # converged in the cut-off with a finite buoy (the default 4 wp ~ S at 1e-3 of its peak) ...
    assert math.sqrt(m4) == pytest.approx(math.sqrt(_rate_moment(hs, tp, r, 16.0)), rel=0.02)
    # ... but not for a point buoy: the slope-rate spectrum grows ~ w (the unphysical case)
    assert _rate_moment(hs, tp, 0.0, 8.0) > 4.0 * _rate_moment(hs, tp, 0.0, 4.0)
    # converges with the number of components to the moment integral
    for n, tol in ((32, 0.05), (128, 0.01), (512, 0.005)):
        sea = W.IrregularSea(W.jonswap_spectrum, hs, tp, n, np.random.default_rng(n), buoy_radius=r)
        var = 0.5 * np.sum((sea.amplitudes * sea.slope_wavenumbers * sea.omegas) ** 2)
        assert math.sqrt(var) == pytest.approx(math.sqrt(m4), rel=tol)
    # the simulated buoy rate (time series of omega_1) has that RMS
    sea = W.IrregularSea(W.jonswap_spectrum, hs, tp, 128, np.random.default_rng(3), buoy_radius=r)
    t = np.arange(0.0, 3600.0, 0.1)
    w1 = sea.slope_angles(t)[0, 1]
    assert w1.std() == pytest.approx(math.sqrt(m4), rel=0.05)
