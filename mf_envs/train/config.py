"""Per-env hyperparameters in the rl-baselines3-zoo YAML format, one file per algorithm
(`configs/ppo.yml`, `sac.yml`, `td3.yml`, as the zoo's `hyperparams/<algo>.yml`).

One top-level key per env id. Recognised keys, as in rl-zoo3:

- `n_timesteps` (training budget), `n_envs` (parallel envs), `policy` (e.g. `MlpPolicy`);
- `normalize`: `true`/`false`, or a string/dict of `VecNormalize` kwargs, e.g.
  `"{'norm_obs': True, 'norm_reward': False}"`;
- `policy_kwargs`: a dict, or the zoo's string form
  `"dict(net_arch=[64, 64], activation_fn=nn.Tanh)"`, parsed by a whitelist (`train.kwargs`:
  numbers, booleans, lists, dicts, activation names; never `eval`);
- `env_wrapper`: the name of a wrapper from the whitelist `WRAPPERS` (the project's
  `DomainRandomization`, a few Gymnasium wrappers), or `{name: {kwargs}}` (a list of either);
  nothing else is imported, so a config cannot run code;
- `env_kwargs`: `gym.make` kwargs (the zoo takes these on its command line; here they may live
  in the file so a config alone reproduces a run);
- `noise_type`, `noise_std`: action noise of SAC/TD3 ('normal' or 'ornstein-uhlenbeck');
- `learning_rate`/`clip_range` as numbers or the zoo's linear schedules `lin_3e-4`;
- every other key is passed to the algorithm (`stable_baselines3.PPO`, `SAC`, `TD3`) unchanged
  (a key it does not take is refused naming it, `check_algo_kwargs`).

Every key is checked for its type and range before anything is built or imported (`ALGO_KEYS`:
numbers finite and in the range SB3 accepts, sizes bounded, schedules as a number or
`lin_<number>`); an unknown key, or one the trainer sets itself (`seed`, `device`,
`tensorboard_log`: command-line options), is refused naming it.

The files load unchanged in rl-zoo3 (`python -m rl_zoo3.train --algo ppo --env ENV_ID
--gym-packages mf_envs -conf FILE`): mf-envs' own options (`--eval-episodes`, `--vec-env`) are
command-line options, as they are the zoo's.
"""

from __future__ import annotations

import ast
import difflib
import importlib
import inspect
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from mf_envs._files import load_yaml
from mf_envs.train.config_check import (
    FLAG,
    MAX_ENVS,
    MAX_TIMESTEPS,
    check_algo_values,
    number,
    short,
)
from mf_envs.train.kwargs import parse_policy_kwargs as whitelist_policy_kwargs
from mf_envs.train.kwargs import resolve_activation

CONFIG_DIR = Path(__file__).parent / "configs"
DEFAULT_CONFIG = CONFIG_DIR / "ppo.yml"
# `mf-envs train --algo`: SB3's PPO, SAC, TD3 and SBX's SAC (the JAX SB3, its update compiled;
# the `sbx` extra), configs/<algo>.yml as rl-zoo3's files; SBX's SAC reads sac.yml (its keys are
# SB3's, as rl-zoo3's SBX runs read hyperparams/sac.yml)
ALGOS = ("ppo", "sac", "td3", "sbx_sac")
CONFIG_OF = {"sbx_sac": "sac"}


def default_config(algo: str = "ppo") -> Path:
    """The shipped rl-zoo3 file of `algo` (`configs/ppo.yml`, `sac.yml`, `td3.yml`)."""
    if algo not in ALGOS:
        raise ValueError(f"algo: one of {ALGOS}, got {algo!r}")
    return CONFIG_DIR / f"{CONFIG_OF.get(algo, algo)}.yml"


_ZOO_KEYS = (
    "n_timesteps",
    "n_envs",
    "policy",
    "normalize",
    "env_wrapper",
    "env_kwargs",
    "noise_type",
    "noise_std",
)
# mf-envs options that earlier configs held: rl-zoo3 would pass them to PPO, so they are
# command-line options now (as the zoo's own --eval-episodes and --vec-env)
_MOVED = {"eval_episodes": "--eval-episodes", "vec_env": "--vec-env"}
_UNSUPPORTED = ("frame_stack", "callback", "vec_env_wrapper", "normalize_kwargs")


