"""What env a policy was trained on, and whether the env it is used on is still that env.

`env_record(env_id, env_kwargs)` (stored in a policy's `meta.json` by `mf-envs train`):
- `env_kwargs_full`: every constructor argument of the env class with the value the run used
  (the class's defaults, overlaid by the id's registered kwargs and the config's `env_kwargs`);
- `env_probe`: the observations of `reset(seed=PROBE_SEED)` and `PROBE_STEPS` steps of the
  zero action, to 10 significant digits: a change of the physics that moves the env shows here
  even when no argument changed;
- `package_version`.

`env_differences(meta, env_id)` lists what differs today; `warn_if_env_differs` turns a non-empty
list into one `PolicyEnvWarning` (`load_policy` and `mf-envs evaluate` call it).
"""

from __future__ import annotations

import functools
import importlib
import inspect
import json
import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

PROBE_SEED = 0
PROBE_STEPS = 3
SKIPPED = ("self", "render_mode")


class PolicyEnvWarning(UserWarning):
    """A policy is used on an env that differs from the one it was trained on."""


def _jsonable(value: Any) -> Any:
    """`value` as JSON would store it (tuples as lists, numpy scalars as numbers, others repr)."""
    return json.loads(json.dumps(value, default=lambda v: v.tolist() if hasattr(v, "tolist")
                                 else repr(v)))  # fmt: skip


def full_kwargs(env_id: str, env_kwargs: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """Every constructor argument of `env_id`'s class: its default, the id's registered kwargs,
    then `env_kwargs` (JSON-normalised)."""
    import gymnasium as gym

    spec = gym.spec(env_id)
    module, name = str(spec.entry_point).split(":")
    cls = getattr(importlib.import_module(module), name)
    params = inspect.signature(cls.__init__).parameters.values()
    kinds = (inspect.Parameter.KEYWORD_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    out = {p.name: (None if p.default is p.empty else p.default) for p in params
           if p.name not in SKIPPED and p.kind in kinds}  # fmt: skip
    out.update(spec.kwargs or {})
    out.update(env_kwargs or {})
    out.pop("max_episode_steps", None)
    return _jsonable(out)


def probe(env_id: str, env_kwargs: Mapping[str, Any] | None = None) -> list[float]:
    """Observations of `reset(seed=PROBE_SEED)` and `PROBE_STEPS` zero-action steps (10 digits)."""
    import gymnasium as gym

    env = gym.make(env_id, **dict(env_kwargs or {}))
    try:
        obs, _ = env.reset(seed=PROBE_SEED)
        seen = [np.asarray(obs, dtype=np.float64).ravel()]
        zero = np.zeros(env.action_space.shape, env.action_space.dtype)
        for _ in range(PROBE_STEPS):
            obs, *_ = env.step(zero)
            seen.append(np.asarray(obs, dtype=np.float64).ravel())
    finally:
        env.close()
    return [float(f"{x:.10g}") for x in np.concatenate(seen)]


def env_record(env_id: str, env_kwargs: Mapping[str, Any] | None = None) -> dict[str, Any]:
    """The `meta.json` fields that say which env a run trained on (module docstring)."""
    from mf_envs import __version__

    return {
        "env_kwargs_full": full_kwargs(env_id, env_kwargs),
        "env_probe": probe(env_id, env_kwargs),
        "package_version": __version__,
    }


@functools.lru_cache(maxsize=64)
def _today(env_id: str, kwargs_json: str) -> tuple[str, tuple[float, ...]]:
    kwargs = json.loads(kwargs_json)
    return json.dumps(full_kwargs(env_id, kwargs), sort_keys=True), tuple(probe(env_id, kwargs))


def env_differences(meta: Mapping[str, Any], env_id: str) -> list[str]:
    """What differs between the env recorded in `meta` and `env_id` today: argument names with
    their recorded and present values, a moved probe, or a record that is missing."""
    recorded = meta.get("env_kwargs_full")
    if not isinstance(recorded, dict) or not isinstance(meta.get("env_probe"), list):
        return ["its meta.json records no env kwargs, so the env it was trained on is unknown"]
    user = meta.get("hyperparams", {}).get("env_kwargs") or {}
    kwargs_now, probe_now = _today(env_id, json.dumps(user, sort_keys=True))
    now = json.loads(kwargs_now)
    keys = sorted(set(recorded) | set(now))
    diffs = [f"{k}: trained with {recorded.get(k)!r}, now {now.get(k)!r}"
             for k in keys if recorded.get(k) != now.get(k)]  # fmt: skip
    if not diffs and tuple(meta["env_probe"]) != probe_now:
        diffs.append("the env's first observations under the zero action moved (the physics or "
                     "a default inside the device changed)")  # fmt: skip
    return diffs


def warn_if_env_differs(meta: Mapping[str, Any], env_id: str, where: str) -> list[str]:
    """One `PolicyEnvWarning` naming the policy folder `where` if its env differs today."""
    diffs = env_differences(meta, env_id)
    if diffs:
        shown = "; ".join(diffs[:4]) + (f"; and {len(diffs) - 4} more" if len(diffs) > 4 else "")
        warnings.warn(
            f"the policy in {where} was trained on a different {env_id} ({shown}); its scores "
            "here are not the ones it was trained for",
            PolicyEnvWarning,
            stacklevel=3,
        )
    return diffs
