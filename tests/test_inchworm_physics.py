"""Inchworm gaits of §4.10 (Eqs. 99-103) on the active C1 beam.

Independent truth: without gravity the quasi-static shape of the sliding simply supported beam is
stress free, kappa = kappa#(S), so under Eq. 102 both ends advance per cycle by L minus the chord
of that shape at the peak actuation (a quadrature, `chord_of_stress_free_shape`)."""

from __future__ import annotations

import numpy as np
import pytest

from mf_envs.physics.beam import NewtonDivergence
from mf_envs.physics.inchworm import (
    Inchworm,
    InchwormParams,
    chord_of_stress_free_shape,
    run_gait,
    seed_linear_kappa,
    seed_uniform_kappa,
)

KAPPA0 = 13.0  # 1/m, the seed's largest actuation
P = InchwormParams()  # L = 0.3 m, 16 elements


def _uniform(S, t):
    return np.full(S.shape, seed_uniform_kappa(t, KAPPA0))


def _linear(S, t):
    return seed_linear_kappa(S, t, KAPPA0, P.length)


GAITS = {
    "seed_uniform": (_uniform, lambda s: np.full(s.shape, -KAPPA0)),
    "seed_linear": (_linear, lambda s: -KAPPA0 * (0.2 + 0.8 * s / P.length)),
}


@pytest.mark.parametrize("gait", sorted(GAITS))
def test_gait_advance_matches_stress_free_chord(gait):
    fn, peak = GAITS[gait]
    sim = Inchworm(P, effects=frozenset({"anchor_switching"}))
    hist = run_gait(sim, fn, n_cycles=2, steps_per_cycle=40)
    expected = P.length - chord_of_stress_free_shape(peak, P.length)
    for x in (hist.x_tail, hist.x_head):
        per_cycle = np.diff(x[::40])
        assert np.allclose(per_cycle, expected, rtol=1e-3), (per_cycle, expected)
    # loading holds the head, unloading holds the tail (Eq. 102)
    assert np.ptp(hist.x_head[:21]) < 1e-12 and np.ptp(hist.x_tail[21:41]) < 1e-12


@pytest.mark.parametrize("gait", sorted(GAITS))
def test_full_model_advances_without_failure_at_kappa0_13(gait):
    """Gravity + shear deformation + switching at kappa0# = 13 1/m: no Newton failure, and the
    stated advance per cycle (uniform 0.5236 L, linear 0.2171 L; gravity changes them < 0.1%)."""
    fn, peak = GAITS[gait]
    sim = Inchworm(P, effects=frozenset({"anchor_switching", "gravity", "shear_deformation"}))
    hist = run_gait(sim, fn, n_cycles=1, steps_per_cycle=40)
    stated = {"seed_uniform": 0.5236, "seed_linear": 0.2171}[gait]
    for x in (hist.x_tail, hist.x_head):
        assert (x[-1] - x[0]) / P.length == pytest.approx(stated, rel=2e-3)
    assert all(np.all(np.isfinite(c)) for c in hist.centerlines)


def test_peak_shape_is_the_circular_arc():
    """Fig. 4-8: uniform kappa# = -13 bends the body into an arc of height (1 - cos(kL/2)) / k."""
    sim = Inchworm(P, effects=frozenset())
    sim.actuate(np.full(sim.kappa.shape, -KAPPA0))
    z = sim.centerline()[:, 1]
    k, L = KAPPA0, P.length
    assert z.max() == pytest.approx((1 - np.cos(k * L / 2)) / k, rel=1e-4)
    assert sim.x_head == pytest.approx(L, abs=1e-12)  # head held (no switching, fig. 4-8)
    assert sim.x_head - sim.x_tail == pytest.approx(2 * np.sin(k * L / 2) / k, rel=1e-3)


def test_no_switching_curls_in_place():
    sim = Inchworm(P, effects=frozenset({"gravity"}))
    hist = run_gait(sim, _uniform, n_cycles=1, steps_per_cycle=20)
    assert abs(hist.x_tail[-1] - hist.x_tail[0]) < 1e-9
    assert abs(hist.x_head[-1] - hist.x_head[0]) < 1e-12


def test_slow_dynamics_approaches_quasi_static():
    """Inertia on (Newmark) with a slow 40 s cycle: advance within 1e-3 of quasi-static."""
    qs = run_gait(Inchworm(P, effects=frozenset({"anchor_switching"})), _uniform, 1, 40)
    sim = Inchworm(P, effects=frozenset({"anchor_switching", "inertia"}))
    for i in range(1, 41):
        sim.actuate(_uniform(sim.model.gauss_S, 2 * np.pi * i / 40), dt=1.0)
    assert sim.x_tail == pytest.approx(qs.x_tail[-1], rel=1e-3)


