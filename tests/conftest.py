"""Suite-wide test settings.

- hypothesis: no per-example deadline. The first example of a property test may include numba's
  compilation of a kernel (seconds on a cold cache, e.g. a fresh venv), which is not the test's
  subject; the properties themselves are unchanged.
- Markers (pyproject.toml): `slow` for long soaks and convergence ladders. The default run
  (`python -m pytest -n 2`, the README command) deselects them via `addopts`; CI's second stage
  runs everything with `-m "slow or not slow"`.
- Tests that need an optional extra skip with a reason naming it, e.g.
  `pytest.importorskip("stable_baselines3",
  reason="needs the train extra: pip install -e '.[train]'")`.
"""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest
from hypothesis import settings

settings.register_profile("mf_envs", deadline=None)
settings.load_profile("mf_envs")


@pytest.fixture
def sine_rollout():
    """`run(env_id, seed, steps, w, **kwargs)`: the observations and rewards of `steps` steps of
    the action sin(w k) from `reset(seed)` of `gym.make(env_id, **kwargs)`, concatenated (for
    comparing two ways of building the same env)."""

    def run(env_id: str, seed: int, steps: int, w: float, **kwargs) -> np.ndarray:
        env = gym.make(env_id, **kwargs)
        out = [env.reset(seed=seed)[0]]
        for k in range(steps):
            obs, r, *_ = env.step(np.array([np.sin(w * k)], dtype=np.float32))
            out.append(np.append(obs, r))
        env.close()
        return np.concatenate(out)

    return run
