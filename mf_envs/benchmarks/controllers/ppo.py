"""PPO rows for `mf-envs bench controllers`: every env with a shipped policy (train/policies/).

Scenes and metrics are each env's own (`benchmarks/controllers/<env>.py`), so PPO rows sit beside
the baselines' rows of the same scene in `controllers.csv`:

- GOWEC-v0: the `SCENES` of `gowec.py`, metric `power_ratio` (mean power over the last three
  quarters of the episode / Eq. 95; ceiling 4/pi for regular seas);
- GyroStabilizer-v0: the scenes of `stabilizer.py`, `rms_roll` after its `SETTLE` and `rr`, the
  RMS roll reduction against the rotor off on the same seeds (the module's `ppo_extra_rows`);
- FloatingGOWEC-v0 and Inchworm-v0: scored beside their baselines by their own modules
  (`SCORES_PPO = True`); any other env: scene `default`, its primary metric.

An env's bench module is its declaration's `bench`; it may define `SCENES` (or `_scenes()`),
`SCORES_PPO` and `ppo_extra_rows(scene, kwargs, per_seed, seeds)`.

The policies were trained on default parameters only: the other scenes measure generalisation.
Robustness: scenes `shift: ...` run PPO and every classical baseline on shifted
physical parameters (the declaration's `shifts`, `train.randomize.shift_scenes`, e.g. wave period
x0.8 / x1.2); baselines are made for the shifted env (`make_baseline(env)`), i.e. they know
whatever they read from it.
PPO is evaluated on unseen seeds 2000.. (training used 0.., `train`'s own evaluation 1000..).
`plot` draws each shipped policy's learning curve (its EvalCallback log).
"""

from __future__ import annotations

import importlib
import importlib.util
import sys
from pathlib import Path
from typing import Any

ORDER = 900  # after the env helpers' own baseline modules
SEEDS = tuple(range(2000, 2005))


def shipped_env_ids() -> list[str]:
    """Env ids with a shipped policy scored here (a bench module with `SCORES_PPO = True` scores
    its env's beside its baselines)."""
    return [e for e in _shipped_all() if not getattr(_bench_module(e), "SCORES_PPO", False)]


def with_ppo(env_id: str, kinds: tuple[str, ...]) -> tuple[str, ...]:
    """`kinds` plus "ppo" when env_id has a shipped policy and the train extra is installed (for
    the env modules that score PPO beside their own baselines)."""
    have = all(_has(m) for m in ("stable_baselines3", "torch", "safetensors"))
    return kinds + (("ppo",) if have and env_id in _shipped_all() else ())


def make_controller(env: Any, env_id: str, kind: str) -> Any:
    """The shipped PPO policy for kind "ppo", else the named classical baseline of env."""
    if kind == "ppo":
        from mf_envs.train.policy import load_policy

        return load_policy(env_id)
    from mf_envs.controllers import make_baseline

    return make_baseline(env, kind)


def _shipped_all() -> list[str]:
    import mf_envs  # noqa: F401
    from mf_envs.envs import available_env_ids
    from mf_envs.train.policy import POLICY_FILE, policy_dir

    return [e for e in available_env_ids() if (policy_dir(e) / POLICY_FILE).is_file()]


def env_scenes(env_id: str) -> dict[str, dict[str, Any]]:
    """Scene name -> gym.make kwargs, as in the env's own controllers benchmark."""
    mod = _bench_module(env_id)
    if mod is not None and hasattr(mod, "SCENES"):
        return dict(mod.SCENES)
    if mod is not None and hasattr(mod, "_scenes"):
        return dict(mod._scenes())
    return {"default": {}}


def rows(quick: bool) -> list[dict[str, Any]]:
    """PPO rows; without the `train` extra they are skipped with one line on stderr."""
    missing = [m for m in ("stable_baselines3", "torch", "safetensors") if not _has(m)]
    if missing:
        from mf_envs._extras import install_hint

        print(
            f"bench controllers: skipping the PPO rows (needs the train extra: "
            f"{install_hint('train')}; missing {', '.join(missing)})",
            file=sys.stderr,
        )
        return []
    return _rows(quick)


def _has(module: str) -> bool:
    return importlib.util.find_spec(module) is not None


def _rows(quick: bool) -> list[dict[str, Any]]:
    from mf_envs.train.evaluate import baseline_factories, episodes, primary_metric, summarize
    from mf_envs.train.policy import load_policy
    from mf_envs.train.randomize import shift_scenes

    out: list[dict[str, Any]] = []
    for env_id in shipped_env_ids():
        policy = load_policy(env_id)
        keep = {primary_metric(env_id).name, "numerical_failure"}
        scenes = env_scenes(env_id)
        shifts = shift_scenes(env_id)
        if quick:
            scenes, shifts = dict(list(scenes.items())[:1]), dict(list(shifts.items())[:1])
        for scene, kwargs in scenes.items():
            per_seed = episodes(env_id, lambda env, p=policy: p, SEEDS, kwargs)
            r = summarize(env_id, scene, "ppo", per_seed)
            out += [dict(x, seeds=_span(SEEDS)) for x in r if x["metric"] in keep]
            if hasattr(mod := _bench_module(env_id), "ppo_extra_rows"):
                out += mod.ppo_extra_rows(scene, kwargs, per_seed, SEEDS)
        ctrls = {"ppo": lambda env, p=policy: p, **baseline_factories(env_id)}
        for name, kwargs in shifts.items():
            for ctrl, factory in ctrls.items():
                r = summarize(
                    env_id, f"shift: {name}", ctrl, episodes(env_id, factory, SEEDS, kwargs)
                )
                out += [
                    dict(x, params=_fmt(kwargs), seeds=_span(SEEDS))
                    for x in r
                    if x["metric"] in keep
                ]
    return out


def plot(out: Path, rows: list[dict[str, Any]]) -> list[Path]:
    from mf_envs.train.curves import plot_learning_curves
    from mf_envs.train.policy import policy_dir

    files = []
    for env_id in shipped_env_ids():
        folder = policy_dir(env_id)
        if (folder / "evaluations.npz").is_file():
            path = out / f"ppo_learning_curve_{env_id}.png"
            files.append(plot_learning_curves([folder], path, f"PPO on {env_id}", ["ppo"]))
    return files


def _bench_module(env_id: str) -> Any:
    """The env's controllers benchmark module (its declaration's `bench`), or None."""
    from mf_envs.envs import declaration

    decl = declaration(env_id)
    if decl is None or decl.bench is None or importlib.util.find_spec(decl.bench) is None:
        return None
    return importlib.import_module(decl.bench)


def _span(seeds: tuple[int, ...]) -> str:
    return f"{seeds[0]}-{seeds[-1]}"


def _fmt(kwargs: dict[str, float]) -> str:
    return " ".join(f"{k}={v:.4g}" for k, v in kwargs.items())
