"""The soft robots' best-known gaits (`benchmarks.gait_search`) and the gait families' new
parameters.

Independent truth: a time shift (a heat wave delays group j by exactly j lag periods), the
envelope's closed form at the head and the tail, the families' start reproducing the default
baselines' scores, and the search's own bookkeeping (its best is re-scored to the same value,
never below its start, inside its bounds)."""

from __future__ import annotations

import json

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the ids)
from mf_envs.benchmarks import gait_search as gs
from mf_envs.benchmarks import rl_tasks
from mf_envs.controllers import baseline_kinds
from mf_envs.controllers.serpentine import Serpenoid
from mf_envs.physics.inchworm.open_loop import heat_cool_gait


def test_heat_wave_delays_each_group_by_its_lag():
    t_heat, t_cool, lag = 1.3, 0.9, 0.25
    period = t_heat + t_cool
    fn, together = (
        heat_cool_gait(t_heat, t_cool, 4, 0.1, lag),
        heat_cool_gait(t_heat, t_cool, 4, 0.1),
    )
    for t in np.linspace(0.01, 3 * period, 97):
        d = fn(t)
        for j in range(4):
            assert d[j] == together(t - j * lag * period)[0]
    assert set(np.unique([fn(t) for t in np.linspace(0, period, 50)])) <= {0.1, 1.0}


def test_serpenoid_envelope_grows_from_head_ratio_to_one():
    env = gym.make("Serpentine-v0")
    env.reset(seed=0)
    r = 0.4
    ctrl = Serpenoid(env, amplitude=10.0, wavelength=1.0, period=2.0, head_ratio=r)
    assert ctrl.envelope[0] == pytest.approx(1.0)  # S = 0: the tail
    assert ctrl.envelope[-1] == pytest.approx(r)  # S = L: the head
    uniform = Serpenoid(env, amplitude=10.0, wavelength=1.0, period=2.0)
    assert np.all(uniform.envelope == 1.0)
    a, b = ctrl.predict(None)[0], uniform.predict(None)[0]
    np.testing.assert_allclose(a, b * ctrl.envelope, rtol=1e-6, atol=1e-7)
    with pytest.raises(ValueError, match="head_ratio"):
        Serpenoid(env, head_ratio=1.5)


def test_serpenoid_wavenumber_standing_and_reversed_waves():
    """q = L / lambda: 1 / wavelength to round-off; q = 0 every control point in phase (a
    standing wave); -q the wave mirrored along the body (it runs tail to head)."""
    env = gym.make("Serpentine-v0")
    env.reset(seed=0)
    kw = dict(amplitude=10.0, period=0.7)
    by_q = Serpenoid(env, wavenumber=1 / 1.3, **kw)
    np.testing.assert_allclose(by_q.phase, Serpenoid(env, wavelength=1.3, **kw).phase, rtol=1e-15)
    standing, fwd, back = (Serpenoid(env, wavenumber=q, **kw) for q in (0.0, 0.4, -0.4))
    for _ in range(9):
        a = standing.predict(None)[0]
        assert np.all(a == a[0])
        t = fwd.k * fwd.dt + fwd.dt
        f, b = fwd.predict(None)[0], back.predict(None)[0]
        s = np.linspace(0.0, 1.0, len(f))
        np.testing.assert_allclose(
            f, 0.4 * np.sin(0.8 * np.pi * (1 - s) - 2 * np.pi * t / 0.7), atol=1e-6
        )
        np.testing.assert_allclose(
            b, 0.4 * np.sin(-0.8 * np.pi * (1 - s) - 2 * np.pi * t / 0.7), atol=1e-6
        )
    with pytest.raises(ValueError, match="wavenumber"):
        Serpenoid(env, wavenumber=float("nan"))


@pytest.mark.parametrize("env_id", sorted(gs.families()))
def test_family_starts_lie_in_the_search_box(env_id):
    """CMA-ES starts from a start's point in the unit box: every start names every parameter of
    the family within its range (the serpentine's second start, PPO_LIKE, included)."""
    fam = gs.families()[env_id]
    for start in (fam.start, *fam.other_starts):
        assert set(start) == set(fam.space)
        for name, (lo, hi) in fam.space.items():
            assert lo <= start[name] <= hi, name


