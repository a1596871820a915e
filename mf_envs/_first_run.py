"""One stderr line when numba starts compiling kernels that are not cached on disk yet.

The kernels are compiled with `cache=True`, so numba stores them in each module's `__pycache__`
(`<module>.<function>-<line>.pyXY.nbi/.nbc`) and later runs load them in milliseconds. The first
run compiles them instead (about a minute on 2 cores), which would otherwise look like a hang.
Detection costs nothing: numba fires its `numba:compile` event only on a cache miss (loading a
cached kernel fires none), so a listener on that event (numba's documented Event API) prints the
notice once per process, at the first real compilation.
"""

from __future__ import annotations

import sys

MESSAGE = (
    "mf_envs: compiling the numba kernels (first run only: about 1 min on 2 cores; "
    "they are cached on disk for later runs)"
)


def install() -> None:
    """Register the one-shot listener (idempotent)."""
    global _INSTALLED
    if _INSTALLED:
        return
    from numba.core import event

    class _Notice(event.Listener):
        shown = False

        def on_start(self, ev: event.Event) -> None:
            if not _Notice.shown:
                _Notice.shown = True
                print(MESSAGE, file=sys.stderr, flush=True)

        def on_end(self, ev: event.Event) -> None:
            pass

    event.register("numba:compile", _Notice())
    _INSTALLED = True


_INSTALLED = False
