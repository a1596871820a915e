"""`mf-envs render ENV_ID [--policy baseline|baseline:KIND|ppo|PATH] --out FILE.gif`.

Runs one episode headless (render_mode="rgb_array") under a baseline controller, the shipped
PPO policy or a saved SB3 policy, and writes the frames as a GIF. User mistakes raise
ValueError (the CLI prints them as one line and exits with status 2). Runs longer than
`MAX_FRAMES` steps record every k-th step (GIF frame rate divided by k, playback speed kept).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path
from typing import Any

DEFAULT_STEPS = 300
MAX_FRAMES = 600  # longer runs record every k-th step


def _check_env_id(env_id: str) -> None:
    import gymnasium as gym

    import mf_envs  # noqa: F401  (registers the available ids)
    from mf_envs.envs import ENV_SPECS, declaration, task_ids

    if declaration(env_id) is None:
        known = task_ids() + [i for i in ENV_SPECS if i not in task_ids()]
        raise ValueError(f"env_id: unknown {env_id!r}; known: {', '.join(known)}")
    if env_id not in task_ids() or env_id not in gym.registry:
        raise ValueError(
            f"env_id: {env_id!r} is not available in this install; available: "
            f"{', '.join(task_ids()) or 'none'}"
        )


def make_policy(env: Any, env_id: str, policy: str) -> Any:
    """An object with `predict(obs, deterministic=True) -> (action, state)` for `policy`:
    "baseline" (the env's default controller), "baseline:KIND", "ppo" (the shipped policy,
    `train.load_policy`) or the path of a saved policy (a folder written by `mf-envs train`;
    pickle-based SB3 `model.zip` files are refused)."""
    if policy == "baseline" or policy.startswith("baseline:"):
        from mf_envs import controllers

        kind = policy.partition(":")[2] or None
        try:
            return controllers.make_baseline(env, kind)
        except ModuleNotFoundError as exc:  # the env landed before its controllers
            raise ValueError(f"policy: no baseline controllers for {env_id} yet ({exc})") from exc
    path = None
    if policy != "ppo":
        path = Path(policy)
        if not path.exists():
            raise ValueError(
                f"policy: expected baseline, baseline:KIND, ppo or the path of a saved policy "
                f"(a folder with policy.json), got {policy!r} (no such file)"
            )
    from mf_envs.train import load_policy

    return load_policy(env_id, path)  # ModuleNotFoundError -> one line naming the train extra


def render_command(args: argparse.Namespace) -> list[Path]:
    """Render one episode of `args.env_id` to the GIF `args.out`; returns [path]."""
    import gymnasium as gym
    from tqdm import tqdm

    from mf_envs._staging import staged_file
    from mf_envs.render import save_gif

    _check_env_id(args.env_id)
    out = Path(args.out)
    if out.suffix.lower() != ".gif":
        raise ValueError(f"out: expected a .gif path, got {str(out)!r}")
    if args.steps is not None and args.steps < 1:
        raise ValueError(f"steps: must be >= 1, got {args.steps}")
    if args.seed < 0:
        raise ValueError(f"seed: must be >= 0, got {args.seed}")
    with staged_file(out) as tmp:  # created now: an unwritable --out fails before the run
        env = gym.make(args.env_id, render_mode="rgb_array")
        try:
            policy = make_policy(env, args.env_id, args.policy)
            limit = env.spec.max_episode_steps if env.spec else None  # a TimeLimit's
            own = getattr(env.unwrapped, "max_episode_steps", None)  # an env that ends itself
            steps = args.steps or limit or own or DEFAULT_STEPS
            every = max(1, math.ceil(steps / MAX_FRAMES))  # keep memory bounded on long runs
            obs, _ = env.reset(seed=args.seed)
            if hasattr(policy, "reset"):
                policy.reset()
            frames = [env.render()]
            for i in tqdm(range(1, steps + 1), desc=f"render {args.env_id}", unit="step"):
                action, _ = policy.predict(obs, deterministic=True)
                obs, _, terminated, truncated, info = env.step(action)
                if info.get("numerical_failure"):  # the state is not finite: nothing to draw
                    msg = f"render {args.env_id}: numerical failure at step {i}, episode ended"
                    tqdm.write(msg, file=sys.stderr)
                    break
                if i % every == 0 or terminated or truncated:
                    frames.append(env.render())
                if terminated or truncated:
                    break
            fps = env.metadata.get("render_fps", 30) / every  # playback speed kept
        finally:
            env.close()
        save_gif(frames, tmp, fps=fps)
    return [out]
