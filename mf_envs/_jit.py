"""`kernel`: numba's njit for hot kernels that only borrow arrays (no reference counting).

Numba's runtime counts references to every array a compiled function binds: each view
(`work[0]`, `y[i]`) and each array argument of a helper inlined with `inline="always"` costs an
atomic increment and decrement (`lock inc` / `lock dec`, each a full memory barrier). In the
ship's RK4-Munthe-Kaas step they took 23 % of the samples (perf) although every array
there belongs to the caller for the whole call. `kernel` compiles such a function with numba's
`_nrt=False` flag (the one numba uses for its own allocation-free helpers), which emits none.

What a kernel may do, and how it is checked (`tests/test_jit.py`):
- allocate nothing, nor call anything that does: numba refuses to compile it (a loud error, at
  the first call), slice copies (`a[:] = b`, which may allocate) included: copy element-wise;
- return no array, nor a tuple holding one (numba allows returning an argument array, but the
  counting caller would then release a reference it never got): `array_returns()`
  lists the compiled kernels that do, and must be empty after the envs have run;
- and numba's allocation counters balance over runs of every env that uses kernels.
Callers with the runtime allocate the scratch and pass it in (`..._rows(..., work)`).

Inlining: a small helper of a hot kernel is `@kernel(forceinline=True)`: numba marks it LLVM
`alwaysinline`, so it is compiled once and LLVM inlines its machine code into every caller (the
same code as numba's `inline="always"`, at a fraction of the compile time). numba's own
`inline="always"` splices a copy of the callee's numba IR into each call site, and that copy is
quadratic in the callee's size (each block is deep-copied with the whole variable scope): with
the ship's right-hand side inlined four times into its RKMK4 step it cost 260 CPU s and 1.9 GB on
the first (uncached) run; keep it for tiny leaves and for helpers that return an array view.
Being a kernel, a forceinline helper is compiled without the runtime whoever calls it first (a
plain `numba.njit` helper inherits its first caller's flags, so its reference counting would
depend on call order).
"""

from __future__ import annotations

import types as pytypes
from collections.abc import Callable
from typing import Any

import numba
from numba.core import types

KERNELS: list[Any] = []  # every dispatcher made by `kernel` (for the checks above)


def kernel(fn: Callable | None = None, **options: Any) -> Any:
    """`numba.njit(cache=True, _nrt=False, **options)`, registered in KERNELS (module doc);
    usable as `@kernel` or `@kernel(nogil=True)`."""
    if fn is None:
        return lambda f: kernel(f, **options)
    disp = numba.njit(cache=True, _nrt=False, **options)(fn)
    KERNELS.append(disp)
    return disp


def _holds_array(t: types.Type) -> bool:
    if isinstance(t, types.Array):
        return True
    if isinstance(t, types.BaseTuple):
        return any(_holds_array(e) for e in t.types)
    return False


def array_returns() -> list[str]:
    """Names of the compiled kernels whose return type holds an array (must be none)."""
    bad = []
    for disp in KERNELS:
        for sig in disp.nopython_signatures:
            if _holds_array(sig.return_type):
                bad.append(f"{disp.py_func.__module__}.{disp.py_func.__qualname__}{sig}")
    return bad


def specialise(template: Callable, anchor: Any, prefix: str, inline: bool | None = False,
               **bindings: Any) -> Any:  # fmt: skip
    """`template` compiled with the names in `bindings` (jitted functions, as the template's
    globals) bound: numba cannot cache a function that receives another jitted function as an
    argument, so the template's code object is re-bound to them and compiled with `cache=True`
    under the name `<prefix>_<anchor's name>`, cached beside `anchor`'s module (the model's:
    `mf_envs._cache` stamps that cache with the module's source and the sources it imports, the
    template's among them, so editing either invalidates it). inline: False a plain
    `numba.njit`, True a `kernel` LLVM inlines into its callers, None numba's IR inlining
    (`inline="always"`, for a small piece with one caller)."""
    py = anchor.py_func
    name = f"{prefix}_{py.__name__}"
    code = template.__code__.replace(
        co_filename=py.__code__.co_filename, co_name=name, co_qualname=name
    )
    fn = pytypes.FunctionType(code, dict(template.__globals__, **bindings), name)
    fn.__module__, fn.__doc__ = py.__module__, template.__doc__
    if inline:
        return kernel(fn, forceinline=True)
    if inline is None:
        return numba.njit(cache=True, inline="always")(fn)
    return numba.njit(cache=True)(fn)
