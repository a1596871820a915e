"""ISWEC-class hull, surge/heave/pitch coefficients (issue 29): the shipped BEM table against
physics no solver run decides (Haskind in finite depth, reciprocity, positive radiated power,
the axisymmetric radiation bound, hydrostatics of the exact cylinder)."""

import math

import numpy as np
import pytest

from mf_envs.physics.gowec.hydro import CylinderHull
from mf_envs.physics.gowec.hydro.checks import haskind_matrix, max_absorbed_power
from mf_envs.physics.gowec.hydro.three_dof import ISWEC_HULL_FILE, ThreeDofCoefficients

SURGE, HEAVE, PITCH = 0, 1, 2


@pytest.fixture(scope="module")
def hull():
    return ThreeDofCoefficients.load()


@pytest.fixture(scope="module")
def band(hull):
    return (hull.omega >= 0.3) & (hull.omega <= 3.0)


def _resolved(hull, band, mode):
    """Where B_ii is >= 10 % of its peak (the cross terms' scale is taken there only: above
    ~2.4 rad/s heave and pitch damping of this flat hull fall like e^{-2 k d})."""
    B = hull.damping[:, mode, mode]
    return band & (B >= 0.1 * B.max())


def test_the_file_is_the_iswec_class_cylinder(hull):
    assert (hull.radius, hull.draft, hull.gyration, hull.water_depth) == (6.0, 2.5, 4.2, 35.0)
    m = hull.rho * math.pi * hull.radius**2 * hull.draft
    assert np.allclose(np.diag(hull.mass_matrix), [m, m, m * hull.gyration**2], rtol=1e-12)
    assert m == pytest.approx(290e3, rel=0.01)  # the reviewer's sizing: 290 t
    with np.load(ISWEC_HULL_FILE, allow_pickle=False) as z:
        assert all(z[k].dtype == np.float64 for k in z.files)


@pytest.mark.parametrize("mode", [SURGE, HEAVE, PITCH])
def test_haskind_each_mode(hull, band, mode):
    # near field (pressure integral) vs far field (excitation), finite depth (c_g of 35 m):
    # within 5 % at every tabulated frequency in 0.3-3 rad/s (measured: surge 0.4 %, heave
    # 2.6 %, pitch 3.0 %, the last two at 2.9-3 rad/s, where B33 and B55 are 0.7-1.7 % of their
    # peaks); the table's two frequencies above 3 rad/s are outside the band (pitch 0.49-0.96)
    Bh = haskind_matrix(hull)[:, mode, mode]
    B = hull.damping[:, mode, mode]
    assert band.sum() == 28
    assert np.max(np.abs(Bh[band] / B[band] - 1.0)) < 0.05


def test_haskind_surge_pitch_coupling(hull, band):
    ok = _resolved(hull, band, PITCH)
    Bh = haskind_matrix(hull)[ok, SURGE, PITCH]
    B = hull.damping[ok, SURGE, PITCH]
    scale = np.sqrt(hull.damping[ok, SURGE, SURGE] * hull.damping[ok, PITCH, PITCH])
    assert np.max(np.abs(Bh - B) / scale) < 0.05


def test_reciprocity(hull, band):
    # A_ij = A_ji and B_ij = B_ji (Green's theorem; Newman 1977 ch. 6). The collocation BEM is
    # not exactly symmetric: the gap, relative to sqrt(M_11 M_55) (its weight in u^T M u), is
    # <= 0.28 % for A and <= 0.45 % for B where B55 >= 10 % of its peak
    ok = _resolved(hull, band, PITCH)
    for M, sel, tol in ((hull.added_mass, slice(None), 0.01), (hull.damping, ok, 0.01)):
        scale = np.sqrt(np.abs(M[sel, SURGE, SURGE] * M[sel, PITCH, PITCH]))
        assert np.max(np.abs(M[sel, SURGE, PITCH] - M[sel, PITCH, SURGE]) / scale) < tol
    # heave decouples from surge and pitch on an axisymmetric hull (odd vs even in x)
    for M in (hull.added_mass, hull.damping):
        off = np.abs(M[:, HEAVE, [SURGE, PITCH]]) / np.abs(M[:, HEAVE, HEAVE])[:, None]
        assert np.max(off) < 1e-3


