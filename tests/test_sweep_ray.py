"""The Ray path of `mf-envs sweep` gives the same numbers as the serial path (local Ray, 2 CPUs).

Needs the `ray` extra (skipped without it). Slow stage: starting Ray and its two workers (each
imports mf_envs and loads the numba caches) takes 20-60 s on a shared 2-core machine.
"""

from __future__ import annotations

import pytest

ray = pytest.importorskip("ray", reason='needs the ray extra: pip install "mf-envs[ray]"')

from mf_envs.sweep import parse_config, run_sweep  # noqa: E402
from mf_envs.sweep.run import init_local_ray  # noqa: E402
from mf_envs.sweep.store import ResultStore  # noqa: E402

# 3 controllers x 4 sea states x 3 seeds = 36 trials (15 s episodes)
CONFIG = {
    "env_id": "GyroStabilizer-v0",
    "seeds": [0, 1, 2],
    "controllers": ["baseline:pid", "baseline:lqr", "baseline:continuous"],
    "env_kwargs": {"episode_seconds": 15.0},
    "scenes": {
        "T2.2": {"wave_period": 2.22},
        "T3.7": {"wave_period": 3.70},
        "T5.9": {"wave_period": 5.92},
        "T3.7_2M0": {"wave_period": 3.70, "wave_moment_amplitude": 16000.0},
    },
}


@pytest.fixture
def local_ray():
    init_local_ray(num_cpus=2)  # 2 workers, 100 MB object store, no dashboard
    try:
        yield
    finally:
        ray.shutdown()


@pytest.mark.slow
def test_ray_sweep_equals_serial(tmp_path, local_ray):
    cfg = parse_config(CONFIG)
    assert len(cfg.trials) == 36
    ray_csv, n_ray = run_sweep(cfg, tmp_path / "ray", progress=False)
    assert ray.is_initialized()  # the caller's Ray is used and left running
    serial_csv, n_serial = run_sweep(cfg, tmp_path / "serial", serial=True, progress=False)
    assert n_ray == n_serial == 36
    a, b = ResultStore(ray_csv).by_id(), ResultStore(serial_csv).by_id()
    assert a.keys() == {t.trial_id for t in cfg.trials}
    assert a == b  # bit-identical metrics (floats round-trip through repr)
    # the sweep distinguishes its trials: a sea-state change changes the roll
    assert len({round(r["rms_roll"], 12) for r in a.values()}) > 30
