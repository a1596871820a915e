"""GyroStabilizer-v0's declaration: what the layers above the env read of it
(`envs.declaration`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mf_envs.envs.declaration import EnvDeclaration, Metric

SETTLE = 10.0  # s: metrics (RMS roll) skip the start-up transient, benches and evaluate alike


def episode_metrics(
    env: Any, rewards: Sequence[float], infos: Sequence[Mapping[str, Any]]
) -> dict[str, float]:
    """`rms_roll`: sqrt(mean(roll^2)) after `SETTLE` seconds (rad); over the whole episode
    `rms_roll_all`, and `max_abs_roll`."""
    steps = infos[1:]
    roll = np.array([i["roll"] for i in steps])
    settled = roll[np.array([i["time"] for i in steps]) > SETTLE]
    return {
        "rms_roll": float(np.sqrt(np.mean(settled**2))),
        "rms_roll_all": float(np.sqrt(np.mean(roll**2))),
        "max_abs_roll": float(np.max(np.abs(roll))),
    }


DECLARATION = EnvDeclaration(
    env_id="GyroStabilizer-v0",
    entry_point="mf_envs.envs.gyro_stabilizer.env:GyroStabilizerEnv",
    vector_entry_point="mf_envs.envs.gyro_stabilizer.vector:GyroStabilizerVectorEnv",
    max_episode_steps=600,  # the default episode: 30 s of 0.05 s
    baselines="mf_envs.controllers.stabilizer",
    metric=Metric("rms_roll", False, "rad"),
    episode_metrics=episode_metrics,
    info_keys=(
        "roll",
        "roll_rate",
        "pitch_rate",
        "yaw_rate",
        "gimbal_angle",
        "gimbal_rate",
        "gyro_moment",
        "wave_moment",
    ),
    bad_reset_options=(("roll", 10.0), ("roll_rate", True), ("gimbal_angle", 4.0)),
    randomize={
        "wave_period": (0.8, 1.2),
        "wave_moment_amplitude": (0.5, 1.5),
        "significant_wave_height": (0.5, 1.5),
        "rotor_speed": (0.9, 1.1),
    },
    shifts={
        "wave_period x0.8": {"wave_period": 0.8},
        "wave_period x1.2": {"wave_period": 1.2},
        "sea x1.5": {"wave_moment_amplitude": 1.5},
    },
    # 600-step episodes (30 s at 0.05 s); SB3 tuning: gamma 0.98, lr 1e-3 (train/configs/ppo.yml)
    rllib={"gamma": 0.98, "lr": 1e-3, "minibatch_size": 128},
    vector_target=(1024, 1.5e6),
    bench="mf_envs.benchmarks.controllers.stabilizer",
    demo="mf_envs.benchmarks.demos.stabilizer",
)
