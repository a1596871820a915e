"""Env ids: `GOWEC-v0` makes its env without Gymnasium's "out of date" warning (no warning filter
hides it); `FloatingGOWEC-v0` is the floating GOWEC; its old id `GOWEC-v1` still makes that env,
single, vectorised (sync and native) and pickled, with one deprecation warning naming the new id."""

from __future__ import annotations

import pickle
import warnings

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the ids)
from mf_envs.envs import ALIASES, DeprecatedIdWarning, canonical_env_id
from mf_envs.envs.gowec_v1.env import GOWECV1Env
from mf_envs.envs.gowec_v1.vector import GOWECV1VectorEnv

NEW = "FloatingGOWEC-v0"


def test_no_process_wide_filter_mentions_our_ids():
    """The old `warnings.filterwarnings("ignore", ".*GOWEC-v0 is out of date")` is gone."""
    assert not [f for f in warnings.filters if f[1] is not None and "GOWEC" in f[1].pattern]


def test_gowec_v0_makes_without_any_warning(recwarn):
    env = gym.make("GOWEC-v0")
    env.reset(seed=0)
    env.close()
    assert [str(w.message) for w in recwarn] == []


def test_a_higher_gowec_version_would_warn():
    """The check above can fail: Gymnasium does warn "out of date" when GOWEC-v1 is a spec of
    the GOWEC family (how `gym.register("GOWEC-v1", ...)` would register the alias)."""
    saved = gym.registry.pop("GOWEC-v1")
    try:
        gym.register(id="GOWEC-v1", entry_point=gym.spec(NEW).entry_point)
        with pytest.warns(DeprecationWarning, match="GOWEC-v0 is out of date"):
            gym.make("GOWEC-v0").close()
    finally:
        gym.registry["GOWEC-v1"] = saved
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        gym.make("GOWEC-v0").close()  # the alias restored: silent again
    assert [str(w.message) for w in rec] == []


def test_no_registered_spec_is_a_gowec_version_above_0():
    versions = [
        s.version for s in gym.registry.values() if s.namespace is None and s.name == "GOWEC"
    ]
    assert versions == [0]


def test_new_id_makes_the_floating_gowec_without_warning(recwarn):
    env = gym.make(NEW, episode_seconds=1.0)
    assert isinstance(env.unwrapped, GOWECV1Env) and env.spec.id == NEW
    env.close()
    assert [str(w.message) for w in recwarn] == []


def _rollout(env_id: str) -> tuple[np.ndarray, float]:
    env = gym.make(env_id, episode_seconds=1.0)
    obs, _ = env.reset(seed=3)
    total = 0.0
    for _ in range(5):
        obs, r, *_ = env.step(np.array([0.5], dtype=np.float32))
        total += float(r)
    env.close()
    return obs, total


def test_old_id_makes_the_same_env_and_warns_naming_the_new_id():
    with pytest.warns(DeprecatedIdWarning, match=NEW) as rec:
        env = gym.make("GOWEC-v1", episode_seconds=1.0)
    assert len(rec) == 1 and str(rec[0].message).count("\n") == 0  # one line
    assert rec[0].filename == __file__  # points at the caller's gym.make line
    assert isinstance(env.unwrapped, GOWECV1Env) and env.spec.id == NEW
    assert issubclass(DeprecatedIdWarning, FutureWarning)  # shown by default, unlike Deprecation
    env.close()
    with pytest.warns(DeprecatedIdWarning):
        old = _rollout("GOWEC-v1")
    new = _rollout(NEW)
    np.testing.assert_array_equal(old[0], new[0])
    assert old[1] == new[1]


@pytest.mark.parametrize("mode", ["vector_entry_point", "sync"])
def test_old_id_vectorises(mode):
    with pytest.warns(DeprecatedIdWarning, match=NEW):
        venv = gym.make_vec("GOWEC-v1", num_envs=2, vectorization_mode=mode, episode_seconds=1.0)
    try:
        if mode == "vector_entry_point":
            assert isinstance(venv.unwrapped, GOWECV1VectorEnv)
        else:
            assert isinstance(venv, gym.vector.SyncVectorEnv)
        assert venv.spec.id == NEW
        obs, _ = venv.reset(seed=0)
        assert obs.shape == (2, 9)  # 9 slots since issue 29 (the wave elevation)
    finally:
        venv.close()


def test_old_id_spec_and_env_pickle():
    spec = pickle.loads(pickle.dumps(gym.spec("GOWEC-v1")))
    assert spec.id == NEW
    with pytest.warns(DeprecatedIdWarning):
        env = gym.make(spec, episode_seconds=1.0)
        again = pickle.loads(pickle.dumps(env))
    assert isinstance(again.unwrapped, GOWECV1Env)
    assert gym.spec("GOWEC-v1").to_json()  # string entry points: serialisable like any spec
    env.close()
    again.close()


def test_canonical_env_id():
    assert ALIASES == {"GOWEC-v1": NEW}
    assert canonical_env_id("GOWEC-v0") == "GOWEC-v0"
    assert canonical_env_id(NEW, notice_alias=False) == NEW
    with pytest.warns(DeprecatedIdWarning, match=NEW):
        assert canonical_env_id("GOWEC-v1") == NEW


def test_old_id_reaches_baselines_and_the_shipped_policy():
    from mf_envs import controllers

    with pytest.warns(DeprecatedIdWarning):
        assert controllers.baseline_kinds("GOWEC-v1") == controllers.baseline_kinds(NEW)
    pytest.importorskip("safetensors", reason="needs the train extra: pip install -e '.[train]'")
    pytest.importorskip("stable_baselines3", reason="needs the train extra")
    from mf_envs.train import load_policy

    # the old id is looked up under the new one (no policy ships for it today: the error says so)
    with pytest.warns(DeprecatedIdWarning), pytest.raises(ValueError, match=f"policy for {NEW}"):
        load_policy("GOWEC-v1")
