"""`mf-envs sweep`: config expansion and validation, the serial path against a direct episode,
resumption after an interruption, and the one-line message without Ray (no Ray needed here;
the Ray path is in test_sweep_ray.py)."""

from __future__ import annotations

import re
import sys

import gymnasium as gym
import pytest
import yaml

import mf_envs  # noqa: F401
from mf_envs.cli import main
from mf_envs.controllers import make_baseline
from mf_envs.sweep import load_config, parse_config, run_sweep
from mf_envs.sweep import run as sweep_run
from mf_envs.sweep.store import ResultStore
from mf_envs.train.evaluate import run_episode

# 2 controllers x 2 sea states x 2 seeds; 10 s episodes keep each trial short
SMALL = {
    "env_id": "GyroStabilizer-v0",
    "seeds": [0, 1],
    "controllers": ["baseline:pid", "baseline:lqr"],
    "env_kwargs": {"episode_seconds": 12.0},
    "scenes": {"short": {"wave_period": 2.22}, "resonance": {"wave_period": 3.7}},
}


def write(tmp_path, data, name="cfg.yml"):
    p = tmp_path / name
    p.write_text(yaml.safe_dump(data))
    return p


def test_grid_expansion_and_stable_ids():
    data = {**SMALL, "grid": {"wave_moment_amplitude": [4000.0, 8000.0, 12000.0]}}
    cfg = parse_config(data)
    assert len(cfg.trials) == 2 * 3 * 2 * 2
    ids = [t.trial_id for t in cfg.trials]
    assert len(set(ids)) == len(ids)
    assert ids == [t.trial_id for t in parse_config(data).trials]  # same params -> same ids
    t = cfg.trials[0]
    assert t.kwargs == {
        "episode_seconds": 12.0,
        "wave_period": 2.22,
        "wave_moment_amplitude": 4000.0,
    }
    assert cfg.axes == ("wave_moment_amplitude",)


def test_random_mode_is_seeded_and_in_bounds():
    data = {
        **SMALL,
        "mode": "random",
        "samples": 7,
        "random": {"wave_period": {"low": 2.0, "high": 6.0}, "wave_moment_amplitude":
                   {"low": 1e3, "high": 1e4, "log": True}},
    }  # fmt: skip
    a, b = parse_config(data), parse_config(data)
    assert [t.trial_id for t in a.trials] == [t.trial_id for t in b.trials]
    periods = {t.point["wave_period"] for t in a.trials}
    assert len(periods) == 7 and all(2.0 <= p <= 6.0 for p in periods)
    other = parse_config({**data, "sampler_seed": 1})
    assert {t.point["wave_period"] for t in other.trials} != periods


@pytest.mark.parametrize(
    "change, key",
    [
        ({"sede": [0]}, "sede"),
        ({"seeds": "0"}, "seeds"),
        ({"seeds": [0, 0]}, "seeds"),
        ({"controllers": ["baseline:nope"]}, "controllers[0]"),
        ({"controllers": ["magic"]}, "controllers[0]"),
        ({"env_id": "Nope-v0"}, "env_id"),
        ({"grid": {"wave_period": 3.0}}, "grid.wave_period"),
        ({"mode": "bayes"}, "mode"),
        ({"mode": "random", "random": {"wave_period": {"low": 1.0}}}, "samples"),
        ({"plot": {"x": "wave_period", "y": "seed"}}, "plot.x"),
    ],
)
def test_bad_config_names_the_key(change, key):
    with pytest.raises(ValueError, match="config: " + re.escape(key)):
        parse_config({**SMALL, **change})


