"""RLlib (Ray) PPO for the mf_envs environments: `mf-envs train ENV_ID --backend rllib`.

`register_rllib_envs()` registers every mf_envs id with `ray.tune.registry.register_env` under
the same name as in Gymnasium. The creator returns a single env, or (when RLlib passes
`num_envs` in the env config, i.e. with `gym_env_vectorize_mode="vector_entry_point"`) the env's
native batched vector env (`gym.make_vec(..., vectorization_mode="vector_entry_point")`).

Native vector envs: RLlib >= 2.4x's `SingleAgentEnvRunner` builds its env with
`gym.make_vec(name, num_envs=num_envs_per_env_runner, vectorization_mode=mode)`, and the
VECTOR_ENTRY_POINT mode hands the whole batch to our creator. Our vector envs use Gymnasium's
NEXT_STEP autoreset, the semantics the runner expects (the step after a done one is the reset
observation), and batched dict infos, which the runner's `DictInfoToList` unpacks. Scenes without
a native vector env (Inchworm-v0 without `friction`) run with RLlib's SYNC vectorisation of
single envs.

`_BASE` with the env declaration's `rllib` overrides (`env_overrides`) is the documented per-env
starting point. Its keys (all optional except those `_BASE` supplies): `timesteps` (training
budget), `num_env_runners` (Ray actors sampling in parallel), `num_envs_per_env_runner`
(sub-envs per runner, batched in one native call),
`train_batch_size_per_learner`, `minibatch_size`, `num_epochs`, `lr`, `gamma`, `lambda_`,
`clip_param`, `entropy_coeff`, `vf_clip_param`, `fcnet_hiddens`, `sample_timeout_s`,
`mean_std_filter` (observation normalisation, RLlib's `MeanStdFilter` connector, the counterpart
of SB3's `VecNormalize`), `env_kwargs`. Discounts and GAE follow the SB3 configs
(`train/configs/ppo.yml`), which were tuned on this machine; the RLlib budgets are NOT tuned
(an iteration is a working default).
`--config FILE` takes a YAML mapping env id -> any of these keys (read with `yaml.safe_load`).
"""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path
from typing import Any

import gymnasium as gym

from mf_envs import _ray
from mf_envs._files import make_dirs
from mf_envs.train.kwargs import MAX_LAYERS, MAX_UNITS

_BASE: dict[str, Any] = {
    "timesteps": 200_000,
    "num_env_runners": 2,
    "num_envs_per_env_runner": 4,
    "train_batch_size_per_learner": 4000,
    "minibatch_size": 250,
    "num_epochs": 10,
    "lr": 3e-4,
    "gamma": 0.99,
    "lambda_": 0.95,
    "clip_param": 0.2,
    "entropy_coeff": 0.0,
    "vf_clip_param": 1e4,  # value targets are not normalised: do not clip the value loss
    "fcnet_hiddens": [64, 64],
    "mean_std_filter": True,
    "env_kwargs": {},
    # a fresh install compiles the numba kernels in each runner on its first step (minutes)
    "sample_timeout_s": 900.0,
}


def env_overrides(env_id: str) -> dict[str, Any]:
    """The env's documented starting point: its declaration's `rllib` overrides of `_BASE`."""
    from mf_envs.envs import declaration

    decl = declaration(env_id)
    return {} if decl is None else dict(decl.rllib)


def require_ray() -> Any:
    """The `ray` module with RLlib, or a ValueError whose one line says what to install."""
    return _ray.require_ray(rllib=True)


def has_native_vector_env(env_id: str, env_kwargs: dict[str, Any] | None = None) -> bool:
    """A native vector env that runs this scene (the inchworm's: the friction scene only)."""
    import mf_envs  # noqa: F401
    from mf_envs.envs import native_vector_supported

    spec = gym.spec(env_id)
    return spec.vector_entry_point is not None and native_vector_supported(env_id, env_kwargs)


def make_env(env_id: str, env_config: dict[str, Any]) -> gym.Env | gym.vector.VectorEnv:
    """RLlib's env creator: a single env, or the native vector env if `num_envs` is given."""
    import mf_envs  # noqa: F401  (registers the ids in a fresh Ray worker)

    kwargs = dict(env_config)
    n = kwargs.pop("num_envs", None)
    if n is None:
        return gym.make(env_id, **kwargs)
    mode = "vector_entry_point" if has_native_vector_env(env_id, kwargs) else "sync"
    return gym.make_vec(env_id, num_envs=int(n), vectorization_mode=mode, **kwargs)


