"""Sweep configuration: a YAML file -> the list of trials (env kwargs x controller x seed).

The YAML keys (read with `yaml.safe_load`; nothing in the file is executed):

- `env_id` (required): a registered env id, e.g. `GOWEC-v0`;
- `seeds` (required): episode seeds, a list of ints or `{start: 0, count: 3}`;
- `controllers` (required): a list of `baseline` (the env's default), `baseline:KIND`
  (`mf_envs.controllers.make_baseline`), `ppo` (the shipped policy, `mf_envs.train.load_policy`),
  `ppo:PATH`, or mappings `{name, kind, params, reset_options}`;
- `mode`: `grid` (default; the cartesian product of `grid`) or `random` (`samples` draws);
- `env_kwargs`: `gym.make` kwargs shared by every trial;
- `scenes`: named kwarg sets (e.g. sea states), crossed with the grid/random points;
- `grid`: axis -> list of values (grid mode);
- `random`: axis -> `{low, high}` (uniform), `{low, high, log: true}` or `{choices: [...]}`;
- `samples`, `sampler_seed`: random mode, number of points (required) and sampler seed (0);
- `plot`: `{metric: NAME, x: AXIS, y: AXIS, log: BOOL}`; default the env's primary metric,
  controller x scene table;
- `name`: label of the sweep (default: the file name).

A trial's kwargs are `env_kwargs | scene | point` (later keys win). Its id is the first 16 hex
digits of the SHA-256 of its canonical JSON (env id, scene, kwargs, controller, seed), so the
same trial has the same id in every run and a resumed sweep skips it (`mf_envs.sweep.store`).
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import load_yaml, safe_name

_KEYS = {
    "env_id", "seeds", "controllers", "mode", "env_kwargs", "scenes", "grid", "random",
    "samples", "sampler_seed", "plot", "name",
}  # fmt: skip
_CONTROLLER_KEYS = {"name", "kind", "params", "reset_options"}
MAX_SEEDS = 10_000  # episode seeds of one sweep
MAX_TRIALS = 1_000_000  # scenes x points x controllers x seeds (a config of a few lines)


@dataclass(frozen=True)
class ControllerSpec:
    """A controller of the sweep: `kind` is `baseline[:KIND]` or `ppo[:PATH]`."""

    name: str
    kind: str
    params: dict[str, Any] = field(default_factory=dict)
    reset_options: dict[str, Any] | None = None


@dataclass(frozen=True)
class Trial:
    """One episode: `gym.make(env_id, **kwargs)`, `controller`, `reset(seed=seed)`.

    `point` holds the swept axis values (including `scene`), the columns of the results CSV.
    """

    env_id: str
    scene: str
    kwargs: dict[str, Any]
    point: dict[str, Any]
    controller: ControllerSpec
    seed: int

    @property
    def trial_id(self) -> str:
        c = self.controller
        key = [self.env_id, self.scene, self.kwargs, c.name, c.kind, c.params, c.reset_options]
        text = json.dumps([*key, self.seed], sort_keys=True, default=_json_default)
        return hashlib.sha256(text.encode()).hexdigest()[:16]


@dataclass(frozen=True)
class SweepConfig:
    """A parsed, validated sweep (see the module docstring for the YAML keys)."""

    name: str
    env_id: str
    trials: tuple[Trial, ...]
    axes: tuple[str, ...]  # swept kwarg names (CSV columns besides `scene`)
    plot: dict[str, Any]


def _json_default(obj: Any) -> Any:
    if isinstance(obj, np.generic):
        return obj.item()
    raise TypeError(f"not JSON-serialisable: {obj!r}")


def _fail(key: str, msg: str) -> ValueError:
    return ValueError(f"config: {key}: {msg}")


def load_config(path: str | Path) -> SweepConfig:
    """Parse and validate the sweep YAML at `path` (ValueError naming the bad key)."""
    p = Path(path)
    data = load_yaml(p, "config")
    return parse_config(data, default_name=safe_name("config", p.stem))


def parse_config(data: Any, default_name: str = "sweep") -> SweepConfig:
    """Validate the already-loaded YAML mapping `data` and expand it into trials."""
    if not isinstance(data, dict):
        raise ValueError("config: the file must hold a mapping of the sweep keys")
    unknown = sorted(set(data) - _KEYS)
    if unknown:
        raise _fail(unknown[0], f"unknown key; known keys: {sorted(_KEYS)}")
    env_id = _env_id(data.get("env_id"))
    seeds = _seeds(data.get("seeds"))
    controllers = _controllers(env_id, data.get("controllers"))
    base = _mapping("env_kwargs", data.get("env_kwargs", {}))
    scenes = _scenes(data.get("scenes"))
    points, axes = _points(data)
    n_trials = len(scenes) * len(points) * len(controllers) * len(seeds)
    if n_trials > MAX_TRIALS:
        raise _fail("grid", f"{n_trials} trials, more than {MAX_TRIALS}; sweep fewer values")
    trials = tuple(
        Trial(env_id, scene, {**base, **skw, **pt}, {"scene": scene, **pt}, ctrl, seed)
        for (scene, skw), pt, ctrl, seed in itertools.product(
            scenes.items(), points, controllers, seeds
        )
    )
    name = safe_name("config: name", data.get("name", default_name))
    return SweepConfig(name, env_id, trials, axes, _plot(data.get("plot"), axes))


def _env_id(value: Any) -> str:
    import gymnasium as gym

    import mf_envs  # noqa: F401  (registers the env ids)

    if not isinstance(value, str):
        raise _fail("env_id", "required, a registered env id string")
    if value not in gym.registry:
        known = sorted(k for k in gym.registry if "-v" in k and k.split("-")[0][:1].isupper())
        raise _fail("env_id", f"{value!r} is not registered (mf_envs ids include {known[:8]})")
    from mf_envs.envs import canonical_env_id

    return canonical_env_id(value)  # a deprecated id (GOWEC-v1): its new id, with a warning


def _seeds(value: Any) -> tuple[int, ...]:
    if isinstance(value, dict) and set(value) == {"start", "count"}:
        start, count = value["start"], value["count"]
        if _plain_int(start) and _plain_int(count) and 1 <= count <= MAX_SEEDS:
            return tuple(range(start, start + count))
    elif isinstance(value, list) and 0 < len(value) <= MAX_SEEDS:
        if all(_plain_int(s) for s in value) and len(set(value)) == len(value):
            return tuple(value)
    raise _fail(
        "seeds",
        f"a non-empty list of at most {MAX_SEEDS} distinct ints in [0, 2**32), or {{start, "
        f"count}} with 1 <= count <= {MAX_SEEDS}; got {_short(value)}",
    )


def _plain_int(v: Any) -> bool:
    """An int usable as an episode seed (bools are not seeds)."""
    return isinstance(v, int) and not isinstance(v, bool) and 0 <= v < 2**32 - MAX_SEEDS


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 80 else f"{text[:60]}... ({len(text)} characters)"


def _mapping(key: str, value: Any) -> dict[str, Any]:
    if not isinstance(value, dict) or not all(isinstance(k, str) for k in value):
        raise _fail(key, f"must be a mapping of kwarg names to values, got {_short(value)}")
    bad = [k for k in value if not k.isidentifier()]
    if bad and key != "scenes":
        raise _fail(f"{key}.{bad[0]}", "a name must be a Python identifier (a kwarg or key name)")
    return dict(value)


def _scenes(value: Any) -> dict[str, dict[str, Any]]:
    if value is None:
        return {"default": {}}
    scenes = _mapping("scenes", value)
    if not scenes:
        raise _fail("scenes", "empty; omit it for a single default scene")
    return {str(k): _mapping(f"scenes.{k}", v or {}) for k, v in scenes.items()}


def _controllers(env_id: str, value: Any) -> tuple[ControllerSpec, ...]:
    if not isinstance(value, list) or not value:
        raise _fail("controllers", "required, a non-empty list")
    specs = tuple(_controller(env_id, i, v) for i, v in enumerate(value))
    names = [s.name for s in specs]
    if len(set(names)) != len(names):
        raise _fail("controllers", f"names must be distinct, got {names}")
    return specs


def _controller(env_id: str, i: int, value: Any) -> ControllerSpec:
    key = f"controllers[{i}]"
    if isinstance(value, str):
        value = {"kind": value}
    if not isinstance(value, dict) or "kind" not in value or set(value) - _CONTROLLER_KEYS:
        raise _fail(key, f"a kind string or a mapping with keys {sorted(_CONTROLLER_KEYS)}")
    kind = str(value["kind"])
    family, _, arg = kind.partition(":")
    if family == "baseline":
        from mf_envs.controllers import baseline_kinds

        kinds = baseline_kinds(env_id)
        kind = f"baseline:{arg or kinds[0]}"
        if (arg or kinds[0]) not in kinds:
            raise _fail(key, f"{arg!r} is not a baseline of {env_id}; available: {kinds}")
    elif family != "ppo":
        raise _fail(key, f"kind must be 'baseline[:KIND]' or 'ppo[:PATH]', got {kind!r}")
    params = _mapping(f"{key}.params", value.get("params") or {})
    opts = value.get("reset_options")
    opts = None if opts is None else _mapping(f"{key}.reset_options", opts)
    return ControllerSpec(str(value.get("name", kind)), kind, params, opts)


def _points(data: dict[str, Any]) -> tuple[list[dict[str, Any]], tuple[str, ...]]:
    mode = data.get("mode", "grid")
    if mode == "grid":
        grid = _mapping("grid", data.get("grid") or {})
        for k, v in grid.items():
            if not isinstance(v, list) or not v:
                raise _fail(f"grid.{k}", f"a non-empty list of values, got {v!r}")
        size = math.prod(len(v) for v in grid.values())
        if size > MAX_TRIALS:
            raise _fail("grid", f"{size} points, more than {MAX_TRIALS}; sweep fewer values")
        combos = itertools.product(*grid.values())
        return [dict(zip(grid, c)) for c in combos], tuple(grid)
    if mode == "random":
        return _random_points(data)
    raise _fail("mode", f"'grid' or 'random', got {mode!r}")


def _random_points(data: dict[str, Any]) -> tuple[list[dict[str, Any]], tuple[str, ...]]:
    axes = _mapping("random", data.get("random") or {})
    n = data.get("samples")
    if not isinstance(n, int) or isinstance(n, bool) or not 1 <= n <= MAX_TRIALS:
        raise _fail("samples", f"random mode needs samples: an int in [1, {MAX_TRIALS}], got {n!r}")
    seed = data.get("sampler_seed", 0)
    if not _plain_int(seed):
        raise _fail("sampler_seed", f"an int in [0, 2**32), got {_short(seed)}")
    rng = np.random.default_rng(seed)
    draws = {k: _draw(f"random.{k}", spec, rng, n) for k, spec in axes.items()}
    return [{k: v[i] for k, v in draws.items()} for i in range(n)], tuple(axes)


def _draw(key: str, spec: Any, rng: np.random.Generator, n: int) -> list[Any]:
    if isinstance(spec, dict) and set(spec) == {"choices"} and isinstance(spec["choices"], list):
        if not spec["choices"]:
            raise _fail(key, "choices: a non-empty list")
        return [spec["choices"][i] for i in rng.integers(0, len(spec["choices"]), n)]
    if isinstance(spec, dict) and {"low", "high"} <= set(spec) <= {"low", "high", "log"}:
        log = spec.get("log", False)
        if not (_real(spec["low"]) and _real(spec["high"]) and isinstance(log, bool)):
            raise _fail(key, f"low and high must be numbers, log true or false; got {spec!r}")
        lo, hi = float(spec["low"]), float(spec["high"])
        if not (math.isfinite(lo) and math.isfinite(hi) and lo < hi and (lo > 0 or not log)):
            raise _fail(key, f"needs finite low < high (and low > 0 with log), got {spec!r}")
        u = rng.uniform(np.log(lo), np.log(hi), n) if log else rng.uniform(lo, hi, n)
        return [float(x) for x in (np.exp(u) if log else u)]
    raise _fail(key, f"{{low, high[, log]}} or {{choices: [...]}}, got {spec!r}")


def _real(v: Any) -> bool:
    """A real number (not a bool or a string)."""
    return isinstance(v, int | float) and not isinstance(v, bool)


def _plot(value: Any, axes: tuple[str, ...]) -> dict[str, Any]:
    plot = _mapping("plot", value or {})
    if set(plot) - {"metric", "x", "y", "log"}:
        raise _fail("plot", f"keys are metric, x, y, log; got {sorted(plot)}")
    if not isinstance(plot.get("log", False), bool):
        raise _fail("plot.log", f"true or false, got {_short(plot['log'])}")
    if "metric" in plot:
        safe_name("config: plot.metric", plot["metric"])  # it names the picture's file
    for k in ("x", "y"):
        if k in plot and plot[k] not in (*axes, "scene"):
            raise _fail(f"plot.{k}", f"{plot[k]!r} is not a swept axis {['scene', *axes]}")
    if ("x" in plot) != ("y" in plot):
        raise _fail("plot", "give both x and y (a heatmap) or neither (a controller table)")
    return plot
