"""One declaration per env: everything the layers above the env need to know about it.

Each env package `mf_envs/envs/<env>/task.py` defines `DECLARATION = EnvDeclaration(...)`; a
package outside mf_envs declares its env the same way and names it in the `mf_envs.envs`
entry-point group of its distribution (`[project.entry-points."mf_envs.envs"]`
`my_env = "my_pkg.task:DECLARATION"`). `declarations()` collects both; Gymnasium registration,
`make_vec`'s native entry point, the baselines (`controllers.make_baseline`), the evaluation
metric (`train.evaluate`), domain randomisation (`train.randomize`), the RLlib and SB3 starting
hyperparameters, the throughput goals and the contract tests read it from there, so no layer
above `envs/` holds a per-env branch (docs/adding_an_env.md).

A declaration holds strings for everything in a higher layer (the baselines module, the bench
and demo modules): reading a declaration imports nothing heavy, and nothing points upward.
"""

from __future__ import annotations

import importlib
import importlib.metadata
import importlib.util
import pkgutil
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from types import MappingProxyType
from typing import Any

__all__ = [
    "Ceiling",
    "EnvDeclaration",
    "Metric",
    "Variant",
    "RETURN",
    "base_metrics",
    "declaration",
    "declarations",
    "refresh",
    "shipped",
    "task_declarations",
]

ENTRY_POINT_GROUP = "mf_envs.envs"


@dataclass(frozen=True)
class Metric:
    """The quantity an env is judged by: name (a key of its episode metrics), direction, unit."""

    name: str
    higher_is_better: bool
    unit: str


RETURN = Metric("return", True, "1")


@dataclass(frozen=True)
class Ceiling:
    """What no controller of a task can beat, for one of its scores.

    `value` (in `unit`) is a constant, or None when it depends on the episode's scene: then
    `fn`, "module:function", computes it from the env after its reset (e.g. a sea's power
    bound). `note` says what the bound is and why it holds (losses included, causal or not);
    `tight` is False for a valid bound known to lie far above what the device can reach."""

    metric: str
    unit: str
    note: str
    value: float | None = None
    fn: str | None = None
    tight: bool = True

    def __post_init__(self) -> None:
        if (self.value is None) == (self.fn is None):
            raise ValueError(f"ceiling: give exactly one of value and fn ({self.metric!r})")
        if self.fn is not None and ":" not in self.fn:
            raise ValueError(f"fn: {self.fn!r} is not 'module:function'")

    def of(self, env: Any) -> float:
        """The ceiling for `env`'s current scene (`value`, or `fn(env)`)."""
        if self.value is not None:
            return float(self.value)
        return float(load(str(self.fn))(env))


@dataclass(frozen=True)
class Variant:
    """A registered task id built on an env's declaration: the same classes with `kwargs` as
    the spec's kwargs (`gymnasium.register(kwargs=...)`; a user's kwargs override them), its own
    episode length, role ("easy" or "headline"), ceiling and a line saying what it is. Its
    declaration (`declaration(variant_id)`) is its env's with these fields replaced and
    `variant_of` naming the env: baselines, metrics, randomisation and configs are the env's."""

    env_id: str
    kwargs: Mapping[str, Any]
    max_episode_steps: int
    summary: str
    role: str = "headline"
    ceiling: Ceiling | None = None
    headroom: str = ""

    def __post_init__(self) -> None:
        object.__setattr__(self, "kwargs", _frozen(self.kwargs))


ROLES = ("easy", "headline")

# (env, rewards, infos) -> extra per-episode metrics; infos[0] is the reset info
EpisodeMetrics = Callable[[Any, Sequence[float], Sequence[Mapping[str, Any]]], dict[str, float]]


def _frozen(mapping: Mapping[str, Any] | None) -> Mapping[str, Any]:
    return MappingProxyType(dict(mapping or {}))


