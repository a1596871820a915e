"""ToyOscillator-v0's classical baseline: a PD controller on the measured state."""

from __future__ import annotations

import numpy as np
from toy_oscillator.task import DECLARATION

from mf_envs.controllers import register


class PD:
    """u = -(kp x + kd v) / F_max, clipped to [-1, 1]."""

    def __init__(self, env, kp: float = 40.0, kd: float = 8.0) -> None:
        self.kp, self.kd = float(kp), float(kd)
        self.f_max = float(env.unwrapped.max_force)

    def reset(self) -> None:
        pass

    def predict(self, obs, deterministic: bool = True):
        x, v = float(obs[0]), float(obs[1])
        u = np.clip(-(self.kp * x + self.kd * v) / self.f_max, -1.0, 1.0)
        return np.array([u], dtype=np.float32), None


register(DECLARATION.env_id, "pd", PD, default=True)
