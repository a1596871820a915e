"""Wire env -> SB3 PPO -> callbacks; save the run; evaluate it against the default baseline.

A run folder `<out>/<env_id>/seed<S>/` holds the policy files described in `train.policy`, a
`best/` folder (the EvalCallback's best model with the normalisation statistics of that moment),
`evaluations.npz` and `learning_curve.png`. `ship_run` copies a run into
`mf_envs/train/policies/<env_id>/`.
"""

from __future__ import annotations

import functools
import importlib.util
import json
import platform
import shutil
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

import gymnasium as gym

from mf_envs._files import atomic_path, inside, make_dirs
from mf_envs._staging import moved, staged_dir
from mf_envs.train.config import (
    ALGOS,
    Hyperparams,
    check_algo_kwargs,
    default_config,
    load_hyperparams,
    resolve_schedules,
    wrapper_class,
)
from mf_envs.train.evaluate import baseline_factories, evaluate_controllers, primary_metric, score
from mf_envs.train.policy import (
    POLICY_FILE,
    POLICY_ROOT,
    load_policy,
    read_meta,
    save_policy,
    write_meta,
)
from mf_envs.train.provenance import env_record

# unseen seeds: training envs use seed, seed + 1, ...; the EvalCallback env seed + 10_000
EVAL_SEEDS = tuple(range(1000, 1005))
EVALS_PER_RUN = 12  # evaluation checks per run (learning-curve points)
SHIP_FILES = (
    "policy.json",
    "policy.safetensors",
    "obs_normalization.json",
    "evaluations.npz",
    "meta.json",
)


@dataclass
class TrainResult:
    run_dir: Path
    files: list[Path]
    meta: dict[str, Any]


def check_env_id(env_id: str) -> None:
    """ValueError (listing the known mf_envs ids) unless `env_id` is a registered Gymnasium id."""
    import mf_envs  # noqa: F401  (registers the available ids)
    from mf_envs.envs import ENV_SPECS, task_ids

    if env_id in gym.registry:
        return
    extra = " (its module is not installed yet)" if env_id in ENV_SPECS else ""
    raise ValueError(f"env_id: unknown {env_id!r}{extra}; available: {task_ids()}")


def train(
    env_id: str,
    *,
    timesteps: int | None = None,
    seed: int = 0,
    config: str | Path | None = None,
    out: str | Path = "runs",
    tensorboard: bool = False,
    progress_bar: bool = True,
    eval_episodes: int = 5,
    vec_env: str = "auto",
    final_eval_seeds: tuple[int, ...] = EVAL_SEEDS,
    overrides: dict[str, Any] | None = None,
    force: bool = False,
    algo: str = "ppo",
    evaluations: int = EVALS_PER_RUN,
) -> TrainResult:
    """Train `algo` (SB3 "ppo", "sac" or "td3") on `env_id` with the YAML hyperparameters
    (default `configs/<algo>.yml`); returns the run folder and files.

    `overrides`: algorithm kwargs replacing the config's (tests use a tiny `policy_kwargs`);
    `eval_episodes`: per evaluation check (rl-zoo3's default, 5; one per row of the
    evaluation env); `vec_env`: "auto" (the env's
    native vector env where it has one, else `DummyVecEnv`) or "dummy" (the zoo's `--vec-env
    dummy`); `evaluations`: checks during training (the learning curve and the `best/` policy;
    0: none, the benchmark's setting); `final_eval_seeds`: episodes scored after training for
    meta.json (empty: skip).
    The run is written into a temporary folder beside `<out>/<env_id>/seed<S>/` (SAC and TD3:
    `<out>/<env_id>/<algo>/seed<S>/`) and moved there when complete; an existing run folder is
    replaced only with `force` (ValueError otherwise).
    """
    hp, Algo, total = _prepare(env_id, algo, config, overrides, timesteps, eval_episodes, vec_env)
    import torch

    tb_dir = _tensorboard_dir(out, env_id) if tensorboard else None
    if seed < 0:
        raise ValueError(f"seed: must be >= 0, got {seed}")
    if evaluations < 0:
        raise ValueError(f"evaluations: must be >= 0, got {evaluations}")
    final = Path(out) / env_id / ("" if algo == "ppo" else algo) / f"seed{seed}"
    if progress_bar and importlib.util.find_spec("rich") is None:
        progress_bar = False  # SB3's bar needs tqdm and rich; train without it
    with staged_dir(final, replace=True, force=force, root=Path(out)) as run_dir:
        torch.set_num_threads(1)  # tiny MLPs: one thread is fastest and leaves the other core free

        venv, vec_kind, eval_env = _make_envs(hp, seed, vec_env == "auto", eval_episodes)
        model = _model(Algo, hp, venv, seed, tb_dir, overrides)
        meta_run = _learn(model, eval_env, run_dir, hp, (total, evaluations), progress_bar)
        command = _command(env_id, timesteps, seed, config, eval_episodes, vec_env, algo)
        meta = {"env_id": env_id, "algo": algo, "command": command, "seed": seed,
                **meta_run.pop("run"), "vectorization": f"{vec_kind} x{hp.n_envs}",
                "selected": "final", "hyperparams": _jsonable_hp(hp, overrides, total),
                "versions": _versions(), **env_record(env_id, hp.env_kwargs)}  # fmt: skip
        vecnorm = venv if hp.normalize is not None else None
        files = save_policy(run_dir, model, vecnorm, meta)
        venv.close()
        eval_env.close()
        if (run_dir / "best" / POLICY_FILE).is_file():
            best_meta = {**meta, "selected": "best (EvalCallback return, seeds 10000+)"}
            files.append(write_meta(run_dir / "best", {**best_meta, **meta_run}))
        files += _finish_run(env_id, run_dir, final_eval_seeds)
    return TrainResult(final, moved(files, run_dir, final), read_meta(final))