@dataclass(frozen=True)
class EnvDeclaration:
    """What the upper layers know of one env id (all optional except the id and entry point).

    - `entry_point`, `vector_entry_point`: "module:Class" (the vector class has `supports(**kw)`).
    - `max_episode_steps`: control steps of the env's default episode (the contract tests check
      it against the env). The id is registered without a TimeLimit (the env truncates itself),
      so the spec's `max_episode_steps` is None; tools read the default length here.
    - `baselines`: the module that registers the env's classical controllers on import
      (`controllers.register(env_id, kind, factory)`).
    - `metric`, `episode_metrics`: the primary metric and the function computing it (with any
      companions) from one episode's rewards and infos; without it, the episode return.
    - `info_keys`: info keys reported at reset and every step (docs/api.md); `bad_reset_options`:
      (key, value) pairs `reset(options=...)` must reject naming the key (contract tests).
    - `randomize`, `choices`, `shifts`: domain randomisation factors (lo, hi) of nominal kwargs,
      discrete kwarg choices, robustness scenes {name: {kwarg: factor}} (`train.randomize`).
    - `rllib`: RLlib PPO overrides of `train.rllib`'s base config; `hyperparams`: per algorithm
      ("ppo", "sac", "td3") rl-zoo3 keys used when the training YAML has no entry for the id.
    - `vector_target`: (N, env-steps/s goal) of the native vector env; `single_target`:
      ("ratio", x Pendulum-v1) or ("steps_per_s", goal); `vector_n_max`: largest N benched.
    - `bench`, `demo`: modules of the controllers benchmark and the demo (optional).
    - `slow`: steps take about a millisecond (benchmarks time it longer; its native vector env
      may support only some scenes: the vector class's `supports`).
    - `role`, `ceiling`, `headroom`, `summary`: the id as a benchmark task (docs/
      benchmark.md): "easy" (the regular-sea or seed scene) or "headline" (irregular seas, the
      real device), the score's ceiling (`Ceiling`) and, in `headroom`, the best baseline's
      measured gap to it or why none is stated.
    - `variants`: more registered ids on the same classes (`Variant`); `kwargs`, `variant_of`:
      set on a variant's own declaration (`declaration(variant_id)`), empty / None on an env's.
    """

    env_id: str
    entry_point: str
    vector_entry_point: str | None = None
    max_episode_steps: int | None = None
    baselines: str | None = None
    metric: Metric = RETURN
    episode_metrics: EpisodeMetrics | None = None
    info_keys: tuple[str, ...] = ()
    bad_reset_options: tuple[tuple[str, Any], ...] = ()
    randomize: Mapping[str, tuple[float, float]] = field(default_factory=dict)
    choices: Mapping[str, tuple[Any, ...]] = field(default_factory=dict)
    shifts: Mapping[str, Mapping[str, float]] = field(default_factory=dict)
    rllib: Mapping[str, Any] = field(default_factory=dict)
    hyperparams: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)
    vector_target: tuple[int, float] | None = None
    single_target: tuple[str, float] | None = None
    vector_n_max: int | None = None
    bench: str | None = None
    demo: str | None = None
    slow: bool = False
    role: str = "easy"
    summary: str = ""
    ceiling: Ceiling | None = None
    headroom: str = ""
    variants: tuple[Variant, ...] = ()
    kwargs: Mapping[str, Any] = field(default_factory=dict)
    variant_of: str | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.env_id, str) or "-v" not in self.env_id:
            raise ValueError(f"env_id: {self.env_id!r} is not a Gymnasium id like 'Name-v0'")
        for name in ("entry_point", "vector_entry_point"):
            value = getattr(self, name)
            if value is not None and ":" not in value:
                raise ValueError(f"{name}: {value!r} is not 'module:Class'")
        steps = self.max_episode_steps
        if steps is not None and (type(steps) is not int or steps < 1):
            raise ValueError(f"max_episode_steps: an integer >= 1 or None, got {steps!r}")
        if self.role not in ROLES:
            raise ValueError(f"role: one of {ROLES}, got {self.role!r}")
        for v in self.variants:
            if not isinstance(v, Variant) or v.role not in ROLES or "-v" not in v.env_id:
                raise ValueError(f"variants: {v!r} is not a Variant with a role in {ROLES}")
        for name in ("randomize", "choices", "shifts", "rllib", "hyperparams", "kwargs"):
            object.__setattr__(self, name, _frozen(getattr(self, name)))

    @property
    def base_id(self) -> str:
        """The env's id: `variant_of` for a variant, else `env_id` (baselines are keyed by it)."""
        return self.variant_of or self.env_id

    def variant(self, variant_id: str) -> EnvDeclaration:
        """The declaration of one of `variants` (class docstring of `Variant`)."""
        v = next((v for v in self.variants if v.env_id == variant_id), None)
        if v is None:
            raise ValueError(f"env_id: {variant_id!r} is not a variant of {self.env_id}")
        return replace(
            self, env_id=v.env_id, max_episode_steps=v.max_episode_steps, role=v.role,
            summary=v.summary, ceiling=v.ceiling, headroom=v.headroom, variants=(),
            kwargs=v.kwargs, variant_of=self.env_id, vector_target=None, single_target=None,
        )  # fmt: skip

    def metrics(self, env: Any, rewards: Sequence[float], infos: Sequence[Mapping[str, Any]]):
        """The episode's metrics: `base_metrics` and the env's own."""
        extra = {} if self.episode_metrics is None else self.episode_metrics(env, rewards, infos)
        return base_metrics(rewards, infos, extra)

    def installed(self) -> bool:
        """Whether the env's module is importable in this install."""
        return _module_exists(self.entry_point.split(":")[0])

    def vector_installed(self) -> bool:
        entry = self.vector_entry_point
        return entry is not None and _module_exists(entry.split(":")[0])


