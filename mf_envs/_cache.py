"""Numba's on-disk caches of mf_envs' kernels, stamped by the whole package's source.

Numba (`cache=True`) keys a cached kernel on the stamp (mtime and size) of the one file that
defines it. A kernel that calls kernels of other files (the env steps call the physics kernels,
which call the frames' steppers) is therefore not recompiled when only a callee's file changes:
the stale machine code is loaded, with its old layouts and constants. Measured on this project:
after a merge that changed the stabilizer's physics kernels, a cached `GyroStabilizer-v0` step
raised ZeroDivisionError until the caches were deleted; a user upgrading in place keeps the
`__pycache__` files (pip does not list them) and would meet the same.

`install()` puts two locators in front of numba's (`numba.core.caching.CacheImpl` tries its
locator classes in order; these are numba's own NUMBA_CACHE_DIR and in-tree locators, in
numba's order, with another stamp): for a
function defined in a file of this package, the source stamp is one hash of every `.py` file of
the package (paths and bytes, computed once per process, a few ms), so any change to any of them
invalidates every cached kernel, which numba then recompiles and stores again. Functions outside
the package (a plugin env) keep numba's default.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

_ROOT = Path(__file__).resolve().parent
_STAMP: str | None = None
_INSTALLED = False


def package_stamp() -> str:
    """sha1 of every .py file under the package (sorted relative paths and their bytes)."""
    global _STAMP
    if _STAMP is None:
        h = hashlib.sha1()
        for p in sorted(_ROOT.rglob("*.py")):
            h.update(str(p.relative_to(_ROOT)).encode())
            h.update(p.read_bytes())
        _STAMP = h.hexdigest()
    return _STAMP


def install() -> None:
    """Register the package-stamped locator (idempotent)."""
    global _INSTALLED
    if _INSTALLED:
        return
    from numba.core import caching

    def _inside(py_file: str) -> bool:
        try:
            return Path(py_file).resolve().is_relative_to(_ROOT)
        except (OSError, ValueError):
            return False

    class _PackageUserDirLocator(caching.UserProvidedCacheLocator):
        """numba's NUMBA_CACHE_DIR locator (used only when that is set, as numba's) for this
        package's files, with `package_stamp()` as the source stamp."""

        @classmethod
        def from_function(cls, py_func, py_file):  # noqa: ANN001, ANN206
            return super().from_function(py_func, py_file) if _inside(py_file) else None

        def get_source_stamp(self):  # noqa: ANN201
            return package_stamp()

    class _PackageLocator(caching.InTreeCacheLocator):
        """numba's in-tree locator (cache beside the source) for this package's files, with
        `package_stamp()` as the source stamp."""

        @classmethod
        def from_function(cls, py_func, py_file):  # noqa: ANN001, ANN206
            return super().from_function(py_func, py_file) if _inside(py_file) else None

        def get_source_stamp(self):  # noqa: ANN201
            return package_stamp()

    # numba's order: a user-provided NUMBA_CACHE_DIR first, then beside the source
    caching.CacheImpl._locator_classes[:0] = [_PackageUserDirLocator, _PackageLocator]
    _INSTALLED = True
