"""Classical baseline controllers: PLL, PID, LQR (python-control), the seed's open-loop excitations.

`make_baseline(env, kind=None, **params)` returns a controller for that env. A controller has
`reset()` and `predict(obs, deterministic=True) -> (action, None)`, the same call as an SB3
policy. Controllers read only the observation (what a real device measures) unless documented.

Each env's controllers live in their own module (`controllers/<module>.py`, named by the env's
declaration, `EnvDeclaration.baselines`) and register with `register(env_id, kind, factory,
default=...)` at import; `make_baseline` imports that module.
"""

from __future__ import annotations

import importlib
import inspect
from collections.abc import Callable
from typing import Any, Protocol

import numpy as np

_REGISTRY: dict[str, dict[str, Callable[..., Any]]] = {}
_DEFAULT: dict[str, str] = {}


class Controller(Protocol):
    def reset(self) -> None: ...

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]: ...


def register(env_id: str, kind: str, factory: Callable[..., Any], default: bool = False) -> None:
    """Register `factory(env, **params) -> Controller` as `kind` for `env_id`."""
    _REGISTRY.setdefault(env_id, {})[kind] = factory
    if default or env_id not in _DEFAULT:
        _DEFAULT[env_id] = kind


def _env_id(env: Any) -> str:
    spec = getattr(env, "spec", None) or getattr(getattr(env, "unwrapped", None), "spec", None)
    if spec is None:
        raise ValueError("env: has no spec; create it with gymnasium.make(env_id)")
    return spec.id


def _registered(env_id: str) -> tuple[str, list[str]]:
    """(the id the baselines are registered under, its kinds, default first) for `env_id`: its
    baselines module imported; a task variant's are its env's (`EnvDeclaration.base_id`)."""
    from mf_envs.envs import canonical_env_id, declaration, declarations

    env_id = canonical_env_id(env_id)  # a deprecated id (GOWEC-v1): its new id, with a warning
    decl = declaration(env_id)
    if decl is None or not decl.baselines:
        known = sorted(i for i, d in declarations().items() if d.baselines)
        raise ValueError(f"env_id: no baselines for {env_id!r}; known: {known}")
    importlib.import_module(decl.baselines)
    base = decl.base_id
    default = _DEFAULT.get(base)
    return base, sorted(_REGISTRY.get(base, {}), key=lambda k: (k != default, k))


def baseline_kinds(env_id: str) -> list[str]:
    """The controller kinds available for `env_id`, default first."""
    return _registered(env_id)[1]


def make_baseline(env: Any, kind: str | None = None, **params: Any) -> Any:
    """A baseline controller for `env` (a gymnasium env made with `gym.make`)."""
    env_id = _env_id(env)
    base, kinds = _registered(env_id)
    kind = kinds[0] if kind is None else kind
    if kind not in kinds:
        raise ValueError(f"kind: {kind!r} is not a baseline for {env_id}; available: {kinds}")
    factory = _REGISTRY[base][kind]
    sig = inspect.signature(factory)
    if not any(p.kind is p.VAR_KEYWORD for p in sig.parameters.values()):
        names = [n for n in list(sig.parameters)[1:] if n != "self"]
        unknown = sorted(set(params) - set(names))
        if unknown:
            raise ValueError(
                f"params: {unknown} are not parameters of the {kind!r} baseline of {env_id}; "
                f"it takes {names}"
            )
    return factory(env, **params)
