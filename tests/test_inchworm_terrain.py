"""The `terrain` effect: Bekker/Janosi soil under the inchworm beam instead of kinematic anchors."""

from __future__ import annotations

import numpy as np
import pytest

from mf_envs.physics.beam import banded
from mf_envs.physics.inchworm import (
    Inchworm,
    InchwormParams,
    run_gait,
    seed_linear_kappa,
    seed_uniform_kappa,
)
from mf_envs.physics.terrain import plate_sinkage

P = InchwormParams(n_elements=12)
SOIL = frozenset({"gravity", "terrain", "anchor_switching", "shear_deformation"})


def test_settled_flat_body_sinks_like_a_plate():
    """Flat body at rest: the soil carries the weight, sinkage = Eq. 56 inverted for a plate."""
    sim = Inchworm(P, frozenset({"gravity", "terrain"}))
    r_tail, r_head = sim.support_reactions()
    weight = P.mass_per_length * P.gravity * P.length
    assert r_tail + r_head == pytest.approx(weight, rel=1e-8)
    sink = 0.5 * P.height - sim.state.d[2::6]
    expected = plate_sinkage(sim.terrain.grip.soil, weight, P.width, P.length)
    assert np.allclose(sink, expected, rtol=2e-3)


def test_terrain_load_derivative_matches_finite_differences():
    """The soil's contribution to the Newton tangent, dF/dd, vs central differences."""
    sim = Inchworm(P, SOIL)
    sim.actuate(np.full(sim.kappa.shape, -3.0), anchor="head")
    sim.terrain.anchor = "head"
    d = sim.state.d.copy()
    d[0::6] += 1e-4 * np.linspace(0, 1, len(d[0::6]))  # some slip
    f, ab, _ = sim.terrain.loads(d, np.zeros_like(d))
    k = banded.band_to_dense(ab)
    h = 1e-8
    k_fd = np.zeros_like(k)
    for j in range(len(d)):
        dp, dm = d.copy(), d.copy()
        dp[j] += h
        dm[j] -= h
        k_fd[:, j] = (sim.terrain.loads(dp, d)[0] - sim.terrain.loads(dm, d)[0]) / (2 * h)
    assert np.max(np.abs(k - k_fd)) < 1e-5 * np.max(np.abs(k))


@pytest.mark.parametrize(
    "fn, kinematic",
    [
        (lambda S, t: np.full(S.shape, seed_uniform_kappa(t, 13.0)), 0.5236),
        (lambda S, t: seed_linear_kappa(S, t, 13.0, P.length), 0.2171),
    ],
)
def test_gaits_crawl_on_soil(fn, kinematic):
    """Grip from the contact law: both gaits advance head and tail (dry sand: 0.496 L and
    0.201 L per cycle), a little less than with kinematic anchors (back-slip of the grip)."""
    hist = run_gait(Inchworm(P, SOIL), fn, n_cycles=2, steps_per_cycle=40)
    for x in (hist.x_tail, hist.x_head):
        per_cycle = np.diff(x[::40]) / P.length
        assert np.all(per_cycle > 0.85 * kinematic) and np.all(per_cycle < kinematic)


def test_isotropic_soil_without_switching_goes_nowhere():
    """Symmetric gait, same grip everywhere: by symmetry the body's middle stays put."""
    sim = Inchworm(P, frozenset({"gravity", "terrain"}))
    hist = run_gait(sim, lambda S, t: np.full(S.shape, seed_uniform_kappa(t, 13.0)), 1, 40)
    mid = 0.5 * (hist.x_head + hist.x_tail)
    assert np.max(np.abs(mid - mid[0])) < 1e-6 * P.length


def test_terrain_implies_the_weight():
    a = Inchworm(P, frozenset({"terrain"}))
    b = Inchworm(P, frozenset({"terrain", "gravity"}))
    assert np.array_equal(a.state.d, b.state.d)


def test_dynamics_on_soil_stays_stable():
    """Inertia + terrain (damped Newmark, gamma = 0.6): two fast cycles (4 s) crawl forward."""
    sim = Inchworm(P, SOIL | {"inertia"})
    for i in range(1, 81):
        sim.actuate(np.full(sim.kappa.shape, seed_uniform_kappa(2 * np.pi * i / 40, 13.0)), 0.05)
    assert 0.9 < (sim.x_tail / P.length) / (2 * 0.496) < 1.1
