"""Every model that integrates an attitude is 4th order in R and omega where it claims so.

Truth: the Jacobi-elliptic omega(t) of the torque-free body (`analytic_omega`, Rios 2017 ch. 2
Eqs. 13a-c) and R' = R hat(omega_exact) integrated by scipy's DOP853 at rtol 1e-13
(`attitude_reference`). Scene of issue 11: inertias (1, 2, 3) kg m^2, omega0 = (0.6, 0.8, 0.4)
rad/s, a few seconds of tumbling (rates big enough that a 2nd-order term shows: the ship bug of
issue 11, a sign in dexp^-1, was invisible at 0.02 rad/s).
"""

import numpy as np
import pytest

from mf_envs.benchmarks._io import observed_order
from mf_envs.benchmarks.accuracy.ship_tumble import INERTIA, OMEGA0, tumble_errors
from mf_envs.frames import log_so3
from mf_envs.physics.multibody import Body, Multibody, Spherical
from mf_envs.physics.rigid_body import analytic_omega, simulate
from mf_envs.physics.rigid_body.exact import attitude_reference

DTS = (0.08, 0.04, 0.02)
T_END = 4.0


def _attitude_error(R: np.ndarray, t: np.ndarray, J=INERTIA) -> float:
    rel = np.einsum("nji,njk->nik", attitude_reference(J, OMEGA0, t), R)
    return float(np.linalg.norm(log_so3(rel), axis=-1).max())


def _orders(errs: list[tuple[float, float]]) -> tuple[float, float]:
    return tuple(observed_order(DTS, [e[k] for e in errs]) for k in (0, 1))


def test_ship_fast_path_attitude_is_fourth_order():
    errs = [tumble_errors(dt, T_END)[:2] for dt in DTS]
    r_order, w_order = _orders(errs)
    assert r_order >= 3.7 and w_order >= 3.7, (errs, r_order, w_order)


@pytest.mark.parametrize("method", ["rk4_magnus4", "rk4_magnus4_proj", "splitting4"])
def test_rigid_body_fourth_order_methods(method):
    errs = []
    for dt in DTS:
        run = simulate(INERTIA, OMEGA0, T_END, dt, method)
        w_err = np.abs(run.omega - analytic_omega(INERTIA, OMEGA0, run.t)).max()
        errs.append((_attitude_error(run.R, run.t), w_err))
    r_order, w_order = _orders(errs)
    assert r_order >= 3.7 and w_order >= 3.7, (errs, r_order, w_order)


def test_multibody_free_body_attitude_is_fourth_order():
    """One body on a spherical joint at its centre of mass, no gravity: a free tumbling body
    stepped by the engine's RKMK4 (the frames RK4 stepper in local coordinates)."""
    errs = []
    for dt in DTS:
        mb = Multibody([Body("b", 1.0, INERTIA, Spherical())])
        s = mb.initial_state(u={"b": OMEGA0})
        n = round(T_END / dt)
        R, w = [mb.poses(s)[0][0]], [mb.velocity(s, "b")]
        for _ in range(n):
            s = mb.step(s, dt)
            R.append(mb.poses(s)[0][0])
            w.append(mb.velocity(s, "b"))
        t = np.arange(n + 1) * dt
        w_err = np.abs(np.array(w) - analytic_omega(INERTIA, OMEGA0, t)).max()
        errs.append((_attitude_error(np.array(R), t), w_err))
    r_order, w_order = _orders(errs)
    assert r_order >= 3.7 and w_order >= 3.7, (errs, r_order, w_order)
