"""Our sea spectra and energy flux against MHKiT (`mhkit.wave.resource`, the marine-energy
toolkit that follows IEC TS 62600-100/-2), the second formulation. Needs the compare extra.

MHKiT's JONSWAP is IEC TS 62600-2 Annex C.2: the Pierson-Moskowitz shape times the peak factor,
scaled by the approximate A_gamma = 1 - 0.287 ln(gamma); ours scales the same shape so that
m0 = Hs^2/16 exactly (`physics.waves.jonswap_spectrum`). So the two agree to round-off at
gamma = 1 (Pierson-Moskowitz, where A_gamma = 1 is exact) and, at any gamma, in shape: their ratio
is one constant, the two normalisations' ratio, within 0.3 % of 1.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mf_envs.physics import waves as W

resource = pytest.importorskip("mhkit.wave.resource", reason="needs the compare extra (MHKiT)")

F = np.linspace(0.005, 2.0, 4000)  # Hz
RHO, G = 1025.0, 9.81


def _spectra(hs: float, tp: float, gamma: float):
    ours = 2.0 * math.pi * W.jonswap_spectrum(2.0 * math.pi * F, hs, tp, gamma)  # m^2/Hz
    theirs = resource.jonswap_spectrum(F, tp, hs, gamma=gamma, to_pandas=True)
    return ours, theirs


@pytest.mark.parametrize("hs, tp", [(1.0, 4.0), (1.5, 6.0), (2.5, 8.0)])
def test_pierson_moskowitz_limit_equals_mhkit(hs, tp):
    ours, theirs = _spectra(hs, tp, 1.0)
    np.testing.assert_allclose(ours, np.asarray(theirs).ravel(), rtol=1e-10, atol=0.0)


@pytest.mark.parametrize("hs, tp, gamma", [(1.5, 6.0, 3.3), (2.0, 7.0, 2.0), (2.5, 5.0, 5.0)])
def test_jonswap_shape_equals_mhkit_up_to_the_normalisation(hs, tp, gamma):
    ours, theirs = _spectra(hs, tp, gamma)
    t = np.asarray(theirs).ravel()
    live = t > 1e-12 * t.max()  # below that both underflow towards 0 at the low end
    ratio = ours[live] / t[live]
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-10)  # the same shape
    exact = (hs * hs / 16.0) / np.trapezoid(t, F)
    assert ratio[0] == pytest.approx(exact, rel=1e-4)  # the ratio is m0's correction
    assert abs(ratio[0] - 1.0) < 3e-3  # IEC's A_gamma is within 0.3 % of the exact scaling


@pytest.mark.parametrize("hs, tp, gamma", [(1.5, 6.0, 1.0), (1.5, 6.0, 3.3), (2.5, 8.0, 3.3)])
def test_energy_flux_equals_mhkit(hs, tp, gamma):
    # J = rho g int S(w) c_g(w) dw, deep water c_g = g / (2 w); MHKiT's energy_flux from its own
    # spectrum, ours from ours, rescaled by the normalisations' ratio (1 at gamma = 1)
    ours, theirs = _spectra(hs, tp, gamma)
    w = 2.0 * math.pi * F
    j_ours = np.trapezoid(RHO * G * (ours / (2.0 * math.pi)) * G / (2.0 * w), w)
    j_theirs = float(np.asarray(resource.energy_flux(theirs, h=1e4, deep=True, rho=RHO, g=G)))
    scale = float(ours[len(F) // 3] / np.asarray(theirs).ravel()[len(F) // 3])
    assert j_ours == pytest.approx(j_theirs * scale, rel=1e-6)
    # and both near the deep-water formula with the energy period (IEC: Te = m_-1 / m0)
    te = np.trapezoid(ours / F, F) / np.trapezoid(ours, F)
    assert j_ours == pytest.approx(float(W.deep_water_power_per_metre(hs, te, RHO, G)), rel=2e-3)
