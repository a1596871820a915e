"""The values of a training config's algorithm keys, checked before anything is built: each key
of `ALGO_KEYS` with its type and range (numbers finite and in range, learning-rate schedules as a
number or `lin_<number>`, sizes bounded), keys the trainer sets itself (`RESERVED`) refused, and
unknown keys named with the closest one (`check_algo_values`). The small checkers (`number`,
`whole`, `schedule`, `one_of`, `either`) return None for a valid value, else what is expected;
`train.rllib` checks its own keys with them."""

from __future__ import annotations

import difflib
import math
from typing import Any

MAX_ENVS = 8192  # n_envs: parallel envs (native vector rows) of one run
MAX_TIMESTEPS = 10**10
RESERVED = {"seed": "--seed", "device": "(always cpu)", "tensorboard_log": "--tensorboard",
             "env": "ENV_ID", "verbose": "(set by mf-envs train)"}  # fmt: skip


def number(lo: float, hi: float, *, lo_open: bool = False) -> Any:
    """A checker of a finite real number in [lo, hi] ((lo, hi] with `lo_open`)."""

    def check(v: Any) -> str | None:
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            return "a finite number"
        if v < lo or v > hi or (lo_open and v == lo):
            return f"a number in {'(' if lo_open else '['}{lo:g}, {hi:g}]"
        return None

    return check


def whole(lo: int, hi: int) -> Any:
    """A checker of a whole number in [lo, hi] (`!!float 2e3` included)."""

    def check(v: Any) -> str | None:
        ok = isinstance(v, int | float) and not isinstance(v, bool)
        if not ok or not math.isfinite(v) or v != int(v) or not lo <= v <= hi:
            return f"a whole number in [{lo}, {hi}]"
        return None

    return check


def schedule(lo: float, hi: float) -> Any:
    """A checker of a number in (lo, hi] or the zoo's linear schedule `lin_<number>`."""
    in_range = number(lo, hi, lo_open=True)

    def check(v: Any) -> str | None:
        if isinstance(v, str) and v.startswith("lin_"):
            try:
                v = float(v[4:])
            except ValueError:
                return f"a number in ({lo:g}, {hi:g}] or 'lin_<number>'"
        return None if in_range(v) is None else f"a number in ({lo:g}, {hi:g}] or 'lin_<number>'"

    return check


def one_of(*choices: Any) -> Any:
    """A checker of one of `choices` (by type and value: 1 is not True)."""

    def check(v: Any) -> str | None:
        if any(v is c or (type(v) is type(c) and v == c) for c in choices):
            return None
        return f"one of {list(choices)}"

    return check


def either(*checks: Any) -> Any:
    def check(v: Any) -> str | None:
        errors = [c(v) for c in checks]
        return None if None in errors else " or ".join(errors)

    return check


def entropy(v: Any) -> str | None:
    """ent_coef: a number >= 0; SAC also 'auto' or 'auto_<initial value>'."""
    if isinstance(v, str):
        tail = v[5:] if v.startswith("auto_") else None
        if v == "auto" or (tail and float_ok(tail) and 0 < float(tail) <= 1e6):
            return None
        return "a number >= 0, 'auto' or 'auto_<number>'"
    return number(0.0, 1e6)(v)


def float_ok(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def train_freq(v: Any) -> str | None:
    """SAC/TD3 train_freq: a whole number >= 1, or [n, 'step' | 'episode']."""
    if isinstance(v, list) and len(v) == 2 and v[1] in ("step", "episode"):
        v = v[0]
    return None if whole(1, 10**6)(v) is None else "a whole number >= 1 or [n, 'step'|'episode']"


FLAG = one_of(True, False)
# every algorithm key a config may hold, with its check (None: valid; else what is expected)
ALGO_KEYS: dict[str, Any] = {
    "learning_rate": schedule(0.0, 1.0),
    "clip_range": schedule(0.0, 10.0),
    "clip_range_vf": either(one_of(None), schedule(0.0, 10.0)),
    "n_steps": whole(1, 10**6),
    "batch_size": whole(1, 10**7),
    "n_epochs": whole(1, 1000),
    "gamma": number(0.0, 1.0),
    "gae_lambda": number(0.0, 1.0),
    "ent_coef": entropy,
    "vf_coef": number(0.0, 1e6),
    "max_grad_norm": number(0.0, 1e6, lo_open=True),
    "use_sde": FLAG,
    "sde_sample_freq": whole(-1, 10**6),
    "target_kl": either(one_of(None), number(0.0, 1e6, lo_open=True)),
    "normalize_advantage": FLAG,
    "stats_window_size": whole(1, 10**6),
    "policy_kwargs": lambda v: None,  # the whitelist of train.kwargs (parse_policy_kwargs)
    "buffer_size": whole(1, 10**7),
    "learning_starts": whole(0, 10**9),
    "tau": number(0.0, 1.0),
    "train_freq": train_freq,
    "gradient_steps": either(one_of(-1), whole(1, 10**4)),
    "target_update_interval": whole(1, 10**9),
    "targetentropy": either(one_of("auto"), number(-1e6, 1e6)),
    "use_sde_at_warmup": FLAG,
    "optimize_memory_usage": FLAG,
    "policy_delay": whole(1, 10**6),
    "target_policy_noise": number(0.0, 1e6),
    "target_noise_clip": number(0.0, 1e6),
}


def check_algo_values(env_id: str, ppo: dict[str, Any], n_envs: int) -> None:
    """ValueError naming the first algorithm key of a config entry that is unknown, reserved
    for a command-line option, or of the wrong type or range (`ALGO_KEYS`)."""
    for key, value in ppo.items():
        if not isinstance(key, str):
            raise ValueError(f"config: {env_id}: key {key!r} is not a name")
        if key in RESERVED:
            raise ValueError(
                f"config: {env_id}: {key} is set by mf-envs train ({RESERVED[key]}); remove it"
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
            raise ValueError(f"config: {env_id}: {key} must be {expected}, got {short(value)}")
    if "n_steps" in ppo and int(ppo["n_steps"]) * n_envs < 2:
        raise ValueError(f"config: {env_id}: n_steps x n_envs must be >= 2 (a PPO rollout)")


def short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 80 else f"{text[:60]}... ({len(text)} characters)"
