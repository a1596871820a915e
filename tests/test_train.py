"""PPO training infrastructure (train/): configs, the vector-env adapter, smoke runs, the CLI
error paths and reproducibility (the policy format: test_policy_files.py; the evaluation loop:
test_evaluate_loop.py; domain randomisation: test_domain_randomization.py).

Truth used: Gymnasium's `SyncVectorEnv` + SB3's `DummyVecEnv` on the same seeds (for the
native-vector adapter), rl-zoo3 running the shipped configs unchanged.
"""

from __future__ import annotations

import json
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

sb3 = pytest.importorskip(
    "stable_baselines3", reason="needs the train extra: pip install -e '.[train]'"
)
pytest.importorskip("safetensors", reason="needs the train extra: pip install -e '.[train]'")

import mf_envs  # noqa: E402,F401  (registers the env ids)
from mf_envs.envs import ENV_SPECS, available_env_ids  # noqa: E402
from mf_envs.train.config import (  # noqa: E402
    load_hyperparams,
    parse_policy_kwargs,
    read_config,
    resolve_schedules,
)
from mf_envs.train.evaluate import evaluate_controllers  # noqa: E402
from mf_envs.train.policy import load_policy  # noqa: E402

TINY = {"n_steps": 64, "batch_size": 64, "n_epochs": 1, "policy_kwargs": {"net_arch": [8]}}
SMOKE_IDS = ["Pendulum-v1", *available_env_ids()]


# --------------------------------------------------------------------------- configs
@pytest.mark.parametrize("env_id", ["Pendulum-v1", *ENV_SPECS])
def test_config_parses_for_every_env(env_id):
    import inspect

    from stable_baselines3 import PPO

    from mf_envs.envs import task_ids

    hp = load_hyperparams(env_id)
    assert hp.n_timesteps is not None and hp.n_timesteps > 0 and 1 <= hp.n_envs <= 1024
    if env_id in task_ids(role="headline"):  # the headline ids train on native rows
        assert hp.n_envs >= 64
    kwargs = resolve_schedules(hp.ppo_kwargs)
    accepted = set(inspect.signature(PPO.__init__).parameters)
    assert set(kwargs) <= accepted, set(kwargs) - accepted
    if callable(kwargs.get("learning_rate")):
        assert kwargs["learning_rate"](1.0) > kwargs["learning_rate"](0.5) > 0


def test_config_errors(tmp_path):
    bad = tmp_path / "bad.yml"
    bad.write_text("Pendulum-v1:\n  n_timesteps: 10\n  frame_stack: 4\n")
    with pytest.raises(ValueError, match="frame_stack"):
        load_hyperparams("Pendulum-v1", bad)
    with pytest.raises(ValueError, match="no entry"):
        load_hyperparams("Nope-v0")
    with pytest.raises(ValueError, match="no such file"):
        read_config(tmp_path / "missing.yml")
    with pytest.raises(ValueError, match="not allowed"):
        parse_policy_kwargs("dict(activation_fn=nn.__class__)")
    pk = parse_policy_kwargs("dict(net_arch=[8], activation_fn=nn.Tanh)")
    assert pk["net_arch"] == [8] and pk["activation_fn"].__name__ == "Tanh"


