"""Lazy public names of an env package: `__getattr__, __all__ = lazy(__name__, env="EnvClass",
spec="OBS")` in the package's `__init__.py` imports `<package>.<module>` on first use, so reading
the declarations (`import mf_envs`) loads no physics. Every env module also gives its effects
(AVAILABLE_EFFECTS, DEFAULT_EFFECTS)."""

from __future__ import annotations

import importlib
from collections.abc import Callable
from typing import Any


def lazy(package: str, **modules: str) -> tuple[Callable[[str], Any], list[str]]:
    """(the package's module `__getattr__`, its `__all__`) for `modules`: the package's module
    -> the space-separated public names it defines."""
    table = {"AVAILABLE_EFFECTS": "env", "DEFAULT_EFFECTS": "env"}
    table.update({name: mod for mod, names in modules.items() for name in names.split()})

    def __getattr__(name: str) -> Any:
        if name not in table:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        return getattr(importlib.import_module(f"{package}.{table[name]}"), name)

    return __getattr__, sorted(table)