@pytest.mark.parametrize("env_id", sorted(gs.families()))
def test_family_start_is_the_default_baseline(env_id):
    task = rl_tasks.TASKS[rl_tasks.HEADLINE[env_id]]()
    default = baseline_kinds(env_id)[0]
    base, _ = rl_tasks.test_episodes(task, default, seeds=(3,))
    assert gs.mean_score(env_id, gs.families()[env_id].start, (3,)) == pytest.approx(
        float(base[0]), rel=1e-9, abs=1e-12
    )


@pytest.mark.slow
def test_search_referees_its_finalists_and_rescores_its_choice():
    pytest.importorskip("cma", reason="the train extra")
    res = gs.search("Eel-v0", budget=9, seeds=(1,))
    fam = gs.families()["Eel-v0"]
    for name, (lo, hi) in fam.space.items():
        assert lo <= res["params"][name] <= hi
    trains = [f["train"] for f in res["finalists"]]  # the best on training, then the start
    assert trains[: gs.FINALISTS] == sorted(trains[: gs.FINALISTS], reverse=True)
    assert res["start_score"] in trains and res["train_score"] in trains
    assert res["validation_score"] == max(f["validation"] for f in res["finalists"])
    assert gs.mean_score("Eel-v0", res["params"], (1,)) == pytest.approx(res["train_score"])
    assert gs.mean_score("Eel-v0", res["params"], gs.VALIDATION_SEEDS) == pytest.approx(
        res["validation_score"]
    )


@pytest.mark.parametrize("env_id", sorted(gs.BEST))
def test_stored_best_gait_reproduces_and_is_refereed(env_id):
    """The stored gait scores what the search recorded on the training and the validation
    conditions, and on the validation conditions at least what the default baseline does."""
    best = gs.BEST[env_id]
    fam = gs.families()[env_id]
    params = {k: v for k, v in best.items() if k in fam.space}
    assert gs.mean_score(env_id, params, gs.TUNE_SEEDS) == pytest.approx(best["train_score"])
    valid = gs.mean_score(env_id, params, gs.VALIDATION_SEEDS)
    assert valid == pytest.approx(best["validation_score"])
    assert valid >= gs.mean_score(env_id, fam.start, gs.VALIDATION_SEEDS) - 1e-12


def test_references_copy_keeps_the_ids_it_was_not_given(tmp_path):
    """The references' results file gains the soft robots' rows without losing the marine ids'
    (scored in another folder, on other test seeds)."""
    from mf_envs.benchmarks import references, rl_results

    def records(out, env_id, seeds, kinds):
        for kind, name, score in kinds:
            rl_results.write_record(out, {"env_id": env_id, "kind": kind, "name": name,
                                          "seed": None, "budget": None, "score_name": "s",
                                          "test_seeds": list(seeds),
                                          "scores": [score] * len(seeds)})  # fmt: skip

    marine = [("zero", "zero", 0.0), ("baseline", "lqr", 0.8), ("reference", "oracle", 0.9)]
    soft = [("zero", "zero", 0.0), ("baseline", "heading", 0.05), ("reference", "best_gait", 0.06)]
    records(tmp_path / "a", "GyroStabilizer-JONSWAP-v0", (1, 2), marine)
    records(tmp_path / "b", "Eel-v0", (3, 4, 5), soft)
    dest = tmp_path / "refs.json"
    references.copy_results(tmp_path / "a", dest)
    references.copy_results(tmp_path / "b", dest)
    got = json.loads(dest.read_text())
    assert sorted(got["ids"]) == ["Eel-v0", "GyroStabilizer-JONSWAP-v0"]
    assert got["ids"]["GyroStabilizer-JONSWAP-v0"]["headroom"] == pytest.approx(0.1)
    names = {(r["env_id"], r["name"]) for r in got["rows"]}
    assert ("GyroStabilizer-JONSWAP-v0", "oracle") in names and ("Eel-v0", "best_gait") in names
    eel = next(r for r in got["rows"] if r["name"] == "best_gait")
    assert eel["normalised"] == pytest.approx(1.2)  # (0.06 - 0) / (0.05 - 0)
    references.copy_results(tmp_path / "b", dest)  # again: the Eel rows replaced, not doubled
    assert len(json.loads(dest.read_text())["rows"]) == len(got["rows"])
