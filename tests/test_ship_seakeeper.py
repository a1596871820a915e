"""Seakeeper unit presets and the capacity bound (ship.seakeeper) against independent truth.

Truths: the numbers as published (H = 7015 N m s of the Model 7000, Seakeeper's theory
page; the seed's Table 3-1), the exact cancelling gimbal motion beta(t) = asin(s sin w t)
evaluated on a grid (its peak angle and rate), Froude similarity of the scaled hull, and the
maker's stated boat range for one Model 7000 (seakeeper.com/products_sizing.php; 60,000 lb
quoted elsewhere).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from mf_envs.physics.gyros import SEAKEEPER
from mf_envs.physics.ship import seakeeper as SK
from mf_envs.physics.ship.hulls import Hull
from mf_envs.physics.ship.params import seakeeper_gyro


def test_model_7000_matches_published_numbers():
    u = SK.SEAKEEPER_7000
    assert u.angular_momentum == pytest.approx(7015.0, rel=2e-4)  # theory page: 7015 N m s
    assert u.rotor_inertia == pytest.approx(6.7, rel=1e-12)
    assert math.degrees(u.max_precession) == pytest.approx(60.0)
    lo, hi = u.displacement_range
    assert lo == pytest.approx(15_876.0, abs=1.0) and hi == pytest.approx(24_948.0, abs=1.0)
    assert "90021" in u.source and "products_sizing" in u.source and "theory" in u.source


def test_seed_table_units_kept_as_printed():
    for model, (rpm, h, p) in SEAKEEPER.items():
        u = SK.SEED_TABLE_3_1[model]
        assert (u.rotor_speed_rpm, u.angular_momentum, u.spool_up_power) == (rpm, h, p)
        assert u.max_precession is None and u.displacement_range is None  # not in the seed
    g, ref = SK.SEED_TABLE_3_1["9"].gyro_params(), seakeeper_gyro("9")
    assert g.rotor_inertia == pytest.approx(ref.rotor_inertia, rel=1e-14)
    assert g.angular_momentum == pytest.approx(9000.0, rel=1e-14)


@pytest.mark.parametrize("scale", [0.5, 0.9, 1.0, 1.6])
def test_capacity_is_the_exact_cancellation_limit(scale):
    """Scale the design moment so that capacity takes several values; the exact cancelling
    motion n H sin(beta) = (M0 / w) sin(w t) stays within +-beta_max iff capacity >= 1, and
    its peak rate is M0 / (n H) (the rate cap's bound)."""
    u, hull = SK.SEAKEEPER_7000, Hull.yacht()
    m0, w = SK.design_wave_moment(hull)
    steep = SK.DESIGN_STEEPNESS * scale
    cap = SK.capacity(u, hull, steepness=steep)
    m = m0 * scale
    s = m / (u.angular_momentum * w)
    t = np.linspace(0.0, 2.0 * math.pi / w, 20001)
    x = s * np.sin(w * t)
    feasible = bool(np.all(np.abs(x) <= math.sin(u.max_precession)))
    assert feasible == (cap >= 1.0)
    if feasible:
        beta = np.arcsin(x)
        rate = np.gradient(beta, t)
        assert rate.max() == pytest.approx(m / u.angular_momentum, rel=1e-4)
        # the rate cap's capacity is n H rate / M0: the peak rate above is exactly its limit
        peak = m / u.angular_momentum
        for f in (0.5, 1.01, 100.0):
            got = SK.capacity(u, hull, steepness=steep, max_precession_rate=f * peak)
            assert got == pytest.approx(min(cap, f), rel=1e-12)


def test_similar_hull_is_froude_scaled():
    hull = Hull.yacht()
    big = SK.similar_hull(hull, 8.0 * hull.mass)  # s = 2
    assert big.length == pytest.approx(2.0 * hull.length)
    assert big.natural_roll_period() == pytest.approx(math.sqrt(2.0) * hull.natural_roll_period())
    zeta = hull.roll_damping / (2.0 * math.sqrt(hull.roll_stiffness * sum_j(hull)))
    zeta_big = big.roll_damping / (2.0 * math.sqrt(big.roll_stiffness * sum_j(big)))
    assert zeta_big == pytest.approx(zeta, rel=1e-12)  # damping ratio is scale-free
    assert SK.similar_hull(hull, hull.mass) == hull


def sum_j(h: Hull) -> float:
    return h.inertia[0] + h.added_roll_inertia


def test_model_7000_fits_the_makers_boat_range():
    """With the design sea fixed beforehand (steepness 1/50 at roll resonance, module doc),
    the largest yacht-like hull one Model 7000 can hold level lies in the maker's range:
    above the sizing page's lower bound 35,000 lb and below the 60,000 lb (27.2 t) quoted for
    the Model 7000. A consistency check of the bound, not a validation of the maker's model."""
    m = SK.largest_hull(SK.SEAKEEPER_7000, Hull.yacht())
    assert 35_000.0 * SK.LB <= m <= 60_000.0 * SK.LB
    # the default pairing (docs/stabilizer_physics.md): the 18 t yacht is inside the range
    lo, hi = SK.SEAKEEPER_7000.displacement_range
    assert lo <= Hull.yacht().mass <= hi
    assert SK.capacity(SK.SEAKEEPER_7000, Hull.yacht()) > 1.0
    # two units hold a hull twice the capacity-limited size's roll moment
    m2 = SK.largest_hull(SK.SEAKEEPER_7000, Hull.yacht(), n_units=2)
    assert m2 > m


def test_bad_inputs_raise_naming_parameter():
    u, hull = SK.SEAKEEPER_7000, Hull.yacht()
    with pytest.raises(ValueError, match="max_precession"):
        SK.capacity(SK.SEED_TABLE_3_1["9"], hull)
    with pytest.raises(ValueError, match="steepness"):
        SK.capacity(u, hull, steepness=0.2)
    with pytest.raises(ValueError, match="n_units"):
        SK.capacity(u, hull, n_units=0)
    with pytest.raises(ValueError, match="max_precession_rate"):
        SK.capacity(u, hull, max_precession_rate=-1.0)
    with pytest.raises(ValueError, match="angular_momentum"):
        SK.GyroUnit("x", -1.0, 1000.0, "none")
    with pytest.raises(ValueError, match="displacement_range"):
        SK.GyroUnit("x", 1.0, 1000.0, "none", displacement_range=(2.0, 1.0))
    with pytest.raises(ValueError, match="mass"):
        SK.similar_hull(hull, 0.0)
