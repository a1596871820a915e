"""The RL benchmark's protocol pieces: the interval estimate, the configs it trains
from, and its episode score against the stabilizer grid's own episode (a second formulation)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.stats import trim_mean

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


def test_one_task_bootstrap_matches_scipys_percentile_bootstrap():
    """With one task the stratified bootstrap is the ordinary one: its 95 % percentile interval
    of the IQM agrees with scipy.stats.bootstrap's (an independent implementation) to within
    the Monte Carlo error of 20,000 resamples each."""
    from scipy.stats import bootstrap

    runs = np.random.default_rng(3).normal(0.8, 0.1, 24)
    ours = rb.interval(runs, reps=20000, seed=1)
    ref = bootstrap((runs,), lambda x, axis: trim_mean(x, 0.25, axis=axis), n_resamples=20000,
                    method="percentile", random_state=2).confidence_interval  # fmt: skip
    width = ref.high - ref.low
    assert abs(ours["lo"] - ref.low) < 0.05 * width
    assert abs(ours["hi"] - ref.high) < 0.05 * width


def test_stratified_bootstrap_draws_each_task_on_its_own():
    """Two tasks on different scales: a stratified resample keeps each task's runs in its own
    column, so every bootstrap IQM lies between the two tasks' IQMs' extremes, and the interval
    is narrower than a pooled (unstratified) bootstrap whose samples can hold one task only."""
    rng = np.random.default_rng(0)
    m = np.column_stack([rng.normal(0.2, 0.01, 5), rng.normal(0.9, 0.01, 5)])
    out = rb.interval(m, reps=4000)
    assert out["n"] == 5 and out["iqm"] == pytest.approx(trim_mean(m.ravel(), 0.25), rel=1e-12)
    pooled = trim_mean(rng.choice(m.ravel(), size=(4000, 10)), 0.25, axis=1)
    assert out["hi"] - out["lo"] < 0.5 * (np.percentile(pooled, 97.5) - np.percentile(pooled, 2.5))


@pytest.mark.parametrize("algo", ["ppo", "sac", "td3"])
def test_configs_carry_the_task_scene_and_budget(tmp_path, algo):
    from mf_envs.train.config import load_hyperparams

    task = rb.TASKS["stabilizer_irregular"]()
    hp = load_hyperparams(task.env_id, rb.write_config(task, algo, 12345, tmp_path))
    assert hp.n_timesteps == 12345
    kw = {k: (tuple(v) if isinstance(v, list) else v) for k, v in hp.env_kwargs.items()}
    assert kw == task.env_kwargs
    assert (tmp_path / f"{algo}-12345.yml").parent == tmp_path  # written inside the folder given


def test_episode_score_equals_the_grid_benchs_roll_reduction():
    """1 - rms_on / rms_off of the LQR on two test seeds, 30 s episodes, against
    `stabilizer_grid._episode` (its own loop) on the same cell and seeds."""
    from mf_envs.benchmarks import stabilizer_grid as grid

    seeds = (20_000, 20_001)
    task = rb.TASKS["stabilizer_irregular"]()
    task = rb.Task(**{**task.__dict__, "eval_seconds": 30.0})
    scores = rb.episode_scores(task, "lqr", seeds=seeds)
    for s, score in zip(seeds, scores):
        on = grid._episode(task.env_kwargs, "lqr", s, 30.0)["rms_roll"]
        off = grid._episode(task.env_kwargs, None, s, 30.0)["rms_roll"]
        assert score == pytest.approx(1.0 - on / off, rel=1e-12)
        assert 0.0 < score < 1.0 and math.isfinite(score)


# ------------------------------------------------------------ the grid, its records and docs
def test_smoke_grid_writes_records_resumes_and_generates_docs(tmp_path):
    """`mf-envs bench rl` at a tiny budget scale on one id: a record per controller and per run,
    the results file on the normalised scale (zero action 0, best baseline 1), the docs block
    and both figures; a second run recomputes nothing (the records are untouched)."""
    from mf_envs.benchmarks import rl_results as res
    from mf_envs.cli import main

    out, docs = tmp_path / "b", tmp_path / "docs" / "benchmark.md"
    docs.parent.mkdir()
    docs.write_text("# Benchmark\n\nhand-written text stays\n")
    argv = ["bench", "rl", "--ids", "GyroStabilizer-JONSWAP-v0", "--algos", "ppo", "--seeds",
            "3", "--budget-scale", "1e-4", "--test-seeds", "1", "--out", str(out),
            "--docs", str(docs)]  # fmt: skip
    assert main(argv) == 0
    result = json.loads((out / "results.json").read_text())
    assert result["schema"] == res.SCHEMA and result["budget_scale"] == 1e-4
    a = result["ids"]["GyroStabilizer-JONSWAP-v0"]
    rows = {(r["name"], r["budget"]): r for r in result["rows"]}
    assert rows[("zero", None)]["normalised"] == pytest.approx(0.0, abs=1e-12)
    assert rows[(a["best_baseline"], None)]["normalised"] == pytest.approx(1.0, rel=1e-12)
    ppo = rows[("ppo", 100)]  # 1M x 1e-4: the budget trained
    assert ppo["kind"] == "learner" and ppo["seed"] == 3 and ppo["test_seeds"] == [20_000]
    assert ppo["env_steps"] >= 100 and ppo["wall_s"] > 0 and ("ppo", 1000) in rows
    text = docs.read_text()
    assert (
        "hand-written text stays" in text and res.BEGIN in text and "rl_benchmark_steps.png" in text
    )
    assert (docs.parent / "img" / "rl_benchmark_wallclock.png").is_file()
    copy = json.loads((docs.parent / "results" / "rl_benchmark.json").read_text())
    assert copy["ids"].keys() == result["ids"].keys() and len(copy["rows"]) == len(result["rows"])
    assert "Reduced budgets" in text
    records = sorted((out / "records").rglob("*.json"))
    stamps = [p.stat().st_mtime_ns for p in records]
    assert main(argv) == 0
    assert [p.stat().st_mtime_ns for p in records] == stamps


def test_records_refuse_a_link_out_of_the_folder(tmp_path):
    """A record folder planted as a link to a folder outside --out is refused (ValueError
    naming out), and nothing is written through it."""
    from mf_envs.benchmarks import rl_results as res

    outside = tmp_path / "elsewhere"
    outside.mkdir()
    (tmp_path / "b" / "records").mkdir(parents=True)
    (tmp_path / "b" / "records" / "Eel-v0").symlink_to(outside)
    rec = {
        "env_id": "Eel-v0",
        "kind": "zero",
        "name": "zero",
        "seed": None,
        "budget": None,
        "score_name": "speed_m_s",
        "test_seeds": [1],
        "scores": [0.0],
        "returns": [0.0],
    }
    with pytest.raises(ValueError, match="out"):
        res.write_record(tmp_path / "b", rec)
    assert not any(outside.iterdir())


@pytest.mark.parametrize("env_id", ["Inchworm-v0", "Serpentine-v0", "Eel-v0"])
def test_soft_robot_test_conditions_draw_the_declared_ranges(env_id):
    """A soft robot's test seeds draw its scene: each kwarg of the declared randomisation is a
    factor in its (lo, hi) range of the nominal value, and two seeds draw different scenes."""
    from mf_envs.benchmarks.rl_tasks import HEADLINE, test_kwargs
    from mf_envs.train.randomize import Randomizer, default_ranges

    task = rb.TASKS[HEADLINE[env_id]]()
    nominal = Randomizer(env_id, {}).nominal
    a, b = test_kwargs(task, 20_000), test_kwargs(task, 20_001)
    for name, (lo, hi) in default_ranges(env_id).items():
        x, n = a[name], nominal[name]
        f = next(iter(x.values())) / next(iter(n.values())) if isinstance(x, dict) else x / n
        assert lo <= f <= hi, (name, f)
        assert a[name] != b[name]


def test_rank_agreement_is_spearmans_rho_of_mean_return_and_score():
    """Four controllers whose mean returns rank them as their mean scores do give rho 1; with
    one pair swapped, scipy's rho of the means (the points the tool reports)."""
    from scipy.stats import spearmanr

    from mf_envs.benchmarks.rl_diagnostics import rank_agreement

    def row(name, ret, sc, seed=None):
        budget = None if seed is None else 10
        return {"env_id": "Eel-v0", "name": name, "seed": seed, "budget": budget,
                "returns": [ret, ret + 1.0], "scores": [sc, sc]}  # fmt: skip

    rows = [row("zero", -1.0, 0.0), row("a", 2.0, 0.1), row("b", 5.0, 0.3), row("ppo", 9.0, 0.2, 0)]
    d = rank_agreement({"ids": {"Eel-v0": {}}, "rows": rows})["Eel-v0"]
    assert d["n"] == 4 and d["points"][3]["controller"] == "ppo-1e+01-seed0"
    assert d["spearman"] == pytest.approx(spearmanr([-0.5, 2.5, 5.5, 9.5], [0, 0.1, 0.3, 0.2])[0])
    rows[3]["scores"] = [0.4, 0.4]
    assert rank_agreement({"ids": {"Eel-v0": {}}, "rows": rows})["Eel-v0"]["spearman"] == 1.0


