"""FloatingGOWEC-v0's power matrix and PLL-regime benchmarks (issue 29): one short cell each,
checked against the physics they report (the radiation and motion-limited bounds, the capture
width's definition, the gyro ratio's definition)."""

import math

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401
from mf_envs.benchmarks import gowec_regime, power_matrix
from mf_envs.physics.gowec.hydro.model import motion_limited_bound


def test_power_matrix_cell_within_the_bounds():
    """One cell (Hs 1.5 m, Te 5.5 s): binned on Te (Tp = Te / r with r from the spectrum), the
    energy flux MHKiT's finite-depth one at 35 m: the deep-water rho g^2 Hs^2 Te / (64 pi)
    or up to 3 % more (the sea's long components feel the bottom: c_g above its deep value);
    the mechanical power below the motion-limited bound at the survival tilt (the episode ran
    in operation) and the net below eta P_mech - loss."""
    pytest.importorskip("mhkit")  # the energy flux is MHKiT's (the compare extra)
    rows = power_matrix.matrix(hs=(1.5,), te=(5.5,), seeds=(2000,), seconds=60.0,
                               progress=False)  # fmt: skip
    (r,) = rows
    assert 0.85 < r["te"] / r["tp"] < 0.95 and r["survival"] == 0.0
    deep = 1025.0 * 9.80665**2 * 1.5**2 * 5.5 / (64.0 * math.pi)
    assert deep <= r["J_W_per_m"] <= 1.03 * deep
    env = gym.make("FloatingGOWEC-v0", significant_wave_height=1.5, peak_period=r["tp"],
                   n_components=power_matrix.N_COMPONENTS)  # fmt: skip
    env.reset(seed=2000)
    u = env.unwrapped
    assert 0.0 < r["mech_W"] < motion_limited_bound(u.hull, u.wave, u.pitch_limit)
    assert r["capture_width_m"] == pytest.approx(r["mech_W"] / r["J_W_per_m"], rel=1e-12)
    assert r["cwr"] == pytest.approx(r["capture_width_m"] / 8.0, rel=1e-12)  # the box's beam
    assert power_matrix.hull_width("iswec_class") == 12.0  # the cylinder's diameter
    # net electrical = eta P+ - P- / eta - loss <= eta P_mech - loss (the flywheels' running
    # loss at the speed the baseline set for the sea: 3 kW for the pair at 250 rpm)
    assert 0.0 < r["loss_W"] <= 3000.0 + 1e-9
    assert r["net_W"] <= 0.9 * r["mech_W"] - r["loss_W"] + 1e-6
    assert "| 1.5 |" in power_matrix.table(rows)


def test_regime_ratio_is_the_gyro_moment_over_the_wave_moment():
    r = gowec_regime.run("efficient_pto", 0.3, dict(wave_amplitude=0.5, wave_period=6.0), 2000,
                         30.0)  # fmt: skip
    env = gym.make("FloatingGOWEC-v0", wave_amplitude=0.5, wave_period=6.0)
    u = env.unwrapped
    w = 2 * math.pi / 6.0
    H = 0.3 * u.model.p.gyro[0] * u.model.psid
    assert r["ratio"] == pytest.approx(2 * H * w / (abs(u.hull.at(w)[2]) * 0.5), rel=1e-12)
    assert np.isfinite(r["net_W"]) and r["mech_W"] < u.power_bound()


def test_annual_energy_is_the_weighted_sum(tmp_path):
    """`gowec_annual` on a hand-made 2 x 2 power matrix and a scatter of four bins: two inside
    the matrix (3000 h at Hs 1.4 m, Te 5.2 s -> the (1.5, 5) cell; 4000 h at Hs 2.1, Te 9 s ->
    the (2, 6) cell, Te clamped to the last column), one calm (1000 h, Hs 0.5 m: `below`) and one
    beyond the range (766 h, Hs 4 m: `above`): mean = sum(h_i P_i) / 8766 h, by hand."""
    from mf_envs.benchmarks import gowec_annual as ga

    rows = [dict(hs=1.5, te=5.0, net_W=1000.0), dict(hs=1.5, te=6.0, net_W=2000.0),
            dict(hs=2.0, te=5.0, net_W=4000.0), dict(hs=2.0, te=6.0, net_W=8000.0)]  # fmt: skip
    path = tmp_path / "site.csv"
    path.write_text("hs,te,occurrence\n1.4,5.2,3000\n2.1,9.0,4000\n0.5,5.0,1000\n4.0,7.0,766\n")
    r = ga.annual(rows, ga.read_scatter(path), below=0.0, above=-500.0)
    mean = (3000 * 1000.0 + 4000 * 8000.0 + 1000 * 0.0 + 766 * -500.0) / 8766.0
    assert r["mean_W"] == pytest.approx(mean, rel=1e-12)
    assert r["MWh_per_year"] == pytest.approx(mean * 8766.0 / 1e6, rel=1e-12)
    assert sum(b["MWh"] for b in r["bins"]) == pytest.approx(r["MWh_per_year"], rel=1e-12)
    assert r["shares"] == pytest.approx({"below": 1000 / 8766, "matrix": 7000 / 8766,
                                         "above": 766 / 8766})  # fmt: skip
    bad = tmp_path / "bad.csv"
    bad.write_text("hs,tp\n1,2\n")
    with pytest.raises(ValueError, match="scatter"):
        ga.read_scatter(bad)
    ga.main(["--scatter", str(path), "--matrix", str(_matrix_file(tmp_path, rows)),
             "--out", str(tmp_path)])  # fmt: skip
    assert (tmp_path / "gowec_annual.json").exists() and (tmp_path / "gowec_annual.png").exists()


def _matrix_file(folder, rows):
    import json

    p = folder / "matrix.json"
    p.write_text(json.dumps(rows))
    return p
