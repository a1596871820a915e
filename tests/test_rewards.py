"""Rewards that cannot be gamed (issue 32 item 2): for every shipped env, ending the episode early,
stalling or holding an actuator limit on purpose never returns more than the env's default
baseline, which is its strongest (`controllers.register(..., default=True)`).

The degenerate strategies: every action at -1, at 0 or at +1 for the whole episode (a constant
full command trips GOWEC-v0's overspeed, sends FloatingGOWEC-v0 into survival, drives a gimbal onto
its stops, saturates a wire or a muscle), and a chatter between -1 and +1 every step. Each is
scored by its undiscounted episode return from `reset(seed=1000)`, the id's scene (every
registered id, the task variants included).
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401
from mf_envs.controllers import baseline_kinds, make_baseline
from mf_envs.envs import declarations, task_declarations

SHIPPED = [
    d for d in declarations().values() if d.entry_point.startswith("mf_envs.") and d.baselines
]
# and the task variants (the headline JONSWAP ids): their scenes, the env's baselines
TASKS = [
    d for d in task_declarations().values() if d.entry_point.startswith("mf_envs.") and d.baselines
]
SEED = 1000


def _episode(env_id: str, make_policy) -> tuple[float, int, bool]:
    """(return, steps, ended early) of one default episode under the policy `make_policy(env)`
    returns (reset(), act(obs, k) -> action), made on the episode's own env."""
    env = gym.make(env_id)
    try:
        reset, act = make_policy(env)
        obs, _ = env.reset(seed=SEED)
        reset()
        total, k, term, trunc = 0.0, 0, False, False
        while not (term or trunc):
            obs, r, term, trunc, _ = env.step(act(obs, k))
            total += float(r)
            k += 1
        return total, k, bool(term)
    finally:
        env.close()


def _constant(value):
    def make(env):
        a = np.full(env.action_space.shape, value, dtype=env.action_space.dtype)
        return (lambda: None), (lambda obs, k: a)

    return make


def _chatter(env):
    space = env.action_space
    hi, lo = np.ones(space.shape, space.dtype), -np.ones(space.shape, space.dtype)
    return (lambda: None), (lambda obs, k: hi if k % 2 == 0 else lo)


def _baseline(env):
    ctrl = make_baseline(env)  # the default kind: the strongest; it reads the sea at reset()
    return ctrl.reset, (lambda obs, k: ctrl.predict(obs, deterministic=True)[0])


@pytest.mark.parametrize(
    "decl",
    [pytest.param(d, id=d.env_id, marks=[pytest.mark.slow] if d.slow else []) for d in TASKS],
)
def test_degenerate_strategies_never_beat_the_default_baseline(decl):
    env_id = decl.env_id
    best, steps, _ = _episode(env_id, _baseline)
    assert np.isfinite(best) and steps > 0
    for name, policy in (("-1", _constant(-1.0)), ("0", _constant(0.0)), ("+1", _constant(1.0)),
                         ("chatter", _chatter)):  # fmt: skip
        ret, n, ended = _episode(env_id, policy)
        assert ret < best, (
            f"{env_id}: holding {name} returned {ret:.6g} over {n} steps (ended early: {ended}), "
            f"not less than the default baseline {baseline_kinds(env_id)[0]!r}'s {best:.6g}"
        )


# --------------------------------------------------------------------------- documented terms
def _api_reward_cell(env_id: str) -> str:
    """The reward cell of docs/api.md's env table (id | system | observation | action | reward)."""
    from pathlib import Path

    api = (Path(__file__).resolve().parents[1] / "docs" / "api.md").read_text()
    lines = api[api.index("## Environments (registered") :].splitlines()
    row = next(ln for ln in lines if ln.startswith(f"| `{env_id}` | "))
    return row.split(" | ")[4]


@pytest.mark.parametrize("decl", SHIPPED, ids=[d.env_id for d in SHIPPED])
def test_documented_reward_terms_are_the_codes(decl):
    """The env docstring's Rewards section and docs/api.md's reward column name exactly the terms
    the env reports in `info["reward_terms"]` (the README once had the stabilizer's reward as
    "-0.01 action^2" while the code charged the drive energy)."""
    import re

    env = gym.make(decl.env_id)
    try:
        env.reset(seed=0)
        _, _, _, _, info = env.step(env.action_space.sample())
        keys = set(info["reward_terms"])
        doc = type(env.unwrapped).__doc__ or ""
    finally:
        env.close()
    section = doc[doc.index("## Rewards") :]
    section = section[: section.index("##", 3)]
    formula = re.search(r"reward = ([a-z_]+(?: \+ [a-z_]+)*)", section)
    named = set(re.findall(r"`([a-z_]+)`", section))
    if formula:
        named |= set(formula.group(1).split(" + "))
    assert keys <= named, f"{decl.env_id}: docstring's Rewards section lacks {keys - named}"
    if formula:
        assert set(formula.group(1).split(" + ")) == keys
    api = set(re.findall(r"`([a-z_]+)`", _api_reward_cell(decl.env_id)))
    assert api == keys, f"{decl.env_id}: docs/api.md names {api}, the code reports {keys}"
