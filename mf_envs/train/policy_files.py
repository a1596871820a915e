"""The policy folder's files (format `mf-envs-policy/1`): names, the checked reading of
`policy.json`, `obs_normalization.json` and `meta.json`, and their atomic writing.

A policy folder (written by `mf-envs train`, shipped under `mf_envs/train/policies/<env_id>/`):

- `policy.json` — what to rebuild: algorithm, spaces, `policy_kwargs` (by the whitelist of
  `train.kwargs`: net_arch, activation by name, log_std_init, ...), `use_sde`;
- `policy.safetensors` — the weights (tensors only): of SB3's policy (`ActorCriticPolicy`,
  `SACPolicy`, `TD3Policy`), or of SBX's SAC (its actor's and critics' parameters by path);
- `obs_normalization.json` — the `VecNormalize` observation statistics (mean, var, epsilon, clip);
  absent if the run did not normalise observations;
- `evaluations.npz` — the training's evaluation log (learning curve, read with
  `allow_pickle=False`);
- `meta.json` — env id, exact command, seed, timesteps, wall time, evaluation scores.

Nothing in a policy folder is unpickled or evaluated (docs/design.md): SB3's `model.zip` keeps
cloudpickled objects in its `data` entry that run code on load, so it is refused.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import check_depth, read_regular, safe_name, write_atomic
from mf_envs._validate import check_finite, check_nonnegative, check_range
from mf_envs.train.kwargs import check_arch_size, parse_policy_kwargs

POLICY_FILE = "policy.json"
WEIGHTS_FILE = "policy.safetensors"
NORM_FILE = "obs_normalization.json"
META_FILE = "meta.json"
FORMAT = "mf-envs-policy/1"
REFUSED_SUFFIXES = (".zip", ".pkl", ".pickle", ".pt", ".pth")
# algorithm -> (module, model class, policy module, policy class): what policy.json's "algo"
# may name; "SBX_SAC" is SBX's SAC (JAX; the `sbx` extra)
ALGOS = {
    "PPO": ("stable_baselines3", "PPO", "stable_baselines3.common.policies", "ActorCriticPolicy"),
    "SAC": ("stable_baselines3", "SAC", "stable_baselines3.sac.policies", "SACPolicy"),
    "TD3": ("stable_baselines3", "TD3", "stable_baselines3.td3.policies", "TD3Policy"),
    "SBX_SAC": ("sbx", "SAC", "sbx.sac.policies", "SACPolicy"),
}
MAX_JSON_BYTES = 8 << 20  # a policy folder's JSON files are a few KB
MAX_INPUTS = 65_536  # observation entries of a policy (the envs have fewer than 200)


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
    def from_json(cls, d: dict[str, Any], obs_dim: int | None = None) -> ObsNormalization:
        """From `to_json`'s dict; ValueError naming the field for a missing or non-numeric field,
        a length other than `obs_dim`, NaN/inf, a negative variance or a non-positive
        epsilon/clip (checked here, at load, not at the first `predict`)."""
        missing = sorted({"mean", "var", "epsilon", "clip_obs"} - set(d))
        if missing:
            raise ValueError(f"{NORM_FILE}: missing {missing}")
        mean = check_finite(f"{NORM_FILE}: mean", d["mean"])
        var = check_nonnegative(f"{NORM_FILE}: var", d["var"])
        for name, arr in (("mean", mean), ("var", var)):
            if arr.ndim != 1 or (obs_dim is not None and arr.shape != (obs_dim,)):
                raise ValueError(
                    f"{NORM_FILE}: {name} must list {obs_dim} numbers, got shape {arr.shape}"
                )
        eps = check_range(f"{NORM_FILE}: epsilon", d["epsilon"], 0.0, None)
        clip = check_range(f"{NORM_FILE}: clip_obs", d["clip_obs"], 0.0, None)
        if eps <= 0 or clip <= 0:
            raise ValueError(f"{NORM_FILE}: epsilon and clip_obs must be > 0, got {eps}, {clip}")
        return cls(mean, var, eps, clip)


def refuse_pickles(folder: Path, path: str | Path | None) -> None:
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


def read_description(folder: Path) -> dict[str, Any]:
    """`policy.json`, checked field by field (format, policy, spaces with matching shapes and
    finite bounds, policy_kwargs through the whitelist); ValueError naming the file."""
    p = folder / POLICY_FILE
    desc = read_json(p)
    if desc.get("format") != FORMAT or desc.get("policy") != "MlpPolicy":
        raise ValueError(f"policy: {p} is not an {FORMAT} MlpPolicy file")
    desc.setdefault("algo", "PPO")
    if not isinstance(desc["algo"], str) or desc["algo"] not in ALGOS:
        raise ValueError(f"policy: {p}: algo {desc['algo']!r} is not one of {sorted(ALGOS)}")
    for key in ("observation_space", "action_space"):
        space = desc.get(key)
        if not isinstance(space, dict) or set(space) != {"shape", "low", "high"}:
            raise ValueError(f"policy: {p}: {key} must be {{shape, low, high}}, got {space!r}")
        shape = space["shape"]
        if not (
            isinstance(shape, list)
            and 0 < len(shape) <= 3
            and all(isinstance(n, int) and not isinstance(n, bool) and 0 < n <= 4096 for n in shape)
        ):
            raise ValueError(f"policy: {p}: {key}.shape must be a list of positive ints")
        for bound in ("low", "high"):
            b = space[bound]
            if not isinstance(b, list) or len(b) != math.prod(shape):
                raise ValueError(f"policy: {p}: {key}.{bound} must list {math.prod(shape)} numbers")
            bad = [v for v in b if not _finite_number(v)]
            if bad:
                raise ValueError(f"policy: {p}: {key}.{bound} holds {bad[0]!r}, not a number")
    n = math.prod(desc["observation_space"]["shape"])
    if n > MAX_INPUTS:
        raise ValueError(f"policy: {p}: observation_space has {n} entries, more than {MAX_INPUTS}")
    if not isinstance(desc.get("use_sde", False), bool):
        raise ValueError(f"policy: {p}: use_sde must be true or false")
    try:
        desc["policy_kwargs"] = parse_policy_kwargs(desc.get("policy_kwargs", {}))
        n_act = math.prod(desc["action_space"]["shape"])
        arch = desc["policy_kwargs"].get("net_arch", [64, 64])
        check_arch_size(arch, n, n_act)  # before the network is allocated
    except ValueError as exc:  # its message starts with the key (policy_kwargs, activation_fn)
        raise ValueError(f"policy: {p}: {exc}") from exc
    return desc


def box(d: dict[str, Any]) -> Any:
    from gymnasium.spaces import Box

    low = np.array([_num(v) for v in d["low"]], dtype=np.float32).reshape(d["shape"])
    high = np.array([_num(v) for v in d["high"]], dtype=np.float32).reshape(d["shape"])
    return Box(low, high, dtype=np.float32)


def _finite_number(v: Any) -> bool:
    return isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(float(v))


def _num(v: Any) -> float:
    if _finite_number(v):
        return float(v)
    raise ValueError(f"policy: space bound {v!r} is not a finite number")


def space_json(space: Any) -> dict[str, Any]:
    return {
        "shape": list(space.shape),
        "low": [float(v) for v in np.ravel(space.low)],
        "high": [float(v) for v in np.ravel(space.high)],
    }


def read_json(p: Path) -> dict[str, Any]:
    """The JSON object in `p`: a regular file (a FIFO is refused, not opened for reading) of at
    most MAX_JSON_BYTES nesting at most `_files.MAX_DEPTH` deep; ValueError naming the file."""
    data = read_regular(p, MAX_JSON_BYTES, "policy")
    check_depth(data, f"policy: {p}")
    try:
        d = json.loads(data)
    except ValueError as exc:  # JSONDecodeError and UnicodeDecodeError are ValueErrors
        raise ValueError(f"policy: cannot read {p} ({exc})") from exc
    if not isinstance(d, dict):
        raise ValueError(f"policy: {p} must hold a JSON object")
    return d


def read_meta(folder: Path) -> dict[str, Any]:
    """`folder/meta.json` as a dict ({} if absent); ValueError naming the file if it is not a
    JSON object or its `env_id` is not a plain name (it names folders when a run is shipped)."""
    p = Path(folder) / META_FILE
    if not os.path.lexists(p):
        return {}
    meta = read_json(p)
    if "env_id" in meta:
        safe_name(f"policy: {p}: env_id", meta["env_id"])
    return meta


def write_meta(folder: Path, meta: dict[str, Any]) -> Path:
    p = folder / META_FILE
    write_atomic(p, json.dumps(meta, indent=2, default=_jsonable) + "\n", "policy")
    return p


def _jsonable(v: Any) -> Any:
    if isinstance(v, np.generic):
        return v.item()
    if isinstance(v, np.ndarray):
        return v.tolist()
    return str(v)
