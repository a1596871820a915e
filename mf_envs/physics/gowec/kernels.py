"""Numba kernels of the GOWEC fast path: buoy rates from the wave slope (Eqs. 77-78, 90-93) and
the gimbal equation (module doc of `mf_envs.physics.gowec`), stepped by the frames RK4 stepper."""

from __future__ import annotations

import math
from collections import namedtuple

import numba
import numpy as np

from mf_envs.frames.steppers import make_rk4


@numba.njit(cache=True)
def buoy_rates(t, amp, om, eps, k, cth, sth, two_d):
    """Body rates w (3,) and w' (3,) of the wave-slope buoy R = rot_x(b1) rot_y(b2).

    b1 = d eta/d x2, b2 = -d eta/d x1 at the origin (waves.WaveField); two_d = False keeps
    only b1 (rocking about e1 alone, as in Eq. 94). k (n,) are the SLOPE wavenumbers
    k_i F(k_i r) (`WaveField.slope_wavenumbers`: slope averaged over the buoy waterplane).
    """
    w = np.zeros(3)
    wd = np.zeros(3)
    buoy_rates_into(t, amp, om, eps, k, cth, sth, two_d, w, wd)
    return w, wd


@numba.njit(cache=True)
def buoy_rates_into(t, amp, om, eps, k, cth, sth, two_d, w, wd):
    """`buoy_rates` writing into the caller's w (3,) and w' (3,) (no allocation in the RK4 loop)."""
    w[0], w[1], w[2], wd[0], wd[1], wd[2] = buoy_rates_scalars(t, amp, om, eps, k, cth, sth, two_d)


@numba.njit(cache=True, inline="always")
def buoy_rates_scalars(t, amp, om, eps, k, cth, sth, two_d):
    """`buoy_rates` as six floats (w1, w2, w3, w1', w2', w3'): no array at all (the RK4 stage
    inputs of every row of the batch)."""
    g0 = 0.0
    g1 = 0.0
    g2 = 0.0
    g3 = 0.0
    for i in range(amp.shape[0]):
        arg = -om[i] * t + eps[i]
        ak = amp[i] * k[i]
        sa, ca = math.sin(arg), math.cos(arg)
        g0 -= ak * sa
        g1 += ak * om[i] * ca
        g2 += ak * om[i] * om[i] * sa
        g3 -= ak * om[i] ** 3 * ca
    b1d, b1dd = sth * g1, sth * g2
    if not two_d:
        return b1d, 0.0, 0.0, b1dd, 0.0, 0.0
    b2, b2d, b2dd = -cth * g0, -cth * g1, -cth * g2
    c2, s2 = math.cos(b2), math.sin(b2)
    return (
        b1d * c2,
        b2d,
        b1d * s2,
        b1dd * c2 - b1d * s2 * b2d,
        b2dd,
        b1dd * s2 + b1d * c2 * b2d,
    )


@numba.njit(cache=True, inline="always")
def gimbal_accel(phi, phid, w, wd, Mg, Ja, Jt, Jg1, Jg2, Jg3, psid):
    """phi'' (rad/s^2) from the general gimbal equation (module doc; Eq. 81 as special case)."""
    c, s = math.cos(phi), math.sin(phi)
    O1 = c * w[0] - s * w[2]
    O3 = s * w[0] + c * w[2]
    drive = (Jg3 - Jg1 - Jt) * O1 * O3 + Ja * (O3 + psid) * O1
    return (drive - Mg) / (Jg2 + Jt) - wd[1]


@numba.njit(cache=True, inline="always")
def _stage_inputs(t, args):
    """Buoy rates (w, w') at time t (the wave drives the gimbal; state-free)."""
    amp, om, eps, k, cth, sth, two_d = args[3:]
    w1, w2, w3, d1, d2, d3 = buoy_rates_scalars(t, amp, om, eps, k, cth, sth, two_d)
    return (w1, w2, w3), (d1, d2, d3)


@numba.njit(cache=True, inline="always")
def _stage_rhs(t, x, inp, args, out):
    """(phi', phi'') of x = (phi, phi') under the buoy rates inp and the held torque args[0]."""
    Mg, inert, psid = args[0], args[1], args[2]
    w, wd = inp
    a = gimbal_accel(x[0], x[1], w, wd, Mg, inert[0], inert[1], inert[2], inert[3], inert[4], psid)
    out[0], out[1] = x[1], a


_rk4 = make_rk4(_stage_rhs, _stage_inputs)


Waves = namedtuple("Waves", "amp om eps k cth sth two_d")
Waves.__doc__ = """The wave components a buoy meets: amp (M,) m, om (M,) rad/s, eps (M,) rad and
k (M,) rad/m (the slope wavenumbers k F(k r), `WaveField.slope_wavenumbers`); cth, sth the wave
direction's projections (0 for a still buoy); two_d: both slope angles (`buoy_rates`)."""


@numba.njit(cache=True)
def fast_step(t, phi, phid, Mg, dt, n, inert, psid, waves):
    """n RK4 substeps (the frames stepper) of length dt with the generator torque Mg (N m) held,
    on the `Waves` waves.

    inert = (Ja, Jt, Jg1, Jg2, Jg3). Returns (phi, phi', harvested energy int M_g phi' dt (J),
    buoy rates w1, w2, w3 (rad/s) and the wave elevation at the origin (m) at the end).
    """
    return fast_step_into(t, phi, phid, Mg, dt, n, inert, psid, waves, np.empty((6, 2)))


@numba.njit(cache=True)
def fast_step_into(t, phi, phid, Mg, dt, n, inert, psid, waves, work):
    """`fast_step` with the caller's scratch work (6, 2) (rows 0-4: the RK4 stages, row 5: the
    state): no allocation, so a batch can reuse one scratch for all its rows."""
    amp, om, eps, k, cth, sth, two_d = waves
    energy = 0.0
    args = (Mg, inert, psid, amp, om, eps, k, cth, sth, two_d)
    x = work[5]
    x[0], x[1] = phi, phid
    for _ in range(n):
        _rk4(t, x, dt, args, work)
        dx = work[0]
        energy += Mg * dx[0]  # = M_g (change of phi), exact for the held torque
        x[0] += dx[0]
        x[1] += dx[1]
        t += dt
    w1, w2, w3, _, _, _ = buoy_rates_scalars(t, amp, om, eps, k, cth, sth, two_d)
    eta = 0.0
    for i in range(amp.shape[0]):
        eta += amp[i] * math.cos(-om[i] * t + eps[i])
    return x[0], x[1], energy, w1, w2, w3, eta
