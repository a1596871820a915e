"""Serpentine-v0: `env.py` the Gymnasium class, `task.py` its declaration (`DECLARATION`), the
package's other modules as docs/adding_an_env.md lists them. Names below import on first use, so
reading the declaration (`import mf_envs`) does not load the physics."""

from __future__ import annotations

import importlib
from typing import Any

_LAZY = {
    "AVAILABLE_EFFECTS": "env",
    "DEFAULT_EFFECTS": "env",
    "SerpentineEnv": "env",
    "observation_layout": "spec",
}
__all__ = sorted(_LAZY)


def __getattr__(name: str) -> Any:
    if name not in _LAZY:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(importlib.import_module(f"{__name__}.{_LAZY[name]}"), name)
