"""RLlib: the env creator returns the native vector env, and one PPO iteration runs with two
env runners on the native vector envs (slow stage; needs the `ray` extra, skipped without it)."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401

REASON = 'needs the ray extra: pip install "mf-envs[ray]"'
ray = pytest.importorskip("ray", reason=REASON)
pytest.importorskip("ray.rllib", reason=REASON)

from mf_envs.train import rllib  # noqa: E402

ENV_IDS = [
    "GyroStabilizer-v0",
    pytest.param(
        "FloatingGOWEC-v0",
        marks=pytest.mark.skipif(
            "FloatingGOWEC-v0" not in gym.registry,
            reason="FloatingGOWEC-v0 is not registered in this build yet",
        ),
    ),
]


def test_creator_builds_native_vector_env():
    venv = rllib.make_env("GyroStabilizer-v0", {"num_envs": 3, "episode_seconds": 5.0})
    assert type(venv).__name__ == "GyroStabilizerVectorEnv" and venv.num_envs == 3
    assert venv.metadata["autoreset_mode"] == gym.vector.AutoresetMode.NEXT_STEP
    single = rllib.make_env("GyroStabilizer-v0", {"episode_seconds": 5.0})
    obs_v, _ = venv.reset(seed=4)
    obs_s, _ = single.reset(seed=4)
    np.testing.assert_array_equal(obs_v[0], obs_s)  # sub-env 0 = the single env, same seed
    venv.close()
    single.close()


def test_unknown_setting_is_rejected():
    with pytest.raises(ValueError, match="lrr"):
        rllib.ppo_settings("GyroStabilizer-v0", {"lrr": 1e-3})


@pytest.mark.slow
@pytest.mark.parametrize("env_id", ENV_IDS)
def test_one_ppo_iteration(env_id):
    rllib.init_ray(num_cpus=2)
    try:
        cfg = rllib.ppo_config(
            env_id, seed=0, num_env_runners=2, num_envs_per_env_runner=2,
            train_batch_size_per_learner=400, minibatch_size=100, num_epochs=2,
        )  # fmt: skip
        algo = cfg.build_algo()
        try:
            kinds = algo.env_runner_group.foreach_env_runner(
                lambda r: type(r.env.unwrapped).__name__, local_env_runner=False
            )
            before = {k: v.clone() for k, v in algo.get_module().state_dict().items()}
            result = algo.train()
            after = algo.get_module().state_dict()
        finally:
            algo.stop()
    finally:
        ray.shutdown()
    # the env's own batched vector env where it has one, else RLlib's SyncVectorEnv
    native = rllib.has_native_vector_env(env_id)
    assert len(kinds) == 2 and all((k != "SyncVectorEnv") == native for k in kinds), kinds
    assert rllib._metric(result, "num_env_steps_sampled_lifetime") >= 400
    changed = [k for k in before if not np.array_equal(before[k].numpy(), after[k].numpy())]
    assert changed, "one PPO update changed no weight"


@pytest.mark.slow
def test_rllib_policy_exports_to_the_safe_format_and_acts_alike(tmp_path):
    """An RLlib run's policy, written as policy.json + safetensors + obs statistics, loads with
    `load_policy` and gives RLlib's own deterministic actions (its module on its filter's
    normalisation) on 300 observations; the summary reports the steps asked for."""
    import gymnasium as gym
    import torch

    from mf_envs.train import load_policy
    from mf_envs.train.rllib_export import RLLIB_SMALL_NUMBER, export_policy, filter_statistics

    env_id = "GyroStabilizer-v0"
    rllib.init_ray(num_cpus=2)
    try:
        algo = rllib.ppo_config(
            env_id, seed=0, num_env_runners=1, num_envs_per_env_runner=2,
            train_batch_size_per_learner=400, minibatch_size=100, num_epochs=2,
        ).build_algo()  # fmt: skip
        try:
            algo.train()
            env = gym.make(env_id)
            export_policy(algo, env, tmp_path / "pol", {"env_id": env_id})
            mean, std, clip = filter_statistics(algo)
            module = algo.get_module()
            obs, _ = env.reset(seed=3)
            batch = []
            for _ in range(300):
                batch.append(obs)
                obs, _, term, trunc, _ = env.step(env.action_space.sample())
                if term or trunc:
                    obs, _ = env.reset()
            batch = np.array(batch, dtype=np.float32)
            x = np.clip((batch - mean) / (std + RLLIB_SMALL_NUMBER), -clip, clip)
            with torch.no_grad():
                out = module.forward_inference({"obs": torch.as_tensor(x, dtype=torch.float32)})
            n = env.action_space.shape[0]
            theirs = np.clip(out["action_dist_inputs"].numpy()[:, :n], -1.0, 1.0)
        finally:
            algo.stop()
    finally:
        ray.shutdown()
    ours, _ = load_policy(env_id, tmp_path / "pol").predict(batch)
    np.testing.assert_allclose(ours, theirs, atol=1e-5)
    assert np.ptp(theirs) > 0  # not a constant policy (the comparison could not fail)


@pytest.mark.slow
def test_rllib_short_run_steps_and_summary(tmp_path):
    run_dir, hist = rllib.train(
        "GyroStabilizer-v0", timesteps=300, seed=0, out=tmp_path, num_env_runners=1,
        num_envs_per_env_runner=2,
    )  # fmt: skip
    assert 300 <= hist[-1]["steps"] < 600, hist  # one batch of the budget, not 4000 steps
    line = rllib.summary("GyroStabilizer-v0", hist, run_dir)
    assert "nan" not in line and f"{hist[-1]['steps']:.0f} steps" in line, line
    assert {"policy.json", "policy.safetensors", "meta.json"} <= {p.name for p in run_dir.iterdir()}
