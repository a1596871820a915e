"""One-off, offline: convert the shipped SB3 `model.zip` policies to policy.json + safetensors.

This script unpickles OUR OWN shipped `train/policies/*/model.zip` files once (they were written
by `mf-envs train` in this repository); the library's loader never unpickles anything. For each
env it checks that the rebuilt policy's actions equal the old model's on observations of a
baseline episode and of random states, then deletes the `model.zip`.

    python tools/convert_policies.py [ENV_ID ...]
"""

from __future__ import annotations

import json
import sys

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs.controllers import make_baseline
from mf_envs.train.policy import (
    NORM_FILE,
    POLICY_ROOT,
    ObsNormalization,
    load_policy,
    save_policy_files,
)


def observations(env_id: str, n: int = 400) -> np.ndarray:
    """Observations of a baseline episode (seed 1000) plus samples of the observation space."""
    env = gym.make(env_id)
    obs, _ = env.reset(seed=1000)
    ctrl = make_baseline(env)
    ctrl.reset()
    out = [obs]
    for _ in range(n):
        obs, _, term, trunc, _ = env.step(ctrl.predict(obs)[0])
        out.append(obs)
        if term or trunc:
            break
    lo, hi = np.min(out, axis=0), np.max(out, axis=0)
    rng = np.random.default_rng(0)
    out += list(rng.uniform(lo, hi, size=(100, len(lo))).astype(np.float32))
    return np.asarray(out, dtype=np.float32)


def convert(env_id: str) -> None:
    from stable_baselines3 import PPO

    folder = POLICY_ROOT / env_id
    zip_path = folder / "model.zip"
    old = PPO.load(  # unpickles our own shipped file, once, offline
        zip_path,
        device="cpu",
        custom_objects={"learning_rate": 0.0, "lr_schedule": lambda _: 0.0, "clip_range": 0.2},
    )
    save_policy_files(folder, old)
    norm = ObsNormalization.from_json(json.loads((folder / NORM_FILE).read_text()))
    obs = observations(env_id)
    zip_path.unlink()
    new = load_policy(env_id)  # the safe loader, from the new files only
    a_old, _ = old.predict(norm.apply(obs), deterministic=True)
    a_new, _ = new.predict(obs, deterministic=True)
    np.testing.assert_array_equal(a_new, a_old)
    print(f"{env_id}: converted; actions identical on {len(obs)} observations")


if __name__ == "__main__":
    for eid in sys.argv[1:] or sorted(p.name for p in POLICY_ROOT.iterdir() if p.is_dir()):
        convert(eid)
