"""The evaluation loop (train/evaluate.py): `evaluate_controllers` against hand-rolled episodes,
every env's metrics read from its info, and the metrics' definitions.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the env ids)
from mf_envs.envs import available_env_ids, declaration
from mf_envs.train.evaluate import episode_metrics, evaluate_controllers, run_episode


class _Zero:
    def reset(self):
        pass

    def predict(self, obs, deterministic=True):
        return np.zeros(1, np.float32), None


def test_evaluation_loop_matches_hand_rolled_episodes():
    rows = evaluate_controllers("Pendulum-v1", {"zero": lambda env: _Zero()}, seeds=[5, 6])
    returns = []
    for s in (5, 6):
        env = gym.make("Pendulum-v1")
        env.reset(seed=s)
        total, done = 0.0, False
        while not done:
            _, r, term, trunc, _ = env.step(np.zeros(1, np.float32))
            total += r
            done = term or trunc
        returns.append(total)
    got = {r["metric"]: r for r in rows}
    assert got["return"]["mean"] == pytest.approx(np.mean(returns))
    assert got["return"]["std"] == pytest.approx(np.std(returns, ddof=1))
    assert got["steps"]["mean"] == 200 and got["return"]["n_seeds"] == 2


@pytest.mark.parametrize("env_id", available_env_ids())
def test_env_metrics_from_info(env_id):
    env = gym.make(env_id)
    m = run_episode(env_id, env, _ZeroFor(env), seed=0)
    key = declaration(env_id).metric.name  # the env's primary metric, computed from its infos
    assert np.isfinite(m[key])
    if env_id == "GyroStabilizer-v0":
        assert m["rms_roll"] <= m["max_abs_roll"]


class _ZeroFor(_Zero):
    def __init__(self, env):
        self.shape = env.action_space.shape

    def predict(self, obs, deterministic=True):
        return np.zeros(self.shape, np.float32), None


def test_episode_metrics_definitions():
    class _Env:
        class unwrapped:  # noqa: N801
            @staticmethod
            def analytic_max_power():
                return 4.0

    infos = [
        {"x_tail": 1.0},
        {"power": 1.0, "roll": 0.3, "x_tail": 1.5, "time": 10.0},
        {"power": 3.0, "roll": -0.4, "x_tail": 2.0, "time": 10.05},
    ]
    g = episode_metrics("GOWEC-v0", _Env, [1.0, 2.0], infos)
    assert g["power_ratio_all"] == pytest.approx(0.5) and g["return"] == 3.0
    g = episode_metrics("GOWEC-v0", _Env, [0] * 4, [{}] + [{"power": p} for p in (0, 4, 4, 4)])
    assert g["power_ratio"] == pytest.approx(1.0)  # steady part: the last 3/4 of the steps
    assert g["power_ratio_all"] == pytest.approx(0.75)
    s = episode_metrics("GyroStabilizer-v0", _Env, [0, 0], infos)
    assert s["rms_roll_all"] == pytest.approx(np.sqrt((0.09 + 0.16) / 2))
    assert s["rms_roll"] == pytest.approx(0.4)  # only after the 10 s transient
    i = episode_metrics("Inchworm-v0", _Env, [0, 0], infos)
    assert i["tail_advance_per_step"] == pytest.approx(0.5)
    anchors = ["head", "head", "tail", "tail", "head", "tail", "head"]  # 2 head->tail switches
    infos = [{"x_tail": 0.1 * k, "anchor": a} for k, a in enumerate(anchors)]
    i = episode_metrics("Inchworm-v0", _Env, [0] * 6, infos)
    assert i["gait_cycles"] == 2 and i["tail_advance_per_cycle"] == pytest.approx(0.3)
