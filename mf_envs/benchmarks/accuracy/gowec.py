"""GOWEC work-precision: fast path (numba RK4) vs the general multibody engine (RKMK4), dt ladder.

Scene `gowec`: 10 wave periods (T = 6 s, a = 1 m, Seakeeper 26) with the gimbal held near
phi = w t by a PD torque law sampled every 0.08 s (a well-posed run; the zero-torque gimbal is
chaotic), so that every dt integrates the same sampled-data system.
- quantity `phi (Eq. 79 model)`: max |phi - phi_ref| for `fast_path` and `engine`, with phi_ref
  a fast-path run at dt/16 of the finest step (both integrate the same equation under Eq. 79).
- quantity `phi (real inertias)`: truth = engine with a thick rotor (Jt = 0.7 Ja) and a 10 kg m^2
  gimbal at dt/16; `engine` converges to it, `eq81_fast_path` stalls at the model error of the
  Eq. 79 assumptions.
- quantity `mean power / Eq. 95 - 1`: fast path with the exact locking law (feed-forward of the
  gyroscopic moment + PD) against Eq. 95 (Eq. 86 for this head-on wave).
"""

from __future__ import annotations

import math

import numpy as np

from mf_envs.benchmarks._io import timed
from mf_envs.physics import gowec as gw
from mf_envs.physics.gowec.engine import (
    build_engine_model,
    locking_torque,
    simulate_engine,
    simulate_fast,
)
from mf_envs.physics.waves import G, regular_wave

ORDER = 30
T = 6.0
SEED = frozenset({"gyroscopic", "buoy_rocking", "wave_2d"})
HOLD = 0.08  # s, the torque law is sampled and held like a digital controller (every dt divides)


def _max_err(run, ref, dt, dt_ref):
    step = int(round(dt / dt_ref))
    return float(np.abs(run["phi"] - ref["phi"][::step][: len(run["phi"])]).max())


def _eq79_rows(dts, t_end):
    p = gw.GOWECParams()
    wave = regular_wave(1.0, T)
    gm, mb = gw.GimbalModel(p, wave, SEED), build_engine_model(p, wave, SEED)
    w = 2 * math.pi / T
    law = locking_torque(p, w)
    dt_ref = min(dts) / 16
    ref = simulate_fast(gm, 0.0, w, t_end, dt_ref, law, HOLD)
    models = (("fast_path", simulate_fast, gm), ("engine", simulate_engine, mb))
    return _dt_ladder(models, w, t_end, dts, law, ref, dt_ref, "phi (Eq. 79 model)")


def _real_inertia_rows(dts, t_end):
    p = gw.GOWECParams(
        rotor_transverse_inertia=0.7 * gw.GOWECParams().rotor_inertia,
        gimbal_inertia=(10.0, 10.0, 10.0),
    )
    wave = regular_wave(1.0, T)
    eq81 = gw.GimbalModel(p, wave, SEED)
    truth = build_engine_model(p, wave, SEED | {"gimbal_inertia"})
    w = 2 * math.pi / T
    law = locking_torque(p, w)
    dt_ref = min(dts) / 16
    ref = simulate_fast(
        gw.GimbalModel(p, wave, SEED | {"gimbal_inertia"}), 0.0, w, t_end, dt_ref, law, HOLD
    )
    models = (("eq81_fast_path", simulate_fast, eq81), ("engine", simulate_engine, truth))
    return _dt_ladder(models, w, t_end, dts, law, ref, dt_ref, "phi (real inertias)")


def _dt_ladder(models, w, t_end, dts, law, ref, dt_ref, quantity):
    """Rows of max phi error vs wall seconds for (method, simulate function, model) over dts."""
    rows = []
    for dt in dts:
        for method, fn, model in models:
            extra = (False,) if fn is simulate_engine else ()
            run, sec = timed(fn, model, 0.0, w, t_end, dt, law, *extra, HOLD)
            rows.append(
                dict(
                    scene="gowec",
                    method=method,
                    dt=dt,
                    quantity=quantity,
                    error=_max_err(run, ref, dt, dt_ref),
                    seconds=sec,
                    param="dt",
                )
            )
    return rows


def _power_rows(dts, n_periods):
    p = gw.GOWECParams()
    gm = gw.GimbalModel(p, regular_wave(1.0, T), SEED)
    w = 2 * math.pi / T
    H, J = p.angular_momentum, 0.5 * p.rotor_inertia
    kp, kd = J * 100.0, 2 * J * 10.0

    def law(t, phi, phid):
        w1 = gm.rates(t)[0][0]
        drive = H * w1 * math.cos(phi) + 0.25 * p.rotor_inertia * w1**2 * math.sin(2 * phi)
        return drive + kp * (phi - w * t) + kd * (phid - w)

    P86 = gw.analytic_max_power(p.rotor_inertia, p.rotor_speed, 1.0, T)
    rows = []
    for dt in dts:

        def run(dt=dt):
            out = simulate_fast(gm, 0.0, w, n_periods * T, dt, law)  # torque held per step
            # energy of the held torque per step over whole periods / time
            return float(np.sum(out["Mg"][:-1] * np.diff(out["phi"])) / (n_periods * T))

        Pm, sec = timed(run)
        rows.append(
            dict(
                scene="gowec",
                method="fast_path_locked",
                dt=dt,
                param="dt",
                quantity="mean power / Eq. 95 - 1",
                error=abs(Pm / P86 - 1.0),
                seconds=sec,
                reference_W=P86,
                a_over_g=1.0 / G,
            )
        )
    return rows


def rows(quick: bool) -> list[dict]:
    dts = [0.04, 0.02, 0.01] if quick else [0.08, 0.04, 0.02, 0.01, 0.005]
    t_end = 4 * T if quick else 10 * T
    return (
        _eq79_rows(dts, t_end)
        + _real_inertia_rows(dts, t_end)
        + _power_rows(dts, 4 if quick else 10)
    )
