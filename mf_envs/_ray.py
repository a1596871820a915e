"""Ray, for the layers that use it (sweeps, RLlib): one import check and one start.

Ray's usage-stats reporting (a message to Anyscale's server at each start) is turned off unless
the user turned it on: `RAY_USAGE_STATS_ENABLED` is set to 0 only if it is unset. A cluster
address the user gives (`--address`, `RAY_ADDRESS`) is first probed with a TCP connect of at
most `ADDRESS_TIMEOUT` seconds, to that host and port only, so an address nothing answers on
fails in seconds naming it instead of `ray.init` waiting for minutes.
"""

from __future__ import annotations

import os
import socket
from typing import Any

RAY_INSTALL = 'this needs Ray; pip install "mf-envs[ray]"'
ADDRESS_TIMEOUT = 5.0  # s, the TCP connect to a given cluster address


def quiet_usage_stats() -> None:
    """Ray's usage stats off, unless the user set RAY_USAGE_STATS_ENABLED."""
    os.environ.setdefault("RAY_USAGE_STATS_ENABLED", "0")


def probe_address(address: str, field: str = "address", timeout: float = ADDRESS_TIMEOUT) -> None:
    """ValueError naming `field` and `address` unless a TCP connect to its host:port succeeds
    within `timeout` s (`ray://HOST:PORT` too; "auto" and "local" are Ray's own, not probed)."""
    text = address.strip()
    if text in ("auto", "local"):
        return
    hostport = text.removeprefix("ray://")
    host, sep, port = hostport.rpartition(":")
    if not sep or not host or not port.isdigit() or not 0 < int(port) < 65536:
        raise ValueError(f"{field}: expected HOST:PORT (or ray://HOST:PORT), got {address!r}")
    try:
        socket.create_connection((host.strip("[]"), int(port)), timeout=timeout).close()
    except OSError as exc:
        reason = exc.strerror or type(exc).__name__
        raise ValueError(
            f"{field}: no Ray cluster answers at {address!r} within {timeout:g} s ({reason})"
        ) from None


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
    quiet_usage_stats()
    if os.environ.get("RAY_ADDRESS"):  # Ray's own variable: join that cluster instead
        probe_address(os.environ["RAY_ADDRESS"], "RAY_ADDRESS")
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