def test_config_typo_is_one_line_naming_the_key(tmp_path, capsys):
    from mf_envs.cli import main

    cfg = tmp_path / "typo.yml"
    cfg.write_text("GOWEC-v0:\n  n_timesteps: 64\n  learning_rat: 0.001\n")
    before = sorted(tmp_path.rglob("*"))
    assert main(["train", "GOWEC-v0", "--config", str(cfg), "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "'learning_rat'" in err[0] and "'learning_rate'" in err[0], err
    assert sorted(tmp_path.rglob("*")) == before  # refused before any folder is made
    cfg.write_text("GOWEC-v0:\n  n_timesteps: 64\n  eval_episodes: 2\n")
    with pytest.raises(ValueError, match="--eval-episodes"):
        load_hyperparams("GOWEC-v0", cfg)
    cfg.write_text("GOWEC-v0:\n  n_timesteps: lots\n")
    with pytest.raises(ValueError, match="n_timesteps"):
        load_hyperparams("GOWEC-v0", cfg)


def test_timesteps_option_replaces_a_missing_n_timesteps(tmp_path):
    from mf_envs.train.trainer import train

    cfg = tmp_path / "c.yml"
    cfg.write_text("GOWEC-v0:\n  n_envs: 1\n")
    assert load_hyperparams("GOWEC-v0", cfg).n_timesteps is None
    with pytest.raises(ValueError, match="--timesteps"):
        train("GOWEC-v0", config=cfg, out=tmp_path / "a", progress_bar=False)
    res = train(
        "GOWEC-v0",
        timesteps=64,
        config=cfg,
        out=tmp_path / "b",
        progress_bar=False,
        eval_episodes=1,
        final_eval_seeds=(),
        overrides=TINY,
    )
    assert res.meta["hyperparams"]["n_timesteps"] == 64  # the budget run, not the config's


_ZOO_SCRIPT = """
import argparse, importlib, json, sys
from rl_zoo3.exp_manager import ExperimentManager
algo, conf, logs, *env_ids = sys.argv[1:]
importlib.import_module("mf_envs")  # what the zoo's --gym-packages mf_envs does
small = {"ppo": {"n_steps": 128, "batch_size": 64, "n_epochs": 1},
         "sac": {"learning_starts": 64, "batch_size": 64},
         "td3": {"learning_starts": 64, "batch_size": 64}}[algo]
for env_id in env_ids:
    args = argparse.Namespace(algo=algo, env=env_id, gym_packages=["mf_envs"], conf_file=conf)
    exp = ExperimentManager(
        args, algo, env_id, logs, n_timesteps=256, eval_freq=-1, config=conf, n_eval_envs=1,
        hyperparams=small, vec_env_type="dummy", device="cpu", log_interval=-1, verbose=0,
    )
    model, saved = exp.setup_experiment()
    exp.learn(model)
    print(json.dumps({"env": env_id, "steps": model.num_timesteps, "n": exp.n_timesteps,
                      "algo": type(model).__name__}))
"""


@pytest.mark.parametrize("algo", ["ppo", "sac", "td3"])
def test_shipped_configs_train_in_rl_zoo3_unchanged(algo, tmp_path):
    """rl-zoo3's own ExperimentManager reads the shipped configs/<algo>.yml and trains every env
    a few hundred steps (its hyperparams shrink the rollout or the warm-up only; the file is read
    as shipped). In a subprocess: importing rl_zoo3 replaces gymnasium's TimeLimit process-wide
    (rl_zoo3.gym_patches)."""
    import importlib.util
    import subprocess
    import sys

    from mf_envs.train.config import default_config

    if importlib.util.find_spec("rl_zoo3") is None:  # not importorskip: see the docstring
        pytest.skip("needs the zoo extra: pip install -e '.[zoo]'")
    ids = ["Pendulum-v1", *ENV_SPECS]
    conf = str(default_config(algo))
    out = subprocess.run(
        [sys.executable, "-c", _ZOO_SCRIPT, algo, conf, str(tmp_path / "logs"), *ids],
        capture_output=True, text=True, cwd=tmp_path, timeout=900,
    )  # fmt: skip
    assert out.returncode == 0, out.stderr[-2000:]
    runs = [json.loads(line) for line in out.stdout.strip().splitlines() if line.startswith("{")]
    assert [r["env"] for r in runs] == ids
    assert all(r["steps"] >= 256 and r["n"] == 256 and r["algo"] == algo.upper() for r in runs)


def test_train_sac_smoke_and_summary_label(tmp_path):
    from mf_envs.train.trainer import train

    res = train(
        "GyroStabilizer-v0", algo="sac", timesteps=200, seed=1, out=tmp_path,
        progress_bar=False, eval_episodes=1, final_eval_seeds=(1000,),
        overrides={"learning_starts": 50, "batch_size": 32, "policy_kwargs": {"net_arch": [8]}},
    )  # fmt: skip
    assert res.run_dir == tmp_path / "GyroStabilizer-v0" / "sac" / "seed1"
    assert res.meta["algo"] == "sac" and "--algo sac" in res.meta["command"]
    assert (
        "sac" in res.meta["evaluation"]
        and load_policy("GyroStabilizer-v0", res.run_dir).algo == "SAC"
    )
    with pytest.raises(ValueError, match="algo"):
        train("GyroStabilizer-v0", algo="a2c", timesteps=10, out=tmp_path)


# --------------------------------------------------------------------------- vector envs
def _drive(venv, n_steps, seed):
    """Step `venv` with seeded random actions; stack obs/reward/done/terminal obs."""
    rng = np.random.default_rng(seed)
    venv.seed(seed)
    out = [venv.reset()]
    for _ in range(n_steps):
        a = rng.uniform(-2, 2, size=(venv.num_envs, 1)).astype(np.float32)
        obs, rew, done, infos = venv.step(a)
        term = [i.get("terminal_observation", np.zeros(3)) for i in infos]
        trunc = [i.get("TimeLimit.truncated", False) for i in infos]
        out += [obs, rew, done, np.array(term), np.array(trunc)]
    return out


@pytest.mark.parametrize("mode", ["SAME_STEP", "DISABLED"])
def test_native_vector_adapter_matches_dummy_vec_env(mode):
    from gymnasium.vector import AutoresetMode, SyncVectorEnv
    from stable_baselines3.common.vec_env import DummyVecEnv

    from mf_envs.train.vec import GymVectorToSB3

    fns = [lambda: gym.make("Pendulum-v1") for _ in range(2)]
    native = GymVectorToSB3(SyncVectorEnv(fns, autoreset_mode=AutoresetMode[mode]))
    dummy = DummyVecEnv(fns)
    a, b = _drive(native, 450, seed=3), _drive(dummy, 450, seed=3)  # crosses 2 time limits
    assert len(a) == len(b)
    for x, y in zip(a, b):
        np.testing.assert_allclose(x, y, rtol=1e-6, atol=1e-6)
    assert np.sum(b[3::5]) == 4  # both sub-envs truncated twice (200-step limit)


def test_make_train_env_uses_native_vector_entry_point():
    from gymnasium.vector import AutoresetMode, SyncVectorEnv

    from mf_envs.train.vec import make_train_env

    def vector_entry(num_envs=1, **kw):
        fns = [lambda: gym.make("Pendulum-v1", **kw) for _ in range(num_envs)]
        return SyncVectorEnv(fns, autoreset_mode=AutoresetMode.SAME_STEP)

    if "TestNativePendulum-v0" not in gym.registry:
        gym.register(
            "TestNativePendulum-v0",
            entry_point="gymnasium.envs.classic_control.pendulum:PendulumEnv",
            vector_entry_point=vector_entry,
            max_episode_steps=200,
        )
    venv, kind = make_train_env("TestNativePendulum-v0", 2, seed=0, normalize={})
    assert kind == "native" and venv.num_envs == 2
    venv.reset()
    venv.step(np.zeros((2, 1), np.float32))
    venv.close()
    # CartPole's native vector env autoresets NEXT_STEP: not adaptable -> SB3's DummyVecEnv
    venv, kind = make_train_env("CartPole-v1", 2, seed=0)
    assert kind == "dummy"
    venv.close()


# --------------------------------------------------------------------------- smoke runs
@pytest.mark.parametrize("env_id", SMOKE_IDS)
@pytest.mark.slow
def test_smoke_train_then_evaluate(env_id, tmp_path):
    from mf_envs.train.trainer import train

    res = train(
        env_id,
        timesteps=256,
        seed=1,
        out=tmp_path,
        progress_bar=False,
        eval_episodes=1,
        final_eval_seeds=(),
        overrides=TINY,
    )
    names = {p.name for p in res.files}
    assert {"policy.json", "policy.safetensors", "meta.json", "obs_normalization.json"} <= names
    assert not list(res.run_dir.rglob("*.zip")) and not list(res.run_dir.rglob("*.pkl"))
    assert res.meta["timesteps"] >= 256 and res.meta["steps_per_s"] > 0
    assert (res.run_dir / "evaluations.npz").is_file()
    policy = load_policy(env_id, res.run_dir)
    rows = evaluate_controllers(env_id, {"ppo": lambda env: policy}, seeds=[1000])
    assert {r["metric"] for r in rows} >= {"return", "steps"}


# --------------------------------------------------------------------------- CLI
def test_cli_errors_are_one_line(capsys, tmp_path, monkeypatch):
    from mf_envs.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["evaluate", "Foo-v0"]) == 2
    assert main(["train", "Foo-v0"]) == 2
    assert main(["evaluate", "Pendulum-v1", "--policy", str(tmp_path / "none")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3 and all(line.startswith("mf-envs ") for line in err)


def test_training_is_reproducible(tmp_path):
    """Same command, same seed -> bit-identical weights (what lets meta.json's score be re-made)."""
    import torch

    from mf_envs.train.trainer import train

    def weights(out):
        res = train(
            "Pendulum-v1",
            timesteps=256,
            seed=4,
            out=out,
            progress_bar=False,
            eval_episodes=1,
            final_eval_seeds=(),
            overrides=TINY,
        )
        return load_policy("Pendulum-v1", res.run_dir)

    a, b = weights(tmp_path / "a"), weights(tmp_path / "b")
    for pa, pb in zip(a.policy.parameters(), b.policy.parameters()):
        assert torch.equal(pa, pb)
    np.testing.assert_array_equal(a.normalization.mean, b.normalization.mean)


def test_ship_refuses_a_policy_worse_than_the_baseline(tmp_path, monkeypatch):
    from mf_envs.train import ship

    ev = {
        "metric": "rms_roll",
        "higher_is_better": False,
        "seeds": [1000],
        "ppo": {"mean": 0.2, "std": 0.0},
        "baseline:pid": {"mean": 0.1, "std": 0.0},
    }
    assert not ship.verdict({"evaluation": ev})[0]
    ev["ppo"]["mean"] = 0.05
    assert ship.verdict({"evaluation": ev})[0]
    (tmp_path / "meta.json").write_text(
        json.dumps(
            {"env_id": "GyroStabilizer-v0", "evaluation": {**ev, "ppo": {"mean": 0.3, "std": 0.0}}}
        )
    )
    monkeypatch.setattr("mf_envs.train.trainer.POLICY_ROOT", tmp_path / "never")
    assert ship.main([str(tmp_path)]) == 2
    assert not (tmp_path / "never").exists()


def test_tensorboard_flag_without_tensorboard_is_a_clear_error(tmp_path, capsys):
    import importlib.util

    from mf_envs.cli import main

    if importlib.util.find_spec("tensorboard") is not None:
        pytest.skip("tensorboard is installed; the flag works")
    args = ["train", "Pendulum-v1", "--timesteps", "64", "--out", str(tmp_path), "--tensorboard"]
    assert main(args) == 2
    assert "pip install tensorboard" in capsys.readouterr().err
    assert not any(tmp_path.iterdir())  # refused before training


@pytest.mark.parametrize(
    "path",
    sorted((Path(__file__).parents[1] / "mf_envs" / "train" / "configs").glob("*.yml")),
    ids=str,
)
def test_every_config_file_parses(path):
    from mf_envs.train.config import wrapper_class

    for env_id in read_config(path):
        hp = load_hyperparams(env_id, path)
        for wrapper, _ in hp.env_wrappers:
            assert callable(wrapper_class(wrapper))


NATIVE_IDS = [e for e in available_env_ids() if gym.spec(e).vector_entry_point is not None]


@pytest.mark.parametrize("env_id", NATIVE_IDS)
@pytest.mark.slow
def test_native_vector_training_equals_dummy_vec_env(env_id, tmp_path):
    """The env's native vector env (via GymVectorToSB3) and SB3's DummyVecEnv of single envs
    give bit-identical PPO weights: same seeds, same transitions, same autoreset semantics."""
    import torch
    import yaml

    from mf_envs.train.trainer import train

    base = read_config()[env_id]
    if env_id == "GOWEC-v0":  # 1 wave period per episode (300 steps) keeps the test short
        base["env_kwargs"] = {"n_periods": 1}
    policies = {}
    for mode in ("auto", "dummy"):
        cfg = tmp_path / f"{mode}.yml"
        cfg.write_text(yaml.safe_dump({env_id: base}))
        res = train(
            env_id,
            timesteps=256,
            seed=2,
            config=cfg,
            vec_env=mode,
            out=tmp_path / mode,
            progress_bar=False,
            eval_episodes=1,
            final_eval_seeds=(),
            overrides=TINY,
        )
        assert res.meta["vectorization"].startswith("native" if mode == "auto" else "dummy")
        policies[mode] = load_policy(env_id, res.run_dir)
    a, b = policies["auto"], policies["dummy"]
    for pa, pb in zip(a.policy.parameters(), b.policy.parameters()):
        assert torch.equal(pa, pb)
    np.testing.assert_array_equal(a.normalization.var, b.normalization.var)
