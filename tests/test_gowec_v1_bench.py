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
    rows = power_matrix.matrix(hs=(1.5,), tp=(6.0,), seeds=(2000,), seconds=60.0,
                               progress=False)  # fmt: skip
    (r,) = rows
    env = gym.make("FloatingGOWEC-v0", significant_wave_height=1.5, peak_period=6.0)
    env.reset(seed=2000)
    u = env.unwrapped
    assert r["J_W_per_m"] == pytest.approx(u.wave_power_flux(), rel=1e-12)  # the same sea
    assert 0.0 < r["mech_W"] < motion_limited_bound(u.hull, u.wave, u.pitch_limit)
    assert r["capture_width_m"] == pytest.approx(r["mech_W"] / r["J_W_per_m"], rel=1e-12)
    assert r["cwr"] == pytest.approx(r["capture_width_m"] / 12.0, rel=1e-12)
    # net electrical = eta P+ - P- / eta - loss <= eta P_mech - loss
    assert r["net_W"] <= 0.9 * r["mech_W"] - 3000.0 + 1e-6
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
