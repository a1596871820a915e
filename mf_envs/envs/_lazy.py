"""Lazy public names of an env package: `__getattr__, __all__ = lazy(__name__, {name: module})`
in the package's `__init__.py` imports `<package>.<module>` on first use, so reading the
declarations (`import mf_envs`) loads no physics."""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any


def lazy(package: str, names: Mapping[str, str]) -> tuple[Callable[[str], Any], list[str]]:
    """(the package's module `__getattr__`, its `__all__`) for `names`: public name -> the
    package's module that defines it."""
    table = dict(names)

    def __getattr__(name: str) -> Any:
        if name not in table:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        return getattr(importlib.import_module(f"{package}.{table[name]}"), name)

    return __getattr__, sorted(table)
