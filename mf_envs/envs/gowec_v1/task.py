"""FloatingGOWEC-v0's declaration: what the layers above the env read of it
(`envs.declaration`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from mf_envs.envs.declaration import Ceiling, EnvDeclaration, Metric, Variant, shipped
from mf_envs.physics.waves import group_velocity, wavenumber


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


def absorbed_power_bound(env: Any) -> float:
    """Mean power (W) the hull can absorb from the episode's sea in linear potential flow, by any
    motion of its modes: sum over the sea's components of J_i 3 / k_i, the capture-width limit
    of an axisymmetric body in heave (1 / k = lambda / 2 pi) and surge with pitch (2 / k: both
    radiate the same dipole, so together they absorb no more than either; Newman 1976, Falnes
    2002 ch. 6), at the hull table's water depth h: w^2 = g k tanh(k h), J_i = rho g a_i^2 c_g / 2,
    c_g = w / (2 k) (1 + 2 k h / sinh 2 k h). A device without surge and heave (no 3-DOF
    table): the pitch-only `model.radiation_bound`. Every watt the gyros deliver comes out of
    this, after radiation and drag."""
    u = env.unwrapped
    three = getattr(u.model, "three", None)
    if three is None:
        return float(u.power_bound())
    rho, g, h = float(three.rho), float(three.g), float(three.water_depth)
    a, w = np.asarray(u.wave.amplitudes, float), np.asarray(u.wave.omegas, float)
    k, group = wavenumber(w, h, g), group_velocity(w, h, g)  # finite depth (inf: deep water)
    return float(np.sum(0.5 * rho * g * a * a * group * 3.0 / k))


def net_power_ceiling(env: Any) -> float:
    """Upper bound of the episode's mean net electrical power (W; the `net_power` metric):
    eta_g x min(absorbed_power_bound, n x max_generator_power) - the rotor loss. Loss-inclusive
    (generator efficiency, rotor loss), non-causal (it assumes the sea known), loose: it ignores
    the gyros' coupling, which limits how much of the hull's motion reaches the generator."""
    u = env.unwrapped
    rated = float(u.model.units) * float(u.max_generator_power)
    return u.eta_g * min(absorbed_power_bound(env), rated) - float(u.rotor_loss_power())


CEILING_NOTE = (
    "eta_g min(P_abs, n P_rated) - rotor loss (`net_power_ceiling`): P_abs the capture-width "
    "limit of heave, surge and pitch (3 lambda / 2 pi) in the episode's sea. Loss-inclusive, "
    "non-causal, loose: the gyros' coupling limits how much of it reaches the generator. It "
    "holds while the Morison drag dissipates over the episode (drag relative to the water "
    "could do work; the energy balance's dissipated term was positive in every test episode)"
)
NET_POWER_CEILING = Ceiling(
    "net_power", "W", CEILING_NOTE, fn="mf_envs.envs.gowec_v1.task:net_power_ceiling", tight=False
)
# measured with `python -m mf_envs.benchmarks.rl_benchmark --task gowec_irregular|gowec_regular
# --algos` (baselines only; 20 frozen test seeds 20000-20019, 120 s, the second half scored)
HEADROOM_JONSWAP = (
    "the best baseline (`efficient_pto`, with the flywheel speed scheduled per sea) nets "
    "3.5 % of the ceiling on the first five test "
    "seeds (4.9 kW against 132-141 kW), and the ceiling is loose (`tight=False`): headroom = "
    "the oracle's 5.9 kW - the baseline's 4.9 kW = 1.0 kW (`benchmarks.references`, "
    "docs/benchmark.md)"
)
HEADROOM_REGULAR = (
    "`efficient_pto` nets 13.3 % of the ceiling (30.8 kW against 231 kW, where the generators' "
    "rating binds); loose like the JONSWAP id's"
)

DECLARATION = EnvDeclaration(
    **shipped("FloatingGOWEC-v0", __package__, "GOWECV1Env", "gowec_v1"),
    max_episode_steps=6000,  # the default episode: 120 s of 0.02 s
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
    role="easy",
    summary="ISWEC-class buoy, regular 1 m wave of 6 s",
    ceiling=NET_POWER_CEILING,
    headroom=HEADROOM_REGULAR,
    variants=(
        Variant(
            "FloatingGOWEC-JONSWAP-v0",
            {"significant_wave_height": 1.5, "peak_period": 6.0},
            6000,
            "ISWEC-class buoy in a JONSWAP sea (Hs 1.5 m, Tp 6 s, gamma 3.3): a new sea per seed",
            ceiling=NET_POWER_CEILING,
            headroom=HEADROOM_JONSWAP,
        ),
    ),
)