def _model(Algo: Any, hp: Any, venv: Any, seed: int, tb_dir: Any, overrides: Any) -> Any:
    """The SB3 model on `venv` with the config's kwargs (schedules resolved, `overrides` last)
    and, for SAC/TD3, the zoo's action noise."""
    kwargs = resolve_schedules({**hp.ppo_kwargs, **(overrides or {})})
    if hp.action_noise is not None:
        kwargs["action_noise"] = _action_noise(hp.action_noise, venv.action_space)
    return Algo(hp.policy, venv, seed=seed, device="cpu", tensorboard_log=tb_dir, **kwargs)


def _prepare(
    env_id: str,
    algo: str,
    config: str | Path | None,
    overrides: dict[str, Any] | None,
    timesteps: int | None,
    eval_episodes: int,
    vec_env: str,
) -> tuple[Any, Any, int]:
    """(hyperparameters, SB3 algorithm class, step budget), every argument checked. The config
    first: a bad file is refused before torch and SB3 are imported (seconds)."""
    check_env_id(env_id)
    if algo not in ALGOS:
        raise ValueError(f"algo: one of {ALGOS}, got {algo!r}")
    hp = load_hyperparams(env_id, config if config is not None else default_config(algo))
    Algo = _algorithm(algo)
    check_algo_kwargs(Algo, {**hp.ppo_kwargs, **(overrides or {})}, env_id)
    return hp, Algo, _budget(hp, timesteps, eval_episodes, vec_env)


