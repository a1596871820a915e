"""The floating GOWEC's rigid bodies: M* and the velocity terms of the B-matrix equations.

The hull (1), each gyro unit's gimbal (2) and rotor (3), all centres of mass at G (the
`floating` module doc has the sketch and the kinematics, Rios 2017 ch. 3 Eqs. 37, 45, 49,
73-75). The hull's inertia about G in its own frame is diag(I_1, I_2, I_z) (kg m^2), pitch
theta about e1 and roll rho about e2, each with its axis' infinite-frequency added inertia:
`inertia` = (I_1 + A_inf,theta, I_z, I_2 + A_inf,rho). An axisymmetric hull has I_1 = I_2
(its roll block is its pitch block); a box has its own per axis (`axes`).
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.frames.kernels import sincos_near


@numba.njit(cache=True)
def mass_and_rhs(q, u, inertia, gyro, psid):
    """M* (3,3) and the velocity terms v (3,) = sum B^T (J B' u + w x h) of the `floating`
    module doc (inertia: the module doc's (3,));
    also the spin coupling S = sum_s s w_g3(s) (rad/s) and the gyro units' share of v (3,).
    gyro = (Ja, Jt, Jg1, Jg2, Jg3, n_units); unit s = +1 has gimbal angle phi and spin psi',
    unit s = -1 (dual configuration, ch. 3 Sec. 3.2.3) -phi and -psi'."""
    m = _mass_terms(q[1], q[2], u[0], u[1], u[2], inertia, gyro, psid)
    M = np.zeros((3, 3))
    M[0, 0], M[1, 1], M[1, 2], M[2, 1], M[2, 2] = m[0], m[1], m[2], m[2], m[3]
    return M, np.array([m[4], m[5], m[6]]), m[10], np.array([m[7], m[8], m[9]])


@kernel(forceinline=True)
def _mass_terms(ro, ph, th_d, ro_d, ph_d, inertia, gyro, psid, near=None):
    """`mass_and_rhs` on scalars (the RK4 stages call it 4 times per substep; no arrays, so no
    reference counting): returns (M00, M11, M12 = M21, M22 (M01 = M02 = 0: w_1 of every body
    depends on theta' only), v (3), gy (3), S, the hull's M00 alone, and (cos b, sin b) of
    units 1 and 2 (zeros for a missing unit)).

    cos and sin of rho and phi: libm, or with near = (rho0, cos rho0, sin rho0, phi0, cos phi0,
    sin phi0) at a Runge-Kutta step's start from those (`frames.kernels.sincos_near`: its
    stages sit close to it); b = rho +- phi by the angle-addition formulas (round-off)."""
    if near is None:
        cr_, sr_ = math.cos(ro), math.sin(ro)
        cp_, sp_ = math.cos(ph), math.sin(ph)
    else:
        cr_, sr_ = sincos_near(ro, near[0], near[1], near[2])
        cp_, sp_ = sincos_near(ph, near[3], near[4], near[5])
    Ih, Iz, Ir = inertia[0], inertia[1], inertia[2]  # about e1 (theta), e3, e2 (rho)
    Ja, Jt, Jg1, Jg2, Jg3 = gyro[0], gyro[1], gyro[2], gyro[3], gyro[4]
    # gimbal + rotor (principal in the gimbal frame): J1, J2, J3 (rotor spin added in h3)
    G1, G2, G3 = Jg1 + Jt, Jg2 + Jt, Jg3 + Ja
    m00 = Ih * cr_ * cr_ + Iz * sr_ * sr_
    hull00, m11, m12, m22 = m00, Ir, 0.0, 0.0
    # hull: w = (c th', ro', s th'), h = (Ih w1, Ir w2, Iz w3), B'u = (-s ro' th', 0, c ro' th')
    w1, w2, w3 = cr_ * th_d, ro_d, sr_ * th_d
    d1, d3 = -sr_ * ro_d * th_d, cr_ * ro_d * th_d
    e1 = Ih * d1 + (w2 * Iz * w3 - w3 * Ir * w2)
    e2 = w3 * Ih * w1 - w1 * Iz * w3
    e3 = Iz * d3 + (w1 * Ir * w2 - w2 * Ih * w1)
    gy0, gy1, gy2, spin = 0.0, 0.0, 0.0, 0.0
    c1, s1, c2, s2 = 0.0, 0.0, 0.0, 0.0
    for k in range(int(gyro[5])):
        sg = 1.0 - 2.0 * k
        # w = (cb th', ro' + s ph', sb th'), b = ro + s phi, B'u = (-sb bd th', 0, cb bd th')
        cb, sb = cr_ * cp_ - sg * (sr_ * sp_), sr_ * cp_ + sg * (cr_ * sp_)  # b = ro + sg phi
        if k == 0:
            c1, s1 = cb, sb
        else:
            c2, s2 = cb, sb
        bd = ro_d + sg * ph_d
        m00 += G1 * cb * cb + G3 * sb * sb
        m11 += G2
        m12 += sg * G2
        m22 += G2
        g1, g2, g3 = cb * th_d, bd, sb * th_d
        h1, h2, h3 = G1 * g1, G2 * g2, G3 * g3 + sg * Ja * psid
        f1 = G1 * (-sb * bd * th_d) + (g2 * h3 - g3 * h2)
        f2 = g3 * h1 - g1 * h3
        f3 = G3 * (cb * bd * th_d) + (g1 * h2 - g2 * h1)
        gy0 += cb * f1 + sb * f3
        gy1 += f2
        gy2 += sg * f2
        spin += sg * g3
    v0, v1, v2 = cr_ * e1 + sr_ * e3 + gy0, e2 + gy1, 0.0 + gy2
    return (m00, m11, m12, m22, v0, v1, v2, gy0, gy1, gy2, spin, hull00, c1, s1, c2, s2)


@kernel(forceinline=True)
def _solve_tridiag3(a00, a01, a11, a12, a22, b0, b1, b2):
    """x with A x = b for the symmetric tridiagonal A = [[a00, a01, 0], [a01, a11, a12],
    [0, a12, a22]] (the mass matrix of `mechanics`, positive definite): its cofactors over the
    determinant: one division, where Gaussian elimination chains six (~14 cycles each, on every
    RK4 stage's critical path). A singular A raises ZeroDivisionError (numba's float division;
    `batch.step_row` catches it), a non-finite one gives a non-finite x: the env's failure
    path."""
    c00, c01, c02 = a11 * a22 - a12 * a12, -(a01 * a22), a01 * a12
    c11, c12, c22 = a00 * a22, -(a00 * a12), a00 * a11 - a01 * a01
    inv = 1.0 / (a00 * c00 + a01 * c01)
    return ((c00 * b0 + c01 * b1 + c02 * b2) * inv, (c01 * b0 + c11 * b1 + c12 * b2) * inv,
            (c02 * b0 + c12 * b1 + c22 * b2) * inv)  # fmt: skip
