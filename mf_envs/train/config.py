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
from mf_envs.train.kwargs import parse_policy_kwargs as whitelist_policy_kwargs
from mf_envs.train.kwargs import resolve_activation

CONFIG_DIR = Path(__file__).parent / "configs"
DEFAULT_CONFIG = CONFIG_DIR / "ppo.yml"
ALGOS = ("ppo", "sac", "td3")  # `mf-envs train --algo`; configs/<algo>.yml as rl-zoo3's files


def default_config(algo: str = "ppo") -> Path:
    """The shipped rl-zoo3 file of `algo` (`configs/ppo.yml`, `sac.yml`, `td3.yml`)."""
    if algo not in ALGOS:
        raise ValueError(f"algo: one of {ALGOS}, got {algo!r}")
    return CONFIG_DIR / f"{algo}.yml"


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


MAX_ENVS = 256  # n_envs: parallel envs of one run (the shipped configs use 1 or 2)
MAX_TIMESTEPS = 10**10
_RESERVED = {"seed": "--seed", "device": "(always cpu)", "tensorboard_log": "--tensorboard",
             "env": "ENV_ID", "verbose": "(set by mf-envs train)"}  # fmt: skip


def _num(lo: float, hi: float, *, lo_open: bool = False) -> Any:
    """A checker of a finite real number in [lo, hi] ((lo, hi] with `lo_open`)."""

    def check(v: Any) -> str | None:
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            return "a finite number"
        if v < lo or v > hi or (lo_open and v == lo):
            return f"a number in {'(' if lo_open else '['}{lo:g}, {hi:g}]"
        return None

    return check


def _int(lo: int, hi: int) -> Any:
    """A checker of a whole number in [lo, hi] (`!!float 2e3` included)."""

    def check(v: Any) -> str | None:
        ok = isinstance(v, int | float) and not isinstance(v, bool)
        if not ok or not math.isfinite(v) or v != int(v) or not lo <= v <= hi:
            return f"a whole number in [{lo}, {hi}]"
        return None

    return check


def _schedule(lo: float, hi: float) -> Any:
    """A checker of a number in (lo, hi] or the zoo's linear schedule `lin_<number>`."""
    number = _num(lo, hi, lo_open=True)

    def check(v: Any) -> str | None:
        if isinstance(v, str) and v.startswith("lin_"):
            try:
                v = float(v[4:])
            except ValueError:
                return f"a number in ({lo:g}, {hi:g}] or 'lin_<number>'"
        return None if number(v) is None else f"a number in ({lo:g}, {hi:g}] or 'lin_<number>'"

    return check


def _one_of(*choices: Any) -> Any:
    """A checker of one of `choices` (by type and value: 1 is not True)."""

    def check(v: Any) -> str | None:
        if any(v is c or (type(v) is type(c) and v == c) for c in choices):
            return None
        return f"one of {list(choices)}"

    return check


def _either(*checks: Any) -> Any:
    def check(v: Any) -> str | None:
        errors = [c(v) for c in checks]
        return None if None in errors else " or ".join(errors)

    return check


def _entropy(v: Any) -> str | None:
    """ent_coef: a number >= 0; SAC also 'auto' or 'auto_<initial value>'."""
    if isinstance(v, str):
        tail = v[5:] if v.startswith("auto_") else None
        if v == "auto" or (tail and _float_ok(tail) and 0 < float(tail) <= 1e6):
            return None
        return "a number >= 0, 'auto' or 'auto_<number>'"
    return _num(0.0, 1e6)(v)


