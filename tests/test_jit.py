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


def test_kernel_caches_are_stamped_by_the_whole_package(tmp_path, monkeypatch):
    """A cached kernel must not survive a change to a callee in another file (a stale cached
    GyroStabilizer-v0 step raised ZeroDivisionError after a merge): mf_envs' kernels use the
    package-stamped locator (`mf_envs._cache`), and the stamp changes with any file's bytes."""
    from mf_envs import _cache
    from mf_envs.physics.gowec.hydro import floating

    loc = floating.deriv._cache._impl._locator
    assert type(loc).__name__ in ("_PackageLocator", "_PackageUserDirLocator")
    assert loc.get_source_stamp() == _cache.package_stamp()
    (tmp_path / "a.py").write_text("x = 1\n")
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "b.py").write_text("y = 2\n")
    monkeypatch.setattr(_cache, "_ROOT", tmp_path)
    monkeypatch.setattr(_cache, "_STAMP", None)
    s1 = _cache.package_stamp()
    monkeypatch.setattr(_cache, "_STAMP", None)
    (tmp_path / "sub" / "b.py").write_text("y = 3\n")
    assert _cache.package_stamp() != s1
