"""Anguilliform swimmer (Rios 2017 §4.5 I) on the active C1 beam: Taylor's resistive and
Lighthill's reactive forces (`fluid`), the compiled energy-momentum loop with the entrained
water's momentum (`kernels`), the model (`model`) and the closed-form checks (`theory`). See
docs/eel.md."""

from mf_envs.physics.swimmer.fluid import Water
from mf_envs.physics.swimmer.model import Swimmer

__all__ = ["Swimmer", "Water"]
