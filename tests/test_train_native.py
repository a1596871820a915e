"""Training on native vector rows: SBX's SAC in the safe policy format (its round trip:
test_train.py), the evaluation on rows."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("stable_baselines3")
pytest.importorskip("safetensors")

import mf_envs  # noqa: E402,F401  (registers the ids)
from mf_envs.train.policy import load_policy  # noqa: E402


def test_sbx_weights_that_do_not_fit_are_refused(tmp_path):
    """A weights file missing a tensor of the network policy.json describes is a ValueError
    naming the tensor (nothing is built from the file's contents)."""
    sbx = pytest.importorskip("sbx")
    from safetensors.numpy import load_file, save_file
    from stable_baselines3.common.env_util import make_vec_env

    from mf_envs.train.policy import save_policy_files

    model = sbx.SAC("MlpPolicy", make_vec_env("Pendulum-v1", n_envs=1, seed=0), seed=0,
                    policy_kwargs={"net_arch": [8]})  # fmt: skip
    save_policy_files(tmp_path, model)
    state = load_file(tmp_path / "policy.safetensors")
    dropped = sorted(state)[0]
    save_file({k: v for k, v in state.items() if k != dropped}, tmp_path / "policy.safetensors")
    with pytest.raises(ValueError, match="do not fit"):
        load_policy("Pendulum-v1", tmp_path)


def test_train_sbx_sac_on_native_rows(tmp_path):
    """`train(algo="sbx_sac")` reads sac.yml's entry (64 native rows for the headline id),
    writes an SBX_SAC policy and scores it."""
    pytest.importorskip("sbx")
    from mf_envs.train.trainer import train

    res = train(
        "GyroStabilizer-JONSWAP-v0", algo="sbx_sac", timesteps=640, seed=2, out=tmp_path,
        progress_bar=False, eval_episodes=2, final_eval_seeds=(1000,), evaluations=1,
        overrides={"learning_starts": 128, "batch_size": 32, "gradient_steps": 1,
                   "policy_kwargs": {"net_arch": [8]}},
    )  # fmt: skip
    assert res.run_dir == tmp_path / "GyroStabilizer-JONSWAP-v0" / "sbx_sac" / "seed2"
    assert res.meta["vectorization"] == "native x64" and res.meta["algo"] == "sbx_sac"
    assert "sbx" in res.meta["versions"] and "sbx_sac" in res.meta["evaluation"]
    assert load_policy("GyroStabilizer-JONSWAP-v0", res.run_dir).algo == "SBX_SAC"


def test_row_episodes_match_single_env_returns():
    """`callbacks.row_episodes` on a native vector env: each row's first-episode return and
    length equal the same seed's single-env episode under the same (zero) actions."""
    import gymnasium as gym
    from gymnasium.vector import AutoresetMode

    from mf_envs.train.callbacks import row_episodes
    from mf_envs.train.vec import GymVectorToSB3

    kw = {"episode_seconds": 3.0}
    venv = GymVectorToSB3(gym.make_vec("GyroStabilizer-JONSWAP-v0", num_envs=3,
                                       vectorization_mode="vector_entry_point",
                                       autoreset_mode=AutoresetMode.SAME_STEP, **kw))  # fmt: skip
    venv.seed(7)
    ret, length = row_episodes(lambda obs: np.zeros((len(obs), 1), np.float32), venv)
    for i in range(3):
        env = gym.make("GyroStabilizer-JONSWAP-v0", **kw)
        env.reset(seed=7 + i)
        total, n, done = 0.0, 0, False
        while not done:
            _, r, term, trunc, _ = env.step(np.zeros(1, np.float32))
            total, n, done = total + r, n + 1, term or trunc
        assert length[i] == n
        np.testing.assert_allclose(ret[i], total, rtol=1e-5)


def test_train_speed_table_and_two_env_config(tmp_path):
    """The speed table's ratio is each config's speed over the two-env one of the same id and
    learner (rows made up: no timing here), and the two-env config is the shipped entry with
    two rows and the earlier rollout settings."""
    from mf_envs.benchmarks import train_speed as ts
    from mf_envs.train.config import load_hyperparams

    rows = [
        {
            "env_id": "Eel-v0",
            "learner": "ppo",
            "algo": "ppo",
            "config": c,
            "vectorization": v,
            "timesteps": 100,
            "wall_s": 1.0,
            "steps_per_s": sps,
        }
        for c, v, sps in (("shipped", "native x256", 9000.0), ("two-env", "native x2", 1500.0))
    ]
    md = ts.table({"rows": rows, "date": "d", "machine": "m", "version": "v", "load": "1"})
    assert "| 6.0 |" in md and "| 1.0 |" in md and md.startswith(ts.BEGIN)
    label, algo, changes, _ = ts.CONFIGS["ppo"][1]
    hp = load_hyperparams("Eel-v0", ts._config("Eel-v0", algo, changes, 1000, tmp_path))
    assert label == "two-env" and hp.n_envs == 2 and hp.ppo_kwargs["n_steps"] == 512
    assert load_hyperparams("Eel-v0").n_envs == 256 and hp.n_timesteps == 1000