def test_rank_agreement_ties_speeds_closer_than_their_resolution():
    """Two controllers that do not move (speeds 2e-9 and 5e-7 m/s, below the 1 um/s
    resolution) tie: their returns' order no longer counts, and rho is scipy's with the tie
    (average ranks); the unrounded rho stays reported."""
    from scipy.stats import spearmanr

    from mf_envs.benchmarks.rl_diagnostics import SCORE_RESOLUTION, rank_agreement

    assert SCORE_RESOLUTION["speed_m_s"] == 1e-6
    rows = [{"env_id": "Inchworm-v0", "name": n, "seed": None, "budget": None,
             "returns": [r], "scores": [s]}
            for n, r, s in (("zero", -0.10, 2e-9), ("random", -0.11, 5e-7),
                            ("gait", 2.0, 4e-3), ("tuned", 3.0, 5e-3))]  # fmt: skip
    d = rank_agreement({"ids": {"Inchworm-v0": {"score_name": "speed_m_s"}}, "rows": rows})
    d = d["Inchworm-v0"]
    assert d["spearman"] == pytest.approx(spearmanr([-0.10, -0.11, 2, 3], [0, 0, 4e-3, 5e-3])[0])
    assert d["spearman_raw"] == pytest.approx(0.8)  # the swapped pair below resolution
    assert d["spearman"] > d["spearman_raw"]


