"""Inchworm-v0's declaration: what the layers above the env read of it (`envs.declaration`)."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

from mf_envs.envs.declaration import EnvDeclaration, Metric, shipped


def episode_metrics(
    env: Any, rewards: Sequence[float], infos: Sequence[Mapping[str, Any]]
) -> dict[str, float]:
    """`tail_advance_per_step` = (x_tail(end) - x_tail(reset)) / steps (m); per gait cycle, a
    cycle being one head-grip phase then one tail-grip phase (Eq. 102 anchor switching)."""
    steps = infos[1:]
    advance = float(steps[-1]["x_tail"] - infos[0]["x_tail"])
    anchors = [i.get("anchor") for i in infos]
    cycles = sum(a == "head" and b == "tail" for a, b in zip(anchors, anchors[1:]))
    return {
        "tail_advance": advance,
        "tail_advance_per_step": advance / len(steps),
        "gait_cycles": float(cycles),
        "tail_advance_per_cycle": advance / cycles if cycles else math.nan,
    }


DECLARATION = EnvDeclaration(
    **shipped("Inchworm-v0", __package__, "InchwormEnv", "inchworm"),
    max_episode_steps=400,  # the default episode: 40 s of 0.1 s
    metric=Metric("tail_advance_per_step", True, "m"),
    episode_metrics=episode_metrics,
    info_keys=("x_head", "x_tail", "centerline"),
    bad_reset_options=(("x_tail", 1e17), ("kappa", [1.0, 2.0]), ("kappa", [0.0, 0.0, -61.0])),
    # the body, then the feet's friction: every coefficient of `friction_coefficients` times one
    # factor (`train.randomize`: a dict-valued kwarg), in both feet's scenes
    randomize={
        "youngs_modulus": (0.8, 1.2),
        "mass_per_length": (0.8, 1.2),
        "friction_coefficients": (0.5, 1.5),
    },
    shifts={
        "friction x0.5": {"friction_coefficients": 0.5},
        "youngs_modulus x0.8": {"youngs_modulus": 0.8},
        "mass_per_length x1.2": {"mass_per_length": 1.2},
    },
    # slow steps (a Newton solve per actuation increment): small batches, one runner's worth
    rllib={"num_envs_per_env_runner": 1, "train_batch_size_per_learner": 1000},
    vector_target=(64, 5.0e3),
    single_target=("steps_per_s", 1000.0),
    vector_n_max=256,  # ~1 ms per worm step: 8192 worms take seconds per step
    slow=True,
    role="headline",
    summary="the SMA inchworm of Wang et al. 2014 (PDMS body, SMA wires, gripping feet)",
    headroom=(
        "no ceiling stated: a speed bound over every command sequence (partial strokes, the "
        "wires' heating and cooling, the feet's grip) is not derived. Evidence of headroom: "
        "the tuned gait comes from a 96-point grid and Nelder-Mead over a two-level square "
        "wave only (its speed today: docs/results/headline.json); PPO (60k-225k steps) found "
        "no gait (docs/inchworm.md)"
    ),
)
