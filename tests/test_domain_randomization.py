"""Domain randomisation in training (train/randomize.py): deterministic redraws of the
declared kwargs per reset, discrete choices, robustness shifts on real kwargs only, and every
env's declared ranges accepted by its constructor.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the env ids)
from mf_envs.envs import available_env_ids


def test_domain_randomization_redraws_params_deterministically():
    from mf_envs.train.randomize import DomainRandomization

    def draws(seed):
        env = DomainRandomization(gym.make("Pendulum-v1"), ranges={"g": (0.8, 1.2), "zz": (1, 2)})
        out = []
        obs, info = env.reset(seed=seed)
        out.append((info["randomized"]["g"], env.unwrapped.g, obs))
        for _ in range(3):
            obs, info = env.reset()
            out.append((info["randomized"]["g"], env.unwrapped.g, obs))
        return out

    a, b, c = draws(0), draws(0), draws(1)
    gs = [g for g, _, _ in a]
    assert all(8.0 <= g <= 12.0 for g in gs) and len(set(gs)) == 4
    assert all(g == ug for g, ug, _ in a)  # the env really runs with the drawn g
    for x, y in zip(a, b):
        assert x[0] == y[0] and np.array_equal(x[2], y[2])
    assert a[0][0] != c[0][0]
    with pytest.raises(ValueError, match="none of"):
        DomainRandomization(gym.make("Pendulum-v1"), ranges={"zz": (1, 2)})


def test_domain_randomization_choices_mix_regular_and_irregular_seas():
    """FloatingGOWEC-v0's default choices: the env really runs the drawn sea (regular when
    significant_wave_height is None, JONSWAP of that Hs otherwise), reproducibly."""
    from mf_envs.train.randomize import DomainRandomization

    def draws(seed):
        env = DomainRandomization(gym.make("FloatingGOWEC-v0", episode_seconds=1.0))
        out = [env.reset(seed=seed)[1]["randomized"]]
        out += [env.reset()[1]["randomized"] for _ in range(7)]
        seas = [(env.unwrapped.irregular, env.unwrapped.wave_period)]
        return out, seas

    a, sa = draws(3)
    assert draws(3)[0] == a
    hs = [d["significant_wave_height"] for d in a]
    assert None in hs and any(h is not None for h in hs)
    last = a[-1]
    irregular, period = sa[-1]
    assert irregular == (last["significant_wave_height"] is not None)
    assert period == (last["peak_period"] if irregular else last["wave_period"])
    with pytest.raises(ValueError, match="choices"):
        DomainRandomization(gym.make("FloatingGOWEC-v0"), choices={"no_such_kwarg": (1, 2)})


def test_shift_scenes_only_use_real_kwargs():
    from mf_envs.train.randomize import nominal_kwargs, shift_scenes, shifted_kwargs

    assert shifted_kwargs("Pendulum-v1", {"g": 1.5, "zz": 2.0}) == {"g": 15.0}
    for env_id in available_env_ids():
        nominal = nominal_kwargs(env_id)
        for kw in shift_scenes(env_id).values():
            assert set(kw) <= set(nominal)


@pytest.mark.parametrize("env_id", available_env_ids())
def test_domain_randomization_on_mf_envs(env_id):
    from mf_envs.train.randomize import DomainRandomization, applicable_ranges, nominal_kwargs

    ranges = applicable_ranges(env_id)
    if not ranges:
        pytest.skip(f"{env_id} has none of the randomisable kwargs")
    env = DomainRandomization(gym.make(env_id))
    nominal = nominal_kwargs(env_id)
    drawn = []
    for seed in (0, None):
        obs, info = env.reset(seed=seed)
        assert env.observation_space.contains(obs)
        for k, v in info["randomized"].items():
            # discrete draws (FloatingGOWEC-v0's sea): checked in their own test
            if k in env.choices:
                assert v in env.choices[k]
                continue
            lo, hi = ranges[k]
            if isinstance(nominal[k], dict):  # one factor on every number of the dict
                factors = [v[c] / nominal[k][c] for c in nominal[k]]
                assert set(v) == set(nominal[k])
                assert max(factors) - min(factors) < 1e-12 * max(factors)
                assert lo * (1 - 1e-12) <= factors[0] <= hi * (1 + 1e-12)
                assert getattr(env.unwrapped, k) == pytest.approx(v)  # the env's resolved dict
                continue
            assert lo * nominal[k] <= v <= hi * nominal[k]
            if not env.choices and isinstance(getattr(env.unwrapped, k, None), float):
                assert getattr(env.unwrapped, k) == pytest.approx(v)  # really simulated
        drawn.append(info["randomized"])
        env.step(env.action_space.sample())
    assert drawn[0] != drawn[1]