def test_support_reactions_carry_the_weight():
    sim = Inchworm(P, effects=frozenset({"gravity", "anchor_switching"}))
    sim.actuate(np.full(sim.kappa.shape, -5.0))
    r_tail, r_head = sim.support_reactions()
    # equilibrium to the Newton force tolerance (relative ~1e-8 of the weight)
    assert r_tail + r_head == pytest.approx(P.mass_per_length * P.gravity * P.length, rel=5e-8)


def test_bad_inputs():
    with pytest.raises(ValueError, match="height"):
        InchwormParams(height=-0.01)
    with pytest.raises(ValueError, match="effects"):
        Inchworm(P, effects=frozenset({"magnetism"}))
    with pytest.raises(ValueError, match="anchor"):
        Inchworm(P).actuate(np.zeros((16, 4)), anchor="middle")


def test_newton_failure_raises_divergence():
    """Newton without an iteration/halving budget cannot converge: it raises, never returns NaN."""
    from mf_envs.physics.beam import NewtonSettings

    sim = Inchworm(P, effects=frozenset(), settings=NewtonSettings(1e-9, 1e-9, 2, 0))
    with pytest.raises(NewtonDivergence):
        sim.actuate(np.full(sim.kappa.shape, -40.0), anchor="head")


# ----------------------------------------------------------------- translation invariance
FULL = frozenset({"anchor_switching", "gravity", "shear_deformation"})


@pytest.mark.parametrize("effects", [FULL, FULL | {"inertia"}], ids=["quasi_static", "inertia"])
def test_gait_is_translation_invariant(effects):
    """A physical system is translation invariant: the same gait started at x_tail = 0, 9, 100,
    1e4 m gives the same shape and advance per cycle (to 1e-9). Regression: with nodal x in
    absolute coordinates the round-off of z' = sum N_i' z_i grew with |x| until Newton could not
    meet its tolerance (failure past ~8 m)."""
    runs = {}
    for x0 in (0.0, 9.0, 100.0, 1e4):
        sim = Inchworm(P, effects=effects)
        sim.reset(x_tail=x0)
        runs[x0] = run_gait(sim, _uniform, n_cycles=2, steps_per_cycle=8)
    ref = runs[0.0]
    adv_ref = np.diff(ref.x_tail[::8])
    assert np.all(adv_ref > 0.1 * P.length)  # it does crawl
    for x0, h in runs.items():
        assert h.x_tail[0] - x0 == pytest.approx(ref.x_tail[0], abs=1e-9 * P.length)  # sag
        assert np.allclose(np.diff(h.x_tail[::8]), adv_ref, rtol=1e-9, atol=0.0), x0
        assert np.allclose(np.diff(h.x_head[::8]), np.diff(ref.x_head[::8]), rtol=1e-9, atol=0)
        for a, b, xt, xt_ref in zip(h.centerlines, ref.centerlines, h.x_tail, ref.x_tail):
            shape, shape_ref = a - [xt, 0.0], b - [xt_ref, 0.0]
            assert np.allclose(shape, shape_ref, rtol=0, atol=1e-9 * P.length), x0


def test_terrain_gait_is_translation_invariant():
    """Same with the soil contact (its slip history holds x of the contact points)."""
    soil = frozenset({"gravity", "terrain", "anchor_switching"})
    runs = {}
    for x0 in (0.0, 1e4):
        sim = Inchworm(P, effects=soil)
        sim.reset(x_tail=x0)
        runs[x0] = run_gait(sim, _uniform, n_cycles=1, steps_per_cycle=8)
    a, b = runs[0.0], runs[1e4]
    assert a.x_tail[-1] - a.x_tail[0] > 0.1 * P.length
    assert (b.x_tail[-1] - b.x_tail[0]) == pytest.approx(a.x_tail[-1] - a.x_tail[0], rel=1e-9)
    assert np.allclose(
        b.centerlines[-1] - [b.x_tail[-1], 0],
        a.centerlines[-1] - [a.x_tail[-1], 0],
        rtol=0,
        atol=1e-9 * P.length,
    )


@pytest.mark.slow
def test_long_seed_gait_run_passes_10_m():
    """The coarsest seed gait (2 steps per cycle, the training helper's failure at 8.01 m) crawls
    past x = 10 m with the per-cycle advance of the first cycle (re-centring keeps the local
    coordinates small, so the cycle does not change with the distance travelled)."""
    sim = Inchworm(P, effects=FULL, increment_factor=4.0)
    first = run_gait(sim, _uniform, n_cycles=1, steps_per_cycle=2)
    per_cycle = first.x_tail[-1] - first.x_tail[0]
    n = int(np.ceil(10.5 / per_cycle))  # from x = 0 to past 10 m
    hist = run_gait(sim, _uniform, n_cycles=n, steps_per_cycle=2)
    assert hist.x_tail[-1] > 10.0
    assert np.allclose(np.diff(hist.x_tail[::2]), per_cycle, rtol=1e-9, atol=0)