@dataclass(frozen=True)
class Hyperparams:
    """Parsed hyperparameters of one env id (see the module docstring for the YAML keys)."""

    env_id: str
    n_timesteps: int | None  # None: the config leaves it to --timesteps
    n_envs: int = 1
    policy: str = "MlpPolicy"
    normalize: dict[str, Any] | None = None  # VecNormalize kwargs, None = no normalisation
    env_wrappers: tuple[tuple[str, dict[str, Any]], ...] = ()
    env_kwargs: dict[str, Any] = field(default_factory=dict)
    action_noise: tuple[str, float] | None = None  # the zoo's (noise_type, noise_std): SAC/TD3
    ppo_kwargs: dict[str, Any] = field(default_factory=dict)  # raw, schedules unresolved


def read_config(path: str | Path | None = None) -> dict[str, dict[str, Any]]:
    """The whole YAML file as {env_id: {key: value}} (ValueError if missing or malformed)."""
    p = Path(path) if path is not None else DEFAULT_CONFIG
    data = load_yaml(p, "config")
    if not isinstance(data, dict) or not all(isinstance(v, dict) for v in data.values()):
        raise ValueError(f"config: {p} must map env ids to dicts of hyperparameters")
    return data


def load_hyperparams(env_id: str, path: str | Path | None = None) -> Hyperparams:
    """Hyperparameters of `env_id` from `path` (default `mf_envs/train/configs/ppo.yml`; the
    other algorithms' files: `default_config(algo)`). An env the shipped file has no entry for
    takes its declaration's `hyperparams[algo]` (an env added as a plugin brings its own); a
    task variant without its own entry takes its env's (`EnvDeclaration.variant_of`)."""
    raw = config_entry(env_id, path)
    bad = [k for k in _UNSUPPORTED if k in raw]
    if bad:
        raise ValueError(f"config: rl-zoo3 keys {bad} are not supported by mf-envs train")
    moved = sorted(set(raw) & set(_MOVED))
    if moved:
        k = moved[0]
        raise ValueError(
            f"config: {env_id}: {k} is not an rl-zoo3 key (the zoo would pass it to PPO); "
            f"give it on the command line: mf-envs train {_MOVED[k]}"
        )
    ppo = {k: v for k, v in raw.items() if k not in _ZOO_KEYS}
    n_envs = _count(env_id, "n_envs", raw.get("n_envs", 1), MAX_ENVS)
    check_algo_values(env_id, ppo, n_envs)
    if "policy_kwargs" in ppo:
        ppo["policy_kwargs"] = parse_policy_kwargs(ppo["policy_kwargs"])
    policy = raw.get("policy", "MlpPolicy")
    if policy != "MlpPolicy":
        raise ValueError(f"config: {env_id}: policy must be 'MlpPolicy', got {short(policy)}")
    return Hyperparams(
        env_id=env_id,
        n_timesteps=_count(env_id, "n_timesteps", raw["n_timesteps"], MAX_TIMESTEPS)
        if "n_timesteps" in raw
        else None,
        n_envs=n_envs,
        policy=policy,
        normalize=_parse_normalize(raw.get("normalize", False)),
        env_wrappers=_parse_wrappers(raw.get("env_wrapper")),
        env_kwargs=_env_kwargs(env_id, raw.get("env_kwargs")),
        action_noise=_parse_noise(env_id, raw.get("noise_type"), raw.get("noise_std")),
        ppo_kwargs=ppo,
    )


def config_entry(env_id: str, path: str | Path | None = None) -> dict[str, Any]:
    """The raw rl-zoo3 entry `load_hyperparams` reads for `env_id` from `path` (its docstring:
    the id's own, a variant's env's, or the declaration's), as a new dict; ValueError if none."""
    from mf_envs.envs import declaration

    data = read_config(path)
    raw = data.get(env_id)
    decl = declaration(env_id)
    if raw is None and decl is not None and decl.variant_of is not None:
        raw = data.get(decl.variant_of)
    if raw is None:
        raw = _declared(env_id, Path(path) if path is not None else DEFAULT_CONFIG)
    if raw is None:
        raise ValueError(f"config: no entry for {env_id!r} in {path or DEFAULT_CONFIG}")
    return dict(raw)


def _declared(env_id: str, path: Path) -> dict[str, Any] | None:
    """The declaration's hyperparameters of `env_id` for a shipped file's algorithm, else None."""
    from mf_envs.envs import declaration

    decl = declaration(env_id)
    shipped = path.resolve().parent == CONFIG_DIR.resolve() and path.stem in ALGOS
    if decl is None or not shipped or path.stem not in decl.hyperparams:
        return None
    return dict(decl.hyperparams[path.stem])


