"""Saved PPO policies: JSON + safetensors, and `load_policy` on raw env observations.

A policy folder (written by `mf-envs train`, shipped under `mf_envs/train/policies/<env_id>/`):

- `policy.json` — what to rebuild: algorithm, spaces, `policy_kwargs` (by the whitelist of
  `train.kwargs`: net_arch, activation by name, log_std_init, ...), `use_sde`;
- `policy.safetensors` — the weights of SB3's `ActorCriticPolicy` (tensors only);
- `obs_normalization.json` — the `VecNormalize` observation statistics (mean, var, epsilon, clip);
  absent if the run did not normalise observations;
- `evaluations.npz` — the `EvalCallback` log (learning curve, read with `allow_pickle=False`);
- `meta.json` — env id, exact command, seed, timesteps, wall time, evaluation scores.

Nothing in a policy folder is unpickled or evaluated (docs/design.md): SB3's `model.zip` keeps
cloudpickled objects in its `data` entry that run code on load, so `load_policy` refuses it.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs.train.kwargs import activation_name, parse_policy_kwargs, resolve_activation

POLICY_ROOT = Path(__file__).parent / "policies"
POLICY_FILE = "policy.json"
WEIGHTS_FILE = "policy.safetensors"
NORM_FILE = "obs_normalization.json"
META_FILE = "meta.json"
FORMAT = "mf-envs-policy/1"
REFUSED_SUFFIXES = (".zip", ".pkl", ".pickle", ".pt", ".pth")


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
    """A trained PPO policy acting on the RAW observations of `gym.make(env_id)`.

    Same call as a baseline controller: `reset()` and `predict(obs, deterministic=True) ->
    (action, None)`; actions are clipped to the action space as SB3's `predict` does.
    `policy` is the rebuilt SB3 `ActorCriticPolicy` (torch module, eval mode).
    """

    def __init__(self, policy: Any, normalization: ObsNormalization | None, meta: dict) -> None:
        self.policy = policy
        self.normalization = normalization
        self.meta = meta

    def reset(self) -> None:
        """Stateless (MLP) policy: nothing to reset."""

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        x = self.normalization.apply(obs) if self.normalization is not None else obs
        action, _ = self.policy.predict(x, deterministic=deterministic)
        return action, None


def policy_dir(env_id: str) -> Path:
    """Where the shipped policy of `env_id` lives."""
    return POLICY_ROOT / env_id


def load_policy(env_id: str, path: str | Path | None = None) -> PPOPolicy:
    """The PPO policy for `env_id` (default: the shipped one) acting on raw observations.

    `path`: a policy folder or its `policy.json`. Nothing is unpickled: the policy is rebuilt
    from `policy.json` and its weights read from `policy.safetensors`. ValueError if there is
    none, if it is a pickle-based file (an SB3 `model.zip`), or if its `meta.json` names
    another env. ImportError if stable-baselines3/torch/safetensors (the `train` extra) are
    missing.
    """
    from mf_envs.envs import canonical_env_id

    env_id = canonical_env_id(env_id)  # a deprecated id (GOWEC-v1): its new id, with a warning
    folder = Path(path) if path is not None else policy_dir(env_id)
    if folder.name == POLICY_FILE:
        folder = folder.parent
    _refuse_pickles(folder, path)
    if not (folder / POLICY_FILE).is_file():
        where = "no shipped policy" if path is None else "no policy"
        raise ValueError(f"policy: {where} for {env_id} at {str(folder / POLICY_FILE)!r}")
    meta = read_meta(folder)
    if canonical_env_id(meta.get("env_id", env_id), notice_alias=False) != env_id:
        raise ValueError(f"policy: {folder} was trained on {meta['env_id']}, not {env_id}")
    norm_path = folder / NORM_FILE
    norm = ObsNormalization.from_json(_read_json(norm_path)) if norm_path.is_file() else None
    return PPOPolicy(_rebuild(folder), norm, meta)


def _refuse_pickles(folder: Path, path: str | Path | None) -> None:
    """ValueError for a pickle-based policy file (SB3 model.zip, vecnormalize.pkl, torch.save)."""
    legacy = folder if folder.suffix in REFUSED_SUFFIXES else folder / "model.zip"
    if legacy.is_file() and (
        folder.suffix in REFUSED_SUFFIXES or not (folder / POLICY_FILE).is_file()
    ):
        raise ValueError(
            f"policy: {str(legacy)!r} is a pickle-based file (SB3 model.zip); mf-envs does not "
            "load it because unpickling can run code. Use a folder with policy.json + "
            "policy.safetensors (written by `mf-envs train`)"
        )


def _rebuild(folder: Path) -> Any:
    """SB3 `ActorCriticPolicy` from `policy.json` + `policy.safetensors` (eval mode, CPU)."""
    from safetensors.torch import load_file
    from stable_baselines3.common.policies import ActorCriticPolicy

    desc = _read_json(folder / POLICY_FILE)
    if desc.get("format") != FORMAT or desc.get("policy") != "MlpPolicy":
        raise ValueError(f"policy: {folder / POLICY_FILE} is not an {FORMAT} MlpPolicy file")
    kwargs = resolve_activation(parse_policy_kwargs(desc.get("policy_kwargs", {})))
    pol = ActorCriticPolicy(
        _box(desc["observation_space"]),
        _box(desc["action_space"]),
        lambda _: 0.0,
        use_sde=bool(desc.get("use_sde", False)),
        **kwargs,
    )
    try:
        pol.load_state_dict(load_file(folder / WEIGHTS_FILE, device="cpu"), strict=True)
    except (RuntimeError, OSError) as exc:
        raise ValueError(f"policy: weights in {folder / WEIGHTS_FILE} do not fit ({exc})") from exc
    pol.set_training_mode(False)
    return pol


def _box(d: dict[str, Any]) -> Any:
    from gymnasium.spaces import Box

    low = np.array([_num(v) for v in d["low"]], dtype=np.float32).reshape(d["shape"])
    high = np.array([_num(v) for v in d["high"]], dtype=np.float32).reshape(d["shape"])
    return Box(low, high, dtype=np.float32)


def _num(v: Any) -> float:
    if isinstance(v, int | float) and not isinstance(v, bool):
        return float(v)
    raise ValueError(f"policy: space bound {v!r} is not a number")


def _space_json(space: Any) -> dict[str, Any]:
    return {
        "shape": list(space.shape),
        "low": [float(v) for v in np.ravel(space.low)],
        "high": [float(v) for v in np.ravel(space.high)],
    }


def _read_json(p: Path) -> dict[str, Any]:
    try:
        d = json.loads(p.read_text())
    except (OSError, ValueError) as exc:
        raise ValueError(f"policy: cannot read {p} ({exc})") from exc
    if not isinstance(d, dict):
        raise ValueError(f"policy: {p} must hold a JSON object")
    return d


def save_policy_files(folder: Path, model: Any, vecnorm: Any | None = None) -> list[Path]:
    """Write `policy.json`, `policy.safetensors` (and the obs statistics) of an SB3 PPO model."""
    from safetensors.torch import save_file

    pk = dict(model.policy_kwargs)
    if "activation_fn" in pk:
        pk["activation_fn"] = activation_name(pk["activation_fn"])
    desc = {
        "format": FORMAT,
        "algo": "PPO",
        "policy": "MlpPolicy",
        "observation_space": _space_json(model.observation_space),
        "action_space": _space_json(model.action_space),
        "policy_kwargs": parse_policy_kwargs(pk),
        "use_sde": bool(model.use_sde),
    }
    folder.mkdir(parents=True, exist_ok=True)
    (folder / POLICY_FILE).write_text(json.dumps(desc, indent=1) + "\n")
    state = {k: v.detach().cpu().contiguous() for k, v in model.policy.state_dict().items()}
    save_file(state, folder / WEIGHTS_FILE)
    written = [folder / POLICY_FILE, folder / WEIGHTS_FILE]
    norm = ObsNormalization.from_vecnormalize(vecnorm) if vecnorm is not None else None
    if norm is not None:
        (folder / NORM_FILE).write_text(json.dumps(norm.to_json(), indent=1))
        written.append(folder / NORM_FILE)
    return written


def read_meta(folder: Path) -> dict[str, Any]:
    p = folder / META_FILE
    return json.loads(p.read_text()) if p.is_file() else {}


def save_policy(folder: Path, model: Any, vecnorm: Any | None, meta: dict[str, Any]) -> list[Path]:
    """Write the policy files (`save_policy_files`) and meta.json into `folder`."""
    return [*save_policy_files(folder, model, vecnorm), write_meta(folder, meta)]


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
