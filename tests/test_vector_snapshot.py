"""Snapshot/restore and load_env of the native vector envs (a planner's rows): restoring a
snapshot and stepping reproduces the bits of the step taken without it, and rows loaded from a
single env mid-episode continue its episode bit for bit (its own sea realisation)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401

CASES = [
    ("GyroStabilizer-v0", {"significant_wave_height": 2.0, "wave_period": 8.0}),
    ("GyroStabilizer-v0", {}),
    ("FloatingGOWEC-v0", {"significant_wave_height": 1.0, "peak_period": 6.0}),
    ("FloatingGOWEC-v0", {}),
]


def _vec(env_id, kw, n):
    return gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", **kw)


@pytest.mark.parametrize("env_id, kw", CASES)
def test_restore_then_step_reproduces_the_bits(env_id, kw):
    v = _vec(env_id, kw, 3).unwrapped
    v.reset(seed=5)
    rng = np.random.default_rng(0)
    for _ in range(4):
        v.step(rng.uniform(-1, 1, (3, 1)))
    snap = v.snapshot()
    acts = rng.uniform(-1, 1, (30, 3, 1))  # long enough to cross resets on short episodes
    first = [v.step(a) for a in acts]
    v.step(rng.uniform(-1, 1, (3, 1)))  # move on, then rewind
    v.restore(snap)
    again = [v.step(a) for a in acts]
    for (o1, r1, t1, u1, _), (o2, r2, t2, u2, _) in zip(first, again):
        assert np.array_equal(o1, o2) and np.array_equal(r1, r2)
        assert np.array_equal(t1, t2) and np.array_equal(u1, u2)


@pytest.mark.parametrize("env_id, kw", CASES)
def test_rows_loaded_from_a_single_env_continue_its_episode(env_id, kw):
    env = gym.make(env_id, **kw).unwrapped
    env.reset(seed=11)
    rng = np.random.default_rng(1)
    for _ in range(7):
        env.step(rng.uniform(-1, 1, (1,)).astype(np.float32))
    v = _vec(env_id, kw, 4).unwrapped
    v.reset(seed=99)  # another sea: load_env replaces it by the single env's
    v.load_env(env, rows=np.array([1, 3]))
    acts = rng.uniform(-1, 1, (12, 1)).astype(np.float32)
    rewards = []
    for a in acts:
        _, r, _, _, _ = env.step(a)
        rewards.append(r)
    got = [v.step(np.repeat(a[None], 4, axis=0))[1] for a in acts]
    for r, row in zip(rewards, got):
        assert row[1] == r and row[3] == r  # same bits: the rows know the single env's sea
    assert not all(row[0] == r for r, row in zip(rewards, got))  # row 0 kept its own sea


def test_restore_rejects_a_snapshot_of_another_env():
    a = _vec("GyroStabilizer-v0", {}, 2).unwrapped
    b = _vec("GyroStabilizer-v0", {}, 3).unwrapped
    a.reset(seed=0)
    b.reset(seed=0)
    with pytest.raises(ValueError, match="snap"):
        a.restore(b.snapshot())


def test_loaded_rows_take_the_single_envs_pto():
    """FloatingGOWEC-v0 under a linear PTO set on the single env (`set_pto`, as efficient_pto
    does at reset): the loaded rows run the same drive law, bit for bit."""
    kw = {"significant_wave_height": 1.0, "peak_period": 6.0}
    env = gym.make("FloatingGOWEC-v0", **kw).unwrapped
    env.reset(seed=2)
    env.set_pto(5e4, 3e3)
    v = _vec("FloatingGOWEC-v0", kw, 2).unwrapped
    v.reset(seed=0)
    v.load_env(env)
    zero = np.zeros((1,), np.float32)
    for _ in range(10):
        r = env.step(zero)[1]
        assert np.all(v.step(np.zeros((2, 1), np.float32))[1] == r)


def test_a_vector_env_without_state_arrays_refuses_snapshot_and_restore():
    """GOWEC-v0's rows keep no snapshot: both calls say so instead of copying half a state."""
    v = _vec("GOWEC-v0", {}, 2).unwrapped
    v.reset(seed=0)
    with pytest.raises(TypeError, match="snapshot"):
        v.snapshot()
    with pytest.raises(TypeError, match="restore"):
        v.restore({})
