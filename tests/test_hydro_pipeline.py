"""The BEM pipeline's pieces (issue 29): the keel-graded mesh builder, input validation, and
(slow) re-runs of `from_capytaine` / `three_dof_from_capytaine` at a few frequencies against
the shipped tables, so a change of Capytaine or of the mesh code that moves the data shows."""

import math

import numpy as np
import pytest

from mf_envs.physics.gowec.hydro import CylinderHull, load_hull
from mf_envs.physics.gowec.hydro.meshes import cylinder_profile, graded
from mf_envs.physics.gowec.hydro.three_dof import ISWEC_MESH, ThreeDofCoefficients


def test_graded_stations():
    x = graded(2.0, 10, 1.2)
    h = np.diff(x)
    assert x[0] == 0.0 and x[-1] == pytest.approx(2.0, rel=1e-15)
    assert np.allclose(h[1:] / h[:-1], 1.2, rtol=1e-12)  # geometric growth from 0
    assert np.allclose(np.diff(graded(1.0, 4, 1.0)), 0.25)
    for kw, name in ((dict(n=0), "n"), (dict(ratio=0.9), "ratio"), (dict(length=-1.0), "length")):
        args = dict(length=1.0, n=4, ratio=1.1) | kw
        with pytest.raises(ValueError, match=name):
            graded(**args)


def test_cylinder_profile_runs_up_from_the_axis_with_small_keel_panels():
    p = cylinder_profile(2.5, 2.0, 8, 8, 1.2)
    r, z = p[:, 0], p[:, 2]
    assert (r[0], z[0]) == (0.0, -2.0) and (r[-1], z[-1]) == (2.5, 0.0)
    assert np.all(np.diff(z) >= 0)  # Capytaine sorts by z (stable): the order must survive it
    bottom, side = r[z == -2.0], z[r == 2.5]
    assert np.all(np.diff(bottom) > 0)  # axis -> keel along the flat bottom
    hb, hs = np.diff(bottom), np.diff(side)
    assert hb[-1] < hb[0] and hs[0] < hs[len(hs) // 2]  # smallest panels at the keel edge


def test_solve_rejects_bad_input():
    pytest.importorskip("capytaine", reason="needs the hydro extra")
    from mf_envs.physics.gowec.hydro.bem import solve, solve_depth

    for kw, name in ((dict(omega=[-1.0]), "omega"), (dict(modes=(7,)), "modes"),
                     (dict(water_depth=0.0), "water_depth")):  # fmt: skip
        args = dict(body=None, omega=[1.0], modes=(5,), water_depth=math.inf) | kw
        with pytest.raises(ValueError, match=name):
            solve(**args)
    with pytest.raises(ValueError, match="omega"):
        solve_depth(None, [2.0, 1.0], (3,), 35.0)


@pytest.mark.slow
def test_from_capytaine_reproduces_the_default_table():
    pytest.importorskip("capytaine", reason="needs the hydro extra")
    from mf_envs.physics.gowec.hydro.bem import CONVERGED_MESH, from_capytaine

    h = load_hull()
    idx = [15, 27, 33, 40]  # 1.13, 1.99, 2.42, 2.92 rad/s (>= 4: a table)
    new = from_capytaine(CylinderHull(), h.omega[idx], mesh=CONVERGED_MESH)
    assert np.allclose(new.damping, h.damping[idx], rtol=1e-6)
    assert np.allclose(new.added_mass, h.added_mass[idx], rtol=1e-8)
    assert np.allclose(new.excitation, h.excitation[idx], rtol=1e-6)
    assert new.stiffness == pytest.approx(h.stiffness, rel=1e-10)


@pytest.mark.slow
def test_three_dof_pipeline_reproduces_the_iswec_table():
    pytest.importorskip("capytaine", reason="needs the hydro extra")
    from mf_envs.physics.gowec.hydro.bem import three_dof_from_capytaine

    h = ThreeDofCoefficients.load()
    idx = [3, 8, 12, 20]  # 0.5, 1.0 (finite-depth Green function), 1.4, 2.2 rad/s (deep)
    hull = CylinderHull(h.radius, h.draft, h.zg, h.gyration)
    new = three_dof_from_capytaine(hull, h.omega[idx], h.water_depth, ISWEC_MESH)
    # the finite-depth Green function's Prony fit is not bit-reproducible: 1e-4 of the largest
    # coefficient (the physics tests' tolerances are 2-5 %)
    for M, N in ((new.damping, h.damping[idx]), (new.added_mass, h.added_mass[idx])):
        scale = np.abs(N).max(axis=(1, 2))[:, None, None]
        assert np.all(np.abs(M - N) <= 1e-4 * scale)
    assert np.allclose(new.hydrostatic_stiffness, h.hydrostatic_stiffness, rtol=1e-10, atol=1e-3)
