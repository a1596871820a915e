"""Saved policies (SB3 PPO, SAC, TD3; SBX's SAC): `save_policy` writes a policy folder (its
files: `train.policy_files`), `load_policy` rebuilds the policy acting on raw env observations.

Nothing in a policy folder is unpickled or evaluated (docs/design.md): the network is rebuilt
from `policy.json` and its weights read from `policy.safetensors`.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import atomic_path, write_atomic
from mf_envs.train.kwargs import activation_name, parse_policy_kwargs, resolve_activation
from mf_envs.train.policy_files import (  # noqa: F401  (the names importers take from here)
    ALGOS,
    FORMAT,
    META_FILE,
    NORM_FILE,
    POLICY_FILE,
    WEIGHTS_FILE,
    ObsNormalization,
    box,
    read_description,
    read_json,
    read_meta,
    refuse_pickles,
    space_json,
    write_meta,
)

POLICY_ROOT = Path(__file__).parent / "policies"


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
        self.algo = algo  # "PPO", "SAC", "TD3" or "SBX_SAC" (ALGOS)
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
        sde = (
            {}
            if self.algo in ("TD3", "SBX_SAC")
            else {"use_sde": bool(getattr(self.policy, "use_sde", 0))}
        )
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
        if self.algo == "SBX_SAC":
            from mf_envs.train.policy_sbx import put_sbx_state, sbx_state

            put_sbx_state(model.policy, sbx_state(self.policy), "the loaded policy")
        else:
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
    refuse_pickles(folder, path)
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
        stats = read_json(norm_path)  # a FIFO, a deep or malformed file: named by it
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

    weights = folder / WEIGHTS_FILE
    if desc["algo"] == "SBX_SAC":
        from mf_envs.train.policy_sbx import rebuild_sbx

        obs, act = box(desc["observation_space"]), box(desc["action_space"])
        return rebuild_sbx(obs, act, dict(desc["policy_kwargs"]), weights)
    kwargs = resolve_activation(desc["policy_kwargs"])
    if desc["algo"] != "TD3":  # TD3's deterministic actor has no state-dependent exploration
        kwargs["use_sde"] = desc.get("use_sde", False)
    pol = _class(desc["algo"], 1)(
        box(desc["observation_space"]), box(desc["action_space"]), lambda _: 0.0, **kwargs
    )
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


def save_policy_files(folder: Path, model: Any, vecnorm: Any | None = None) -> list[Path]:
    """Write `policy.json`, `policy.safetensors` (and the obs statistics) of an SB3 PPO, SAC
    or TD3 model (the policy's whole state: actor and critics, for fine-tuning)."""
    from mf_envs.train.policy_sbx import is_sbx, sbx_policy_kwargs, sbx_state

    sbx = is_sbx(model)
    pk = sbx_policy_kwargs(model) if sbx else dict(model.policy_kwargs)
    pk.pop("use_sde", None)  # SAC keeps it among its policy kwargs; stored as "use_sde" below
    if "activation_fn" in pk:
        pk["activation_fn"] = activation_name(pk["activation_fn"])
    desc = {
        "format": FORMAT,
        "algo": ("SBX_" if sbx else "") + type(model).__name__,
        "policy": "MlpPolicy",
        "observation_space": space_json(model.observation_space),
        "action_space": space_json(model.action_space),
        "policy_kwargs": parse_policy_kwargs(pk),
        "use_sde": bool(getattr(model, "use_sde", False)),
    }
    if desc["algo"] not in ALGOS:
        raise ValueError(f"algo: {desc['algo']} policies are not saved; use one of {sorted(ALGOS)}")
    folder.mkdir(parents=True, exist_ok=True)
    write_atomic(folder / POLICY_FILE, json.dumps(desc, indent=1) + "\n", "policy")
    with atomic_path(folder / WEIGHTS_FILE, "policy") as tmp:
        if sbx:
            from safetensors.numpy import save_file as save_arrays

            save_arrays(sbx_state(model.policy), tmp)
        else:
            from safetensors.torch import save_file

            pol = model.policy
            save_file({k: v.detach().cpu().contiguous() for k, v in pol.state_dict().items()}, tmp)
    written = [folder / POLICY_FILE, folder / WEIGHTS_FILE]
    norm = ObsNormalization.from_vecnormalize(vecnorm) if vecnorm is not None else None
    if norm is not None:
        write_atomic(folder / NORM_FILE, json.dumps(norm.to_json(), indent=1), "policy")
        written.append(folder / NORM_FILE)
    return written


def save_policy(folder: Path, model: Any, vecnorm: Any | None, meta: dict[str, Any]) -> list[Path]:
    """Write the policy files (`save_policy_files`) and meta.json into `folder`."""
    return [*save_policy_files(folder, model, vecnorm), write_meta(folder, meta)]
