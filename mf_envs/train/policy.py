"""Saved PPO policies: files beside the model, and `load_policy` on raw env observations.

A policy folder (as written by `mf-envs train` and shipped under `train/policies/<env_id>/`):

- `model.zip` — the SB3 PPO model;
- `obs_normalization.json` — the `VecNormalize` observation statistics (mean, var, epsilon, clip),
  plain JSON so loading needs no pickle; absent if the run did not normalise observations;
- `vecnormalize.pkl` — the full `VecNormalize` object (rl-zoo3 convention, to resume training);
- `evaluations.npz` — the `EvalCallback` log (learning curve);
- `meta.json` — env id, exact command, seed, timesteps, wall time, evaluation scores.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

POLICY_ROOT = Path(__file__).parent / "policies"
MODEL_FILE = "model.zip"
NORM_FILE = "obs_normalization.json"
VECNORM_FILE = "vecnormalize.pkl"
META_FILE = "meta.json"


@dataclass(frozen=True)
class ObsNormalization:
    """SB3 `VecNormalize` observation transform: clip((obs - mean) / sqrt(var + eps), +-clip).

    mean, var: (obs_dim,) float64 running statistics of the raw observations.
    """

    mean: np.ndarray
    var: np.ndarray
    epsilon: float
    clip_obs: float

    @classmethod
    def from_vecnormalize(cls, vn: Any) -> ObsNormalization | None:
        if not getattr(vn, "norm_obs", False):
            return None
        rms = vn.obs_rms
        return cls(np.array(rms.mean, float), np.array(rms.var, float), vn.epsilon, vn.clip_obs)

    def apply(self, obs: np.ndarray) -> np.ndarray:
        """Normalised float32 observation(s), same shape as `obs` ((obs_dim,) or (n, obs_dim))."""
        z = (np.asarray(obs, dtype=np.float64) - self.mean) / np.sqrt(self.var + self.epsilon)
        return np.clip(z, -self.clip_obs, self.clip_obs).astype(np.float32)

    def to_json(self) -> dict[str, Any]:
        return {
            "mean": self.mean.tolist(),
            "var": self.var.tolist(),
            "epsilon": self.epsilon,
            "clip_obs": self.clip_obs,
        }

    @classmethod
    def from_json(cls, d: dict[str, Any]) -> ObsNormalization:
        return cls(
            np.array(d["mean"], float), np.array(d["var"], float), d["epsilon"], d["clip_obs"]
        )


class PPOPolicy:
    """A trained PPO model acting on the RAW observations of `gym.make(env_id)`.

    Same call as a baseline controller: `reset()` and `predict(obs, deterministic=True) ->
    (action, None)`; actions are clipped to the action space as SB3's `predict` does.
    """

    def __init__(self, model: Any, normalization: ObsNormalization | None, meta: dict) -> None:
        self.model = model
        self.normalization = normalization
        self.meta = meta

    def reset(self) -> None:
        """Stateless (MLP) policy: nothing to reset."""

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        x = self.normalization.apply(obs) if self.normalization is not None else obs
        action, _ = self.model.predict(x, deterministic=deterministic)
        return action, None


def policy_dir(env_id: str) -> Path:
    """Where the shipped policy of `env_id` lives."""
    return POLICY_ROOT / env_id


def load_policy(env_id: str, path: str | Path | None = None) -> PPOPolicy:
    """The PPO policy for `env_id` (default: the shipped one) acting on raw observations.

    `path`: a policy folder or its `model.zip`. ValueError if there is none, or if its
    `meta.json` names another env.
    """
    from stable_baselines3 import PPO

    folder = Path(path) if path is not None else policy_dir(env_id)
    model_path = folder if folder.suffix == ".zip" else folder / MODEL_FILE
    folder = model_path.parent
    if not model_path.is_file():
        where = "no shipped policy" if path is None else "no policy"
        raise ValueError(f"policy: {where} for {env_id} at {str(model_path)!r}")
    meta = read_meta(folder)
    if meta.get("env_id", env_id) != env_id:
        raise ValueError(f"policy: {folder} was trained on {meta['env_id']}, not {env_id}")
    norm_path = folder / NORM_FILE
    norm = (
        ObsNormalization.from_json(json.loads(norm_path.read_text()))
        if norm_path.is_file()
        else None
    )
    # schedules are training-only; do not deserialise them
    model = PPO.load(
        model_path,
        device="cpu",
        custom_objects={"learning_rate": 0.0, "lr_schedule": lambda _: 0.0, "clip_range": 0.2},
    )
    return PPOPolicy(model, norm, meta)


def read_meta(folder: Path) -> dict[str, Any]:
    p = folder / META_FILE
    return json.loads(p.read_text()) if p.is_file() else {}


def save_policy(folder: Path, model: Any, vecnorm: Any | None, meta: dict[str, Any]) -> list[Path]:
    """Write model, normalisation statistics and meta.json into `folder`; returns the files."""
    folder.mkdir(parents=True, exist_ok=True)
    model.save(folder / MODEL_FILE)
    written = [folder / MODEL_FILE]
    norm = ObsNormalization.from_vecnormalize(vecnorm) if vecnorm is not None else None
    if norm is not None:
        (folder / NORM_FILE).write_text(json.dumps(norm.to_json(), indent=1))
        written.append(folder / NORM_FILE)
    if vecnorm is not None:
        vecnorm.save(str(folder / VECNORM_FILE))
        written.append(folder / VECNORM_FILE)
    written.append(write_meta(folder, meta))
    return written


def write_meta(folder: Path, meta: dict[str, Any]) -> Path:
    p = folder / META_FILE
    p.write_text(json.dumps(meta, indent=2, default=_jsonable) + "\n")
    return p


def _jsonable(v: Any) -> Any:
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    return str(v)
