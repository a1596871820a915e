"""The policy format (train/policy.py, policy_files.py, policy_sbx.py): policies saved as
JSON + safetensors load without unpickling and act as the library's own model; pickles and
oversized or malformed files are refused.

Truth used: SB3's (and SBX's) own `predict` on `VecNormalize.normalize_obs` observations (a
second route through the library for `load_policy`), and the weights' arrays themselves.
"""

from __future__ import annotations

import json
import warnings

import gymnasium as gym
import numpy as np
import pytest

pytest.importorskip("stable_baselines3", reason="needs the train extra: pip install -e '.[train]'")
pytest.importorskip("safetensors", reason="needs the train extra: pip install -e '.[train]'")

import mf_envs  # noqa: E402,F401  (registers the env ids)
from mf_envs.train.policy import POLICY_ROOT, load_policy, save_policy  # noqa: E402
from mf_envs.train.provenance import PolicyEnvWarning  # noqa: E402

TINY = {"n_steps": 64, "batch_size": 64, "n_epochs": 1, "policy_kwargs": {"net_arch": [8]}}


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


def test_cli_evaluate_writes_table_and_csv(tmp_path, monkeypatch, capsys):
    from mf_envs.cli import main

    _trained_model(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert main(["evaluate", "Pendulum-v1", "--policy", "pol", "--episodes", "2"]) == 0
    out = capsys.readouterr().out
    assert "ppo" in out and "±" in out
    csv = (tmp_path / "mf_envs_eval" / "Pendulum-v1" / "evaluate.csv").read_text()
    assert csv.startswith("env_id,scene,controller,metric,mean,std,n_seeds")