def test_the_grid_covers_every_headline_id_with_its_budgets():
    """`--all` runs every registered headline id: PPO at 1M and 10M and SBX's SAC at 1M on the
    marine ids, PPO at 1M on the soft robots, five training seeds."""
    from mf_envs.envs import task_ids

    assert sorted(rb.HEADLINE) == sorted(task_ids(role="headline"))
    grid = rb.cells(list(rb.HEADLINE.values()), ["ppo", "sbx_sac"], rb.TRAIN_SEEDS)
    per = {}
    for task, algo, budget, _ in grid:
        per.setdefault((task.env_id, algo), set()).add(budget)
    assert per[("GyroStabilizer-JONSWAP-v0", "ppo")] == {1_000_000, 10_000_000}
    assert per[("FloatingGOWEC-JONSWAP-v0", "sbx_sac")] == {1_000_000}
    assert per[("Eel-v0", "ppo")] == {1_000_000} and ("Eel-v0", "sbx_sac") not in per
    assert len(grid) == 5 * (2 * 3 + 3 * 1) and len(rb.TRAIN_SEEDS) == 5


def test_the_oracle_reference_sets_the_headroom(tmp_path):
    """A reference record named "oracle" enters the results on the normalised scale and its
    id's headroom is oracle - best baseline, stated in the generated block beside the ceiling."""
    from mf_envs.benchmarks import rl_results as res

    env_id = "GyroStabilizer-JONSWAP-v0"
    base = {
        "env_id": env_id,
        "seed": None,
        "budget": None,
        "score_name": "rms_roll_reduction",
        "test_seeds": [1, 2],
        "returns": [0.0, 0.0],
    }
    for kind, name, scores in (("zero", "zero", [0.0, 0.0]), ("baseline", "lqr", [0.8, 0.9]),
                               ("baseline", "pid", [0.7, 0.7]),
                               ("reference", "oracle", [0.9, 1.0])):  # fmt: skip
        res.write_record(tmp_path, {**base, "kind": kind, "name": name, "scores": scores})
    result = res.collect(tmp_path)
    a = result["ids"][env_id]
    assert a["best_baseline"] == "lqr" and a["oracle"] == pytest.approx(0.95)
    assert a["headroom"] == pytest.approx(0.95 - 0.85)
    (oracle,) = [r for r in result["rows"] if r["name"] == "oracle"]
    assert oracle["normalised"] == pytest.approx(0.95 / 0.85)
    block = res.markdown(result, "r.json", [])
    assert "headroom = oracle - best baseline = 0.1" in block and "ceiling 1" in block
