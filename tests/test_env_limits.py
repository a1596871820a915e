"""Episode length: the ids are registered without Gymnasium's TimeLimit and every env truncates
itself at its own length (docs/api.md, "Episode length"): its default (the declaration's
`max_episode_steps`), its own length argument (`episode_seconds`, GOWEC-v0's `n_periods`) alone,
or `max_episode_steps` given to the constructor or the native vector env; a `max_episode_steps`
given to `gym.make` is Gymnasium's TimeLimit, which ends an episode earlier, never later."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the ids)
from mf_envs.envs import VECTOR_SPECS, declaration, declarations, task_ids
from mf_envs.envs.base import episode_steps_arg
from mf_envs.envs.declaration import EnvDeclaration, load
from mf_envs.envs.gyro_stabilizer.env import GyroStabilizerEnv

OURS = sorted(k for k in gym.registry if "mf_envs" in str(gym.registry[k].entry_point))
IDS = sorted(declarations())
# a longer episode than the default, in each env's own length argument
LONGER = {
    "GOWEC-v0": {"n_periods": 21},
    "FloatingGOWEC-v0": {"episode_seconds": 121.0},
    "GyroStabilizer-v0": {"episode_seconds": 31.0},
    "Inchworm-v0": {"episode_seconds": 41.0},
    "Serpentine-v0": {"episode_seconds": 21.0},
    "Eel-v0": {"episode_seconds": 11.0},
}


@pytest.fixture(autouse=True)
def _quiet_alias():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", FutureWarning)
        yield


def test_every_id_is_covered():
    assert set(LONGER) == set(IDS)
    assert set(OURS) >= set(IDS) and "GOWEC-v1" in OURS
    assert set(OURS) >= set(task_ids()) > set(IDS)  # the task variants are registered too


@pytest.mark.parametrize("env_id", OURS)
def test_no_time_limit_and_the_declared_default_episode(env_id):
    assert gym.spec(env_id).max_episode_steps is None  # no TimeLimit from gym.make
    decl = declaration(env_id)
    steps = decl.max_episode_steps
    assert isinstance(steps, int) and steps >= 1
    # built directly (a task variant: with its scene's kwargs): its own default
    assert load(decl.entry_point)(**decl.kwargs).max_steps == steps
    env = gym.make(env_id)
    assert env.unwrapped.max_episode_steps == steps and env.spec.max_episode_steps is None
    assert "TimeLimit" not in str(env)
    env.close()


@pytest.mark.parametrize("env_id", IDS)
def test_a_longer_episode_via_gym_make_alone(env_id):
    cls = load(declaration(env_id).entry_point)
    steps = cls(**LONGER[env_id]).max_steps
    assert steps > declaration(env_id).max_episode_steps
    env = gym.make(env_id, **LONGER[env_id])
    assert env.unwrapped.max_steps == steps
    env.close()
    with pytest.raises(ValueError, match=rf"{next(iter(LONGER[env_id]))}.*max_episode_steps"):
        cls(max_episode_steps=steps + 1, **LONGER[env_id])  # both given: they must agree
    assert cls(max_episode_steps=steps, **LONGER[env_id]).max_steps == steps


@pytest.mark.parametrize("env_id", IDS)
def test_max_episode_steps_given_to_the_constructor_is_the_envs_length(env_id):
    cls = load(declaration(env_id).entry_point)
    u = cls(max_episode_steps=777)
    assert u.max_steps == 777
    assert u.episode_seconds == pytest.approx(777 * u.control_dt)
    env = gym.make(env_id, max_episode_steps=5)  # gym.make's: its TimeLimit
    assert env.spec.max_episode_steps == 5
    env.close()


def test_gym_make_max_episode_steps_truncates_where_it_says():
    """gym.make's max_episode_steps=7 (its TimeLimit) ends the 600-step default episode at 7, a
    truncation; episode_seconds=1.0 alone ends it at 20, by the env."""
    for kw, end in (({"max_episode_steps": 7}, 7), ({"episode_seconds": 1.0}, 20)):
        env = gym.make("GyroStabilizer-v0", **kw)
        env.reset(seed=0)
        for k in range(1, end + 1):
            *_, term, trunc, _ = env.step(np.zeros(1, np.float32))
            assert trunc == (k == end) and not term
        env.close()


def test_a_long_episode_runs_to_its_end():
    """40 s of GyroStabilizer-v0 from gym.make with episode_seconds alone truncates at step 800."""
    env = gym.make("GyroStabilizer-v0", episode_seconds=40.0)
    env.reset(seed=1)
    steps, trunc = 0, False
    while not trunc:
        *_, term, trunc, info = env.step(np.zeros(1, np.float32))
        steps += 1
        assert not term
    assert steps == 800 and info["time"] == pytest.approx(40.0)
    # a finer control_dt makes the default 30 s episode 1500 steps
    assert gym.make("GyroStabilizer-v0", control_dt=0.02).unwrapped.max_steps == 1500


@pytest.mark.parametrize("bad", [0, -2, 2.5, 100.0, "10", True, np.float64(3.0)])
def test_bad_max_episode_steps_names_it(bad):
    with pytest.raises(ValueError, match="max_episode_steps"):
        episode_steps_arg(bad)
    with pytest.raises(ValueError, match="max_episode_steps"):
        GyroStabilizerEnv(max_episode_steps=bad)
    with pytest.raises(ValueError, match="max_episode_steps"):
        gym.make_vec("GyroStabilizer-v0", 2, vectorization_mode="vector_entry_point",
                     max_episode_steps=bad)  # fmt: skip
    assert episode_steps_arg(np.int64(12)) == 12 and episode_steps_arg(None) is None


@pytest.mark.parametrize("env_id", sorted(VECTOR_SPECS))
def test_make_vec_native_lengths(env_id):
    default = declaration(env_id).max_episode_steps
    venv = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point")
    assert venv.template.max_steps == default
    venv.close()
    steps = load(declaration(env_id).entry_point)(**LONGER[env_id]).max_steps
    venv = gym.make_vec(env_id, 2, vectorization_mode="vector_entry_point", **LONGER[env_id])
    assert venv.template.max_steps == steps
    venv.close()
    venv = gym.make_vec(env_id, 2, vectorization_mode="vector_entry_point", max_episode_steps=9)
    assert venv.template.max_steps == 9
    venv.close()


def test_make_vec_native_and_sync_truncate_and_autoreset_alike():
    """Native and SyncVectorEnv under make_vec agree on the step that truncates (7: through
    max_episode_steps, the native env's rows and Sync's TimeLimit; 20: episode_seconds alone,
    the env) and both autoreset the step after it (NEXT_STEP: reward 0, flags False)."""
    for kw, end in (({"max_episode_steps": 7}, 7), ({"episode_seconds": 1.0}, 20)):
        nat = gym.make_vec("GyroStabilizer-v0", 2, vectorization_mode="vector_entry_point", **kw)
        syn = gym.make_vec("GyroStabilizer-v0", 2, vectorization_mode="sync", **kw)
        for venv in (nat, syn):
            venv.reset(seed=3)
            out = [venv.step(np.zeros((2, 1), np.float32)) for _ in range(end + 2)]
            assert [o[3].tolist() for o in out] == [[False] * 2] * (end - 1) + [[True] * 2] + [
                [False] * 2
            ] * 2
            assert not any(o[2].any() for o in out)  # a truncation, never a termination
            assert out[end][1].tolist() == [0.0, 0.0]  # the autoreset step
            venv.close()


def test_remaking_from_the_spec_keeps_a_given_length():
    env = gym.make("GyroStabilizer-v0", episode_seconds=40.0)
    again = gym.make(env.spec)
    assert again.unwrapped.max_steps == 800
    venv = gym.make_vec(env.spec, 2, vectorization_mode="vector_entry_point")
    assert venv.template.max_steps == 800
    venv.close()


def test_alias_makes_its_length():
    assert gym.make("GOWEC-v1", episode_seconds=121.0).unwrapped.max_steps == 6050
    venv = gym.make_vec("GOWEC-v1", 2, vectorization_mode="vector_entry_point",
                        episode_seconds=121.0)  # fmt: skip
    assert venv.template.max_steps == 6050
    venv.close()


def test_declaration_validates_max_episode_steps():
    for bad in (0, 2.0, True):
        with pytest.raises(ValueError, match="max_episode_steps"):
            EnvDeclaration("X-v0", "m:C", max_episode_steps=bad)


def test_domain_randomization_remakes_with_the_same_length():
    from mf_envs.train.randomize import DomainRandomization

    for kw, limit, steps in (
        ({}, None, 600),
        ({"episode_seconds": 1.0}, None, 20),
        ({"episode_seconds": 40.0}, None, 800),
        ({"max_episode_steps": 50}, 50, 600),  # gym.make's TimeLimit, kept on the re-made env
    ):
        env = DomainRandomization(gym.make("GyroStabilizer-v0", **kw))
        env.reset(seed=0)
        assert env.env.spec.max_episode_steps == limit and env.unwrapped.max_steps == steps
        env.close()
