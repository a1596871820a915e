"""Environment throughput: every env id, single (gym.make) and native vector, against Gymnasium.

All rates come from ONE process, each candidate timed in rounds alternating with its reference
(best round of each) in CPU seconds of the stepping thread (`time.thread_time`; PPO: process
time with one torch thread), so that other jobs on a shared machine do not enter the figures.
Actions are pre-sampled (sampling a Box costs more than a cheap env step); resets at episode ends
are included, as in training.

Cases (columns `case, variant, steps_per_s, reference, reference_steps_per_s, ratio`, plus
`n_envs`, `bytes_per_env`, `target`, `meets_target` where they apply):

- `single_env`: `gym.make(id)` steps/s vs Pendulum-v1 (`ratio`) and Acrobot-v1 (`ratio_acrobot`);
  `bytes_per_env` = tracemalloc peak of make + reset. Gymnasium's own two are rows too.
- `vector_env`: `gym.make_vec(id, N, "vector_entry_point")` env-steps/s at N = 1, 64, 1024,
  8192 vs Pendulum-v1 through gym.make (a SyncVectorEnv of it runs at about its single-env rate);
  `bytes_per_env` = batch state bytes / N; `target`, `meets_target`: the throughput goal of each id
  (the env declaration's `vector_target`; single env: `single_target`).
- `effects`: the native vector env at N = 1024 (256 with --quick; single env for ids without
  one) with no effect, each effect alone, the default and every effect, each timed alternating
  with the no-effect env (the reference): `ratio` < 1 is the cost of the effect; an effect
  that is off costs nothing when `none` and single effects sit at ~1.
- `ppo`: SB3 PPO training steps/s (tiny MLP) on the native vector env via `train.vec`'s adapter
  vs the same env as SB3 `DummyVecEnv` of single envs (skipped without stable-baselines3).

Inchworm-v0's gait throughput and beam step time vs elements are `beam_elastica`'s rows (not
repeated here); Inchworm-v0 appears in `single_env` and `effects`.
"""

from __future__ import annotations

import importlib.util
import math
import os
import time
import tracemalloc
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs._files import save_figure
from mf_envs.envs import VECTOR_SPECS, available_env_ids, declaration

ORDER = 20
PENDULUM, ACROBOT = "Pendulum-v1", "Acrobot-v1"
# CPU seconds of the stepping thread: on a machine shared with other jobs, wall time measures the
# scheduler; the thread's CPU time measures the env (numba kernels run in the calling thread)
CLOCK = time.thread_time
TARGET_VECTOR = 1.0e6  # env-steps/s at N = 1024, the default target
# the throughput goals come from each env's declaration: `vector_target` (N, native vector env-
# steps/s, random actions, autoreset included; default TARGET_VECTOR at N = 1024), `single_target`
# (a multiple of Pendulum-v1 in the same run, or absolute steps/s), `vector_n_max` (the ladder's
# largest N for envs whose steps take ~1 ms: 8192 of them take seconds per step)
N_LADDER = (1, 8, 64, 256, 1024, 4096, 8192)
N_LADDER_QUICK = (1, 64, 1024, 8192)


def _decl(env_id: str) -> Any:
    return declaration(env_id)


def vector_targets() -> dict[str, tuple[int, float]]:
    """env id -> (N, goal) of every available env with a native vector env."""
    return {i: _decl(i).vector_target or (1024, TARGET_VECTOR) for i in _vector_ids()}


def _vector_ids() -> list[str]:
    return [
        i
        for i in available_env_ids()
        if i in VECTOR_SPECS and importlib.util.find_spec(VECTOR_SPECS[i].split(":")[0])
    ]


def _effect_sets(env_id: str) -> dict[str, tuple[str, ...]]:
    """variant -> effects: none, each alone, the default, all (from the env module)."""
    import importlib

    mod = importlib.import_module(gym.spec(env_id).entry_point.split(":")[0])
    avail = mod.AVAILABLE_EFFECTS
    sets = {"none": ()}
    sets.update({f"+{e}": (e,) for e in avail})
    sets["default"] = tuple(mod.DEFAULT_EFFECTS)
    sets["all"] = tuple(avail)
    return sets