def _float_ok(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def _train_freq(v: Any) -> str | None:
    """SAC/TD3 train_freq: a whole number >= 1, or [n, 'step' | 'episode']."""
    if isinstance(v, list) and len(v) == 2 and v[1] in ("step", "episode"):
        v = v[0]
    return None if _int(1, 10**6)(v) is None else "a whole number >= 1 or [n, 'step'|'episode']"


_FLAG = _one_of(True, False)
# every algorithm key a config may hold, with its check (None: valid; else what is expected)
ALGO_KEYS: dict[str, Any] = {
    "learning_rate": _schedule(0.0, 1.0),
    "clip_range": _schedule(0.0, 10.0),
    "clip_range_vf": _either(_one_of(None), _schedule(0.0, 10.0)),
    "n_steps": _int(1, 10**6),
    "batch_size": _int(1, 10**7),
    "n_epochs": _int(1, 1000),
    "gamma": _num(0.0, 1.0),
    "gae_lambda": _num(0.0, 1.0),
    "ent_coef": _entropy,
    "vf_coef": _num(0.0, 1e6),
    "max_grad_norm": _num(0.0, 1e6, lo_open=True),
    "use_sde": _FLAG,
    "sde_sample_freq": _int(-1, 10**6),
    "target_kl": _either(_one_of(None), _num(0.0, 1e6, lo_open=True)),
    "normalize_advantage": _FLAG,
    "stats_window_size": _int(1, 10**6),
    "policy_kwargs": lambda v: None,  # the whitelist of train.kwargs (parse_policy_kwargs)
    "buffer_size": _int(1, 10**7),
    "learning_starts": _int(0, 10**9),
    "tau": _num(0.0, 1.0),
    "train_freq": _train_freq,
    "gradient_steps": _either(_one_of(-1), _int(1, 10**4)),
    "target_update_interval": _int(1, 10**9),
    "target_entropy": _either(_one_of("auto"), _num(-1e6, 1e6)),
    "use_sde_at_warmup": _FLAG,
    "optimize_memory_usage": _FLAG,
    "policy_delay": _int(1, 10**6),
    "target_policy_noise": _num(0.0, 1e6),
    "target_noise_clip": _num(0.0, 1e6),
}


def check_algo_values(env_id: str, ppo: dict[str, Any], n_envs: int) -> None:
    """ValueError naming the first algorithm key of a config entry that is unknown, reserved
    for a command-line option, or of the wrong type or range (`ALGO_KEYS`)."""
    for key, value in ppo.items():
        if not isinstance(key, str):
            raise ValueError(f"config: {env_id}: key {key!r} is not a name")
        if key in _RESERVED:
            raise ValueError(
                f"config: {env_id}: {key} is set by mf-envs train ({_RESERVED[key]}); remove it"
            )
        check = ALGO_KEYS.get(key)
        if check is None:
            close = difflib.get_close_matches(key, sorted(ALGO_KEYS), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ValueError(
                f"config: {env_id}: {key!r} is not a parameter mf-envs train passes to "
                f"stable-baselines3{hint}"
            )
        expected = check(value)
        if expected is not None:
            raise ValueError(f"config: {env_id}: {key} must be {expected}, got {_short(value)}")
    if "n_steps" in ppo and int(ppo["n_steps"]) * n_envs < 2:
        raise ValueError(f"config: {env_id}: n_steps x n_envs must be >= 2 (a PPO rollout)")


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 80 else f"{text[:60]}... ({len(text)} characters)"


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
        raise ValueError(f"config: {env_id}: policy must be 'MlpPolicy', got {_short(policy)}")
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
            f"config: {env_id}: {key} must be a whole number in [1, {high}], got {_short(value)}"
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
    "norm_obs": _FLAG,
    "norm_reward": _FLAG,
    "clip_obs": _num(0.0, 1e9, lo_open=True),
    "clip_reward": _num(0.0, 1e9, lo_open=True),
    "gamma": _num(0.0, 1.0),
    "epsilon": _num(0.0, 1.0, lo_open=True),
}


def _parse_normalize(value: Any) -> dict[str, Any] | None:
    """`normalize`: a bool, or a mapping (or its string form, read as a Python literal, never
    run) of VecNormalize kwargs (`_NORMALIZE_KEYS`); ValueError naming normalize."""
    if isinstance(value, str):
        try:
            value = ast.literal_eval(value)
        except (SyntaxError, ValueError, TypeError, MemoryError, RecursionError):
            raise ValueError(
                f"normalize: {_short(value)} is not a literal bool or dict of VecNormalize kwargs"
            ) from None
    if value is True:
        return {}
    if value is False or value is None:
        return None
    if not isinstance(value, dict):
        raise ValueError(
            f"normalize: expected a bool or a dict of VecNormalize kwargs, got {_short(value)}"
        )
    for key, v in value.items():
        check = _NORMALIZE_KEYS.get(key) if isinstance(key, str) else None
        if check is None:
            raise ValueError(f"normalize: unknown key {key!r}; known: {sorted(_NORMALIZE_KEYS)}")
        expected = check(v)
        if expected is not None:
            raise ValueError(f"normalize: {key} must be {expected}, got {_short(v)}")
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