def register_rllib_envs() -> list[str]:
    """Register every mf_envs id with RLlib (`register_env`, same names); the ids."""
    require_ray()
    from ray.tune.registry import register_env

    from mf_envs.envs import available_env_ids

    ids = available_env_ids()
    for env_id in ids:
        register_env(env_id, lambda cfg, env_id=env_id: make_env(env_id, cfg))
    return ids


def _checks() -> dict[str, Any]:
    """The type and range of each `_BASE` key (the SB3 config's checkers)."""
    from mf_envs.train.config_check import FLAG, number, whole

    def hiddens(v: Any) -> str | None:
        ok = isinstance(v, list) and 0 < len(v) <= MAX_LAYERS
        ok = ok and all(whole(1, MAX_UNITS)(n) is None for n in v)
        return None if ok else f"a list of 1..{MAX_LAYERS} layer sizes in [1, {MAX_UNITS}]"

    def mapping(v: Any) -> str | None:
        ok = isinstance(v, dict) and all(isinstance(k, str) for k in v)
        return None if ok else "a mapping of env kwargs"

    return {
        "timesteps": whole(1, 10**10), "num_env_runners": whole(0, 256),
        "num_envs_per_env_runner": whole(1, 1024),
        "train_batch_size_per_learner": whole(1, 10**7), "minibatch_size": whole(1, 10**7),
        "num_epochs": whole(1, 1000), "lr": number(0.0, 1.0, lo_open=True),
        "gamma": number(0.0, 1.0), "lambda_": number(0.0, 1.0),
        "clip_param": number(0.0, 1e6, lo_open=True), "entropy_coeff": number(0.0, 1e6),
        "vf_clip_param": number(0.0, 1e300, lo_open=True), "fcnet_hiddens": hiddens,
        "mean_std_filter": FLAG, "env_kwargs": mapping,
        "sample_timeout_s": number(0.0, 1e6, lo_open=True),
    }  # fmt: skip


def ppo_settings(env_id: str, overrides: dict[str, Any] | None = None) -> dict[str, Any]:
    """`_BASE | env_overrides(env_id) | overrides`; ValueError naming an unknown key or a value
    of the wrong type or range."""
    out = {**_BASE, **env_overrides(env_id)}
    bad = sorted(str(k) for k in set(overrides or {}) - set(_BASE))
    if bad:
        raise ValueError(f"config: unknown RLlib PPO key(s) {bad}; known: {sorted(_BASE)}")
    checks = _checks()
    for key, value in (overrides or {}).items():
        expected = checks[key](value)
        if expected is not None:
            raise ValueError(f"config: {env_id}: {key} must be {expected}, got {value!r}"[:300])
    return {**out, **(overrides or {})}


def ppo_config(env_id: str, seed: int = 0, **overrides: Any) -> Any:
    """An RLlib `PPOConfig` (new API stack) for `env_id`; see the module docstring for keys."""
    require_ray()
    from ray.rllib.algorithms.ppo import PPOConfig
    from ray.rllib.core.rl_module.default_model_config import DefaultModelConfig

    register_rllib_envs()
    s = ppo_settings(env_id, overrides)
    native = has_native_vector_env(env_id, s["env_kwargs"])
    connector = None
    if s["mean_std_filter"]:
        from ray.rllib.connectors.env_to_module.mean_std_filter import MeanStdFilter

        connector = _mean_std_filter(MeanStdFilter)
    return (
        PPOConfig()
        .environment(env_id, env_config=dict(s["env_kwargs"]))
        .env_runners(
            num_env_runners=s["num_env_runners"],
            num_envs_per_env_runner=s["num_envs_per_env_runner"],
            gym_env_vectorize_mode="vector_entry_point" if native else "sync",
            env_to_module_connector=connector,
            sample_timeout_s=s["sample_timeout_s"],
        )
        .training(
            train_batch_size_per_learner=s["train_batch_size_per_learner"],
            minibatch_size=s["minibatch_size"],
            num_epochs=s["num_epochs"],
            lr=s["lr"],
            gamma=s["gamma"],
            lambda_=s["lambda_"],
            clip_param=s["clip_param"],
            entropy_coeff=s["entropy_coeff"],
            vf_clip_param=s["vf_clip_param"],
        )
        .rl_module(model_config=DefaultModelConfig(fcnet_hiddens=list(s["fcnet_hiddens"])))
        .debugging(seed=seed)
    )


def _mean_std_filter(cls: Any) -> Any:
    def connector(env: Any, spaces: Any = None, device: Any = None) -> Any:
        return cls()

    return connector


def init_ray(num_cpus: int = 2) -> bool:
    """Start a small local Ray (`mf_envs._ray.init_local_ray`) unless one is running; True if
    this call started it."""
    ray = require_ray()
    if ray.is_initialized():
        return False
    _ray.init_local_ray(num_cpus)
    return True


