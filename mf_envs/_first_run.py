"""One stderr line when numba starts compiling kernels that are not cached on disk yet.

The kernels are compiled with `cache=True`, so numba stores them in each module's `__pycache__`
(`<module>.<function>-<line>.pyXY.nbi/.nbc`) and later runs load them in milliseconds. The first
run compiles them instead (4-35 s of CPU per env, about 2 min for `mf-envs demo`, measured on 2
cores), which would otherwise look like a hang.
Detection costs nothing: numba fires its `numba:compile` event only on a cache miss (loading a
cached kernel fires none), so a listener on that event (numba's documented Event API) prints the
notice once per process, at the first real compilation.
"""

from __future__ import annotations

import sys

MESSAGE = (
    "mf_envs: compiling the numba kernels (first run only: 4-35 s per env, about 2 min for "
    "the demo; they are cached on disk for later runs)"
)


def _say(line: str) -> None:
    """line on stderr on a line of its own: through `tqdm.write` while a tqdm bar is drawn
    there (`mf-envs demo`), which lifts the bar off the line first; else a plain print."""
    tqdm = sys.modules.get("tqdm")
    if tqdm is not None and getattr(tqdm.tqdm, "_instances", None):
        tqdm.tqdm.write(line, file=sys.stderr)
        return
    print(line, file=sys.stderr, flush=True)


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
                _say(MESSAGE)

        def on_end(self, ev: event.Event) -> None:
            pass

    event.register("numba:compile", _Notice())
    _INSTALLED = True


_INSTALLED = False
