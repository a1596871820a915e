"""Ship attitude integrator on a free tumbling hull: the 4th-order proof of the ship fast path.

Scene `ship_tumble`: the ship fast path (`mf_envs.physics.ship`, RKMK4 of `mf_envs.frames.kernels`)
with the gyros off (no spin, no gimbal inertia, a 1e-9 kg m^2 rotor held at phi = 0), no
hydrodynamics and no waves, hull inertias (1, 2, 3) kg m^2, body rates (0.6, 0.8, 0.4) rad/s,
tumbling for 5 s. Errors (max over the run):
- `body_rate`: |omega - omega_exact| in rad/s against the Jacobi-elliptic solution
  (`mf_envs.physics.rigid_body.analytic_omega`, ch. 2 Eqs. 13a-c);
- `attitude`: |log(R_ref^T R)| in rad against `rigid_body.attitude_reference` (R' = R hat(omega)
  driven by the exact omega, DOP853 at rtol 1e-13: there is no closed-form R in the package).
Column `order`: the observed order (least-squares slope of log error vs log dt) of the quantity,
the same in every row of it. An earlier bug (a dexp^-1 sign) made the attitude 2nd order.
"""

from __future__ import annotations

import numpy as np

from mf_envs.benchmarks._io import observed_order, timed
from mf_envs.frames import log_so3
from mf_envs.physics.rigid_body import analytic_omega
from mf_envs.physics.rigid_body.exact import attitude_reference
from mf_envs.physics.ship import (
    GimbalDrive,
    GyroParams,
    ShipParams,
    initial_state,
    pack_params,
    simulate,
)

ORDER = 31
INERTIA = (1.0, 2.0, 3.0)  # kg m^2
OMEGA0 = (0.6, 0.8, 0.4)  # rad/s
T_END = 5.0  # s


def free_hull() -> tuple[np.ndarray, np.ndarray]:
    """(P, J): packed parameters of the free hull and its total principal inertias (kg m^2)."""
    gyro = GyroParams(rotor_inertia=1e-9, gimbal_inertia=0.0, rotor_speed=0.0)
    P = pack_params(ShipParams(inertia=INERTIA), gyro, 1, (), GimbalDrive())
    return P, P[0:3] + P[3:6]  # hull + (stopped rotor at phi = 0) about the same axes


def tumble_errors(dt: float, t_end: float = T_END) -> tuple[float, float, float]:
    """(attitude error rad, body-rate error rad/s, wall seconds) of the ship fast path at dt."""
    P, J = free_hull()
    y0, R0 = initial_state(omega=OMEGA0)
    simulate(P, dt, dt, y0, R0)  # compile / warm up
    run, sec = timed(simulate, P, t_end, dt, y0, R0)
    w_err = np.abs(run.omega - analytic_omega(J, OMEGA0, run.t)).max()
    R_ref = attitude_reference(J, OMEGA0, run.t)
    rel = np.einsum("nji,njk->nik", R_ref, run.R)
    r_err = np.linalg.norm(log_so3(rel), axis=-1).max()
    return float(r_err), float(w_err), sec


def rows(quick: bool) -> list[dict]:
    dts = (0.08, 0.04, 0.02, 0.01) if quick else (0.16, 0.08, 0.04, 0.02, 0.01)
    errs = {dt: tumble_errors(dt) for dt in dts}
    out = []
    for k, q in enumerate(("attitude", "body_rate")):
        order = observed_order(dts, [errs[dt][k] for dt in dts])
        for dt in dts:
            out.append(
                dict(
                    scene="ship_tumble",
                    method="ship_fast_rkmk4",
                    dt=dt,
                    param="dt",
                    quantity=q,
                    error=errs[dt][k],
                    seconds=errs[dt][2],
                    order=order,
                )
            )
    return out
