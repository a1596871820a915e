"""The seed's open-loop inchworm gaits for Inchworm-v0, driven through the env's action interface.

* `seed_uniform` (default): uniform kappa#(t) = -kappa0 (1 + cos(t - pi)) / 2 (Rios 2017 Eq. 101);
* `seed_linear`: kappa#(S, t) = -kappa0 (c1 + c2 S / L)(1 + cos(t - pi)) / 2, c1 = 0.2, c2 = 0.8
  (Eq. 103).

The bookkeeping period 2 pi is mapped to `steps_per_cycle` env steps. The anchor follows Eq. 102:
the head grips while kappa# decreases (loading), the tail while it increases (unloading). The
controllers keep their own step counter (open loop); the observation is not used.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from mf_envs._validate import check_int, check_positive
from mf_envs.controllers import register


class SeedGait:
    """Open-loop gait kappa#(S, t) = -kappa0 (c1 + c2 S / L) (1 + cos(t - pi)) / 2."""

    def __init__(
        self,
        env: Any,
        kappa0: float | None = None,
        c1: float = 1.0,
        c2: float = 0.0,
        steps_per_cycle: int = 40,
    ) -> None:
        base = env.unwrapped
        self.max_curvature = float(base.max_curvature)
        self.kappa0 = self.max_curvature if kappa0 is None else float(kappa0)
        check_positive("kappa0", self.kappa0)
        if self.kappa0 * max(abs(c1), abs(c1 + c2)) > self.max_curvature * (1 + 1e-12):
            raise ValueError("kappa0: the gait exceeds the env's max_curvature")
        self.steps_per_cycle = check_int("steps_per_cycle", steps_per_cycle, low=2)
        self.shape = c1 + c2 * base.S_ctrl / base.params.length  # kappa0#(S) / kappa0
        self.switching = bool(base.switching)
        self.reset()

    def reset(self) -> None:
        self.k = 0

    def kappa(self, k: int) -> np.ndarray:
        """kappa# at the control points [1/m] after k steps."""
        t = 2.0 * np.pi * k / self.steps_per_cycle
        return -0.5 * self.kappa0 * self.shape * (1.0 + np.cos(t - np.pi))

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        del obs, deterministic  # open loop
        now, nxt = self.kappa(self.k), self.kappa(self.k + 1)
        self.k += 1
        a = 2.0 * nxt / -self.max_curvature - 1.0
        if self.switching:  # Eq. 102 (neutral phase counted as loading)
            grip = 1.0 if float(np.mean(nxt - now)) <= 0.0 else -1.0
            a = np.append(a, grip)
        return np.clip(a, -1.0, 1.0).astype(np.float32), None


def seed_uniform(env: Any, **params: Any) -> SeedGait:
    """Eq. 101: uniform actuation curvature."""
    return SeedGait(env, c1=1.0, c2=0.0, **params)


def seed_linear(env: Any, c1: float = 0.2, c2: float = 0.8, **params: Any) -> SeedGait:
    """Eq. 103: actuation growing linearly from tail to head."""
    return SeedGait(env, c1=c1, c2=c2, **params)


register("Inchworm-v0", "seed_uniform", seed_uniform, default=True)
register("Inchworm-v0", "seed_linear", seed_linear)