def _count(env_id: str, key: str, value: Any, high: int) -> int:
    """A whole number in [1, high] (`!!float 3e5` included), ValueError naming the key."""
    x = float(value) if isinstance(value, int | float) and not isinstance(value, bool) else math.nan
    if not (math.isfinite(x) and 1 <= x <= high and x.is_integer()):
        raise ValueError(
            f"config: {env_id}: {key} must be a whole number in [1, {high}], got {short(value)}"
        )
    return int(x)


def _env_kwargs(env_id: str, value: Any) -> dict[str, Any]:
    """The config's `env_kwargs`: a mapping whose names the env's constructor takes (checked
    against its signature, before the env is built); ValueError naming the key."""
    if value is None:
        return {}
    if not isinstance(value, dict) or not all(isinstance(k, str) for k in value):
        raise ValueError(f"config: {env_id}: env_kwargs must be a mapping of names to values")
    params = _constructor_params(env_id)
    if params is not None:
        for key in value:
            if key not in params:
                close = difflib.get_close_matches(key, sorted(params), n=1)
                hint = f" (did you mean {close[0]!r}?)" if close else ""
                raise ValueError(
                    f"config: {env_id}: env_kwargs: {key!r} is not a parameter of {env_id}{hint}"
                )
    return dict(value)


def _constructor_params(env_id: str) -> set[str] | None:
    """The keyword names `gym.make(env_id, ...)` passes on to the env's class; None when the
    class takes **kwargs or cannot be inspected without building it."""
    import gymnasium as gym

    spec = gym.registry.get(env_id)
    entry = getattr(spec, "entry_point", None)
    try:
        cls = gym.envs.registration.load_env_creator(entry) if isinstance(entry, str) else entry
        sig = inspect.signature(cls)
    except (ValueError, TypeError, ImportError, AttributeError):
        return None
    if any(p.kind is p.VAR_KEYWORD for p in sig.parameters.values()):
        return None
    return {n for n, p in sig.parameters.items() if p.kind is not p.VAR_POSITIONAL} | {
        "max_episode_steps",
        "render_mode",
    }


