"""Episode length and Gymnasium's TimeLimit (issue 32, `mf_envs.envs._limit`): every registered
id has `max_episode_steps` in its spec, equal to its env's default episode; an episode longer
than the spec's via `gym.make` / `gym.make_vec` is honoured when `max_episode_steps` says so and
refused (ValueError naming both arguments) when it does not, never cut short by the TimeLimit;
a `max_episode_steps` given to `gym.make` is the env's own length too."""

from __future__ import annotations

import warnings

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the ids)
from mf_envs.envs import VECTOR_SPECS, declaration, declarations, task_ids
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
def test_spec_max_episode_steps_is_the_default_episode(env_id):
    limit = gym.spec(env_id).max_episode_steps
    assert isinstance(limit, int) and limit >= 1
    decl = declaration(env_id)
    cls = load(decl.entry_point)
    # built directly (a task variant: with its scene's kwargs): no TimeLimit, its own default
    assert cls(**decl.kwargs).max_steps == limit
    env = gym.make(env_id)
    assert env.spec.max_episode_steps == limit == env.unwrapped.max_episode_steps
    env.close()


@pytest.mark.parametrize("env_id", IDS)
def test_a_longer_episode_via_gym_make_is_refused_without_max_episode_steps(env_id):
    with pytest.raises(ValueError, match="max_episode_steps") as err:
        gym.make(env_id, **LONGER[env_id])
    name = next(iter(LONGER[env_id]))
    assert name in str(err.value)
    assert f"TimeLimit(max_episode_steps={gym.spec(env_id).max_episode_steps})" in str(err.value)


@pytest.mark.parametrize("env_id", IDS)
def test_a_longer_episode_with_its_max_episode_steps_is_honoured(env_id):
    cls = load(declaration(env_id).entry_point)
    steps = cls(**LONGER[env_id]).max_steps
    assert steps > gym.spec(env_id).max_episode_steps
    env = gym.make(env_id, max_episode_steps=steps, **LONGER[env_id])
    assert env.spec.max_episode_steps == steps == env.unwrapped.max_steps
    env.close()
    env = gym.make(env_id, max_episode_steps=-1, **LONGER[env_id])  # no TimeLimit
    assert env.spec.max_episode_steps is None and env.unwrapped.max_steps == steps
    env.close()
    with pytest.raises(ValueError, match=rf"{next(iter(LONGER[env_id]))}.*max_episode_steps"):
        gym.make(env_id, max_episode_steps=steps + 1, **LONGER[env_id])


@pytest.mark.parametrize("env_id", IDS)
def test_max_episode_steps_given_to_gym_make_is_the_envs_length(env_id):
    env = gym.make(env_id, max_episode_steps=777)
    u = env.unwrapped
    assert env.spec.max_episode_steps == 777 == u.max_steps
    assert u.episode_seconds == pytest.approx(777 * u.control_dt)
    env.close()
    assert load(declaration(env_id).entry_point)(max_episode_steps=5).max_steps == 5


def test_remaking_from_the_spec_keeps_a_given_length():
    """`gym.make(env.spec)` (the spec of the TimeLimit, max_episode_steps=800) makes the same
    800-step env, and so does make_vec from that spec."""
    env = gym.make("GyroStabilizer-v0", max_episode_steps=800)
    again = gym.make(env.spec)
    assert again.spec.max_episode_steps == 800 == again.unwrapped.max_steps
    venv = gym.make_vec(env.spec, 2, vectorization_mode="vector_entry_point")
    assert venv.template.max_steps == 800
    venv.close()
    with pytest.raises(ValueError, match="max_episode_steps"):  # and agrees or refuses
        gym.make(env.spec, episode_seconds=60.0)


@pytest.mark.parametrize("bad", [0, -2, 2.5, "10", True])
def test_bad_max_episode_steps_names_it(bad):
    with pytest.raises(ValueError, match="max_episode_steps"):
        GyroStabilizerEnv(max_episode_steps=bad)
    if bad != -2:  # gym.make's -1 is "no TimeLimit"; other values reach the env
        with pytest.raises(ValueError, match="max_episode_steps"):
            gym.make("GyroStabilizer-v0", max_episode_steps=bad)


