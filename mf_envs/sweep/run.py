"""Running the trials of a sweep: in-process (`serial`) or as Ray tasks, with one results CSV.

Ray core tasks, not Ray Tune: a trial here is one deterministic episode with no training loop to
checkpoint, no search algorithm that learns from earlier results and no early stopping, which
is what Tune's trial actors, schedulers and experiment state exist for. One `@ray.remote`
function per trial and `ray.wait` in the driver give the same code path as the serial loop
(`run_trial` is the task body), results in completion order for the progress bar and the CSV,
and resumption through our own trial ids (`config.Trial.trial_id`) rather than Tune's
experiment directory. Random search is a seeded draw in `config` (no Tune searcher needed).
"""

from __future__ import annotations

import functools
import json
import time
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import gymnasium as gym

from mf_envs._ray import init_local_ray, probe_address, quiet_usage_stats
from mf_envs._ray import require_ray as _require_ray
from mf_envs.sweep.config import SweepConfig, Trial
from mf_envs.sweep.store import ResultStore

FIRST_COLUMNS = ("trial_id", "env_id", "scene", "controller", "seed", "kwargs")


class _ResetOptions(gym.Wrapper):
    """Passes fixed `options` to every `reset` (e.g. the stabilizer's `wave_phase`)."""

    def __init__(self, env: gym.Env, options: dict[str, Any]) -> None:
        super().__init__(env)
        self._options = options

    def reset(self, *, seed: int | None = None, options: dict | None = None) -> Any:
        return self.env.reset(seed=seed, options={**self._options, **(options or {})})


@functools.lru_cache(maxsize=8)
def _policy(env_id: str, path: str | None) -> Any:
    from mf_envs.train import load_policy

    return load_policy(env_id, path)


def make_controller(env: gym.Env, kind: str, params: dict[str, Any]) -> Any:
    """`baseline:KIND` -> `make_baseline(env, KIND, **params)`; `ppo[:PATH]` -> `load_policy`."""
    family, _, arg = kind.partition(":")
    if family == "ppo":
        return _policy(env.spec.id, arg or None)
    from mf_envs.controllers import make_baseline

    return make_baseline(env, arg or None, **params)


def run_trial(trial: Trial) -> dict[str, Any]:
    """Run one trial; its CSV row (labels, swept values, `episode_metrics`, `wall_s`)."""
    import mf_envs  # noqa: F401  (registers the env ids in a fresh Ray worker)
    from mf_envs.train.evaluate import run_episode

    t0 = time.perf_counter()
    env = gym.make(trial.env_id, **trial.kwargs)
    if trial.controller.reset_options:
        env = _ResetOptions(env, trial.controller.reset_options)
    try:
        ctrl = make_controller(env, trial.controller.kind, trial.controller.params)
        metrics = run_episode(trial.env_id, env, ctrl, trial.seed)
    finally:
        env.close()
    return {
        "trial_id": trial.trial_id,
        "env_id": trial.env_id,
        "controller": trial.controller.name,
        "seed": trial.seed,
        "kwargs": json.dumps(trial.kwargs, sort_keys=True),
        **trial.point,
        **metrics,
        "wall_s": time.perf_counter() - t0,
    }


def check_env_kwargs(cfg: SweepConfig) -> None:
    """Construct the env once per distinct kwargs and each baseline once with its params, so a
    bad kwarg or controller param fails before any trial runs."""
    seen: set[str] = set()
    for t in cfg.trials:
        key = json.dumps(t.kwargs, sort_keys=True)
        if key not in seen:
            seen.add(key)
            try:
                gym.make(t.env_id, **t.kwargs).close()
            except TypeError as exc:  # an unknown kwarg name
                raise ValueError(f"config: env kwargs {key}: {exc}") from exc
    first = cfg.trials[0]
    env = gym.make(first.env_id, **first.kwargs)
    try:
        for ctrl in {t.controller.name: t.controller for t in cfg.trials}.values():
            if ctrl.kind.startswith("baseline"):
                try:  # an unknown or wrongly typed param fails here, before any trial
                    make_controller(env, ctrl.kind, ctrl.params)
                except (TypeError, ValueError) as exc:
                    raise ValueError(f"config: controllers: {ctrl.name}: {exc}") from None
    finally:
        env.close()


def run_serial(trials: Sequence[Trial], sink: Callable[[dict[str, Any]], None]) -> None:
    for t in trials:
        sink(run_trial(t))


def run_ray(
    trials: Sequence[Trial],
    sink: Callable[[dict[str, Any]], None],
    address: str | None = None,
    num_cpus: int | None = 2,
) -> None:
    """Every trial as a Ray task (1 CPU each); `sink(row)` in completion order, in the driver.

    Starts a small local Ray (`init_local_ray`) unless `address` names a running cluster
    (`ray start --head` on one node, `ray start --address` on others) or Ray is already
    initialised by the caller. Shuts down only a Ray it started itself.
    """
    ray = require_ray()
    started = not ray.is_initialized()
    if started and address:
        probe_address(address)  # seconds, not minutes, when nothing answers there
        quiet_usage_stats()
        try:
            ray.init(address=address, include_dashboard=False, log_to_driver=False)
        except (ConnectionError, RuntimeError) as exc:
            msg = " ".join(str(exc).split())[:200]
            raise ValueError(f"address: no Ray cluster reachable at {address!r} ({msg})") from exc
    elif started:
        init_local_ray(num_cpus)
    try:
        task = ray.remote(num_cpus=1)(run_trial)
        pending = [task.remote(t) for t in trials]
        while pending:
            done, pending = ray.wait(pending, num_returns=1)
            sink(ray.get(done[0]))
    finally:
        if started:
            ray.shutdown()


def require_ray() -> Any:
    """The `ray` module, or a ValueError: install the extra, or run the sweep with --serial."""
    return _require_ray(hint=" (or run the sweep with --serial)")


def run_sweep(
    cfg: SweepConfig,
    out: Path,
    serial: bool = False,
    address: str | None = None,
    num_cpus: int | None = 2,
    progress: bool = True,
) -> tuple[Path, int]:
    """Run the trials of `cfg` not yet in `out/trials.csv`; (CSV path, trials run now)."""
    from tqdm import tqdm

    if not serial:
        require_ray()
        if address:
            probe_address(address)  # before any env is built or any file written
    check_env_kwargs(cfg)
    store = ResultStore(Path(out) / "trials.csv")
    done = store.done_ids()
    todo = [t for t in cfg.trials if t.trial_id not in done]
    first = (*FIRST_COLUMNS, *cfg.axes)
    bar = tqdm(
        total=len(cfg.trials), initial=len(cfg.trials) - len(todo), disable=not progress,
        desc=cfg.name, unit="trial",
    )  # fmt: skip

    def sink(row: dict[str, Any]) -> None:
        store.append(row, first)
        bar.update(1)

    try:
        if serial:
            run_serial(todo, sink)
        elif todo:
            run_ray(todo, sink, address=address, num_cpus=num_cpus)
    finally:
        bar.close()
    return store.path, len(todo)
