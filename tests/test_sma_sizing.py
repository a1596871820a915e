"""Wires sized to the moment (`mf_envs.physics.actuators.sizing`) and the buildable preset
(`mf_envs.physics.inchworm.presets`), issue 31. Truth: hand computation of EI kappa, F = M / e,
the maker's 172 MPa rating and the issue's seed figures (52 N m, 6.5 % surface strain)."""

import math

import pytest

from mf_envs.physics.actuators.sizing import section_stiffness, size_wires
from mf_envs.physics.inchworm.presets import SOURCES, BuildableInchworm


def test_the_seed_section_needs_52_newton_metres_and_thousands_of_wires():
    s = size_wires(2.4e9, 0.02, 0.01, 13.0, 150e-6, 0.0046)
    assert s.moment == pytest.approx(2.4e9 * 0.02 * 0.01**3 / 12 * 13.0, rel=1e-12)
    assert s.moment == pytest.approx(52.0, rel=1e-12)
    assert s.surface_strain == pytest.approx(0.065, rel=1e-12)
    per_wire = 172e6 * math.pi * (150e-6) ** 2 / 4
    assert s.count == math.ceil(52.0 / 0.0046 / per_wire) and s.count > 1000


def test_surface_wires_of_the_seed_exceed_the_repeatable_strain():
    """Wires at the seed's surface (e = h/2) would strain 6.5 % > 6 %: ValueError naming kappa."""
    with pytest.raises(ValueError, match="kappa"):
        size_wires(2.4e9, 0.02, 0.01, 13.0, 150e-6, 0.005)


@pytest.mark.parametrize(
    "args, name",
    [((-1.0, 0.02, 0.01, 13.0, 1e-4, 1e-3), "youngs_modulus"),
     ((1e6, 0.02, 0.01, 13.0, 1e-4, 0.006), "lever_arm"),
     ((1e6, 0.02, 0.01, 0.0, 1e-4, 1e-3), "kappa"),
     ((1e6, 0.02, 0.01, 13.0, -1e-4, 1e-3), "diameter")],
)  # fmt: skip
def test_bad_input_names_the_parameter(args, name):
    with pytest.raises(ValueError, match=name):
        size_wires(*args)


def test_buildable_preset_is_buildable():
    b = BuildableInchworm()
    s = b.sizing()
    ei = section_stiffness(b.youngs_modulus, b.width, b.height)
    assert s.moment == pytest.approx(ei * b.kappa, rel=1e-12)
    assert s.count * s.per_wire >= s.force  # the wires hold the hump
    assert 0.02 <= s.wire_strain <= b.alloy.repeatable_strain[1]
    assert s.reset_margin > 1.0  # the straightening body re-stretches the cool wires
    # kappa L = 3 rad: a circular arc's chord 2 sin(kL/2)/k = 2/3 L, the published stride L/3
    chord = 2.0 * math.sin(b.kappa * b.length / 2.0) / b.kappa
    assert 1.0 - chord / b.length == pytest.approx(1.0 / 3.0, rel=0.01)
    assert b.beam().EI == pytest.approx(ei, rel=1e-12)
    assert b.wires().n_wires == s.count
    assert {"youngs_modulus", "wire", "lever_arm", "length"} <= set(SOURCES)