def _metric(result: dict[str, Any], key: str) -> float:
    for where in (result.get("env_runners", {}), result):
        if key in where:
            return float(where[key])
    return float("nan")


def train(
    env_id: str,
    timesteps: int | None = None,
    seed: int = 0,
    out: str | Path = "runs",
    config: str | Path | None = None,
    iterations: int | None = None,
    **overrides: Any,
) -> tuple[Path, list[dict[str, float]]]:
    """Train RLlib PPO until `timesteps` env steps (or `iterations`); (run dir, history).

    Writes `<out>/<env_id>_rllib_seed<seed>/`: the policy in the project's format
    (`policy.json`, `policy.safetensors`, `obs_normalization.json`; `train.rllib_export`), which
    `evaluate`, `render` and `load_policy` read, `checkpoint/` (`Algorithm.save_to_path`, RLlib's
    own, pickle-based) and `meta.json` (settings, Ray version, per-iteration steps and mean
    episode return, wall time). A budget below one training batch trains one batch of that size.
    """
    ray = require_ray()
    settings = ppo_settings(env_id, {**_read_overrides(env_id, config), **overrides})
    budget = int(timesteps if timesteps is not None else settings["timesteps"])
    if budget < 1:
        raise ValueError(f"timesteps: must be >= 1, got {budget}")
    # a budget below one training batch runs one batch of the budget's size (not a whole batch)
    batch = min(int(settings["train_batch_size_per_learner"]), budget)
    settings["train_batch_size_per_learner"] = batch
    settings["minibatch_size"] = min(int(settings["minibatch_size"]), batch)
    started = init_ray(num_cpus=max(2, settings["num_env_runners"]))
    history: list[dict[str, float]] = []
    t0 = time.perf_counter()
    algo = ppo_config(env_id, seed=seed, **{k: v for k, v in settings.items()}).build_algo()
    try:
        while (iterations is None and (not history or history[-1]["steps"] < budget)) or (
            iterations is not None and len(history) < iterations
        ):
            r = algo.train()
            history.append(
                {
                    "iteration": len(history) + 1,
                    "steps": _metric(r, "num_env_steps_sampled_lifetime"),
                    "episode_return_mean": _metric(r, "episode_return_mean"),
                    "wall_s": time.perf_counter() - t0,
                }
            )
        run_dir = make_dirs(out, Path(out) / f"{env_id}_rllib_seed{seed}")  # no planted link
        algo.save_to_path(str((run_dir / "checkpoint").resolve()))
        meta = {"env_id": env_id, "backend": "rllib", "ray": ray.__version__, "seed": seed}
        meta |= {"timesteps_asked": budget, "settings": settings, "history": history}
        from mf_envs.train.rllib_export import export_policy

        env = gym.make(env_id, **settings["env_kwargs"])
        export_policy(algo, env, run_dir, meta)  # the safe policy format evaluate/render read
        env.close()
    finally:
        algo.stop()
        if started:
            ray.shutdown()
    return run_dir, history


def _read_overrides(env_id: str, path: str | Path | None) -> dict[str, Any]:
    """The `env_id` entry of a YAML file mapping env ids to RLlib PPO keys ({} if absent)."""
    from mf_envs.train.config import read_config

    return {} if path is None else dict(read_config(path).get(env_id, {}))


def train_command(args: argparse.Namespace) -> list[Path]:
    """`mf-envs train ENV_ID --backend rllib [--timesteps N] [--seed S] [--config FILE]`."""
    require_ray()
    from mf_envs.train.trainer import check_env_id

    if getattr(args, "algo", "ppo") != "ppo":
        raise ValueError(f"algo: the RLlib backend trains PPO only, got {args.algo!r}")

    check_env_id(args.env_id)
    run_dir, hist = train(args.env_id, args.timesteps, args.seed, args.out, args.config)
    print(summary(args.env_id, hist, run_dir))
    return [run_dir / "meta.json"]


def summary(env_id: str, hist: list[dict[str, float]], run_dir: Path) -> str:
    """One line: steps, time, iterations and the last mean episode return that RLlib measured
    (or that no episode ended yet: RLlib reports nan then)."""
    last = hist[-1]
    returns = [h["episode_return_mean"] for h in hist if math.isfinite(h["episode_return_mean"])]
    ret = (
        f"mean episode return {returns[-1]:.4g}"
        if returns
        else "no episode ended yet (no return to report)"
    )
    return (
        f"{env_id} (RLlib PPO): {last['steps']:.0f} steps in {last['wall_s']:.0f} s, "
        f"{len(hist)} iteration(s), {ret}; policy (mf-envs format) and checkpoint in {run_dir}"
    )
