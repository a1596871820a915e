"""The kernels compiled without reference counting (`mf_envs._jit.kernel`) keep its rules: they
return no array, they allocate nothing (numba refuses to compile one that does), and numba's
allocation counters balance over runs of every env that uses them. The checks are shown to
fail on kernels that break the rules."""

from __future__ import annotations

import gc
import importlib

import gymnasium as gym
import numba
import numpy as np
import pytest
from numba.core.runtime import _nrt_python, rtsys

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs import _jit

KERNEL_ENVS = ("GyroStabilizer-v0", "FloatingGOWEC-v0")
ENTRY = {  # each env's vector step (a numba dispatcher called from Python)
    "GyroStabilizer-v0": ("mf_envs.envs.gyro_stabilizer.vector", "step_rows"),
    "FloatingGOWEC-v0": ("mf_envs.envs.gowec_v1.rows", "step_rows"),
}


def _run(env_id: str, steps: int) -> None:
    """steps random steps of the single env and of a 3-env native vector env (with resets)."""
    env = gym.make(env_id, episode_seconds=0.3)
    env.reset(seed=0)
    env.action_space.seed(0)
    for _ in range(steps):
        if any(env.step(env.action_space.sample())[2:4]):
            env.reset()
    vec = gym.make_vec(
        env_id, num_envs=3, vectorization_mode="vector_entry_point", episode_seconds=0.3
    )
    vec.reset(seed=0)
    vec.action_space.seed(0)
    for _ in range(steps):
        vec.step(vec.action_space.sample())


def _live() -> int:
    """Allocations minus frees of numba's runtime so far (counters switched on on first use)."""
    if not _nrt_python.memsys_stats_enabled():
        _nrt_python.memsys_enable_stats()
    gc.collect()
    stats = rtsys.get_allocation_stats()
    return stats.alloc - stats.free


@pytest.mark.parametrize("env_id", KERNEL_ENVS)
def test_kernels_return_no_array_and_leak_nothing(env_id: str) -> None:
    """After the envs ran (their kernels compiled or loaded), no kernel returns an array, and
    numba's live allocations do not grow with the number of steps."""
    _run(env_id, 5)  # compiles / loads everything the steps use
    live = _live()
    _run(env_id, 30)
    assert _live() == live
    # the envs' steps went through compiled code: the vector step's entry point (called from
    # Python, so it holds a signature whether it was compiled now or loaded from the cache; the
    # kernels it calls get one only when compiled in this process, which made a count of them
    # depend on the cache and on which test ran first in the worker)
    module, name = ENTRY[env_id]
    assert getattr(importlib.import_module(module), name).signatures
    assert _jit.array_returns() == []


def test_the_checks_catch_a_kernel_that_breaks_the_rules() -> None:
    """A kernel that allocates, itself or in a function it calls, does not compile; one that
    returns its argument array compiles (numba allows that), and `array_returns` lists it."""

    @numba.njit
    def fresh(n):
        return np.zeros(n)

    def allocates(n):
        return np.zeros(n)[0]

    def calls_an_allocation(n):
        return fresh(n)[0]

    def returns_argument(a):
        return a

    n_kernels = len(_jit.KERNELS)
    try:
        for fn in (allocates, calls_an_allocation):
            with pytest.raises(numba.core.errors.NumbaError):
                _jit.kernel(fn)(3)
        assert _jit.array_returns() == []
        _jit.kernel(returns_argument)(np.zeros(3))
        assert len(_jit.array_returns()) == 1 and "returns_argument" in _jit.array_returns()[0]
    finally:
        del _jit.KERNELS[n_kernels:]


def _tree(root, files):
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


def test_kernel_caches_are_stamped_by_their_dependencies():
    """A cached kernel must not survive a change to a callee in another file (a stale cached
    GyroStabilizer-v0 step raised ZeroDivisionError after a merge): mf_envs' kernels use the
    dependency-stamped locator (`mf_envs._cache`): the stamp of the ship's kernels covers the
    steppers and SO(3) kernels they call, and no CLI, training or benchmark file."""
    from mf_envs import _cache
    from mf_envs.physics.gowec.hydro import floating
    from mf_envs.physics.ship import kernels

    loc = floating.deriv._cache._impl._locator
    assert type(loc).__name__ in ("_InTreeLocator", "_UserDirLocator")
    assert loc.get_source_stamp() == _cache.source_stamp(floating.__file__)
    root = _cache._ROOT
    deps = {p.relative_to(root).as_posix() for p in _cache.dependencies(kernels.__file__)}
    assert {"physics/ship/kernels.py", "frames/steppers.py", "frames/kernels.py"} <= deps
    for mod in ("envs/gyro_stabilizer/rows.py", "envs/gowec_v1/rows.py", "envs/serpentine/rows.py"):
        deps = {p.relative_to(root).parts[0] for p in _cache.dependencies(root / mod)}
        assert not deps & set(_cache.NOT_KERNEL_CODE), mod


def test_a_cli_edit_leaves_kernel_stamps_alone_and_a_callee_edit_changes_them(tmp_path):
    """In a package tree of three modules (a kernel module importing a callee, relatively and
    absolutely, and a CLI module): editing the CLI file keeps the kernel module's stamp, editing
    the callee changes it."""
    from mf_envs import _cache

    root = tmp_path / "mf_envs"
    _tree(root, {
        "__init__.py": "",
        "physics/__init__.py": "",
        "physics/callee.py": "A = 1\n",
        "physics/rows.py": "from .callee import A\nimport mf_envs.frames.k\n",
        "frames/__init__.py": "",
        "frames/k.py": "B = 1\n",
        "cli/__init__.py": "",
        "cli/main.py": '"""doc"""\nfrom mf_envs.physics import rows\n',
    })  # fmt: skip
    kernel_file = str(root / "physics" / "rows.py")
    deps = {p.relative_to(root).as_posix() for p in _cache.dependencies(kernel_file, root)}
    assert deps == {"physics/rows.py", "physics/callee.py", "frames/k.py"}
    stamp = _cache.source_stamp.__wrapped__(kernel_file, root)
    (root / "cli" / "main.py").write_text('"""another doc"""\nfrom mf_envs.physics import rows\n')
    assert _cache.source_stamp.__wrapped__(kernel_file, root) == stamp
    (root / "frames" / "k.py").write_text("B = 2\n")
    assert _cache.source_stamp.__wrapped__(kernel_file, root) != stamp