def _learn(
    model: Any,
    eval_env: Any,
    run_dir: Path,
    hp: Any,
    budget: tuple[int, int],
    progress_bar: bool,
) -> dict[str, Any]:
    """`model.learn` for `budget` = (steps, checks) with a `PeriodicEvaluation` (the checks, the
    best policy saved to run_dir/best; no checks: none); {"run": timesteps, wall time,
    steps/s} plus the best checkpoint's step and return."""
    from mf_envs.train.callbacks import PeriodicEvaluation

    n_steps = int(getattr(model, "n_steps", 1))  # PPO: one rollout; SAC/TD3: any step
    total, checks = budget
    freq = max(total // (max(checks, 1) * hp.n_envs), n_steps) if checks > 0 else 0
    eval_cb = PeriodicEvaluation(eval_env, freq, run_dir, run_dir / "best")
    t0 = time.perf_counter()
    model.learn(total_timesteps=total, callback=eval_cb, progress_bar=progress_bar)
    wall = time.perf_counter() - t0
    run = {
        "timesteps": int(model.num_timesteps),
        "wall_time_s": round(wall, 2),
        "steps_per_s": round(model.num_timesteps / wall, 1),
    }
    best_return = float(eval_cb.best_mean_reward) if eval_cb.timesteps else None
    best = {"best_timestep": eval_cb.best_timestep, "best_eval_return": best_return}
    return {"run": run, **best}


def _finish_run(env_id: str, run_dir: Path, seeds: tuple[int, ...]) -> list[Path]:
    """Score the final and the best model on `seeds` into their meta.json; learning curves."""
    from mf_envs.train.curves import plot_learning_curves

    files = []
    for folder in (run_dir, run_dir / "best"):
        if not (folder / POLICY_FILE).is_file():
            continue
        meta = read_meta(folder)
        if seeds:
            meta["evaluation"] = evaluation_summary(env_id, folder, seeds)
            write_meta(folder, meta)
        if (run_dir / "evaluations.npz").is_file():
            if folder != run_dir:
                files.append(Path(shutil.copy2(run_dir / "evaluations.npz", folder)))
            ev = meta.get("evaluation", {})
            refs = {f"{k} (final eval)": v["return"] for k, v in ev.items() if isinstance(v, dict)}
            label = (
                f"{meta.get('algo', 'ppo')} (EvalCallback); shipped: {meta['selected'].split()[0]}"
            )
            path = folder / "learning_curve.png"
            files.append(plot_learning_curves([run_dir], path, env_id, [label], refs))
    return files


def evaluation_summary(env_id: str, run_dir: Path, seeds: tuple[int, ...]) -> dict[str, Any]:
    """Primary metric of the run's policy and of the env's default baseline on `seeds`."""
    metric = primary_metric(env_id)
    algo = read_meta(run_dir).get("algo", "ppo")  # the label of the trained policy's rows
    ctrls: dict[str, Any] = {algo: lambda env: load_policy(env_id, run_dir)}
    baselines = baseline_factories(env_id)
    if baselines:
        name = next(iter(baselines))
        ctrls[name] = baselines[name]
    rows = evaluate_controllers(env_id, ctrls, seeds)
    summary: dict[str, Any] = {"metric": metric.name, "higher_is_better": metric.higher_is_better}
    summary["seeds"] = list(seeds)
    for name in ctrls:
        summary[name] = dict(zip(("mean", "std"), score(rows, name, metric.name)))
        summary[name]["return"] = score(rows, name, "return")[0]
    return summary


def ship_run(run_dir: str | Path, root: Path = POLICY_ROOT) -> list[Path]:
    """Copy a run's policy files into `root/<env_id>/` (the shipped policy); returns them."""
    run_dir = Path(run_dir)
    meta = read_meta(run_dir)
    if "env_id" not in meta:
        raise ValueError(f"run_dir: {run_dir} has no meta.json with an env_id")
    dest = inside(root, Path(root) / meta["env_id"], f"{run_dir}/meta.json: env_id")
    make_dirs(root, Path(root) / meta["env_id"])  # a link in place of the folder is refused
    out = []
    for name in SHIP_FILES:
        if (run_dir / name).is_file():
            with atomic_path(dest / name) as tmp:  # never copied through a link at dest
                shutil.copy2(run_dir / name, tmp)
            out.append(dest / name)
    return out


def _algorithm(algo: str) -> Any:
    """The SB3 (or, "sbx_<name>", SBX) class of `algo` (one of ALGOS, checked by the caller);
    ModuleNotFoundError naming the `sbx` extra if SBX is missing."""
    if algo.startswith("sbx_"):
        from mf_envs._extras import install_hint

        try:
            import sbx
        except ModuleNotFoundError as exc:
            raise ModuleNotFoundError(
                f"algo {algo}: needs the sbx extra ({exc.name} is missing): {install_hint('sbx')}",
                name=exc.name,
            ) from exc
        return getattr(sbx, algo.removeprefix("sbx_").upper())
    import stable_baselines3

    return getattr(stable_baselines3, algo.upper())


def _action_noise(noise: tuple[str, float], space: Any) -> Any:
    """The zoo's action noise for SAC/TD3: zero mean, `std` in every action dimension."""
    import numpy as np
    from stable_baselines3.common.noise import NormalActionNoise, OrnsteinUhlenbeckActionNoise

    kind, std = noise
    n = int(np.prod(space.shape))
    cls = NormalActionNoise if kind == "normal" else OrnsteinUhlenbeckActionNoise
    return cls(mean=np.zeros(n), sigma=std * np.ones(n))


def _budget(hp: Hyperparams, timesteps: int | None, eval_episodes: int, vec_env: str) -> int:
    """The steps to train (`timesteps`, else the config's n_timesteps), after checking the
    command-line options; ValueError naming the option."""
    if vec_env not in ("auto", "dummy"):
        raise ValueError(f"vec-env: 'auto' or 'dummy', got {vec_env!r}")
    if eval_episodes < 1:
        raise ValueError(f"eval-episodes: must be >= 1, got {eval_episodes}")
    if timesteps is None and hp.n_timesteps is None:
        raise ValueError(f"config: {hp.env_id} has no n_timesteps; give --timesteps")
    total = int(timesteps if timesteps is not None else hp.n_timesteps)
    if total <= 0:
        raise ValueError(f"timesteps: must be positive, got {total}")
    return total


def _make_envs(
    hp: Hyperparams, seed: int, prefer_native: bool, eval_rows: int = 1
) -> tuple[Any, str, Any]:
    """(training VecEnv, its vectorisation label, evaluation VecEnv on default parameters with
    `eval_rows` envs: the EvalCallback's episodes run side by side, one per row)."""
    from mf_envs.train.vec import make_train_env

    wrappers = [
        functools.partial(wrapper_class(path), **kw) if kw else wrapper_class(path)
        for path, kw in hp.env_wrappers
    ]
    venv, kind = make_train_env(
        hp.env_id,
        hp.n_envs,
        seed,
        hp.env_kwargs,
        wrappers=wrappers,
        normalize=hp.normalize,
        prefer_native=prefer_native,
    )
    norm_eval = None if hp.normalize is None else {**hp.normalize, "norm_reward": False}
    # the same wrapper layout as training (SB3 syncs the VecNormalize stats layer by layer)
    eval_env, _ = make_train_env(
        hp.env_id,
        eval_rows,
        seed + 10_000,
        hp.env_kwargs,
        normalize=norm_eval,
        prefer_native=kind == "native",
    )
    if norm_eval is not None:
        eval_env.training = False
    return venv, kind, eval_env


def _tensorboard_dir(out: str | Path, env_id: str) -> str:
    try:
        import tensorboard  # noqa: F401
    except ImportError:
        raise ValueError(
            "tensorboard: the package is not installed (pip install tensorboard, or the "
            'extra: pip install "mf-envs[tensorboard]"), or run without --tensorboard'
        ) from None
    return str(make_dirs(out, Path(out) / env_id / "tensorboard"))


def _command(
    env_id: str,
    timesteps: int | None,
    seed: int,
    config: Any,
    eval_episodes: int,
    vec_env: str,
    algo: str = "ppo",
) -> str:
    parts = ["mf-envs", "train", env_id, "--seed", str(seed)]
    if algo != "ppo":
        parts += ["--algo", algo]
    if timesteps is not None:
        parts += ["--timesteps", str(timesteps)]
    if config is not None:
        parts += ["--config", str(config)]
    if eval_episodes != 5:
        parts += ["--eval-episodes", str(eval_episodes)]
    if vec_env != "auto":
        parts += ["--vec-env", vec_env]
    return " ".join(parts)


def _jsonable_hp(hp: Hyperparams, overrides: dict[str, Any] | None, total: int) -> dict[str, Any]:
    """The hyperparameters as run: n_timesteps is the budget trained (--timesteps wins)."""
    d = {**asdict(hp), "n_timesteps": total}
    d["ppo_kwargs"] = {**d["ppo_kwargs"], **(overrides or {})}
    return json.loads(json.dumps(d, default=repr))


def _versions() -> dict[str, str]:
    import numpy
    import stable_baselines3
    import torch

    return {
        "python": platform.python_version(),
        "stable_baselines3": stable_baselines3.__version__,
        "torch": torch.__version__,
        "gymnasium": gym.__version__,
        "numpy": numpy.__version__,
        **{name: _version_of(name) for name in ("sbx", "jax") if name in sys.modules},
    }


def _version_of(module: str) -> str:
    return str(getattr(sys.modules[module], "__version__", "unknown"))
