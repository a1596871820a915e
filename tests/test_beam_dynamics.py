"""Time schemes of the active C1 beam (dynamics.py, algorithmic.py) against independent truth:
finite differences of the algorithmic force, the static force it must reduce to, the exact
discrete energy balance, Euler-Bernoulli/Timoshenko frequencies, energy conservation over 100
periods, and the linear spectral radius."""

from __future__ import annotations

import numpy as np
import pytest

from mf_envs.physics.beam import (
    BeamModel,
    BeamParams,
    NewtonDivergence,
    TimeScheme,
    simulate_cantilever,
)
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.algorithmic import assemble_algorithmic


def _pair(seed, element):
    rng = np.random.default_rng(seed)
    model = BeamModel(BeamParams(1.3, 2e4, 7e3, 2.0, 3, element=element))
    a = model.straight() + 0.3 * rng.standard_normal(model.n_dof)
    b = a + 0.4 * rng.standard_normal(model.n_dof)
    ka, kb = rng.standard_normal((2, 3, el.N_GAUSS))
    shift = 0.1 * rng.standard_normal((3, model.quad[0].shape[0], 3))
    return model, a, b, ka, kb, shift


def _pbar(model, a, b, ka, kb, theta, shift, geo=1.0):
    return assemble_algorithmic(a, b, model.le, ka, kb, *model.quad, theta, shift, True, geo)


@pytest.mark.parametrize("element", el.ELEMENTS)
@pytest.mark.parametrize("seed", [0, 1])
def test_algorithmic_tangent_matches_finite_differences(element, seed):
    """dPbar/db (exact, unsymmetric) vs central differences in b: 1e-6 relative."""
    model, a, b, ka, kb, shift = _pair(seed, element)
    _, ab, _ = _pbar(model, a, b, ka, kb, 0.6, shift)
    k = el.band_to_dense(ab)
    h, k_fd = 1e-6, np.zeros_like(k)
    for j in range(model.n_dof):
        bp, bm = b.copy(), b.copy()
        bp[j] += h
        bm[j] -= h
        fp = _pbar(model, a, bp, ka, kb, 0.6, shift)[0]
        k_fd[:, j] = (fp - _pbar(model, a, bm, ka, kb, 0.6, shift)[0]) / (2 * h)
    assert np.max(np.abs(k - k_fd)) / np.max(np.abs(k)) < 1e-6


@pytest.mark.parametrize("element", el.ELEMENTS)
def test_algorithmic_force_reduces_to_static_force(element):
    """Pbar(d, d) at theta = 1 is P(d) of element.assemble_internal (a second formulation), and
    twice the geometric part gives its tangent."""
    model, a, _, ka, _, _ = _pair(4, element)
    zero = np.zeros((3, model.quad[0].shape[0], 3))
    p, ab, _ = _pbar(model, a, a, ka, ka, 1.0, zero, geo=2.0)
    p_ref, ab_ref = model.internal(a, ka)
    assert np.allclose(p, p_ref, rtol=0, atol=1e-11 * np.max(np.abs(p_ref)))
    assert np.allclose(ab, ab_ref, rtol=0, atol=1e-10 * np.max(np.abs(ab_ref)))


@pytest.mark.parametrize("element", el.ELEMENTS)
@pytest.mark.parametrize("seed", [5, 6])
def test_discrete_gradient_gives_exact_energy_difference(element, seed):
    """Pbar(a, b; theta = 1/2) . (b - a) = W(b) - W(a) for large finite steps (the
    energy-momentum property), with W from element.assemble_internal."""
    model, a, b, ka, _, _ = _pair(seed, element)
    zero = np.zeros((3, model.quad[0].shape[0], 3))
    p, _, _ = _pbar(model, a, b, ka, ka, 0.5, zero)
    dw = model.elastic_energy(b, ka) - model.elastic_energy(a, ka)
    assert p @ (b - a) == pytest.approx(dw, rel=1e-11, abs=1e-11 * model.elastic_energy(b, ka))
