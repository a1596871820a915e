"""Module discovery for the benchmark/demo packages (no shared list to edit)."""

from __future__ import annotations

import importlib
import pkgutil
from types import ModuleType


def discover(package: str, only: list[str] | None = None) -> list[ModuleType]:
    """Import every public submodule of `package`, sorted by its ORDER (default 100), then name.

    `only`: restrict to these module names (ValueError naming unknown ones).
    """
    pkg = importlib.import_module(package)
    names = sorted(m.name for m in pkgutil.iter_modules(pkg.__path__) if not m.name.startswith("_"))
    if only:
        unknown = [n for n in only if n not in names]
        if unknown:
            raise ValueError(f"scene: unknown {unknown}; available: {', '.join(names)}")
        names = [n for n in names if n in only]
    mods = [importlib.import_module(f"{package}.{n}") for n in names]
    return sorted(mods, key=lambda m: (getattr(m, "ORDER", 100), m.__name__))
