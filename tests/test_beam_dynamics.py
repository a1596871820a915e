"""Time schemes of the active C1 beam (dynamics.py, algorithmic.py) against independent truth:
finite differences of the algorithmic force, the static force it must reduce to, the exact
discrete energy balance, Euler-Bernoulli/Timoshenko frequencies, energy conservation over 100
periods, and the linear spectral radius."""

from __future__ import annotations

import numpy as np
import pytest

from mf_envs.benchmarks.accuracy.beam import strip, strip_release
from mf_envs.physics.beam import (
    BeamModel,
    BeamParams,
    NewtonDivergence,
    NewtonSettings,
    TimeScheme,
    banded,
    simulate_cantilever,
    solve_cantilever,
)
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.algorithmic import assemble_algorithmic
from mf_envs.physics.beam.dynamics import NewmarkState, initial_acceleration, time_step
from mf_envs.physics.beam.reference import timoshenko_cantilever_frequency
from mf_envs.physics.beam.simulate import clamped_root, linear_modes, simulate_clamped


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
    k = banded.band_to_dense(ab)
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


SLENDER, STOCKY = strip()[:6], strip(0.06)[:6]  # EA L^2 / EI = 4.3e6 and 300


def _mode(model, k=0, amplitude=1e-4):
    w, modes = linear_modes(model)
    return w, model.straight() + amplitude * model.params.length * modes[:, k] / np.max(
        np.abs(modes[:, k])
    )


def _period(hist):
    z, t = hist.tip_position[:, 1], hist.t
    i = np.where((z[:-1] < 0) & (z[1:] >= 0))[0]
    return float(np.mean(np.diff(t[i] - z[i] * (t[i + 1] - t[i]) / (z[i + 1] - z[i]))))


@pytest.mark.parametrize("scheme", ["energy_momentum", "generalized_alpha"])
@pytest.mark.parametrize("section", [SLENDER, STOCKY], ids=["slender", "stocky"])
def test_first_bending_period_matches_timoshenko(section, scheme):
    """Released in its first mode, 10 elements, dt = T1/100: period within 0.1 % of the
    Timoshenko eigen-BVP (= Euler-Bernoulli for the slender strip). Trapezoidal-family
    period error (omega dt)^2 / 12 = 3.3e-4."""
    L, ea, gas, ei, m, j = section
    t1 = 2 * np.pi / timoshenko_cantilever_frequency(L, ei, gas, m, j)
    if section == SLENDER:
        assert t1 * 1.875104068711961**2 * np.sqrt(ei / (m * L**4)) == pytest.approx(
            2 * np.pi, 1e-5
        )
    model = BeamModel(BeamParams(L, ea, gas, ei, 10, m, j))
    _, d0 = _mode(model)
    hist = simulate_clamped(model, d0, 4 * t1, t1 / 100, scheme=TimeScheme(scheme))
    assert abs(_period(hist) / t1 - 1) < 1e-3


def _strip_release(n_periods, scheme, rho_inf=1.0):
    return strip_release(n_periods, 50, scheme, rho_inf)


def test_seed_newmark_is_not_energy_stable():
    """The documented instability: the seed's Newmark (and generalized-alpha at rho_inf = 1,
    the same trapezoidal rule) on the slender strip released at alpha = 0.5, dt = T1/50: Newton
    fails within 20 periods; energy_momentum runs the same 20 periods holding energy to 1e-6."""
    for scheme in ("newmark", "generalized_alpha"):
        with pytest.raises(NewtonDivergence, match=r"t = .* residual"):
            _strip_release(20, scheme)
    e = _strip_release(20, "energy_momentum").total_energy
    assert np.max(np.abs(e / e[0] - 1)) < 1e-6


@pytest.mark.slow
def test_energy_momentum_holds_energy_for_100_periods():
    """Acceptance: slender strip (EA L^2/EI = 4.3e6) released from alpha = 0.5 (tip 0.16 L),
    rho_inf = 1, dt = T1/50, 100 periods: total energy within 1 % (it holds to ~1e-8), Newton
    never fails (no step halving in simulate_cantilever)."""
    hist = _strip_release(100, "energy_momentum")
    e = hist.total_energy
    assert np.max(np.abs(e / e[0] - 1)) < 1e-2
    assert hist.stats.halvings == 0 and hist.stats.steps == 5000


@pytest.mark.parametrize("scheme", ["energy_momentum", "generalized_alpha"])
def test_rho_08_keeps_first_mode_and_damps_high_modes(scheme):
    """rho_inf = 0.8, dt = T1/50: the first mode loses < 0.5 % of its energy per period; every
    mode above 10 omega_1 loses > 30 % of its energy within one T1."""
    L, ea, gas, ei, m, j = SLENDER
    model = BeamModel(BeamParams(L, ea, gas, ei, 10, m, j))
    w, d0 = _mode(model)
    t1, ts = 2 * np.pi / w[0], TimeScheme(scheme, 0.8)
    e = simulate_clamped(model, d0, 5 * t1, t1 / 50, scheme=ts).total_energy
    assert 0 < 1 - (e[-1] / e[0]) ** (1 / 5) < 5e-3
    for k in np.flatnonzero(w > 10 * w[0])[:4]:
        e = simulate_clamped(model, _mode(model, k, 1e-6)[1], t1, t1 / 50, scheme=ts).total_energy
        assert e[-1] / e[0] < 0.7, (k, w[k] / w[0])


