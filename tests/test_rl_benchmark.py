"""The RL benchmark's protocol pieces (issue 32): the interval estimate, the configs it trains
from, and its episode score against the stabilizer grid's own episode (a second formulation)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import trim_mean

pytest.importorskip("rliable", reason="needs the train extra (rliable)")
pytest.importorskip("stable_baselines3", reason="needs the train extra")

from mf_envs.benchmarks import rl_benchmark as rb  # noqa: E402


def test_interval_is_the_interquartile_mean_and_covers_it():
    runs = np.array([0.91, 0.62, 0.80, 0.85, 0.77, 0.70, 0.88, 0.95])
    out = rb.interval(runs, reps=500)
    assert out["iqm"] == pytest.approx(trim_mean(runs, 0.25), rel=1e-12)
    assert out["lo"] <= out["iqm"] <= out["hi"]
    assert out["mean"] == pytest.approx(runs.mean()) and out["n"] == runs.size
    # with three runs the IQM trims nothing: the mean
    assert rb.interval(runs[:3], reps=200)["iqm"] == pytest.approx(runs[:3].mean(), rel=1e-12)
    # deterministic for a given bootstrap seed
    assert rb.interval(runs, reps=300, seed=4) == rb.interval(runs, reps=300, seed=4)


@pytest.mark.parametrize("algo", rb.ALGOS)
def test_configs_carry_the_task_scene_and_budget(tmp_path, algo):
    from mf_envs.train.config import load_hyperparams

    task = rb.TASKS["stabilizer_irregular"]()
    hp = load_hyperparams(task.env_id, rb.write_config(task, algo, tmp_path))
    assert hp.n_timesteps == task.budgets[algo]
    kw = {k: (tuple(v) if isinstance(v, list) else v) for k, v in hp.env_kwargs.items()}
    assert kw == task.env_kwargs
    assert (tmp_path / f"{algo}.yml").parent == tmp_path  # written inside the folder given


def test_episode_score_equals_the_grid_benchs_roll_reduction(monkeypatch):
    """1 - rms_on / rms_off of the LQR on two test seeds, 30 s episodes, against
    `stabilizer_grid._episode` (its own loop) on the same cell and seeds."""
    from mf_envs.benchmarks import stabilizer_grid as grid

    monkeypatch.setattr(rb, "TEST_SEEDS", (20_000, 20_001))
    task = rb.TASKS["stabilizer_irregular"]()
    task = rb.Task(**{**task.__dict__, "eval_seconds": 30.0})
    scores = rb.episode_scores(task, "lqr")
    for s, score in zip(rb.TEST_SEEDS, scores):
        on = grid._episode(task.env_kwargs, "lqr", s, 30.0)["rms_roll"]
        off = grid._episode(task.env_kwargs, None, s, 30.0)["rms_roll"]
        assert score == pytest.approx(1.0 - on / off, rel=1e-12)
        assert 0.0 < score < 1.0 and math.isfinite(score)