def test_cli_bad_config_one_line_exit_2(tmp_path, capsys):
    path = write(tmp_path, {**SMALL, "seeds": "zero"})
    assert main(["sweep", str(path), "--serial", "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "seeds" in err
    assert main(["sweep", str(tmp_path / "missing.yml"), "--serial"]) == 2


def test_bad_env_kwarg_fails_before_any_trial(tmp_path):
    cfg = parse_config({**SMALL, "env_kwargs": {"wave_periodd": 3.0}})
    with pytest.raises(ValueError, match="wave_periodd"):
        run_sweep(cfg, tmp_path, serial=True, progress=False)
    assert not (tmp_path / "trials.csv").exists()


def test_serial_rows_equal_a_direct_episode(tmp_path):
    cfg = parse_config(SMALL)
    path, n = run_sweep(cfg, tmp_path, serial=True, progress=False)
    rows = ResultStore(path).rows()
    assert n == len(rows) == len(cfg.trials) == 8
    # second path: the same episode run by hand with the public API
    env = gym.make("GyroStabilizer-v0", episode_seconds=12.0, wave_period=3.7)
    ref = run_episode("GyroStabilizer-v0", env, make_baseline(env, "lqr"), 1)
    row = next(r for r in rows if r["scene"] == "resonance" and r["controller"] == "baseline:lqr"
               and r["seed"] == 1)  # fmt: skip
    assert row["rms_roll"] == ref["rms_roll"] and row["return"] == ref["return"]
    assert row["steps"] == 240 and row["wall_s"] > 0


def test_interrupted_sweep_reruns_only_unfinished_trials(tmp_path, monkeypatch):
    cfg = parse_config(SMALL)
    real = sweep_run.run_trial
    calls: list[str] = []

    def interrupting(trial):
        if len(calls) == 3:
            raise KeyboardInterrupt  # Ctrl-C during the 4th trial
        calls.append(trial.trial_id)
        return real(trial)

    monkeypatch.setattr(sweep_run, "run_trial", interrupting)
    with pytest.raises(KeyboardInterrupt):
        run_sweep(cfg, tmp_path / "a", serial=True, progress=False)
    store = ResultStore(tmp_path / "a" / "trials.csv")
    assert store.done_ids() == set(calls)
    # a torn last line (killed mid-write) is dropped and its trial re-run
    with open(store.path, "a") as fh:
        fh.write("deadbeefdeadbeef,GyroStabilizer-v0,sho")

    rerun: list[str] = []

    def counting(trial):
        rerun.append(trial.trial_id)
        return real(trial)

    monkeypatch.setattr(sweep_run, "run_trial", counting)
    _, n = run_sweep(cfg, tmp_path / "a", serial=True, progress=False)
    all_ids = [t.trial_id for t in cfg.trials]
    assert n == len(rerun) == len(all_ids) - 3
    assert set(rerun) == set(all_ids) - set(calls)
    # the resumed CSV holds the same numbers as an uninterrupted run
    monkeypatch.setattr(sweep_run, "run_trial", real)
    fresh_path, _ = run_sweep(cfg, tmp_path / "b", serial=True, progress=False)
    resumed = ResultStore(tmp_path / "a" / "trials.csv").by_id()
    assert resumed == ResultStore(fresh_path).by_id()
    _, n_again = run_sweep(cfg, tmp_path / "a", serial=True, progress=False)
    assert n_again == 0


def test_cli_serial_writes_csv_and_picture(tmp_path, capsys):
    path = write(tmp_path, SMALL)
    assert main(["sweep", str(path), "--serial", "--no-progress", "--out", str(tmp_path)]) == 0
    assert (tmp_path / "trials.csv").is_file()
    assert (tmp_path / "cfg_rms_roll.png").stat().st_size > 10_000


def test_shipped_configs_parse():
    from mf_envs.sweep.cli import CONFIG_DIR

    names = sorted(CONFIG_DIR.glob("*.yml"))
    assert len(names) >= 2
    for p in names:
        assert load_config(p).trials


@pytest.mark.parametrize(
    "argv",
    [["sweep", "stabilizer_table"], ["train", "GyroStabilizer-v0", "--backend", "rllib"]],
)
def test_without_ray_one_line_naming_the_extra(argv, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "ray", None)  # import ray -> ImportError
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and 'pip install "mf-envs[ray]"' in err


def test_shipped_ppo_policy_as_a_controller(tmp_path):
    for module in ("stable_baselines3", "safetensors"):
        pytest.importorskip(module, reason="needs the train extra: pip install -e '.[train]'")
    from mf_envs.train import load_policy

    data = {"env_id": "GOWEC-v0", "seeds": [3], "controllers": ["ppo"],
            "env_kwargs": {"n_periods": 3}, "scenes": {"s": {"wave_period": 6.5}}}  # fmt: skip
    path, _ = run_sweep(parse_config(data), tmp_path, serial=True, progress=False)
    (row,) = ResultStore(path).rows()
    env = gym.make("GOWEC-v0", n_periods=3, wave_period=6.5)
    ref = run_episode("GOWEC-v0", env, load_policy("GOWEC-v0"), 3)
    assert row["controller"] == "ppo" and row["power_ratio"] == ref["power_ratio"]
