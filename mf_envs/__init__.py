"""mf_envs: Gymnasium environments whose physics is the moving frame method (Rios 2017).

Importing the package registers the environments with Gymnasium (see `mf_envs.envs`).
"""

from mf_envs import _cache, _first_run

_cache.install()  # numba's caches stamped by the whole package's source (stale-callee guard)
_first_run.install()  # one stderr line when numba compiles (its on-disk cache is cold)

from mf_envs.envs import register_envs  # noqa: E402

__version__ = "0.1.0"

register_envs()

__all__ = ["register_envs", "__version__"]
