"""Where a native vector env's step spends its CPU time: the compiled rows against the Python
around them (actions, info, masks, autoreset), on one thread.

    python tools/profile_step.py ENV_ID [--num-envs N] [--steps K] [--kw JSON]

Fixed random actions (seed 0), `num_threads=1`, process (CPU) time, so another process on the
machine slows the figures less than wall time would; the best of five windows of K steps.
The rows' time is what `RowBlocks.run` spends (the one compiled call per step, dispatch
included); the rest of `step` is the wrapper. Compare two commits by running this in turns.
"""

from __future__ import annotations

import argparse
import json
import time

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401  (registers the envs)


def profile(env_id: str, num_envs: int, steps: int, kw: dict) -> dict[str, float]:
    """CPU microseconds per step: whole step, the rows' compiled call, the wrapper (the
    difference), and env-steps per CPU second; the best of five windows."""
    env = gym.make_vec(
        env_id, num_envs, vectorization_mode="vector_entry_point", num_threads=1, **kw
    )
    env.reset(seed=0)
    rng = np.random.default_rng(0)
    shape = (num_envs, *env.single_action_space.shape)
    acts = [rng.uniform(-1, 1, shape).astype(np.float32) for _ in range(50)]
    run, spent = env.blocks.run, [0.0]

    def timed_run(*args):
        c0 = time.process_time()
        run(*args)
        spent[0] += time.process_time() - c0

    env.blocks.run = timed_run
    for k in range(max(5, steps // 5)):  # warm: compiled, caches filled
        env.step(acts[k % 50])
    best = None
    for _ in range(5):
        spent[0] = 0.0
        c0 = time.process_time()
        for k in range(steps):
            env.step(acts[k % 50])
        total = time.process_time() - c0
        if best is None or total < best[0]:
            best = (total, spent[0])
    env.close()
    total, rows = best
    us = 1e6 / steps
    return {"step_us": total * us, "rows_us": rows * us, "wrapper_us": (total - rows) * us,
            "env_steps_per_cpu_s": steps * num_envs / total}  # fmt: skip


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("env_id")
    p.add_argument("--num-envs", type=int, default=1024)
    p.add_argument("--steps", type=int, default=100)
    p.add_argument("--kw", default="{}", help="env kwargs as JSON")
    a = p.parse_args()
    r = profile(a.env_id, a.num_envs, a.steps, json.loads(a.kw))
    print(f"{a.env_id} N={a.num_envs}: step {r['step_us']:.0f} us = rows {r['rows_us']:.0f} us "
          f"+ wrapper {r['wrapper_us']:.0f} us; {r['env_steps_per_cpu_s']:,.0f} env-steps "
          "per CPU s")  # fmt: skip


if __name__ == "__main__":
    main()
