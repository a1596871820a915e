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
    assert P_deep == pytest.approx(0.4877e3 * hs**2 * T, rel=2e-3)  # "0.48 Hs^2 T kW/m"
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
