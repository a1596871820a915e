"""Feet that must grip (`mf_envs.physics.beam.contact.grip`, issue 31). Truth: symmetry of the
two-foot balance, the hard-Coulomb ratchet of the existing law (computed here independently),
the rest-to-rest bound 4 D / T^2 and the issue's figures (8 m/s^2, 0.33 N vs 0.14-0.24 N)."""

import math

import numpy as np
import pytest

from mf_envs.physics.beam.contact import grip as G
from mf_envs.physics.beam.contact.friction import FrictionParams

LAW = G.GripLaw()
STROKE, PERIOD = 0.02, 1.0


def _advance(law, on, off):
    return G.advance_per_cycle(law, STROKE, PERIOD, G.inchworm_grips(on, off))


def test_one_gripping_foot_advances_by_the_stroke():
    assert _advance(LAW, 1.0, 0.0) == pytest.approx(STROKE, rel=0.05)


def test_feet_just_below_the_threshold_do_not_crawl():
    """Both feet at threshold - 1 %: advance <= 5 % of one foot gripping (the issue's test);
    also the issue's never-gripping 0.38 / 0.62 schedule."""
    full = _advance(LAW, 1.0, 0.0)
    th = LAW.threshold - 0.01
    assert abs(_advance(LAW, th, th)) <= 0.05 * full
    assert abs(_advance(LAW, 0.62, 0.38)) <= 0.05 * full


def test_the_hard_coulomb_law_ratchets_without_gripping():
    """The contrast: quasi-static Coulomb with the existing coefficients (anisotropic slide
    0.1 / 0.15, mu linear in g) at engagements 0.38 / 0.62 advances by (almost) the whole
    stroke: the foot with the lower limit slips, the other holds."""
    fp = FrictionParams()

    def holds(rate, g_t, g_h):  # which foot moves: the one whose limit is lower
        s_t, s_h = (-1, 1) if rate > 0 else (1, -1)  # extension pushes tail back, head on
        return fp.mu(g_t, s_t) >= fp.mu(g_h, s_h)  # True: tail holds, head moves

    n, x_t, x_h = 400, 0.0, 0.0
    for k in range(n):
        t = (k + 0.5) / n
        rate = -STROKE * math.pi * math.sin(2 * math.pi * t) / n
        g_t, g_h = (0.38, 0.62) if t < 0.5 else (0.62, 0.38)
        if holds(rate, g_t, g_h):
            x_h += rate
        else:
            x_t -= rate
    assert 0.5 * (x_t + x_h) == pytest.approx(STROKE, rel=1e-4)  # midpoint rule in 400 steps


def test_advance_is_continuous_in_the_engagement():
    """A 1 % step of g near the threshold changes the advance by a fraction, not a switch."""
    full = _advance(LAW, 1.0, 0.0)
    off = LAW.threshold - 0.01
    a = [_advance(LAW, LAW.threshold + k * 0.01, off) / full for k in range(-1, 4)]
    assert a[0] == pytest.approx(0.0, abs=1e-12)
    assert all(0.0 <= a[k + 1] - a[k] <= 0.3 for k in range(len(a) - 1))


def test_force_balance_and_bad_input():
    v_t = G.split_velocity(LAW, 0.05, 0.2, 0.95, (0.2, 0.3))
    f = LAW.force(v_t, 0.2, 0.2) + LAW.force(v_t + 0.05, 0.95, 0.3)
    assert abs(f) < 1e-12
    with pytest.raises(ValueError, match="threshold"):
        G.GripLaw(threshold=0.9, width=0.2)
    with pytest.raises(ValueError, match="width"):
        G.GripLaw(width=0.0)


def test_quasi_static_error_flags_the_fast_gait():
    """The issue's figures: a foot moving 20 mm and stopping within 0.1 s needs >= 8 m/s^2;
    half the seed's body (m_A L / 2 = 0.0417 kg) then needs 0.33 N against 0.14-0.24 N of
    friction: the error exceeds 1 (flagged)."""
    a = G.foot_acceleration(np.array([0.0, 0.02]), 0.1)
    assert a == pytest.approx(4 * 0.02 / 0.1**2, rel=1e-12) and a >= 8.0 - 1e-12
    m = 0.278 * 0.3 / 2
    assert m * a == pytest.approx(0.3336, rel=1e-3)
    for friction in (0.14, 0.24):
        assert G.quasi_static_error(np.array([0.0, 0.02]), 0.1, m, friction) > 1.0
    # a slow step (1 mm in 1 s) on the same body is quasi-static
    assert G.quasi_static_error(np.linspace(0.0, 1e-3, 11), 1.0, m, 0.14) < 0.01


def test_foot_acceleration_sees_a_move_inside_the_step():
    """Back and forth within the step (no net displacement): the samples' velocity changes."""
    x = np.array([0.0, 0.01, 0.0])
    assert G.foot_acceleration(x, 0.1) == pytest.approx((2 * 0.01 / 0.05) / 0.05, rel=1e-12)
    with pytest.raises(ValueError, match="x"):
        G.foot_acceleration(np.array([0.0]), 0.1)
