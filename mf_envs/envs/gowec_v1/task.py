"""FloatingGOWEC-v0's declaration: what the layers above the env read of it
(`envs.declaration`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mf_envs.envs.declaration import EnvDeclaration, Metric


def episode_metrics(
    env: Any, rewards: Sequence[float], infos: Sequence[Mapping[str, Any]]
) -> dict[str, float]:
    """Over the last half of the episode (as the controllers benchmark): `capture_width`, mean
    mechanical PTO power / wave power flux (m); `bound_ratio`, the same over the radiation bound;
    `net_power`, mean electrical power (W)."""
    steps = infos[1:]
    half = len(steps) // 2
    p_mech = float(np.mean([i["power_mechanical"] for i in steps[half:]]))
    return {
        "capture_width": p_mech / float(env.unwrapped.wave_power_flux()),
        "bound_ratio": p_mech / float(env.unwrapped.power_bound()),
        "net_power": float(np.mean([i["power"] for i in steps[half:]])),
    }


DECLARATION = EnvDeclaration(
    env_id="FloatingGOWEC-v0",
    entry_point="mf_envs.envs.gowec_v1.env:GOWECV1Env",
    vector_entry_point="mf_envs.envs.gowec_v1.vector:GOWECV1VectorEnv",
    max_episode_steps=6000,  # the default episode: 120 s of 0.02 s
    baselines="mf_envs.controllers.gowec_v1",
    metric=Metric("capture_width", True, "m"),
    episode_metrics=episode_metrics,
    info_keys=(
        "power",
        "power_mechanical",
        "buoy_pitch",
        "buoy_roll",
        "buoy_rate",
        "excitation_moment",
        "gimbal_angle",
        "gimbal_rate",
    ),
    bad_reset_options=(
        ("buoy_pitch", 10.0),
        ("gimbal_rate", float("inf")),
        ("buoy_roll", "0.1"),
    ),
    # sea period around the 6 s default; regular sea height 1 m nominal, >= 0.25 m
    randomize={
        "wave_period": (0.75, 1.25),
        "peak_period": (0.75, 1.25),
        "wave_amplitude": (0.25, 1.0),
    },
    # a fifth of the episodes regular waves (None), the rest JONSWAP seas of the power
    # matrix's heights (benchmarks/power_matrix.py)
    choices={"significant_wave_height": (None, 1.0, 1.5, 2.0, 2.5)},
    # GOWEC-v0's settings as the starting point (untuned)
    rllib={"gamma": 0.995, "lambda_": 0.98, "minibatch_size": 512, "timesteps": 300_000},
    vector_target=(1024, 5.0e5),
    single_target=("ratio", 1.0),
    bench="mf_envs.benchmarks.controllers.gowec_v1",
    demo="mf_envs.benchmarks.demos.gowec_v1",
)
