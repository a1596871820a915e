"""GyroStabilizer-v0's declaration: what the layers above the env read of it
(`envs.declaration`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mf_envs.envs.declaration import Ceiling, EnvDeclaration, Metric, Variant, shipped

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


# the headline sea: the stabilizer grid's cell Hs0.8_Tp5.92_beam_U0 (benchmarks/stabilizer_grid):
# JONSWAP Hs 0.8 m, Tp = 1.6 x the yacht's natural roll period (3.6970 s), beam, zero speed,
# where the largest waves exceed the unit's capacity (demand 1.43)
JONSWAP_KWARGS = {
    "effects": ("gyroscopic", "gimbal_inertia", "added_inertia", "hydrostatic_restoring",
                "roll_damping", "quadratic_roll_damping", "gimbal_limits", "irregular_waves"),
    "significant_wave_height": 0.8,
    "wave_period": 5.915175067009688,
    "heading": 0.5 * np.pi,
    "ship_speed": 0.0,
    "episode_seconds": 120.0,
}  # fmt: skip
RR_CEILING = Ceiling(
    "rms_roll_reduction", "1",
    "1 - RMS roll / RMS roll of the same sea with the rotor off <= 1 (no roll left): valid for "
    "any controller, loose (a capacity-limited causal bound is not computed)",
    value=1.0, tight=False,
)  # fmt: skip
# measured with `python -m mf_envs.benchmarks.stabilizer_tuning --check` (20 frozen test seeds
# 20000-20019, 120 s, RMS roll after 10 s) and `python -m mf_envs.benchmarks.references`
# (the oracle, test seeds 20000-20004; docs/benchmark.md "References")
HEADROOM_JONSWAP = (
    "the tuned `scheduled_lqr`, the best baseline, reaches 90 % of the loose ceiling (RR IQM "
    "0.904 [0.887, 0.914]; tuned `lqr` 0.899, PID 0.796, random 0.49); headroom = the oracle's "
    "0.913 - the baseline's 0.887 on the first five test seeds = 0.026 (a causal MPC: 0.906)"
)
HEADROOM_RESONANCE = (
    "saturated (the easy task): LQR 94 % of the ceiling (RR 0.943), PID 92 %; a test seed "
    "sets only the wave's phase"
)

DECLARATION = EnvDeclaration(
    **shipped("GyroStabilizer-v0", __package__, "GyroStabilizerEnv", "stabilizer"),
    max_episode_steps=600,  # the default episode: 30 s of 0.05 s
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
    role="easy",
    summary="Seakeeper 7000 on an 18 t yacht, regular beam wave at the roll resonance",
    ceiling=RR_CEILING,
    headroom=HEADROOM_RESONANCE,
    variants=(
        Variant(
            "GyroStabilizer-JONSWAP-v0",
            JONSWAP_KWARGS,
            2400,  # 120 s of 0.05 s
            "Seakeeper 7000 on an 18 t yacht, JONSWAP beam sea Hs 0.8 m, Tp 5.92 s, 120 s",
            ceiling=RR_CEILING,
            headroom=HEADROOM_JONSWAP,
        ),
    ),
)
