"""Ray, for the layers that use it (sweeps, RLlib): one import check and one local start."""

from __future__ import annotations

import os
from typing import Any

RAY_INSTALL = 'this needs Ray; pip install "mf-envs[ray]"'


def require_ray(rllib: bool = False, hint: str = "") -> Any:
    """The `ray` module (with RLlib if `rllib`), or a ValueError whose one line says what to
    install (and `hint`, e.g. how to do without)."""
    try:
        import ray

        if rllib:
            import ray.rllib  # noqa: F401
    except ImportError as exc:
        raise ValueError(RAY_INSTALL + hint) from exc
    return ray


def init_local_ray(num_cpus: int | None = 2) -> None:
    """`ray.init` of a small local Ray: `num_cpus`, 100 MB object store, no dashboard.

    Ray runs its workers at niceness 15 by default (`RAY_worker_niceness`), which on a machine
    shared with other jobs starves them; here they are the foreground job (niceness 0) unless
    the variable is set. With `RAY_ADDRESS` set, joins that cluster instead.
    """
    ray = require_ray()
    if os.environ.get("RAY_ADDRESS"):  # Ray's own variable: join that cluster instead
        ray.init(log_to_driver=False)
        return
    os.environ.setdefault("RAY_worker_niceness", "0")
    ray.init(
        address="local",  # a new instance, never a cluster left behind by `ray start`
        num_cpus=num_cpus,
        object_store_memory=100 * 1024**2,
        include_dashboard=False,
        log_to_driver=False,
    )