def test_damping_positive_semidefinite(hull):
    # radiated power 1/2 u^H B u >= 0 for any motion: eigenvalues >= 0 up to the mesh error of
    # the one combination of surge and pitch that radiates nothing (rank-one surge-pitch block)
    for Bn in hull.damping:
        ev = np.linalg.eigvalsh(0.5 * (Bn + Bn.T))
        assert ev[0] >= -0.01 * ev[-1]
        assert np.all(np.diag(Bn) >= 0)


def test_radiation_bound(hull, band):
    # Budal & Falnes / Newman: |X_i|^2 / (8 B_ii) = J lambda / 2 pi (heave) and J lambda / pi
    # (surge, pitch); all three modes together 3 J lambda / 2 pi (Evans 1976, Newman 1976)
    J = hull.wave_power_flux()
    lam = 2.0 * np.pi / hull.wavenumber
    single = np.abs(hull.excitation) ** 2 / (8.0 * np.diagonal(hull.damping, 0, 1, 2))
    for mode, width in ((SURGE, lam / np.pi), (HEAVE, lam / (2 * np.pi)), (PITCH, lam / np.pi)):
        ok = _resolved(hull, band, mode)
        assert np.allclose(single[ok, mode], (J * width)[ok], rtol=0.05), mode
    ok = _resolved(hull, band, HEAVE) & _resolved(hull, band, PITCH)
    assert np.allclose(max_absorbed_power(hull)[ok], (3 * J * lam / (2 * np.pi))[ok], rtol=0.05)


def test_hydrostatics_from_geometry(hull):
    geo = CylinderHull(hull.radius, hull.draft, hull.zg, hull.gyration)
    C = hull.hydrostatic_stiffness
    awp = math.pi * hull.radius**2
    assert C[HEAVE, HEAVE] == pytest.approx(hull.rho * hull.g * awp, rel=0.005)
    assert C[PITCH, PITCH] == pytest.approx(geo.stiffness(hull.rho, hull.g), rel=0.005)
    assert C[SURGE, SURGE] == 0.0 and abs(C[HEAVE, PITCH]) < 1e-6 * C[HEAVE, HEAVE]


def test_long_wave_limits(hull):
    # long waves: X3 -> rho g A_wp (the hull follows the surface; 0.970 of it at 0.2 rad/s,
    # k R = 0.065)
    X3 = np.abs(hull.excitation[0, HEAVE])
    assert X3 == pytest.approx(hull.rho * hull.g * math.pi * hull.radius**2, rel=0.04)


def _copy(h, **kw):
    d = {k: getattr(h, k) for k in h.__dataclass_fields__}
    d.update(kw)
    return ThreeDofCoefficients(**d)


def test_bad_input(hull, tmp_path):
    with pytest.raises(ValueError, match="nope.npz"):
        ThreeDofCoefficients.load(tmp_path / "nope.npz")
    with pytest.raises(ValueError, match="increasing"):
        _copy(hull, omega=hull.omega[::-1].copy())
    with pytest.raises(ValueError, match="wavenumber"):
        _copy(hull, water_depth=10.0)
    with pytest.raises(ValueError, match="damping"):
        _copy(hull, damping=hull.damping[:, :2, :2])
    B = hull.damping.copy()
    B[3, 1, 1] = -1.0
    with pytest.raises(ValueError, match="negative"):
        _copy(hull, damping=B)
    with pytest.raises(ValueError, match="zg"):
        _copy(hull, zg=-3.0)
    bad = tmp_path / "bad.npz"
    np.savez(bad, omega=np.arange(3.0))
    with pytest.raises(ValueError, match="bad.npz"):
        ThreeDofCoefficients.load(bad)
    p = tmp_path / "h.npz"
    hull.save(p)
    h2 = ThreeDofCoefficients.load(p)
    assert np.array_equal(h2.excitation, hull.excitation)
    assert np.array_equal(h2.damping, hull.damping)