# ---------------------------------------------------------------------- timers
def _actions(space: gym.Space, shape_n: tuple[int, ...], k: int, seed: int = 0) -> np.ndarray:
    """k pre-sampled actions (k, *shape_n, *space.shape) inside the action space."""
    rng = np.random.default_rng(seed)
    if isinstance(space, gym.spaces.Discrete):
        return rng.integers(0, space.n, (k, *shape_n)).astype(np.int64)
    lo, hi = space.low, space.high
    return rng.uniform(lo, hi, (k, *shape_n, *space.shape)).astype(space.dtype)


def single_rate(env: gym.Env, seconds: float) -> float:
    """steps/s of env.step with pre-sampled actions, resetting at episode ends."""
    acts = list(_actions(env.action_space, (), 256))
    env.reset(seed=0)
    env.step(acts[0])
    n, t0 = 0, CLOCK()
    while True:
        for a in acts[n % 256 : n % 256 + 16]:
            out = env.step(a)
            if out[2] or out[3]:
                env.reset()
        n += 16
        el = CLOCK() - t0
        if el >= seconds:
            return n / el


def vector_rate(venv: gym.vector.VectorEnv, seconds: float) -> float:
    """env-steps/s of venv.step (N envs per call) with pre-sampled batched actions (the env is
    reset on the first call only: a reset of 8192 envs goes through 8192 single-env resets)."""
    k = max(2, min(64, 2**20 // venv.num_envs))
    acts = _actions(venv.single_action_space, (venv.num_envs,), k)
    if not getattr(venv, "_bench_reset", False):
        venv.reset(seed=0)
        venv.step(acts[0])
        venv._bench_reset = True
    n, t0 = 0, CLOCK()
    while True:
        for a in acts:
            venv.step(a)
        n += len(acts)
        el = CLOCK() - t0
        if el >= seconds:
            return n * venv.num_envs / el


def side_by_side(cand: Callable[[], float], refs: list[Callable[[], float]], rounds: int):
    """Best of `rounds` alternating runs: (candidate rate, [reference rates])."""
    best_c, best_r = 0.0, [0.0] * len(refs)
    for _ in range(rounds):
        for j, ref in enumerate(refs):
            best_r[j] = max(best_r[j], ref())
        best_c = max(best_c, cand())
    return best_c, best_r


def make_bytes(env_id: str, **kw: Any) -> int:
    """tracemalloc peak (bytes) of gym.make(env_id) + reset."""
    tracemalloc.start()
    env = gym.make(env_id, **kw)
    env.reset(seed=0)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    env.close()
    return int(peak)


def _row(case, variant, rate, ref, ref_rate, **extra) -> dict[str, Any]:
    return dict(case=case, variant=variant, steps_per_s=rate, reference=ref,
                reference_steps_per_s=ref_rate, ratio=rate / ref_rate, **extra)  # fmt: skip


# ---------------------------------------------------------------------- cases
def single_rows(quick: bool) -> list[dict[str, Any]]:
    sec, rounds = (0.15, 4) if quick else (0.5, 6)
    pend, acro = gym.make(PENDULUM), gym.make(ACROBOT)
    refs = [lambda: single_rate(pend, sec), lambda: single_rate(acro, sec)]
    out = []
    for env_id in [PENDULUM, ACROBOT, *available_env_ids()]:
        env = gym.make(env_id)
        decl = _decl(env_id)
        s = sec * (4 if decl is not None and decl.slow else 1)
        rate, (rp, ra) = side_by_side(partial(single_rate, env, s), refs, rounds)
        row = _row("single_env", f"{env_id} gym.make", rate, PENDULUM, rp,
                   ratio_acrobot=rate / ra, acrobot_steps_per_s=ra, n_envs=1,
                   bytes_per_env=make_bytes(env_id), load=os.getloadavg()[0])  # fmt: skip
        if decl is not None and decl.single_target is not None:
            key, goal = decl.single_target
            row.update(target=f"{key} >= {goal:g}", meets_target=bool(row[key] >= goal))
        out.append(row)
        env.close()
    return out


def vector_rows(quick: bool) -> list[dict[str, Any]]:
    sec, rounds = (0.2, 3) if quick else (0.5, 6)
    pend = gym.make(PENDULUM)
    ref = [lambda: single_rate(pend, sec)]
    out = []
    for n in N_LADDER_QUICK if quick else N_LADDER:
        for env_id in _vector_ids():
            if n > (_decl(env_id).vector_n_max or n):
                continue
            venv = gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point")
            rate, (rp,) = side_by_side(partial(vector_rate, venv, sec), ref, rounds)
            nbytes = venv.unwrapped.state_nbytes() / n
            extra: dict[str, Any] = {"n_envs": n, "bytes_per_env": nbytes}
            at, goal = vector_targets()[env_id]
            if n == at:
                extra.update(target=goal, meets_target=bool(rate >= goal))
            out.append(_row("vector_env", f"{env_id} native N={n}", rate,
                            f"{PENDULUM} gym.make (1 env)", rp, load=os.getloadavg()[0],
                            **extra))  # fmt: skip
            venv.close()
    return out


def _effect_timer(env_id: str, n_vec: int, sec: float, effects: tuple[str, ...]):
    """A rate timer for env_id with these effects: native vector of n_vec envs, or single."""
    if n_vec:
        venv = gym.make_vec(env_id, n_vec, "vector_entry_point", effects=effects)
        return partial(vector_rate, venv, sec)
    return partial(single_rate, gym.make(env_id, effects=effects), sec)


def effect_rows(quick: bool) -> list[dict[str, Any]]:
    sec, n_vec = (0.12, 256) if quick else (0.4, 1024)
    out = []
    for env_id in available_env_ids():
        slow = _decl(env_id).slow  # its native vector env may run some scenes only
        native = env_id in _vector_ids() and not slow
        rounds = 1 if slow else (3 if quick else 4)
        make = partial(_effect_timer, env_id, n_vec if native else 0, sec)
        sets = _effect_sets(env_id)
        if slow and quick:
            sets = {k: v for k, v in sets.items() if k in ("none", "default", "all")}
        none = make(())
        how = f"native vector N={n_vec}" if native else "single env"
        for variant, effects in sets.items():
            rate, (ref,) = side_by_side(make(effects), [none], rounds)
            out.append(_row("effects", f"{env_id} {variant} ({how})", rate,
                            f"{env_id} no effect (alternated)", ref))  # fmt: skip
    return out


def ppo_rows(quick: bool) -> list[dict[str, Any]]:
    if importlib.util.find_spec("stable_baselines3") is None:
        return []
    import torch
    from gymnasium.vector import AutoresetMode
    from stable_baselines3 import PPO
    from stable_baselines3.common.env_util import make_vec_env

    from mf_envs.train.vec import GymVectorToSB3

    def native_sb3(env_id: str, n: int) -> GymVectorToSB3:
        mode = AutoresetMode.SAME_STEP  # train.vec adapts SAME_STEP (NEXT_STEP is the default)
        return GymVectorToSB3(gym.make_vec(env_id, n, "vector_entry_point", autoreset_mode=mode))

    torch.set_num_threads(1)
    n_envs, n_steps = 64, 32
    total = n_envs * n_steps * (2 if quick else 6)

    def train_rate(make: Callable[[], Any]) -> float:
        venv = make()
        model = PPO("MlpPolicy", venv, n_steps=n_steps, batch_size=512, n_epochs=1, seed=0,
                    policy_kwargs={"net_arch": [32, 32]}, device="cpu", verbose=0)  # fmt: skip
        model.learn(n_envs * n_steps)  # warm-up
        t0 = time.process_time()
        model.learn(total, reset_num_timesteps=False)
        venv.close()
        return total / (time.process_time() - t0)

    out = []
    for env_id in _vector_ids():
        native = partial(native_sb3, env_id, n_envs)
        dummy = partial(make_vec_env, env_id, n_envs=n_envs, seed=0)
        rate, (rd,) = side_by_side(partial(train_rate, native), [partial(train_rate, dummy)], 1)
        out.append(_row("ppo", f"{env_id} PPO on native vector N={n_envs}", rate,
                        f"{env_id} PPO on SB3 DummyVecEnv N={n_envs}", rd,
                        n_envs=n_envs))  # fmt: skip
    return out


def rows(quick: bool) -> list[dict[str, Any]]:
    """All cases (--quick: shorter timings, fewer Inchworm effect variants, N = 256 effects)."""
    return single_rows(quick) + vector_rows(quick) + effect_rows(quick) + ppo_rows(quick)


# ---------------------------------------------------------------------- plot
def plot(out: Path, rows: list[dict[str, Any]]) -> list[Path]:
    """speed_envs.png: vector ladder, single-env ratios, effect costs."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 3, figsize=(17, 4.8))
    vec = [r for r in rows if r["case"] == "vector_env"]
    for env_id in sorted({r["variant"].split()[0] for r in vec}):
        rr = [r for r in vec if r["variant"].startswith(env_id)]
        ax[0].loglog([r["n_envs"] for r in rr], [r["steps_per_s"] for r in rr], "o-",
                     label=f"{env_id} native")  # fmt: skip
    if vec:
        rr = [r for r in vec if r["variant"].startswith(vec[0]["variant"].split()[0])]
        ax[0].loglog([r["n_envs"] for r in rr], [r["reference_steps_per_s"] for r in rr],
                     "s--", color="0.5", label=f"{PENDULUM} gym.make")  # fmt: skip
    for k, (env_id, (at, goal)) in enumerate(vector_targets().items()):
        ax[0].plot([at], [goal], marker="*", ms=11, ls="none", color=f"C{k}", mec="r",
                   label=f"{env_id} goal ({goal:.2g} at N = {at})")  # fmt: skip
    ax[0].set(xlabel="N envs", ylabel="env-steps/s", title="native vector envs")
    ax[0].set_ylim(top=3 * TARGET_VECTOR)
    ax[0].legend(fontsize=7)
    single = [r for r in rows if r["case"] == "single_env"]
    names = [r["variant"].split()[0] for r in single]
    ax[1].barh(names, [r["ratio"] for r in single], color="C0")
    ax[1].axvline(1.0, color="r", lw=0.8)
    ax[1].set_xscale("log")
    ax[1].set(xlabel=f"steps/s / {PENDULUM} (gym.make)", title="single env")
    for i, r in enumerate(single):
        ax[1].text(r["ratio"], i, f" {r['steps_per_s']:.3g}/s", va="center", fontsize=7)
    eff = [r for r in rows if r["case"] == "effects"]
    ax[2].barh([r["variant"].split(" (")[0] for r in eff], [r["ratio"] for r in eff], color="C2")
    ax[2].axvline(1.0, color="k", lw=0.8)
    ax[2].tick_params(axis="y", labelsize=6)
    ax[2].set(xlabel="steps/s relative to no effect", title="cost per effect")
    fig.tight_layout()
    path = out / "speed_envs.png"
    save_figure(fig, path, dpi=110)
    return [path]


def summary(rows: list[dict[str, Any]]) -> list[str]:
    """The throughput goals' verdicts from one run's rows."""
    lines = []
    for r in rows:
        if r["case"] == "single_env" or (r["case"] == "vector_env" and "target" in r):
            goal = f"; goal {r['target']}: {'met' if r['meets_target'] else 'NOT met'}"
            lines.append(f"{r['variant']}: {r['steps_per_s']:.4g} steps/s = "
                         f"{r['ratio']:.3g} x {r['reference']}"
                         + (goal if "target" in r else ""))  # fmt: skip
    return lines


if __name__ == "__main__":  # python -m benchmarks.speed.envs [--quick]
    import sys

    res = rows("--quick" in sys.argv)
    for line in summary(res):
        print(line)
    print(f"load average {os.getloadavg()[0]:.2f}; nan rows: "
          f"{sum(1 for r in res if not math.isfinite(r['ratio']))}")  # fmt: skip