def test_energy_momentum_decay_identity_at_large_amplitude():
    """rho_inf = 0.8 on the alpha = 0.5 release, dt = T1/50: the modified energy
    H = kinetic + strain + (chi/2) int |De|_D^2 (dynamics.py) never grows, step by step, in the
    nonlinear regime; the true energy stays within 0.5 % of H and, once the unresolved modes
    are gone, loses < 0.5 % per period."""
    L, ea, gas, ei, m, j = SLENDER
    t1 = 2 * np.pi / (1.875104068711961**2 * np.sqrt(ei / (m * L**4)))
    model = BeamModel(BeamParams(L, ea, gas, ei, 10, m, j))
    d0 = solve_cantilever(L, ea, gas, ei, 10, (0.0, -0.5 * ei / L**2)).d
    fixed, kap, zero = clamped_root(model), np.zeros((10, 4)), np.zeros(model.n_dof)
    st = NewmarkState(d0, zero.copy(), initial_acceleration(model, d0, kap, zero, fixed))
    ts, dt = TimeScheme("energy_momentum", 0.8), t1 / 50
    xi, w, stiff = model.quad
    e_true, h = [], []
    for _ in range(150):
        st = time_step(model, st, dt, kap, zero, fixed, scheme=ts)
        e = 0.5 * st.v @ banded.band_matvec(model.mass, st.v) + model.elastic_energy(st.d, kap)
        de = st.strain_rate * dt
        wq = w[None, :, None] * model.le[:, None, None] * stiff[None, :, :]
        e_true.append(e)
        h.append(e + 0.5 * ts.chi * float(np.sum(wq * de**2)))
    h, e_true = np.array(h), np.array(e_true)
    assert np.all(np.diff(h) <= 1e-9 * h[0])
    assert np.max(np.abs(e_true / h - 1)) < 5e-3
    assert 0 < 1 - e_true[-1] / e_true[-51] < 5e-3


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"n_elements": 0}, "n_elements"),
        ({"n_elements": -3}, "n_elements"),
        ({"EA": 0.0}, "EA"),
        ({"GAs": -1.0}, "GAs"),
        ({"EI": 0.0}, "EI"),
        ({"length": -1.0}, "length"),
        ({"dt": 0.0}, "dt"),
        ({"dt": -1e-3}, "dt"),
        ({"t_end": 0.0}, "t_end"),
        ({"mass_per_length": 0.0}, "mass_per_length"),
        ({"scheme": "rk4"}, "scheme"),
        ({"rho_inf": 1.5}, "rho_inf"),
        ({"initial_tip_force": (1.0,)}, "initial_tip_force"),
    ],
)
def test_simulate_cantilever_bad_input_names_parameter(kwargs, name):
    args = {
        "length": 1.0,
        "EA": 1e4,
        "GAs": 1e4,
        "EI": 1.0,
        "mass_per_length": 1.0,
        "rotary_inertia": 1e-4,
        "n_elements": 4,
        "t_end": 0.1,
        "dt": 0.01,
    }
    args = {**args, **kwargs}
    beam = ("length", "EA", "GAs", "EI", "n_elements", "mass_per_length", "rotary_inertia")
    with pytest.raises(ValueError, match=name):
        params = BeamParams(**{k: args.pop(k) for k in beam})
        simulate_cantilever(params, **args)


def test_simulate_cantilever_newton_failure_names_time_and_residual():
    with pytest.raises(NewtonDivergence, match=r"t = 0 s .*residual"):
        simulate_cantilever(
            BeamParams(1.0, 1e4, 1e4, 1.0, 4, 1.0, 1e-4),
            1.0,
            0.1,
            tip_force=(0.0, -5.0),
            settings=NewtonSettings(max_iter=1, max_halvings=0),
        )


def test_simulate_cantilever_history_shapes_and_units():
    """Released from rest: t starts at 0, kinetic energy 0 at t = 0, tip at the static
    deflection of the initial load (solve_cantilever)."""
    hist = simulate_cantilever(
        BeamParams(1.0, 1e4, 1e4, 1.0, 4, 1.0, 1e-4), 0.05, 0.01, (0.0, -0.1)
    )
    assert hist.t.shape == (6,) and hist.tip_position.shape == (6, 2)
    assert hist.kinetic_energy.shape == hist.strain_energy.shape == (6,)
    assert hist.kinetic_energy[0] == 0.0 and hist.kinetic_energy[-1] > 0.0
    static = solve_cantilever(1.0, 1e4, 1e4, 1.0, 4, (0.0, -0.1))
    assert np.allclose(hist.tip_position[0], static.tip_position)