def shipped(env_id: str, package: str, env_class: str, name: str, demos: bool = True) -> dict:
    """`env_id` and the modules of an env shipped in mf_envs, as its package and its baselines
    are laid out (docs/adding_an_env.md): `entry_point` `<package>.env:<env_class>`,
    `vector_entry_point` `<package>.vector:<Name>VectorEnv` (`env_class` `<Name>Env`),
    `baselines` `mf_envs.controllers.<name>` and, with `demos`, `bench` and `demo`
    `mf_envs.benchmarks.controllers.<name>`, `mf_envs.benchmarks.demos.<name>` (else None).
    For `EnvDeclaration(**shipped(...), ...)`."""
    if not env_class.endswith("Env"):
        raise ValueError(f"env_class: {env_class!r} is not named '<Name>Env'")
    benchmarks = "mf_envs.benchmarks"
    return {
        "env_id": env_id,
        "entry_point": f"{package}.env:{env_class}",
        "vector_entry_point": f"{package}.vector:{env_class[:-3]}VectorEnv",
        "baselines": f"mf_envs.controllers.{name}",
        "bench": f"{benchmarks}.controllers.{name}" if demos else None,
        "demo": f"{benchmarks}.demos.{name}" if demos else None,
    }


def base_metrics(
    rewards: Sequence[float],
    infos: Sequence[Mapping[str, Any]],
    extra: Mapping[str, float] | None = None,
) -> dict[str, float]:
    """Every episode's metrics: `return` (undiscounted), `steps`, then `extra`, then
    `numerical_failure` (1.0 if any step reported one). `infos[0]` is the reset info."""
    out = {"return": float(sum(float(r) for r in rewards)), "steps": float(len(rewards))}
    out.update(extra or {})
    out["numerical_failure"] = float(any(i.get("numerical_failure", False) for i in infos[1:]))
    return out


def _module_exists(module: str) -> bool:
    try:
        return importlib.util.find_spec(module) is not None
    except ModuleNotFoundError:
        return False


_CACHE: dict[str, EnvDeclaration] = {}


def _own() -> list[EnvDeclaration]:
    """The declarations of the env packages shipped in mf_envs.envs (their `task.DECLARATION`)."""
    import mf_envs.envs as pkg

    out = []
    for info in sorted(pkgutil.iter_modules(pkg.__path__), key=lambda m: m.name):
        if info.ispkg and not info.name.startswith("_"):
            name = f"{pkg.__name__}.{info.name}.task"
            if _module_exists(name):
                decl = getattr(importlib.import_module(name), "DECLARATION", None)
                if isinstance(decl, EnvDeclaration):
                    out.append(decl)
    return out


def _plugins() -> list[EnvDeclaration]:
    """Declarations named in the `mf_envs.envs` entry-point group of installed distributions."""
    out = []
    for ep in importlib.metadata.entry_points(group=ENTRY_POINT_GROUP):
        decl = ep.load()
        if not isinstance(decl, EnvDeclaration):
            raise ValueError(f"entry point {ep.name!r} ({ep.value}) is not an EnvDeclaration")
        out.append(decl)
    return out


def refresh() -> dict[str, EnvDeclaration]:
    """Collect the declarations again (the shipped envs first, then plugins in name order)."""
    found: dict[str, EnvDeclaration] = {}
    for decl in _own() + _plugins():
        if decl.env_id in found and found[decl.env_id] != decl:
            raise ValueError(f"env_id: {decl.env_id!r} is declared twice")
        found[decl.env_id] = decl
    _CACHE.clear()
    _CACHE.update(found)
    return dict(found)


def declarations() -> dict[str, EnvDeclaration]:
    """env id -> its declaration (collected once; `refresh()` collects again)."""
    if not _CACHE:
        refresh()
    return dict(_CACHE)


def task_declarations() -> dict[str, EnvDeclaration]:
    """Every registered task id -> its declaration: each env's own, then its variants'."""
    out: dict[str, EnvDeclaration] = {}
    for env_id, decl in declarations().items():
        out[env_id] = decl
        for v in decl.variants:
            if v.env_id in out or v.env_id in declarations():
                raise ValueError(f"env_id: {v.env_id!r} is declared twice")
            out[v.env_id] = decl.variant(v.env_id)
    return out


def declaration(env_id: str) -> EnvDeclaration | None:
    """The declaration of `env_id` (a deprecated alias resolves to its env; a variant id gives
    the variant's declaration, `EnvDeclaration.variant`), or None."""
    from mf_envs.envs._alias import canonical_env_id

    env_id = canonical_env_id(env_id, notice_alias=False)
    found = declarations().get(env_id)
    if found is not None:
        return found
    for decl in declarations().values():
        if any(v.env_id == env_id for v in decl.variants):
            return decl.variant(env_id)
    return None


def load(entry: str) -> Any:
    """The object named by "module:attribute"."""
    module, _, name = entry.partition(":")
    return getattr(importlib.import_module(module), name)
