"""`mf-envs train` and `mf-envs evaluate` (parsers in `mf_envs/cli/__init__.py`): thin wrappers."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from mf_envs.train.evaluate import (
    baseline_factories,
    evaluate_controllers,
    format_table,
    primary_metric,
    write_rows_csv,
)


def train_command(args: argparse.Namespace) -> list[Path]:
    """`mf-envs train ENV_ID [--timesteps N] [--seed S] [--config FILE] [--out DIR]
    [--tensorboard]`: train PPO, save the run, score it against the default baseline."""
    from mf_envs.train.trainer import train

    res = train(
        args.env_id,
        timesteps=args.timesteps,
        seed=args.seed,
        config=args.config,
        out=args.out,
        tensorboard=args.tensorboard,
        force=args.force,
        eval_episodes=args.eval_episodes,
        vec_env=args.vec_env,
        algo=args.algo,
    )
    m = res.meta
    print(
        f"{args.env_id}: {m['timesteps']} steps in {m['wall_time_s']:.0f} s "
        f"({m['steps_per_s']:.0f} steps/s, {m['vectorization']}); policy in {res.run_dir}"
    )
    from mf_envs.train.policy import read_meta

    for folder in (res.run_dir, res.run_dir / "best"):
        ev = read_meta(folder).get("evaluation")
        if ev:
            scores = ", ".join(
                f"{k} {v['mean']:.4g} ± {v['std']:.2g}"
                for k, v in ev.items()
                if isinstance(v, dict)
            )
            print(f"{folder.name}: {ev['metric']} on seeds {ev['seeds']}: {scores}")
    return res.files


def evaluate_command(args: argparse.Namespace) -> list[Path]:
    """`mf-envs evaluate ENV_ID [--policy PATH] [--episodes N] [--seed S] [--out DIR] [--force]`:
    PPO vs baselines; writes DIR/ENV_ID/evaluate.csv (DIR default `mf_envs_eval`)."""
    from mf_envs._staging import check_out, moved, staged_dir
    from mf_envs.train.policy import load_policy
    from mf_envs.train.trainer import check_env_id

    check_env_id(args.env_id)
    if args.episodes < 1:
        raise ValueError(f"episodes: must be >= 1, got {args.episodes}")
    if args.seed < 0:
        raise ValueError(f"seed: must be >= 0, got {args.seed}")
    target = check_out(Path(args.out)) / args.env_id
    # checked and created now: a bad --out fails before the episodes
    with staged_dir(target, replace=True, force=args.force, root=Path(args.out)) as tmp:
        rows = _evaluate_rows(args, load_policy(args.env_id, args.policy))
        files = [write_rows_csv(tmp / "evaluate.csv", rows)]
    return moved(files, tmp, target)


def _evaluate_rows(args: argparse.Namespace, policy: Any) -> list[dict[str, Any]]:
    """Rows of the shipped/given PPO policy and every baseline on the evaluation seeds."""
    seeds = list(range(args.seed, args.seed + args.episodes))
    train_seed = policy.meta.get("seed")
    if train_seed is not None and train_seed in seeds:
        print(f"warning: evaluation seeds {seeds} include the training seed {train_seed}")
    controllers = {"ppo": lambda env: policy, **baseline_factories(args.env_id)}
    rows = evaluate_controllers(args.env_id, controllers, seeds)
    print(format_table(rows, args.env_id))
    metric = primary_metric(args.env_id)
    print(f"({metric.name}: {'higher' if metric.higher_is_better else 'lower'} is better)")
    return rows
