"""PPO training infrastructure (train/): configs, vector-env adapter, normalised policies,
smoke runs, domain randomisation, evaluation and the CLI error paths.

Truth used: SB3's own `VecNormalize.normalize_obs` and `PPO.predict` (a second route through the
library for `load_policy`), Gymnasium's `SyncVectorEnv` + SB3's `DummyVecEnv` on the same seeds
(for the native-vector adapter), and hand-rolled episodes (for the evaluation loop).
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

sb3 = pytest.importorskip(
    "stable_baselines3", reason="needs the train extra: pip install -e '.[train]'"
)
pytest.importorskip("safetensors", reason="needs the train extra: pip install -e '.[train]'")

import mf_envs  # noqa: E402,F401  (registers the env ids)
from mf_envs.envs import ENV_SPECS, available_env_ids, declaration  # noqa: E402
from mf_envs.train.config import (  # noqa: E402
    load_hyperparams,
    parse_policy_kwargs,
    read_config,
    resolve_schedules,
)
from mf_envs.train.evaluate import episode_metrics, evaluate_controllers, run_episode  # noqa: E402
from mf_envs.train.policy import POLICY_ROOT, load_policy, save_policy  # noqa: E402
from mf_envs.train.provenance import PolicyEnvWarning  # noqa: E402

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


@pytest.mark.parametrize("algo", ["SAC", "TD3", "SBX_SAC"])
def test_off_policy_policies_save_and_load_without_pickle(algo, tmp_path):
    """An SB3 SAC/TD3 (or SBX SAC) model saved as JSON + safetensors loads with `load_policy`
    and acts as its own model on 500 observations (normalised by its VecNormalize); `to_sb3`
    rebuilds the same algorithm, critics (SBX: and target critics) included."""
    import stable_baselines3 as sb3

    lib = pytest.importorskip("sbx") if algo == "SBX_SAC" else sb3
    from stable_baselines3.common.env_util import make_vec_env
    from stable_baselines3.common.vec_env import VecNormalize

    from mf_envs.train.policy import save_policy_files

    venv = VecNormalize(make_vec_env("Pendulum-v1", n_envs=1, seed=0), norm_reward=False)
    model = getattr(lib, algo.removeprefix("SBX_"))(
        "MlpPolicy", venv, learning_starts=50, batch_size=32, seed=0,
        policy_kwargs={"net_arch": [16, 16]}, device="cpu",
    )  # fmt: skip
    model.learn(200)
    save_policy_files(tmp_path / "pol", model, venv)
    (tmp_path / "pol" / "meta.json").write_text(json.dumps({"env_id": "Pendulum-v1"}))
    policy = load_policy("Pendulum-v1", tmp_path / "pol")
    assert policy.algo == algo
    obs = np.random.default_rng(0).uniform(-1, 1, (500, 3)).astype(np.float32) * [1, 1, 8]
    theirs, _ = model.predict(venv.normalize_obs(obs), deterministic=True)
    ours, _ = policy.predict(obs)
    np.testing.assert_allclose(ours, theirs, rtol=1e-6, atol=1e-6)
    assert np.ptp(theirs) > 0
    again = policy.to_sb3(learning_starts=10)
    assert type(again) is type(model)
    if algo == "SBX_SAC":
        from mf_envs.train.policy_sbx import sbx_state

        mine, copy = sbx_state(model.policy), sbx_state(again.policy)
        assert {k.split("/")[0] for k in mine} == {"actor", "qf", "qf_target"}
        assert (
            all(np.array_equal(v, copy[k]) for k, v in mine.items()) and mine.keys() == copy.keys()
        )
        return
    for key, value in model.policy.state_dict().items():
        assert torch_equal(value, again.policy.state_dict()[key]), key


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


# --------------------------------------------------------------------------- policies
def _trained_model(tmp_path):
    """A few PPO updates on Pendulum with VecNormalize, saved with save_policy."""
    from stable_baselines3 import PPO

    from mf_envs.train.vec import make_train_env

    venv, _ = make_train_env("Pendulum-v1", 2, seed=0, normalize={})
    model = PPO("MlpPolicy", venv, seed=0, device="cpu", **TINY)
    model.learn(256)
    save_policy(tmp_path / "pol", model, venv, {"env_id": "Pendulum-v1", "seed": 0})
    return model, venv


def test_load_policy_on_raw_obs_equals_sb3_on_normalized_obs(tmp_path):
    model, venv = _trained_model(tmp_path)
    assert not np.allclose(venv.obs_rms.mean, 0.0)  # statistics really moved
    names = {p.name for p in (tmp_path / "pol").iterdir()}
    assert names == {"policy.json", "policy.safetensors", "obs_normalization.json", "meta.json"}
    policy = load_policy("Pendulum-v1", tmp_path / "pol")  # rebuilt from JSON + safetensors
    env = gym.make("Pendulum-v1")
    obs, _ = env.reset(seed=7)
    for _ in range(50):
        a, state = policy.predict(obs, deterministic=True)
        assert state is None and env.action_space.contains(a)
        ref, _ = model.predict(venv.normalize_obs(obs), deterministic=True)  # SB3, in memory
        np.testing.assert_array_equal(a, ref)
        obs, *_ = env.step(a)
    batch = np.stack([env.observation_space.sample() for _ in range(4)])
    ab, _ = policy.predict(batch)
    assert ab.shape == (4, 1)
    # normalisation is not the identity, so skipping it would change the actions
    raw, _ = model.predict(batch, deterministic=True)
    assert not np.allclose(raw, ab)


def _payload_zip(path, marker):
    """An SB3-style model.zip whose `data` entry unpickles to os.system('touch marker')."""
    import base64
    import os
    import pickle
    import zipfile

    class Payload:
        def __reduce__(self):
            return (os.system, (f"touch {marker}",))

    blob = base64.b64encode(pickle.dumps(Payload())).decode()
    data = {"policy_class": {":type:": "<class 'abc.ABCMeta'>", ":serialized:": blob}}
    with zipfile.ZipFile(path, "w") as z:
        z.writestr("data", json.dumps(data))
        z.writestr("_stable_baselines3_version", "2.9.2")


@pytest.mark.parametrize("as_folder", [False, True])
def test_pickle_payload_is_refused_and_never_runs(tmp_path, capsys, as_folder):
    from mf_envs.cli import main

    marker = tmp_path / "PWNED"
    folder = tmp_path / "evil"
    folder.mkdir()
    _payload_zip(folder / "model.zip", marker)
    target = folder if as_folder else folder / "model.zip"
    with pytest.raises(ValueError, match="pickle"):
        load_policy("Pendulum-v1", target)
    assert main(["evaluate", "Pendulum-v1", "--policy", str(target), "--out", str(tmp_path / "e")])
    assert main(["render", "GOWEC-v0", "--policy", str(target), "--out", str(tmp_path / "r.gif")])
    err = capsys.readouterr().err.strip().splitlines()
    assert all("pickle" in line for line in err) and len(err) == 2
    assert not marker.exists()
    # the payload is real: SB3's own loader does run it (so the test above can fail)
    from stable_baselines3.common.save_util import json_to_data

    json_to_data(_zip_data(folder / "model.zip"))
    assert marker.exists()


def _zip_data(path):
    import zipfile

    with zipfile.ZipFile(path) as z:
        return z.read("data").decode()


def test_policy_kwargs_whitelist(tmp_path):
    from mf_envs.train.kwargs import parse_policy_kwargs as whitelist

    marker = tmp_path / "ran"
    for text in (
        f"dict(x=th.os.system('touch {marker}'))",
        f"dict(net_arch=__import__('os').system('touch {marker}'))",
        "dict(activation_fn=nn.Module)",
        "dict(activation_fn=nn.Tanh.__class__)",
        "[i for i in range(3)]",
    ):
        with pytest.raises(ValueError, match="not allowed"):
            whitelist(text)
    with pytest.raises(ValueError, match="unknown key 'foo'"):
        whitelist("dict(net_arch=[8], foo=1)")
    with pytest.raises(ValueError, match="net_arch"):
        whitelist({"net_arch": [8, "x"]})
    assert not marker.exists()
    pk = whitelist(
        "dict(log_std_init=-1.5, activation_fn=th.nn.ReLU, net_arch=dict(pi=[4], vf=[4]))"
    )
    assert pk == {"log_std_init": -1.5, "activation_fn": "ReLU", "net_arch": {"pi": [4], "vf": [4]}}
    assert whitelist({"activation_fn": "nn.Tanh", "ortho_init": False})["activation_fn"] == "Tanh"


def test_load_policy_errors(tmp_path):
    _trained_model(tmp_path)
    with pytest.raises(ValueError, match="trained on Pendulum-v1"):
        load_policy("CartPole-v1", tmp_path / "pol")
    with pytest.raises(ValueError, match="no policy"):
        load_policy("Pendulum-v1", tmp_path / "nothing")
    with pytest.raises(ValueError, match="no shipped policy"):
        load_policy("Pendulum-v1")


@pytest.mark.parametrize("env_id", sorted(p.name for p in POLICY_ROOT.glob("*") if p.is_dir()))
def test_shipped_policies_load_and_act(env_id):
    meta = json.loads((POLICY_ROOT / env_id / "meta.json").read_text())
    for key in ("command", "seed", "timesteps", "wall_time_s", "evaluation", "package_version"):
        assert key in meta
    with warnings.catch_warnings():
        warnings.simplefilter("error", PolicyEnvWarning)  # it matches today's env
        policy = load_policy(env_id)
    env = gym.make(env_id)
    obs, _ = env.reset(seed=123)
    a, _ = policy.predict(obs)
    assert env.action_space.contains(np.asarray(a, dtype=np.float32))


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


# --------------------------------------------------------------------------- evaluation
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


# --------------------------------------------------------------------------- randomisation
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


# --------------------------------------------------------------------------- CLI
def test_cli_errors_are_one_line(capsys, tmp_path, monkeypatch):
    from mf_envs.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["evaluate", "Foo-v0"]) == 2
    assert main(["train", "Foo-v0"]) == 2
    assert main(["evaluate", "Pendulum-v1", "--policy", str(tmp_path / "none")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 3 and all(line.startswith("mf-envs ") for line in err)


def test_cli_evaluate_writes_table_and_csv(tmp_path, monkeypatch, capsys):
    from mf_envs.cli import main

    _trained_model(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert main(["evaluate", "Pendulum-v1", "--policy", "pol", "--episodes", "2"]) == 0
    out = capsys.readouterr().out
    assert "ppo" in out and "±" in out
    csv = Path(tmp_path / "mf_envs_eval" / "Pendulum-v1" / "evaluate.csv").read_text()
    assert csv.startswith("env_id,scene,controller,metric,mean,std,n_seeds")


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


@pytest.mark.parametrize("env_id", ["GOWEC-v0"])
def test_to_sb3_acts_as_the_loaded_policy_and_fine_tunes(env_id):
    """`load_policy(...).to_sb3()`: an SB3 PPO built from the safetensors weights (no pickle)
    gives the loaded policy's actions on 500 observations (normalised by its VecNormalize), and
    trains on."""
    policy = load_policy(env_id)
    model = policy.to_sb3(n_steps=64, batch_size=64, n_epochs=1)
    venv = model.get_env()
    env = gym.make(env_id)
    obs, _ = env.reset(seed=7)
    rng = np.random.default_rng(7)
    observations = []
    for _ in range(500):
        observations.append(obs)
        obs, _, term, trunc, _ = env.step(rng.uniform(-1, 1, env.action_space.shape))
        if term or trunc:
            obs, _ = env.reset()
    batch = np.array(observations, dtype=np.float32)
    ours, _ = policy.predict(batch)
    x = venv.normalize_obs(batch) if policy.normalization is not None else batch
    theirs, _ = model.predict(x, deterministic=True)
    np.testing.assert_array_equal(ours, theirs)
    before = {k: v.clone() for k, v in model.policy.state_dict().items()}
    model.learn(64)
    after = model.policy.state_dict()
    assert any(not torch_equal(before[k], after[k]) for k in before)


def torch_equal(a, b) -> bool:
    import torch

    return bool(torch.equal(a, b))