def test_shorter_episodes_end_themselves_before_the_time_limit():
    """The spec's max_episode_steps bounds the episode: a shorter one (episode_seconds or a
    coarser control_dt) is the env's, ended by the env (truncated at its own last step)."""
    env = gym.make("GyroStabilizer-v0", episode_seconds=1.0)
    assert env.unwrapped.max_steps == 20 and env.spec.max_episode_steps == 600
    env.reset(seed=0)
    for k in range(1, 21):
        *_, term, trunc, _ = env.step(np.zeros(1, np.float32))
        assert trunc == (k == 20) and not term
    # a finer control_dt makes the default 30 s episode 1500 steps: refused, then honoured
    with pytest.raises(
        ValueError, match=r"the default episode \(30 s at control_dt=0.02 s\) is 1500"
    ):
        gym.make("GyroStabilizer-v0", control_dt=0.02)
    env = gym.make("GyroStabilizer-v0", control_dt=0.02, max_episode_steps=1500)
    assert env.unwrapped.episode_seconds == 30.0
    with pytest.raises(ValueError, match="steps_per_period=301"):  # GOWEC-v0: 20 x 301 steps
        gym.make("GOWEC-v0", steps_per_period=301)


def test_a_long_episode_runs_to_its_end_not_to_the_specs():
    """The case the refusal guards: 40 s of GyroStabilizer-v0 (800 steps) with its
    max_episode_steps truncates at step 800, not at the spec's 600."""
    env = gym.make("GyroStabilizer-v0", episode_seconds=40.0, max_episode_steps=800)
    env.reset(seed=1)
    steps, trunc = 0, False
    while not trunc:
        *_, term, trunc, info = env.step(np.zeros(1, np.float32))
        steps += 1
        assert not term
    assert steps == 800 and info["time"] == pytest.approx(40.0)


@pytest.mark.parametrize("env_id", sorted(VECTOR_SPECS))
def test_make_vec_native_with_the_specs_max_episode_steps(env_id):
    limit = gym.spec(env_id).max_episode_steps
    kw: dict = {}
    venv = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point", **kw)
    assert venv.template.max_steps == limit and venv.spec.max_episode_steps == limit
    venv.close()
    with pytest.raises(ValueError, match="max_episode_steps"):
        gym.make_vec(env_id, 2, vectorization_mode="vector_entry_point", **LONGER[env_id], **kw)
    cls = load(declaration(env_id).entry_point)
    steps = cls(**LONGER[env_id], **kw).max_steps
    venv = gym.make_vec(env_id, 2, vectorization_mode="vector_entry_point",
                        max_episode_steps=steps, **LONGER[env_id], **kw)  # fmt: skip
    assert venv.template.max_steps == steps
    venv.close()
    venv = gym.make_vec(env_id, 2, vectorization_mode="vector_entry_point", max_episode_steps=9,
                        **kw)  # fmt: skip
    assert venv.template.max_steps == 9  # given: the length
    venv.close()


def test_make_vec_native_truncates_where_sync_does():
    """Native and SyncVectorEnv under make_vec with max_episode_steps agree on the step that
    truncates (both 7), the native env through its rows, Sync through TimeLimit and the env."""
    kw = {"num_envs": 2, "max_episode_steps": 7}
    nat = gym.make_vec("GyroStabilizer-v0", vectorization_mode="vector_entry_point", **kw)
    syn = gym.make_vec("GyroStabilizer-v0", vectorization_mode="sync", **kw)
    for venv in (nat, syn):
        venv.reset(seed=3)
        flags = [venv.step(np.zeros((2, 1), np.float32))[3].tolist() for _ in range(7)]
        assert flags == [[False, False]] * 6 + [[True, True]]
        venv.close()
    with pytest.raises(ValueError, match="episode_seconds=31.0.*max_episode_steps"):
        gym.make_vec("GyroStabilizer-v0", 2, vectorization_mode="sync", episode_seconds=31.0)


def test_alias_is_checked_through_its_entry_point():
    with pytest.raises(ValueError, match="max_episode_steps"):
        gym.make("GOWEC-v1", episode_seconds=121.0)
    with pytest.raises(ValueError, match="max_episode_steps"):
        gym.make_vec("GOWEC-v1", 2, vectorization_mode="vector_entry_point", episode_seconds=121.0)


def test_declaration_validates_max_episode_steps():
    for bad in (0, 2.0, True):
        with pytest.raises(ValueError, match="max_episode_steps"):
            EnvDeclaration("X-v0", "m:C", max_episode_steps=bad)


def test_domain_randomization_remakes_with_the_same_time_limit():
    from mf_envs.train.randomize import DomainRandomization

    for kw, limit in (
        ({}, 600),
        ({"episode_seconds": 1.0}, 600),  # a shorter episode under the spec's limit
        ({"episode_seconds": 40.0, "max_episode_steps": 800}, 800),
        ({"episode_seconds": 40.0, "max_episode_steps": -1}, None),
    ):
        env = DomainRandomization(gym.make("GyroStabilizer-v0", **kw))
        env.reset(seed=0)
        steps = {1.0: 20, 40.0: 800}.get(kw.get("episode_seconds"), 600)
        assert env.env.spec.max_episode_steps == limit and env.unwrapped.max_steps == steps
        env.close()
