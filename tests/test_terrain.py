"""Bekker/Janosi terrain contact (ch. 4 §4.5, Eqs. 56-57)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from mf_envs.physics import terrain as tr

SOIL_NAMES = list(tr.SOILS)


def _contact(name: str, **kw) -> tr.TerrainContact:
    return tr.TerrainContact(tr.soil(name), width=0.02, **kw)


@pytest.mark.parametrize("name", SOIL_NAMES)
def test_pressure_follows_eq_56_below_the_regularisation_depth(name):
    c = _contact(name)
    s = c.soil
    for depth in (2e-5, 1e-3, 0.03):
        expected = (s.k_c / 0.02 + s.k_phi) * depth**s.n  # Eq. 56 by hand
        out = c.loads(np.zeros(1), np.array([-depth]), tr.SlipState.at_rest(np.zeros(1)))
        assert out.pressure[0] == pytest.approx(expected, rel=1e-13)
        assert out.fz[0] == pytest.approx(0.02 * expected, rel=1e-13)
        assert tr.bekker_pressure(s, 0.02, depth) == pytest.approx(expected, rel=1e-13)


@pytest.mark.parametrize("name", SOIL_NAMES)
def test_plate_sinkage_matches_the_closed_form(name):
    # a rigid plate b x l of weight W on the soil: find z where the contact carries W
    c = _contact(name)
    b, l, W = 0.02, 0.3, 40.0
    x = np.linspace(0.0, l, 11)
    st = tr.SlipState.at_rest(x)

    def excess(depth: float) -> float:
        return l * float(np.mean(c.loads(x, np.full(x.size, -depth), st).fz)) - W

    depth = brentq(excess, 0.0, 1.0, xtol=1e-15, rtol=1e-14)
    k = c.soil.k_c / b + c.soil.k_phi
    assert depth == pytest.approx((W / (b * l * k)) ** (1 / c.soil.n), rel=1e-10)
    assert tr.plate_sinkage(c.soil, W, b, l) == pytest.approx(depth, rel=1e-10)
    assert depth > c.reg_depth  # the case is in the unregularised range


def test_janosi_shear_saturates_at_tau_max_with_the_initial_slope_1_over_k():
    c = _contact("sandy_loam")
    s = c.soil
    depth = 4e-3
    p = (s.k_c / 0.02 + s.k_phi) * depth**s.n
    tau_max = s.cohesion + p * math.tan(s.friction_angle)
    x0 = np.zeros(1)
    st = tr.SlipState.at_rest(x0)
    for j in (1e-3, 0.01, 0.05):
        out = c.loads(x0 + j, np.array([-depth]), st)
        assert out.fx[0] == pytest.approx(
            -0.02 * tau_max * (1 - math.exp(-j / s.shear_deformation_modulus)), rel=1e-13
        )
    far = c.loads(x0 + 40 * s.shear_deformation_modulus, np.array([-depth]), st)
    assert far.fx[0] == pytest.approx(-0.02 * tau_max, rel=1e-12)
    back = c.loads(x0 - 40 * s.shear_deformation_modulus, np.array([-depth]), st)
    assert back.fx[0] == pytest.approx(0.02 * tau_max, rel=1e-12)  # opposes the slip
    at0 = c.loads(x0, np.array([-depth]), st)
    assert at0.fx[0] == 0.0
    assert at0.dfx_dx[0] == pytest.approx(-0.02 * tau_max / s.shear_deformation_modulus, rel=1e-13)


def _points(rng: np.random.Generator, c: tr.TerrainContact, n: int = 200):
    depth = np.concatenate(
        [
            rng.uniform(0.05, 1.0, n) * c.reg_depth,  # inside the regularisation band
            rng.uniform(1.2, 500.0, n) * c.reg_depth,  # Bekker proper
        ]
    )
    x = rng.normal(0.0, 0.02, 2 * n)
    j = rng.normal(0.0, 0.02, 2 * n)
    return x, -depth, tr.SlipState(j, x + rng.normal(0.0, 0.005, 2 * n))


@pytest.mark.parametrize("name", SOIL_NAMES)
def test_derivatives_match_finite_differences(name):
    rng = np.random.default_rng(3)
    c = _contact(name, normal_damping=2e4)
    x, z, st = _points(rng, c)
    vz = rng.normal(0.0, 0.1, x.size)
    out = c.loads(x, z, st, vz)
    hz = 1e-4 * c.reg_depth
    hx = 1e-7
    up, dn = c.loads(x, z + hz, st, vz), c.loads(x, z - hz, st, vz)
    right, left = c.loads(x + hx, z, st, vz), c.loads(x - hx, z, st, vz)
    fast, slow = c.loads(x, z, st, vz + 1e-4), c.loads(x, z, st, vz - 1e-4)
    fd = {
        "dfz_dz": (up.fz - dn.fz) / (2 * hz),
        "dfx_dz": (up.fx - dn.fx) / (2 * hz),
        "dfx_dx": (right.fx - left.fx) / (2 * hx),
        "dfz_dvz": (fast.fz - slow.fz) / 2e-4,
    }
    for key, approx in fd.items():
        exact = getattr(out, key)
        scale = np.max(np.abs(exact))
        assert scale > 0
        assert np.max(np.abs(exact - approx)) < 1e-6 * scale, key
    assert np.all((right.fz - left.fz) == 0.0)  # dfz_dx = 0 on flat ground


@pytest.mark.parametrize("name", SOIL_NAMES)
def test_no_force_out_of_contact_and_slip_is_forgotten(name):
    c = _contact(name, normal_damping=1e4)
    x = np.linspace(0.0, 1.0, 5)
    st = tr.SlipState(np.full(5, 0.01), x - 0.003)
    out = c.loads(x, np.array([0.0, 1e-9, 1e-3, 0.1, 5.0]), st, vz=np.full(5, -1.0))
    for key in ("fx", "fz", "dfx_dx", "dfx_dz", "dfz_dz", "dfz_dvz", "pressure", "sinkage"):
        assert np.all(getattr(out, key) == 0.0), key
    assert not out.in_contact.any()
    assert np.all(out.slip.j == 0.0)
    assert np.array_equal(out.slip.x_ref, x)


@pytest.mark.parametrize("name", SOIL_NAMES)
def test_loads_are_continuous_and_c1_at_contact_onset_and_at_the_blend(name):
    c = _contact(name)
    st = tr.SlipState(np.array([0.004]), np.zeros(1))
    x = np.zeros(1)

    def at(depth: float) -> tr.ContactLoads:
        return c.loads(x, np.array([-depth]), st)

    tiny = at(1e-14)
    assert abs(tiny.fz[0]) < 1e-12 * at(c.reg_depth).fz[0]
    assert abs(tiny.fx[0]) < 1e-12 * abs(at(c.reg_depth).fx[0])
    assert abs(tiny.dfz_dz[0]) < 1e-7 * abs(at(c.reg_depth).dfz_dz[0])
    eps = 1e-12 * c.reg_depth
    lo, hi = at(c.reg_depth - eps), at(c.reg_depth + eps)
    for key in ("fz", "fx", "dfz_dz", "dfx_dz", "dfx_dx"):
        a, b = getattr(lo, key)[0], getattr(hi, key)[0]
        assert a == pytest.approx(b, rel=1e-6), key
    # the pressure keeps rising through the blend (0 < n < 3)
    depth = np.linspace(0.0, 3 * c.reg_depth, 301)
    p, dp = c.pressure(depth)
    assert np.all(np.diff(p) > 0) and np.all(dp[1:] > 0)


def test_slip_accumulates_from_the_last_committed_step():
    c = _contact("clay")
    x = np.array([0.1, 0.2])
    z = np.array([-1e-3, -1e-3])
    st = tr.SlipState.at_rest(x)
    out = c.loads(x + [0.002, -0.001], z, st)
    assert np.allclose(out.slip.j, [0.002, -0.001])
    out2 = c.loads(x + [0.005, -0.001], z, out.slip)
    assert np.allclose(out2.slip.j, [0.005, -0.001])
    assert out2.fx[0] < 0 < out2.fx[1]


def test_gravity_and_bad_inputs():
    assert np.allclose(tr.gravity_line_load(0.278, 9.81), [0.0, -0.278 * 9.81])
    with pytest.raises(ValueError, match="name"):
        tr.soil("moon_dust")
    with pytest.raises(ValueError, match="width"):
        tr.TerrainContact(tr.soil("clay"), width=0.0)
    with pytest.raises(ValueError, match="n"):
        tr.SoilParams(1.0, 1.0, 3.5, 0.0, 0.3, 0.01)
    with pytest.raises(ValueError, match="friction_angle"):
        tr.SoilParams(1.0, 1.0, 1.0, 0.0, 2.0, 0.01)
    with pytest.raises(ValueError, match="z"):
        c = _contact("clay")
        c.loads(np.zeros(2), np.array([np.nan, 0.0]), tr.SlipState.at_rest(np.zeros(2)))
