"""ToyOscillator-v0's declaration: the one place the layers above the env read it from."""

from __future__ import annotations

import numpy as np

from mf_envs.envs.declaration import EnvDeclaration, Metric


def episode_metrics(env, rewards, infos):
    """`rms_position`: sqrt(mean(x^2)) over the episode's steps (m)."""
    x = np.array([i["position"] for i in infos[1:]])
    return {"rms_position": float(np.sqrt(np.mean(x**2)))}


DECLARATION = EnvDeclaration(
    env_id="ToyOscillator-v0",
    entry_point="toy_oscillator.env:ToyOscillatorEnv",
    max_episode_steps=100,  # the default episode: 5 s of 0.05 s
    baselines="toy_oscillator.baselines",
    metric=Metric("rms_position", False, "m"),
    episode_metrics=episode_metrics,
    info_keys=("position", "velocity", "force", "time"),
    bad_reset_options=(("position", 10.0), ("velocity", float("nan")), ("position", "0.1")),
    randomize={"stiffness": (0.8, 1.2)},
    shifts={"stiffness x1.2": {"stiffness": 1.2}},
    hyperparams={"ppo": {"n_timesteps": 1024, "n_steps": 256, "batch_size": 64, "n_epochs": 2}},
)