def check_algo_kwargs(algo: Any, kwargs: dict[str, Any], env_id: str) -> None:
    """ValueError naming a config key that `algo` (an SB3 class) does not take, with the
    closest parameter name: a typo (`learning_rat`) is one line, not a traceback."""
    params = set(inspect.signature(algo.__init__).parameters) - {"self", "policy", "env"}
    if algo.__name__ != "SAC" and isinstance(kwargs.get("ent_coef"), str):
        raise ValueError(
            f"config: {env_id}: ent_coef 'auto' is SAC's; {algo.__name__} takes a number"
        )
    for key in kwargs:
        if key not in params:
            close = difflib.get_close_matches(key, sorted(params), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(f"config: {env_id}: {key!r} is not a {algo.__name__} parameter{hint}")


def parse_policy_kwargs(text: str | dict[str, Any]) -> dict[str, Any]:
    """The zoo's `"dict(net_arch=[64, 64], activation_fn=nn.Tanh)"` (or a mapping) -> PPO's
    `policy_kwargs`, parsed by the whitelist of `train.kwargs` (never `eval`)."""
    return resolve_activation(whitelist_policy_kwargs(text))


def resolve_schedules(ppo_kwargs: dict[str, Any]) -> dict[str, Any]:
    """Turn the zoo's `lin_<x>` strings into SB3 linear schedules (progress 1 -> 0)."""
    out = dict(ppo_kwargs)
    for key in ("learning_rate", "clip_range", "clip_range_vf"):
        v = out.get(key)
        if isinstance(v, str):
            if not v.startswith("lin_"):
                raise ValueError(f"{key}: expected a number or 'lin_<value>', got {v!r}")
            out[key] = _linear(float(v[4:]))
        elif v is not None:
            out[key] = float(v)
    return out


class _linear:  # a picklable linear schedule, as rl-zoo3's linear_schedule
    def __init__(self, initial: float) -> None:
        self.initial = initial

    def __call__(self, progress_remaining: float) -> float:
        return progress_remaining * self.initial


def _parse_noise(env_id: str, kind: Any, std: Any) -> tuple[str, float] | None:
    """The zoo's `noise_type` ('normal' or 'ornstein-uhlenbeck') and `noise_std` (action units,
    the actions being in [-1, 1]) -> (kind, std); None without noise_type."""
    if kind is None and std is None:
        return None
    if kind not in ("normal", "ornstein-uhlenbeck"):
        raise ValueError(f"config: {env_id}: noise_type must be 'normal' or 'ornstein-uhlenbeck'")
    try:
        sigma = float(std)
    except (TypeError, ValueError):
        sigma = math.nan
    if not (math.isfinite(sigma) and 0.0 < sigma <= 10.0):
        raise ValueError(f"config: {env_id}: noise_std must be in (0, 10], got {std!r}")
    return str(kind), sigma


# VecNormalize's kwargs a config's `normalize` may set, with their checks
_NORMALIZE_KEYS = {
    "norm_obs": FLAG,
    "norm_reward": FLAG,
    "clip_obs": number(0.0, 1e9, lo_open=True),
    "clip_reward": number(0.0, 1e9, lo_open=True),
    "gamma": number(0.0, 1.0),
    "epsilon": number(0.0, 1.0, lo_open=True),
}


def _parse_normalize(value: Any) -> dict[str, Any] | None:
    """`normalize`: a bool, or a mapping (or its string form, read as a Python literal, never
    run) of VecNormalize kwargs (`_NORMALIZE_KEYS`); ValueError naming normalize."""
    if isinstance(value, str):
        try:
            value = ast.literal_eval(value)
        except (SyntaxError, ValueError, TypeError, MemoryError, RecursionError):
            raise ValueError(
                f"normalize: {short(value)} is not a literal bool or dict of VecNormalize kwargs"
            ) from None
    if value is True:
        return {}
    if value is False or value is None:
        return None
    if not isinstance(value, dict):
        raise ValueError(
            f"normalize: expected a bool or a dict of VecNormalize kwargs, got {short(value)}"
        )
    for key, v in value.items():
        check = _NORMALIZE_KEYS.get(key) if isinstance(key, str) else None
        if check is None:
            raise ValueError(f"normalize: unknown key {key!r}; known: {sorted(_NORMALIZE_KEYS)}")
        expected = check(v)
        if expected is not None:
            raise ValueError(f"normalize: {key} must be {expected}, got {short(v)}")
    return dict(value)


def _parse_wrappers(value: Any) -> tuple[tuple[str, dict[str, Any]], ...]:
    if value is None:
        return ()
    items = value if isinstance(value, list) else [value]
    out = []
    for item in items:
        if isinstance(item, str):
            out.append((item, {}))
        elif isinstance(item, dict) and len(item) == 1:
            ((name, kwargs),) = item.items()
            if kwargs is not None and not isinstance(kwargs, dict):
                raise ValueError(
                    f"env_wrapper: kwargs of {name!r} must be a mapping, got {kwargs!r}"
                )
            out.append((str(name), dict(kwargs or {})))
        else:
            raise ValueError(
                f"env_wrapper: expected 'module.Class' or {{path: kwargs}}, got {item!r}"
            )
    for name, kwargs in out:
        cls = wrapper_class(name)  # a name outside WRAPPERS: ValueError naming env_wrapper
        sig = inspect.signature(cls)
        params = [n for n, p in sig.parameters.items() if p.kind is not p.VAR_KEYWORD]
        unknown = [k for k in kwargs if k not in params[1:]]  # the first is the env
        if unknown and len(params) == len(sig.parameters):
            raise ValueError(
                f"env_wrapper: {name}: unknown argument {unknown[0]!r}; it takes {params[1:]}"
            )
        try:  # a required argument missing
            sig.bind(None, **kwargs)
        except TypeError as exc:
            raise ValueError(f"env_wrapper: {name}: {exc}") from None
    return tuple(out)


# The wrappers a config may name (`env_wrapper`): nothing else is imported or called, so a config
# file cannot run code (an arbitrary dotted path once let `pydoc.pipepager` run a shell command).
# Each name maps to (module, attribute); the short `train.randomize...` form is the README's.
WRAPPERS: dict[str, tuple[str, str]] = {
    "mf_envs.train.randomize.DomainRandomization": (
        "mf_envs.train.randomize",
        "DomainRandomization",
    ),
    "train.randomize.DomainRandomization": ("mf_envs.train.randomize", "DomainRandomization"),
    **{
        f"gymnasium.wrappers.{name}": ("gymnasium.wrappers", name)
        for name in (
            "ClipAction",
            "RescaleAction",
            "TimeLimit",
            "TimeAwareObservation",
            "FlattenObservation",
            "NormalizeObservation",
            "NormalizeReward",
            "RecordEpisodeStatistics",
        )
    },
}


def wrapper_class(name: str) -> Any:
    """The wrapper class a config's `env_wrapper` names, from the whitelist `WRAPPERS` only
    (ValueError naming `env_wrapper` for any other name)."""
    if name not in WRAPPERS:
        raise ValueError(
            f"env_wrapper: {name!r} is not one of the wrappers a config may name "
            f"({sorted(WRAPPERS)}); nothing else is imported from a config"
        )
    module, attr = WRAPPERS[name]
    return getattr(importlib.import_module(module), attr)
