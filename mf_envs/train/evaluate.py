"""One evaluation loop for PPO policies and classical baselines: unseen seeds -> metrics.

Every controller (an SB3-like object with `reset()` and `predict(obs, deterministic=True)`) runs
full episodes of `gym.make(env_id, **env_kwargs)` from `reset(seed=s)` for each seed; per
episode the env's metrics are computed from the SI quantities in `info` (docs/api.md keys), then
summarised as mean and sample std over seeds. Each env's metrics, and the primary one its issue
judges it by, are its declaration's (`episode_metrics` and `metric` in `envs/<env>/task.py`, the
same definitions as its own `benchmarks/controllers/<env>.py`); an id without a declaration
(e.g. Pendulum-v1) is judged by the undiscounted episode return.
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

from mf_envs._files import atomic_path
from mf_envs.envs.declaration import RETURN, Metric, base_metrics, declaration


def primary_metric(env_id: str) -> Metric:
    """The metric the issue's acceptance line judges `env_id` by (its declaration's; the episode
    return for an id without one)."""
    decl = declaration(env_id)
    return RETURN if decl is None else decl.metric


def episode_metrics(
    env_id: str, env: gym.Env, rewards: Sequence[float], infos: Sequence[dict[str, Any]]
) -> dict[str, float]:
    """Metrics of one finished episode (the env declaration's `metrics`). `infos[0]` is the reset
    info, `infos[1:]` the step infos."""
    decl = declaration(env_id)
    return base_metrics(rewards, infos) if decl is None else decl.metrics(env, rewards, infos)


def run_episode(env_id: str, env: gym.Env, controller: Any, seed: int) -> dict[str, float]:
    """Run one full episode from `reset(seed=seed)` with `controller`; its metrics."""
    obs, info = env.reset(seed=seed)
    controller.reset()
    rewards: list[float] = []
    infos = [info]
    done = False
    while not done:
        action, _ = controller.predict(obs, deterministic=True)
        obs, reward, terminated, truncated, info = env.step(action)
        rewards.append(float(reward))
        infos.append(info)
        done = terminated or truncated
    return episode_metrics(env_id, env, rewards, infos)


def episodes(
    env_id: str,
    factory: Callable[[gym.Env], Any],
    seeds: Iterable[int],
    env_kwargs: dict[str, Any] | None = None,
) -> list[dict[str, float]]:
    """Per-seed metrics of the controller `factory(env)` (made once, reset every episode)."""
    env = gym.make(env_id, **(env_kwargs or {}))
    try:
        ctrl = factory(env)
        return [run_episode(env_id, env, ctrl, s) for s in seeds]
    finally:
        env.close()


def summarize(
    env_id: str, scene: str, controller: str, per_seed: Sequence[dict[str, float]]
) -> list[dict[str, Any]]:
    """Rows `env_id, scene, controller, metric, mean, std (sample), n_seeds`, one per metric."""
    rows = []
    for metric in per_seed[0]:
        vals = np.array([m.get(metric, 0.0) for m in per_seed], dtype=float)
        std = float(vals.std(ddof=1)) if len(vals) > 1 else 0.0
        rows.append(
            {
                "env_id": env_id,
                "scene": scene,
                "controller": controller,
                "metric": metric,
                "mean": float(vals.mean()),
                "std": std,
                "n_seeds": len(vals),
            }
        )
    return rows


def evaluate_controllers(
    env_id: str,
    controllers: dict[str, Callable[[gym.Env], Any]],
    seeds: Iterable[int],
    env_kwargs: dict[str, Any] | None = None,
    scene: str = "default",
) -> list[dict[str, Any]]:
    """Rows `env_id, scene, controller, metric, mean, std, n_seeds` for each controller x metric.

    `controllers`: name -> factory(env) -> controller (made once per env, reset every episode).
    """
    seeds = list(seeds)
    rows: list[dict[str, Any]] = []
    for name, factory in controllers.items():
        rows += summarize(env_id, scene, name, episodes(env_id, factory, seeds, env_kwargs))
    return rows


def baseline_factories(env_id: str) -> dict[str, Callable[[gym.Env], Any]]:
    """`baseline:<kind>` -> factory for every registered classical baseline (default first)."""
    from mf_envs import controllers

    try:
        kinds = controllers.baseline_kinds(env_id)
    except (ValueError, ModuleNotFoundError):
        return {}
    return {
        f"baseline:{k}": (lambda env, k=k: controllers.make_baseline(env, kind=k)) for k in kinds
    }


def format_table(rows: Sequence[dict[str, Any]], env_id: str) -> str:
    """A text table: one line per (scene, controller), one column per metric, mean ± std."""
    primary = primary_metric(env_id).name
    metrics = sorted({r["metric"] for r in rows}, key=lambda m: (m != primary, m))
    lines: dict[tuple[str, str], dict[str, str]] = {}
    for r in rows:
        cell = f"{r['mean']:.4g} ± {r['std']:.2g}"
        lines.setdefault((r["scene"], r["controller"]), {})[r["metric"]] = cell
    head = ["scene", "controller", *metrics]
    body = [[s, c, *(cells.get(m, "") for m in metrics)] for (s, c), cells in lines.items()]
    widths = [max(len(str(x)) for x in col) for col in zip(head, *body)]
    fmt = "  ".join(f"{{:<{w}}}" for w in widths)
    n = rows[0]["n_seeds"] if rows else 0
    out = [f"{env_id}: mean ± std over {n} unseen seeds (primary metric: {primary})"]
    out += [fmt.format(*head), fmt.format(*("-" * w for w in widths))]
    out += [fmt.format(*b) for b in body]
    return "\n".join(out)


def write_rows_csv(path: Path, rows: Sequence[dict[str, Any]]) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    cols = ["env_id", "scene", "controller", "metric", "mean", "std", "n_seeds"]
    with atomic_path(path) as tmp, tmp.open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in r.items()})
    return path


def score(rows: Sequence[dict[str, Any]], controller: str, metric: str) -> tuple[float, float]:
    """(mean, std) of `metric` for `controller` in `rows` (NaN if absent)."""
    for r in rows:
        if r["controller"] == controller and r["metric"] == metric:
            return r["mean"], r["std"]
    return math.nan, math.nan
