"""Serpentine robot (Rios 2017 §4.5 II) on the active C1 beam: belly friction (`friction`),
travelling-wave muscles as kappa#(S, t) (`gait`), the compiled energy-momentum loop (`kernels`)
and the model (`model`). See docs/serpentine.md."""

from mf_envs.physics.serpentine.friction import BellyFriction
from mf_envs.physics.serpentine.gait import WaveGait, elastica_muscles, serpenoid
from mf_envs.physics.serpentine.model import Serpentine, SnakeHistory, rod_params

__all__ = [
    "BellyFriction",
    "Serpentine",
    "SnakeHistory",
    "WaveGait",
    "elastica_muscles",
    "rod_params",
    "serpenoid",
]
