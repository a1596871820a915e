"""Numba's on-disk caches of mf_envs' kernels, stamped by the sources a kernel depends on.

Numba (`cache=True`) keys a cached kernel on the one file that defines it. A kernel that calls
kernels of other files (the env rows call the physics kernels, which call the frames' steppers)
is therefore not recompiled when only a callee's file changes: the stale machine code is
loaded, with its old layouts and constants. Measured on this project: after a merge that
changed the stabilizer's physics kernels, a cached `GyroStabilizer-v0` step raised
ZeroDivisionError until the caches were deleted; a user upgrading in place keeps the
`__pycache__` files (pip does not list them) and would meet the same.

`install()` puts two locators in front of numba's (`numba.core.caching.CacheImpl` tries its
locator classes in order; these are numba's own NUMBA_CACHE_DIR and in-tree locators, in
numba's order, with another stamp): for a function defined in a file of this package, the
source stamp is `source_stamp(file)`, one hash of that file and of every package module it
imports, transitively (`dependencies`: the `import` statements read from the source, not run).
A kernel can only call what its module imports (or what those modules import), so an edit to a
callee's module recompiles its callers, and an edit elsewhere (a CLI docstring, the training
code) recompiles nothing. The walk never enters `NOT_KERNEL_CODE` (the CLI, training, sweeps,
benchmarks, controllers, rendering: no kernel calls into them). Functions outside the package
(a plugin env) keep numba's default. The locators subclass numba's internal classes, hence the
upper bound on numba in pyproject.toml (docs/design.md).
"""

from __future__ import annotations

import hashlib
import re
from functools import cache
from pathlib import Path

_ROOT = Path(__file__).resolve().parent
PACKAGE = "mf_envs"
# subpackages no kernel depends on: never part of a kernel's stamp
NOT_KERNEL_CODE = ("cli", "train", "sweep", "benchmarks", "controllers", "render")
_INSTALLED = False


def _module_file(name: str, root: Path) -> Path | None:
    """The file of package module `name` ("mf_envs.a.b") under `root`, if it is one of ours."""
    parts = name.split(".")
    if parts[0] != PACKAGE or (len(parts) > 1 and parts[1] in NOT_KERNEL_CODE):
        return None
    base = root.joinpath(*parts[1:])
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


# `import a.b, c as d` and `from .a import (b, c as d)` statements, anywhere in a line's start
# (a match inside a docstring only adds a dependency, never loses one)
_IMPORT = re.compile(r"^[ \t]*import[ \t]+([\w. \t,]+)", re.M)
_FROM = re.compile(r"^[ \t]*from[ \t]+(\.*)([\w.]*)[ \t]+import[ \t]+(\([^)]*\)|[^\n#;]*)", re.M)


def _names(text: str) -> list[str]:
    return [n.split()[0] for n in text.strip("()").replace("\\", " ").split(",") if n.split()]


@cache
def _imports(path: Path, root: Path) -> frozenset[Path]:
    """The package files that `path`'s import statements name (a `from m import x` names m
    and, if it is a module, m.x)."""
    rel = path.relative_to(root).with_suffix("").parts
    package = (PACKAGE, *rel[:-1])  # the package `path` is in (or is the __init__ of)
    source = path.read_text(encoding="utf-8")
    names = [n for m in _IMPORT.finditer(source) for n in _names(m.group(1))]
    for dots, module, what in _FROM.findall(source):
        if dots:  # relative: from the package len(dots) - 1 levels up
            base = package[: len(package) - len(dots) + 1]
            module = ".".join((*base, module) if module else base)
        names += [module] + [f"{module}.{n}" for n in _names(what)]
    return frozenset(f for f in (_module_file(n, root) for n in names) if f is not None)


def dependencies(py_file: str | Path, root: Path = _ROOT) -> list[Path]:
    """`py_file` and every package file it imports, transitively (sorted)."""
    start = Path(py_file).resolve()
    seen, todo = {start}, [start]
    while todo:
        for dep in _imports(todo.pop(), root):
            if dep not in seen:
                seen.add(dep)
                todo.append(dep)
    return sorted(seen)


@cache
def source_stamp(py_file: str, root: Path = _ROOT) -> str:
    """sha1 of the sources a kernel of `py_file` depends on (`dependencies`: relative paths and
    bytes); computed once per file and process."""
    h = hashlib.sha1()
    for p in dependencies(py_file, root):
        h.update(str(p.relative_to(root)).encode())
        h.update(p.read_bytes())
    return h.hexdigest()


def _inside(py_file: str) -> bool:
    try:
        return Path(py_file).resolve().is_relative_to(_ROOT)
    except (OSError, ValueError):
        return False


def install() -> None:
    """Register the dependency-stamped locators (idempotent)."""
    global _INSTALLED
    if _INSTALLED:
        return
    from numba.core import caching

    class _Stamped:
        """A numba locator for this package's files, stamped by `source_stamp`."""

        @classmethod
        def from_function(cls, py_func, py_file):  # noqa: ANN001, ANN206
            if not _inside(py_file):
                return None
            locator = super().from_function(py_func, py_file)
            if locator is not None:
                locator.stamp_file = str(Path(py_file).resolve())
            return locator

        def get_source_stamp(self):  # noqa: ANN201
            return source_stamp(self.stamp_file)

    class _UserDirLocator(_Stamped, caching.UserProvidedCacheLocator):
        """numba's NUMBA_CACHE_DIR locator (used only when that is set, as numba's)."""

    class _InTreeLocator(_Stamped, caching.InTreeCacheLocator):
        """numba's in-tree locator (the cache beside the source)."""

    # numba's order: a user-provided NUMBA_CACHE_DIR first, then beside the source
    caching.CacheImpl._locator_classes[:0] = [_UserDirLocator, _InTreeLocator]
    _INSTALLED = True
