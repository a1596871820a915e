"""GOWEC-v0's declaration: what the layers above the env read of it (`envs.declaration`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mf_envs.envs.declaration import Ceiling, EnvDeclaration, Metric, shipped


def episode_metrics(
    env: Any, rewards: Sequence[float], infos: Sequence[Mapping[str, Any]]
) -> dict[str, float]:
    """`power_ratio`: mean power after the first quarter of the episode / Eq. 95 (as the
    controllers benchmark's `episode_ratio`); `power_ratio_all` over the whole episode."""
    power = np.array([i["power"] for i in infos[1:]])
    ref = float(env.unwrapped.analytic_max_power())
    return {
        "mean_power": float(power.mean()),
        "power_ratio": float(power[len(power) // 4 :].mean()) / ref,
        "power_ratio_all": float(power.mean()) / ref,
    }


DECLARATION = EnvDeclaration(
    **shipped("GOWEC-v0", __package__, "GOWECEnv", "gowec"),
    max_episode_steps=6000,  # the default episode: 20 wave periods of 300 steps
    metric=Metric("power_ratio", True, "1"),
    episode_metrics=episode_metrics,
    info_keys=("power", "gimbal_angle", "gimbal_rate", "buoy_rate", "wave_elevation"),
    bad_reset_options=(("gimbal_rate", 1e9), ("gimbal_angle", float("nan")), ("wave_phase", "1")),
    randomize={"wave_period": (0.8, 1.2), "wave_amplitude": (0.5, 1.5), "rotor_speed": (0.9, 1.1)},
    shifts={
        "wave_period x0.8": {"wave_period": 0.8},
        "wave_period x1.2": {"wave_period": 1.2},
        "rotor_speed x0.9": {"rotor_speed": 0.9},
    },
    # 6000-step episodes (20 wave periods x 300 steps): a horizon of a wave period, gamma 0.995
    rllib={"gamma": 0.995, "lambda_": 0.98, "minibatch_size": 512, "timesteps": 300_000},
    vector_target=(1024, 1.0e6),
    role="easy",
    summary="the dissertation's GOWEC (Sec. 3.2): prescribed buoy rocking, regular wave",
    ceiling=Ceiling(
        "power_ratio",
        "1",
        "4/pi x Eq. 95: the mean power of any gimbal motion with |sin phi| <= 1 under the "
        "prescribed rocking, reached by a square wave of sin phi (docs/derivations.md)",
        value=4.0 / np.pi,
    ),  # fmt: skip
    headroom=(
        "saturated by design (the easy task): bang-bang reaches 1.2714 of Eq. 95, 99.86 % of the "
        "ceiling; the GOWEC's headline task is FloatingGOWEC-JONSWAP-v0"
    ),
)
