"""Saved policies (SB3 PPO, SAC, TD3): JSON + safetensors, and `load_policy` on raw env
observations.

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
import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import atomic_path, check_depth, read_regular, safe_name, write_atomic
from mf_envs._validate import check_finite, check_nonnegative, check_range
from mf_envs.train.kwargs import (
    activation_name,
    check_arch_size,
    parse_policy_kwargs,
    resolve_activation,
)

POLICY_ROOT = Path(__file__).parent / "policies"
POLICY_FILE = "policy.json"
WEIGHTS_FILE = "policy.safetensors"
NORM_FILE = "obs_normalization.json"
META_FILE = "meta.json"
FORMAT = "mf-envs-policy/1"
REFUSED_SUFFIXES = (".zip", ".pkl", ".pickle", ".pt", ".pth")
# algorithm -> (SB3 module, model class, policy class): what policy.json's "algo" may name
ALGOS = {
    "PPO": ("stable_baselines3", "PPO", "stable_baselines3.common.policies", "ActorCriticPolicy"),
    "SAC": ("stable_baselines3", "SAC", "stable_baselines3.sac.policies", "SACPolicy"),
    "TD3": ("stable_baselines3", "TD3", "stable_baselines3.td3.policies", "TD3Policy"),
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


class PPOPolicy:
    """A trained policy (PPO, SAC or TD3: `algo`) acting on the RAW observations of
    `gym.make(env_id)`.

    Same call as a baseline controller: `reset()` and `predict(obs, deterministic=True) ->
    (action, None)`; actions are clipped to the action space as SB3's `predict` does.
    `policy` is the rebuilt SB3 policy (`ActorCriticPolicy`, `SACPolicy` or `TD3Policy`; torch
    module, eval mode).
    """

    def __init__(
        self,
        policy: Any,
        normalization: ObsNormalization | None,
        meta: dict,
        policy_kwargs: dict[str, Any] | None = None,
        algo: str = "PPO",
    ) -> None:
        self.algo = algo  # "PPO", "SAC" or "TD3" (ALGOS)
        self.policy = policy
        self.normalization = normalization
        self.meta = meta
        self.policy_kwargs = resolve_activation(policy_kwargs or {})  # as PPO takes them

    def reset(self) -> None:
        """Stateless (MLP) policy: nothing to reset."""

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        x = self.normalization.apply(obs) if self.normalization is not None else obs
        action, _ = self.policy.predict(x, deterministic=deterministic)
        return action, None

    def to_sb3(self, env: Any = None, **ppo_kwargs: Any) -> Any:
        """An SB3 model of this policy's algorithm (`PPO`, `SAC`, `TD3`) holding these weights
        (actor and, for SAC/TD3, the critics), to fine-tune with `learn()` (or save to the
        Hub with SB3's own tools), built without unpickling anything.

        `env`: an SB3 `VecEnv` of this policy's env; default a `DummyVecEnv` of `gym.make(
        meta["env_id"])`. When the policy was trained on normalised observations the env is
        wrapped in `VecNormalize` carrying the saved statistics (observations only; training
        updates them, as in SB3), so `model.predict(model.get_env().normalize_obs(obs))` acts as
        `predict(obs)`. `ppo_kwargs` go to the algorithm (learning rate, n_steps, ...).
        """
        from stable_baselines3.common.env_util import make_vec_env
        from stable_baselines3.common.vec_env import VecNormalize

        if env is None:
            if "env_id" not in self.meta:
                raise ValueError("env: this policy's meta.json names no env_id; pass env=")
            env = make_vec_env(self.meta["env_id"], n_envs=1)
        if self.normalization is not None:
            n = self.normalization
            env = VecNormalize(env, norm_obs=True, norm_reward=False, clip_obs=n.clip_obs,
                               epsilon=n.epsilon)  # fmt: skip
            env.obs_rms.mean, env.obs_rms.var = n.mean.copy(), n.var.copy()
        sde = {} if self.algo == "TD3" else {"use_sde": bool(getattr(self.policy, "use_sde", 0))}
        model = _class(self.algo, 0)(
            "MlpPolicy", env, policy_kwargs=dict(self.policy_kwargs), device="cpu",
            **sde, **ppo_kwargs,
        )  # fmt: skip
        # the network needs the observation's shape and the action space (its clip); the
        # observation bounds may have been widened since the policy was trained
        ours, theirs = self.policy, model
        if (theirs.observation_space.shape != ours.observation_space.shape
                or theirs.action_space != ours.action_space):  # fmt: skip
            raise ValueError(
                f"env: spaces {theirs.observation_space}, {theirs.action_space} do not fit the "
                f"policy's {ours.observation_space}, {ours.action_space}"
            )
        model.policy.load_state_dict(self.policy.state_dict(), strict=True)
        return model


def policy_dir(env_id: str) -> Path:
    """Where the shipped policy of `env_id` lives."""
    return POLICY_ROOT / env_id


def load_policy(env_id: str, path: str | Path | None = None) -> PPOPolicy:
    """The PPO policy for `env_id` (default: the shipped one) acting on raw observations.

    `path`: a policy folder or its `policy.json`. Nothing is unpickled: the policy is rebuilt
    from `policy.json` and its weights read from `policy.safetensors`. ValueError if there is
    none, if it is a pickle-based file (an SB3 `model.zip`), or if its `meta.json` names
    another env. ModuleNotFoundError naming the `train` extra if stable-baselines3, torch or
    safetensors are missing. A `PolicyEnvWarning` if the env it was trained on (its meta.json's
    `env_kwargs_full` and `env_probe`, `train.provenance`) differs from `env_id`'s today.
    """
    from mf_envs.envs import canonical_env_id
    from mf_envs.train.provenance import warn_if_env_differs

    _need_train_extra()

    env_id = canonical_env_id(env_id)  # a deprecated id (GOWEC-v1): its new id, with a warning
    folder = Path(path) if path is not None else policy_dir(env_id)
    if folder.name == POLICY_FILE:
        folder = folder.parent
    _refuse_pickles(folder, path)
    if not os.path.lexists(folder / POLICY_FILE):
        where = "no shipped policy" if path is None else "no policy"
        raise ValueError(f"policy: {where} for {env_id} at {str(folder / POLICY_FILE)!r}")
    meta = read_meta(folder)
    if canonical_env_id(meta.get("env_id", env_id), notice_alias=False) != env_id:
        raise ValueError(f"policy: {folder} was trained on {meta['env_id']}, not {env_id}")
    desc = read_description(folder)
    norm_path = folder / NORM_FILE
    norm = None
    if os.path.lexists(norm_path):  # a FIFO or a folder there is an error, not "absent"
        obs_dim = math.prod(desc["observation_space"]["shape"])
        stats = _read_json(norm_path)  # a FIFO, a deep or malformed file: named by it
        try:
            norm = ObsNormalization.from_json(stats, obs_dim)
        except ValueError as exc:
            raise ValueError(f"policy: {norm_path}: {exc}") from exc
    policy = PPOPolicy(_rebuild(folder, desc), norm, meta, desc["policy_kwargs"], desc["algo"])
    warn_if_env_differs(meta, env_id, str(folder))
    return policy


def _need_train_extra() -> None:
    """ModuleNotFoundError that names the `train` extra when one of its packages is missing."""
    from mf_envs._extras import install_hint, missing_extra

    try:
        import safetensors  # noqa: F401
        import stable_baselines3  # noqa: F401
        import torch  # noqa: F401
    except ModuleNotFoundError as exc:
        extra = missing_extra(exc) or "train"
        raise ModuleNotFoundError(
            f"load_policy needs the {extra} extra ({exc.name} is missing): {install_hint(extra)}",
            name=exc.name,
        ) from exc


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


def read_description(folder: Path) -> dict[str, Any]:
    """`policy.json`, checked field by field (format, policy, spaces with matching shapes and
    finite bounds, policy_kwargs through the whitelist); ValueError naming the file."""
    p = folder / POLICY_FILE
    desc = _read_json(p)
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


def _class(algo: str, which: int) -> Any:
    """ALGOS[algo]'s model class (which=0) or policy class (which=1)."""
    import importlib

    module, name = ALGOS[algo][2 * which], ALGOS[algo][2 * which + 1]
    return getattr(importlib.import_module(module), name)


def _rebuild(folder: Path, desc: dict[str, Any]) -> Any:
    """The SB3 policy of `desc["algo"]` (ActorCriticPolicy, SACPolicy, TD3Policy) from
    `policy.json` (already checked) + `policy.safetensors` (eval mode, CPU); ValueError naming
    the weights file if it is not safetensors or does not fit the network (a pickle renamed
    `.safetensors` is refused by the format, never run)."""
    from safetensors.torch import load_file

    kwargs = resolve_activation(desc["policy_kwargs"])
    if desc["algo"] != "TD3":  # TD3's deterministic actor has no state-dependent exploration
        kwargs["use_sde"] = desc.get("use_sde", False)
    pol = _class(desc["algo"], 1)(
        _box(desc["observation_space"]), _box(desc["action_space"]), lambda _: 0.0, **kwargs
    )
    weights = folder / WEIGHTS_FILE
    try:
        state = load_file(weights, device="cpu")
    except Exception as exc:  # noqa: BLE001 - safetensors raises its own SafetensorError
        raise ValueError(f"policy: {weights} is not a safetensors file ({exc})") from exc
    for key, t in state.items():  # NaN weights are named here, not at the first predict
        if t.is_floating_point() and not bool(t.isfinite().all()):
            raise ValueError(f"policy: {weights}: tensor {key!r} holds NaN or inf values")
    try:
        pol.load_state_dict(state, strict=True)
    except (RuntimeError, OSError) as exc:
        raise ValueError(f"policy: weights in {weights} do not fit ({exc})") from exc
    pol.set_training_mode(False)
    return pol


def _box(d: dict[str, Any]) -> Any:
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


def _space_json(space: Any) -> dict[str, Any]:
    return {
        "shape": list(space.shape),
        "low": [float(v) for v in np.ravel(space.low)],
        "high": [float(v) for v in np.ravel(space.high)],
    }


def _read_json(p: Path) -> dict[str, Any]:
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


def save_policy_files(folder: Path, model: Any, vecnorm: Any | None = None) -> list[Path]:
    """Write `policy.json`, `policy.safetensors` (and the obs statistics) of an SB3 PPO, SAC
    or TD3 model (the policy's whole state: actor and critics, for fine-tuning)."""
    from safetensors.torch import save_file

    pk = dict(model.policy_kwargs)
    pk.pop("use_sde", None)  # SAC keeps it among its policy kwargs; stored as "use_sde" below
    if "activation_fn" in pk:
        pk["activation_fn"] = activation_name(pk["activation_fn"])
    desc = {
        "format": FORMAT,
        "algo": type(model).__name__,
        "policy": "MlpPolicy",
        "observation_space": _space_json(model.observation_space),
        "action_space": _space_json(model.action_space),
        "policy_kwargs": parse_policy_kwargs(pk),
        "use_sde": bool(getattr(model, "use_sde", False)),
    }
    if desc["algo"] not in ALGOS:
        raise ValueError(f"algo: {desc['algo']} policies are not saved; use one of {sorted(ALGOS)}")
    folder.mkdir(parents=True, exist_ok=True)
    write_atomic(folder / POLICY_FILE, json.dumps(desc, indent=1) + "\n", "policy")
    state = {k: v.detach().cpu().contiguous() for k, v in model.policy.state_dict().items()}
    with atomic_path(folder / WEIGHTS_FILE, "policy") as tmp:
        save_file(state, tmp)
    written = [folder / POLICY_FILE, folder / WEIGHTS_FILE]
    norm = ObsNormalization.from_vecnormalize(vecnorm) if vecnorm is not None else None
    if norm is not None:
        write_atomic(folder / NORM_FILE, json.dumps(norm.to_json(), indent=1), "policy")
        written.append(folder / NORM_FILE)
    return written


def read_meta(folder: Path) -> dict[str, Any]:
    """`folder/meta.json` as a dict ({} if absent); ValueError naming the file if it is not a
    JSON object or its `env_id` is not a plain name (it names folders when a run is shipped)."""
    p = Path(folder) / META_FILE
    if not os.path.lexists(p):
        return {}
    meta = _read_json(p)
    if "env_id" in meta:
        safe_name(f"policy: {p}: env_id", meta["env_id"])
    return meta


def save_policy(folder: Path, model: Any, vecnorm: Any | None, meta: dict[str, Any]) -> list[Path]:
    """Write the policy files (`save_policy_files`) and meta.json into `folder`."""
    return [*save_policy_files(folder, model, vecnorm), write_meta(folder, meta)]


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
