"""An RLlib PPO run as an mf-envs policy folder (JSON + safetensors, no pickle).

RLlib checkpoints are pickles and RLlib's own classes; `evaluate`, `render`, `load_policy` and
`to_sb3` read the project's policy format instead (`train.policy`), so every RLlib run also writes
that format beside its checkpoint (`export_policy`).

The mapping (RLlib's default PPO module on the new API stack, `vf_share_layers=True`, `tanh`
encoder, a linear head giving the Gaussian's mean and log std):
- the encoder's layers -> SB3's `mlp_extractor.policy_net` (and `value_net`, the same shared
  layers), net_arch `dict(pi=H, vf=H)` with `Tanh`;
- the head's first `act_dim` rows -> `action_net` (the mean: RLlib's deterministic action);
- the head's remaining bias -> SB3's state-independent `log_std` (RLlib's log std depends on the
  state through the head's weights; the exported policy's exploration noise is that bias only, its
  deterministic actions are RLlib's);
- the value head, if the module has one -> `value_net`, else zeros (acting does not use it);
- RLlib's `MeanStdFilter` (clip((x - mean) / (std + 1e-6), +-10), std the unbiased sample std)
  -> `obs_normalization.json` with var = (std + 1e-6)^2 and epsilon 1e-300, so that SB3's
  sqrt(var + epsilon) is RLlib's std + 1e-6.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import atomic_path, write_atomic
from mf_envs.train.policy_files import (
    FORMAT,
    META_FILE,
    NORM_FILE,
    POLICY_FILE,
    WEIGHTS_FILE,
    space_json,
)

RLLIB_SMALL_NUMBER = 1e-6  # ray.rllib.utils.numpy.SMALL_NUMBER, added to the filter's std


def filter_statistics(algo: Any) -> tuple[np.ndarray, np.ndarray, float] | None:
    """(mean, std, clip) of the run's MeanStdFilter connector, or None if it has none."""
    from ray.rllib.utils.filter import RunningStat

    runner = algo.env_runner_group.local_env_runner
    states = (
        [runner.get_state(components="env_to_module_connector")]
        if runner is not None
        else algo.env_runner_group.foreach_env_runner(
            lambda r: r.get_state(components="env_to_module_connector"), local_env_runner=False
        )
    )
    connector = states[0].get("env_to_module_connector", {})
    if "MeanStdFilter" not in connector:
        return None
    (agent_state,) = connector["MeanStdFilter"].values()
    (stats,) = [RunningStat.from_state(s) for s in agent_state["running_stats"]]
    clip = float(agent_state.get("clip_by_value") or 0.0) or np.inf
    return np.asarray(stats.mean, np.float64), np.asarray(stats.std, np.float64), clip


def export_policy(algo: Any, env: Any, folder: Path, meta: dict[str, Any]) -> list[Path]:
    """Write `algo`'s policy (see the module docstring) into `folder` as an mf-envs policy of
    `env`'s spaces; returns the files written."""
    from safetensors.torch import save_file

    state, kwargs = sb3_state(algo.get_module(), env)
    folder.mkdir(parents=True, exist_ok=True)
    desc = {
        "format": FORMAT,
        "algo": "PPO",
        "policy": "MlpPolicy",
        "observation_space": space_json(env.observation_space),
        "action_space": space_json(env.action_space),
        "policy_kwargs": kwargs,
        "use_sde": False,
        "source": "rllib",
    }
    write_atomic(folder / POLICY_FILE, json.dumps(desc, indent=1) + "\n", "policy")
    with atomic_path(folder / WEIGHTS_FILE, "policy") as tmp:
        save_file({k: v.contiguous() for k, v in state.items()}, tmp)
    files = [folder / POLICY_FILE, folder / WEIGHTS_FILE]
    stats = filter_statistics(algo)
    if stats is not None:
        mean, std, clip = stats
        norm = {
            "mean": mean.tolist(),
            "var": ((std + RLLIB_SMALL_NUMBER) ** 2).tolist(),
            "epsilon": 1e-300,
            "clip_obs": clip if np.isfinite(clip) else 1e300,
        }
        write_atomic(folder / NORM_FILE, json.dumps(norm, indent=1), "policy")
        files.append(folder / NORM_FILE)
    write_atomic(folder / META_FILE, json.dumps(meta, indent=1, default=str) + "\n", "policy")
    return [*files, folder / META_FILE]


def sb3_state(module: Any, env: Any) -> tuple[dict[str, Any], dict[str, Any]]:
    """(state dict of an SB3 ActorCriticPolicy, its policy_kwargs) holding the RLlib module's
    weights as the module docstring maps them; ValueError for another module layout."""
    import torch
    from stable_baselines3.common.policies import ActorCriticPolicy

    cfg = module.model_config
    hidden = [int(h) for h in cfg["fcnet_hiddens"]]
    if cfg.get("fcnet_activation") != "tanh" or not cfg.get("vf_share_layers", False):
        raise ValueError("rllib: export needs the default PPO module (tanh, shared encoder)")
    sd = {k: v.detach().cpu() for k, v in module.state_dict().items()}
    enc = sorted({k.rsplit(".", 2)[0] for k in sd if k.startswith("encoder.")})
    if len(enc) != 1:
        raise ValueError(f"rllib: unexpected encoder layout {enc}")
    n_act = int(np.prod(env.action_space.shape))
    kwargs = {"net_arch": {"pi": hidden, "vf": hidden}, "activation_fn": "Tanh"}
    pol = ActorCriticPolicy(env.observation_space, env.action_space, lambda _: 0.0,
                            net_arch=kwargs["net_arch"], activation_fn=torch.nn.Tanh)  # fmt: skip
    state = pol.state_dict()
    for i in range(len(hidden)):
        for part in ("weight", "bias"):
            w = sd[f"{enc[0]}.{2 * i}.{part}"]
            state[f"mlp_extractor.policy_net.{2 * i}.{part}"] = w.clone()
            state[f"mlp_extractor.value_net.{2 * i}.{part}"] = w.clone()
    head_w, head_b = sd["pi.net.mlp.0.weight"], sd["pi.net.mlp.0.bias"]
    if head_w.shape[0] != 2 * n_act:
        raise ValueError(f"rllib: the pi head has {head_w.shape[0]} outputs, not 2 x {n_act}")
    state["action_net.weight"], state["action_net.bias"] = head_w[:n_act], head_b[:n_act]
    state["log_std"] = head_b[n_act:].clone()
    vf = [k for k in sd if k.startswith("vf.") and k.endswith(".weight")]
    if len(vf) == 1:
        state["value_net.weight"], state["value_net.bias"] = sd[vf[0]], sd[vf[0][:-6] + "bias"]
    else:  # an inference-only module has no value head; acting does not use it
        state["value_net.weight"] = torch.zeros_like(state["value_net.weight"])
        state["value_net.bias"] = torch.zeros_like(state["value_net.bias"])
    pol.load_state_dict(state, strict=True)  # every key mapped, every shape right
    return pol.state_dict(), kwargs
