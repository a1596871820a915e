"""The ship's SIMD lanes (`mf_envs.physics.ship.lanes`) against the scalar step they replace.

The native GyroStabilizer-v0 vector env steps rows LANES at a time in the lanes when they share
their parameters; each row must keep the bits of `kernels.advance_with` (the single env's step,
which `tests/test_vector_envs.py` ties to SyncVectorEnv). Second formulation: the same batch
with the lanes switched off; and, row by row, `advance_block` against `advance_with` from states
that push every series out of range (the scalar fallback)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401
from mf_envs.frames.steppers import rk4_work, rkmk4_rwork
from mf_envs.physics.ship import kernels as K
from mf_envs.physics.ship import lanes
from mf_envs.physics.ship.layout import Slot as S

N, STEPS = 2 * lanes.LANES + 7, 260  # two lane blocks and a scalar remainder; an autoreset
FULL = ("gyroscopic", "gimbal_inertia", "added_inertia", "hydrostatic_restoring",
        "roll_damping", "quadratic_roll_damping", "wave_moment", "gimbal_limits")  # fmt: skip
SCENES = {
    "default": {},
    "electric": {"gimbal_drive": "electric"},
    "jonswap_hs15": {"effects": (*FULL, "irregular_waves"), "significant_wave_height": 1.5},
    "two_gyros": {"n_gyros": 2},
    "seed_form": {"form": "seed"},
    "seed_preset": {"preset": "seed"},
    "friction": {
        "gimbal_drive": "electric",
        "gimbal_damping": 50.0,
        "effects": (*FULL, "gimbal_damping"),
    },  # fmt: skip
    "big_wave": {"wave_moment_amplitude": 60000.0},
}


def _run(kwargs: dict, lanes_on: bool) -> list[tuple[np.ndarray, ...]]:
    envs = gym.make_vec("GyroStabilizer-v0", num_envs=N, vectorization_mode="vector_entry_point",
                        num_threads=1, episode_seconds=10.0, **kwargs)  # fmt: skip
    if not lanes_on:
        envs._lane_params = lambda: np.empty(0)
    envs.reset(seed=3)
    assert (envs._lane_params().size > 0) == lanes_on
    rng = np.random.default_rng(4)
    out = []
    for k in range(STEPS):
        a = rng.uniform(-1.0, 1.0, (N, 1)).astype(np.float32)
        if k % 40 >= 30:  # bang-bang: the gimbal at its rate cap and its cushions
            a = np.sign(a)
        obs, rew, term, trunc, info = envs.step(a)
        out.append((obs, rew, term, trunc, info["mount_moment"], info["drive_energy"],
                    envs.b["y"].copy(), envs.b["R"].copy(), envs.b["t"].copy()))  # fmt: skip
    envs.close()
    return out


@pytest.mark.filterwarnings("ignore:GyroStabilizer-v0. capacity")
@pytest.mark.parametrize("scene", sorted(SCENES))
def test_lanes_give_the_scalar_steps_bits(scene):
    """Observations, rewards, flags, infos and the whole state are bit-identical with and
    without the lanes, over episodes with random and bang-bang actions and an autoreset."""
    with_lanes, without = _run(SCENES[scene], True), _run(SCENES[scene], False)
    for k, (a, b) in enumerate(zip(with_lanes, without)):
        for x, y in zip(a, b):
            assert np.array_equal(x, y), f"{scene}: step {k} differs"


@pytest.mark.parametrize(
    "kwargs",
    [
        {"hull": "mss_naval_vessel", "coupling": True},
        {"gimbal_drive": "damper"},
        {"hull": "mss_naval_vessel"},
        {"effects": (*FULL, "translation")},
    ],
    ids=["mss_coupling", "damper", "mss_cubic_gz", "heave"],
)
@pytest.mark.filterwarnings("ignore:GyroStabilizer-v0. capacity")
def test_scenes_the_lanes_do_not_model_take_the_scalar_step(kwargs):
    envs = gym.make_vec("GyroStabilizer-v0", num_envs=8, vectorization_mode="vector_entry_point",
                        **kwargs)  # fmt: skip
    envs.reset(seed=0)
    assert envs._lane_params().size == 0
    assert not lanes.supported(envs.b["P"][0])


def test_rows_may_differ_in_the_wave_phase_only():
    envs = gym.make_vec("GyroStabilizer-v0", num_envs=8, vectorization_mode="vector_entry_point")
    envs.reset(seed=0)
    assert envs._lane_params().size > 0
    P = envs.b["P"].copy()
    assert len(set(P[:, int(S.WPHASE)])) == 8  # each row its own phase, the lanes still on
    P[3, 0] *= 1.5
    assert lanes.uniform(envs.b["P"]) and not lanes.uniform(P)


def test_block_falls_back_row_by_row_where_a_series_is_out_of_range():
    """advance_block on LANES rows, a third of them with gimbal rates (6-12 rad/s: the
    sin/cos series' range is 0.1 rad per stage), body rates (the Rodrigues / dexp^-1 series)
    or pitch (the asin series) beyond the series, equals advance_with row by row."""
    envs = gym.make_vec("GyroStabilizer-v0", num_envs=lanes.LANES,
                        vectorization_mode="vector_entry_point")  # fmt: skip
    envs.reset(seed=5)
    b = envs.b
    rng = np.random.default_rng(6)
    n = lanes.LANES
    y, R = b["y"].copy(), b["R"].copy()
    y[:, :3] = rng.normal(0.0, 0.05, (n, 3))
    y[:, 3] = rng.uniform(-0.8, 0.8, n)
    y[:, 4] = rng.uniform(-1.5, 1.5, n)
    y[::3, 4] = rng.choice([-1.0, 1.0], len(y[::3])) * rng.uniform(6.0, 12.0, len(y[::3]))
    y[1::7, :3] = rng.normal(0.0, 3.0, (len(y[1::7]), 3))
    for i in range(2, n, 9):  # pitched by 0.1 rad
        c, s = np.cos(0.1), np.sin(0.1)
        R[i] = R[i] @ np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])
    t = rng.uniform(0.0, 30.0, n)
    u = rng.uniform(-2.0, 2.0, n)
    dt, nsub = envs._dt.copy(), int(envs._nsub[0])
    P, tab = b["P"], b["tab"]
    ref = (t.copy(), y.copy(), R.copy(), np.zeros((n, K.N_OUT)))
    work, Rwork = rk4_work(K.N_STATE), rkmk4_rwork()
    for i in range(n):
        ref[0][i] = K.advance_with(ref[0][i], ref[1][i], ref[2][i], u[i], dt[i], nsub, P[i],
                                   tab[i], ref[3][i], work, Rwork)  # fmt: skip
    got = (t.copy(), y.copy(), R.copy(), np.zeros((n, K.N_OUT)))
    lanes.advance_block(np.arange(n), got[0], got[1], got[2], u, dt, nsub, P, tab, got[3],
                        P[0].copy(), np.empty(lanes.N_X * n), np.empty(lanes.N_K * n),
                        np.empty(6 * n), np.empty(n), work, Rwork)  # fmt: skip
    for a, r in zip(got, ref):
        assert np.array_equal(a, r)
    # the fallback ran: the lanes' own flags for the first substep
    X, KL = np.empty(lanes.N_X * n), np.empty(lanes.N_K * n)
    for m in range(lanes.N_X):
        X[m * n : (m + 1) * n] = 0.0
    X[lanes.XW1 * n : lanes.XW1 * n + n] = y[:, 0]
    X[lanes.XW2 * n : lanes.XW2 * n + n] = y[:, 1]
    X[lanes.XW3 * n : lanes.XW3 * n + n] = y[:, 2]
    X[lanes.XPHI * n : lanes.XPHI * n + n] = y[:, 3]
    X[lanes.XNPHI * n : lanes.XNPHI * n + n] = y[:, 3]
    X[lanes.XPHID * n : lanes.XPHID * n + n] = y[:, 4]
    X[lanes.XR2 * n : lanes.XR2 * n + n] = 1.0
    X[lanes.XNC * n : lanes.XNC * n + n] = np.cos(y[:, 3])
    X[lanes.XNS * n : lanes.XNS * n + n] = np.sin(y[:, 3])
    X[lanes.XDT * n : lanes.XDT * n + n] = dt
    lanes.lane_block(X, KL, P[0].copy())
    flags = KL[lanes.KBAD * n : lanes.KBAD * n + n]
    assert 0 < flags.sum() < n
