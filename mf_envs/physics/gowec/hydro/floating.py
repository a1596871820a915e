"""The floating GOWEC: a Cummins-equation buoy two-way coupled to one gyroscope (numba fast path).

Not in the seed's simplified model (ch. 3 Sec. 3.2.6 prescribes the buoy); this is its general
model (Eqs. 48-75) with the buoy free in pitch and roll and loaded by linear hydrodynamics:

        wave --> hull (1): R = rot_x(theta) rot_y(rho)   pitch theta about e1, roll rho about e2
        +-----------------------------+                  (yaw and translation of G held by the
        |  gimbal (2): angle phi about e2^(1), generator torque M_g (PTO)      mooring)
        |     rotor (3): spins at psi' about e3^(2) (motor holds psi')
        +-----------------------------+      all centres of mass at G (gyro at the buoy's G)

Body angular velocities (body frames) in terms of u = (theta', rho', phi') (Eqs. 37, 45, 49):
    w_h = (cos(rho) theta', rho', sin(rho) theta')
    w_g = (cos(b) theta', rho' + phi', sin(b) theta'),  b = rho + phi   (roll and gimbal share e2)
    w_r = w_g + psi' e3 (the axisymmetric rotor, written in the gimbal frame)
and with B_k = d w_k / d u, h_k = J_k w_k, the B-matrix equations (Eqs. 73-75)

    sum_k B_k^T (J_k B_k u' + J_k B_k' u + w_frame x h_k) = Q
    Q = (M_x - C theta - mu_theta, M_y - C rho - mu_rho, -n M_g)                 (Cummins 1962)

With the dual configuration (`gyro_units` = 2, the seed's Fig. 3-2) a second unit turns
at -phi with spin -psi' (a mirrored pair sharing one generator law); its roll and yaw reactions
cancel those of the first, and Q_phi = -2 M_g. J_h = diag(I + A_inf, I + A_inf, I_z)
(A_inf, the infinite-frequency added inertia, rides with the hull), mu = radiation memory
from the state-space fit x' = Ar x + Br q', mu = Cr x (one copy per axis,
`radiation.fit_radiation`), C the hydrostatic stiffness, M_x, M_y the wave excitation moments
(`excitation_coefficients`), and an optional linear viscous damping b_v q' on each axis.
The PTO torque M_g = clip(tau_cmd + c phi' + k phi) (torque and power limits) is evaluated at every
RK4 stage: a damper held over a control step is unstable once c dt / J > 2 (docs/design.md).
`engine_model` builds the same system in the general multibody engine; a test checks the two.

The RK4 step evaluates the sea at t, t + dt/2 and t + dt of each substep from the wave
components' phasors (cos, sin of w_i t), taken once per control step and rotated by w_i dt/2
between stage times (`rk4_steps_into`): for an irregular sea of M components that is 2 M
sin/cos pairs per control step instead of 3 M per substep, equal to the direct evaluation to
round-off (tests/test_gowec_v1_physics.py).

Added, each free when off: quadratic Morison drag relative to the incident wave's
water (`drag_loads`), a ramp of the incident wave (`ramp`), and surge along the wave and heave
(`translation_params` in `model`; `mechanics` eliminates s'' so the solve stays 3 x 3).

State y: [theta, rho, phi, theta', rho', phi', x_theta (nr), x_rho (nr), (with surge and heave
free: s, z, s', z', the stacked radiation states of K11, K15, K51, K33), E_exc, E_rad, E_visc,
E_pto, E_elec, E_motor] with the energies (J) integrated by the same RK4 as the motion:
excitation work, radiated, viscous and drag, PTO mechanical (positive harvested), PTO
electrical (eta_g when generating, 1/eta_m when motoring), rotor-motor work (`energy_index`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import NDArray

from mf_envs._jit import kernel
from mf_envs.frames.kernels import sincos_near
from mf_envs.frames.steppers import make_rk4_given, rk4_work

N_MECH = 6
N_ENERGY = 6


@dataclass(frozen=True)
class FloatingParams:
    """Packed numbers of the fast path (SI). inertia = (I + A_inf, I_z) of the hull (kg m^2);
    gyro = (Ja, Jt, Jg1, Jg2, Jg3) kg m^2; psid rad/s; stiffness C (N m/rad); viscous b_v
    (N m s/rad); radiation (Ar (nr,nr), Br (nr,), Cr (nr,)); pto = (c N m s/rad, k N m/rad,
    max torque N m, max power W, eta_generator, eta_motor)."""

    inertia: NDArray[np.float64]
    gyro: NDArray[np.float64]  # (Ja, Jt, Jg1, Jg2, Jg3, n_units)
    psid: float
    stiffness: float
    viscous: float
    Ar: NDArray[np.float64]
    Br: NDArray[np.float64]
    Cr: NDArray[np.float64]
    pto: NDArray[np.float64]

    @property
    def n_state(self) -> int:
        """Without the translation block (`FloatingModel.n_state` adds it)."""
        return N_MECH + 2 * self.Ar.shape[0] + N_ENERGY


def excitation_coefficients(
    X: NDArray[np.complex128], amplitudes: NDArray, phases: NDArray, direction: float
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Complex moment coefficients (N m) c_i such that M(t) = sum Re(c_i e^{-i w_i t}) about e1
    (pitch) and e2 (roll) for components eta = a_i cos(k x.n - w_i t + eps_i) travelling in
    `direction` (rad from x1). X (n,) is the hull's pitch excitation (about y, wave along +x) at
    w_i; by axisymmetry the moment about e2 is X cos(direction) and about e1 -X sin(direction)."""
    c = np.asarray(X) * np.asarray(amplitudes) * np.exp(1j * np.asarray(phases))
    return -math.sin(direction) * c, math.cos(direction) * c


# quadratic drag: N_KEEL nodes on the keel plate, N_SIDE on the side, and the sea's
# per-node water velocities; the sea parameters `sp` (SP_LEN,) = [drag on (0/1), ramp time (s),
# c_keel (N_KEEL) = 1/2 rho C_d area (kg/m), x_keel, y_keel (N_KEEL, m from the axis),
# c_side (N_SIDE) = 1/2 rho C_d D dz (kg/m), lever z - z_G of the side nodes (N_SIDE, m),
# cos(direction), sin(direction)] (`drag_geometry`)
N_KEEL = 6
N_SIDE = 2
SP_CK = 2
SP_XK = SP_CK + N_KEEL
SP_YK = SP_XK + N_KEEL
SP_CS = SP_YK + N_KEEL
SP_ZS = SP_CS + N_SIDE
SP_DIR = SP_ZS + N_SIDE
SP_TRANS = SP_DIR + 2  # 1 when surge and heave are free (`sea_inputs` adds their forces)
SP_LEN = SP_TRANS + 1
N_LOADS = N_KEEL + N_SIDE + 2  # dk's columns: node velocities, then surge and heave forces
# the translation parameters `tp` (TP_LEN,) (`translation_params`): on, M1 = m + A11_inf (kg),
# A15_inf (kg m, about G, symmetrised), mooring stiffness (N/m), M3 = m + A33_inf (kg), C33 (N/m),
# then the start of each radiation block in the stacked state (11 from s', 15 from alpha' to
# the surge force, 51 from s' to the moment, 33 from z') and the stacked order nt
TP_ON, TP_M1, TP_A15, TP_K, TP_M3, TP_C33, TP_O11, TP_O15, TP_O51, TP_O33, TP_NT = range(11)
TP_LEN = 11


@kernel(forceinline=True)
def ramp(t, tr):
    """Start-up ramp of the incident wave: 1/2 (1 - cos(pi t / tr)) for t < tr, else 1."""
    if t >= tr:
        return 1.0
    return 0.5 * (1.0 - math.cos(math.pi * t / tr))


@numba.njit(cache=True)
def sea_inputs(t, om, cp, cr, dk, sp):
    """The sea at time t (s), ramped (`ramp`): `sea_sum` of the components' phasors at t (for
    resets and the Python side; the RK4 step forms its stage phasors by rotation instead,
    `rk4_steps_into`)."""
    ph = np.empty((2, om.shape[0]))
    for i in range(om.shape[0]):
        ph[0, i], ph[1, i] = math.cos(om[i] * t), math.sin(om[i] * t)
    return sea_sum(ph, ramp(t, sp[1]), cp, cr, dk, sp)


@kernel(forceinline=True)
def sea_sum(ph, r, cp, cr, dk, sp):
    """The sea from the components' phasors ph (2, M) = (cos w_i t, sin w_i t) at a time t and
    the ramp factor r there: (M_x, M_y) (N m), sum Re(c e^{-i w t}) of the excitation
    coefficients cp (pitch) and cr (roll) (`excitation_coefficients`), then the water's
    vertical velocity at the N_KEEL keel nodes and its horizontal speed along the wave
    direction at the N_SIDE side nodes (m/s), then the surge force along the wave and the heave
    force (N), each sum Re(dk[i, j] e^{-i w_i t}) (zeros, and no work, when neither the drag
    nor the translation is on), all times r."""
    mx, my = 0.0, 0.0
    v0, v1, v2, v3, v4, v5, v6, v7 = 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    fs, fz = 0.0, 0.0
    drag, trans = sp[0] != 0.0, sp[SP_TRANS] != 0.0
    for i in range(ph.shape[1]):
        c, s = ph[0, i], ph[1, i]
        mx += cp[i].real * c + cp[i].imag * s
        my += cr[i].real * c + cr[i].imag * s
        if drag or trans:
            d = dk[i]
            v0 += d[0].real * c + d[0].imag * s
            v1 += d[1].real * c + d[1].imag * s
            v2 += d[2].real * c + d[2].imag * s
            v3 += d[3].real * c + d[3].imag * s
            v4 += d[4].real * c + d[4].imag * s
            v5 += d[5].real * c + d[5].imag * s
            v6 += d[6].real * c + d[6].imag * s
            v7 += d[7].real * c + d[7].imag * s
            fs += d[8].real * c + d[8].imag * s
            fz += d[9].real * c + d[9].imag * s
    return (r * mx, r * my, r * v0, r * v1, r * v2, r * v3, r * v4, r * v5, r * v6, r * v7,
            r * fs, r * fz)  # fmt: skip


@kernel(forceinline=True)
def _advance_phasors(ph):
    """ph[0:2] (cos w_i t, sin w_i t) -> their values at t + h, by the rotation ph[2:4] =
    (cos w_i h, sin w_i h): the angle-addition formulas (a few ulp per rotation, against the
    ~20 ns of a sin/cos pair)."""
    for i in range(ph.shape[1]):
        c, s, rc, rs = ph[0, i], ph[1, i], ph[2, i], ph[3, i]
        ph[0, i] = c * rc - s * rs
        ph[1, i] = s * rc + c * rs


@kernel(forceinline=True)
def drag_loads(th_d, ro_d, s_d, z_d, inp, sp):
    """Quadratic (Morison) drag on the hull rotating at (theta', rho'), surging at s' along
    the wave and heaving at z' in the water of `sea_inputs` inp: keel nodes -c |v_rel| v_rel on
    the vertical velocity relative to the water (body: theta' y - rho' x + z'), side nodes on
    the horizontal one (body: (rho' z, -theta' z) + s' (cos, sin) of the wave direction).
    Returns (M_x, M_y) (N m, moments r x F about G), the surge force along the wave and the
    heave force (N); zeros when the drag is off."""
    if sp[0] == 0.0:
        return 0.0, 0.0, 0.0, 0.0
    mx, my, fz = 0.0, 0.0, 0.0
    for j in range(N_KEEL):
        x, yk = sp[SP_XK + j], sp[SP_YK + j]
        rel = th_d * yk - ro_d * x + z_d - inp[2 + j]
        f = -sp[SP_CK + j] * abs(rel) * rel
        mx += yk * f
        my -= x * f
        fz += f
    cb, sb = sp[SP_DIR], sp[SP_DIR + 1]
    fs = 0.0
    for j in range(N_SIDE):
        z = sp[SP_ZS + j]
        u = inp[2 + N_KEEL + j] - s_d
        rx, ry = ro_d * z - u * cb, -th_d * z - u * sb
        c = -sp[SP_CS + j] * math.sqrt(rx * rx + ry * ry)
        mx -= z * c * ry
        my += z * c * rx
        fs += c * (rx * cb + ry * sb)
    return mx, my, fs, fz


@kernel(forceinline=True)
def pto_torque(phi, phid, tau, pto):
    """M_g (N m): tau + c phi' + k phi, clipped to the torque limit and to |M_g phi'| <= P_max."""
    m = tau + pto[0] * phid + pto[1] * phi
    lim = pto[2]
    if abs(phid) * lim > pto[3]:
        lim = pto[3] / abs(phid)
    return min(max(m, -lim), lim)


@numba.njit(cache=True)
def mass_and_rhs(q, u, inertia, gyro, psid):
    """M* (3,3) and the velocity terms v (3,) = sum B^T (J B' u + w x h) of the module doc;
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
    Ih, Iz = inertia[0], inertia[1]
    Ja, Jt, Jg1, Jg2, Jg3 = gyro[0], gyro[1], gyro[2], gyro[3], gyro[4]
    # gimbal + rotor (principal in the gimbal frame): J1, J2, J3 (rotor spin added in h3)
    G1, G2, G3 = Jg1 + Jt, Jg2 + Jt, Jg3 + Ja
    m00 = Ih * cr_ * cr_ + Iz * sr_ * sr_
    hull00, m11, m12, m22 = m00, Ih, 0.0, 0.0
    # hull: w = (c th', ro', s th'), B'u = (-s ro' th', 0, c ro' th')
    w1, w2, w3 = cr_ * th_d, ro_d, sr_ * th_d
    d1, d3 = -sr_ * ro_d * th_d, cr_ * ro_d * th_d
    e1 = Ih * d1 + (w2 * Iz * w3 - w3 * Ih * w2)
    e2 = w3 * Ih * w1 - w1 * Iz * w3
    e3 = Iz * d3 + (w1 * Ih * w2 - w2 * Ih * w1)
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


@kernel(forceinline=True)
def mechanics(t, y, tau, args, inp, near=None):
    """The mechanical part of `deriv` at (t, y) with the sea `sea_inputs` inp at t:
    (u' (3), the mass terms of `_mass_terms`, radiation moments mu_t, mu_r (N m), M_g (N m),
    drag moments (dx, dy) (N m), translation tr = (s'', z'' (m/s^2), surge and heave
    excitation (N), surge radiation force mu_11 + mu_15 (N), the moment mu_51 about the axis
    across the wave (N m), heave radiation force mu_33 (N), surge and heave drag (N)); tr is
    zeros when surge and heave are held (`translation` module doc below). near: as
    `_mass_terms`."""
    p_in, p_gy, psid, C, bv, Ar, _, Cr, pto = args[:9]
    sp, tp = args[13], args[14]
    mx, my = inp[0], inp[1]
    nr = Ar.shape[0]
    trans = tp[TP_ON] != 0.0
    b = N_MECH + 2 * nr  # translation block: s, z, s', z', stacked radiation states
    s_d, z_d = (y[b + 2], y[b + 3]) if trans else (0.0, 0.0)
    dx, dy, dfs, dfz = drag_loads(y[3], y[4], s_d, z_d, inp, sp)
    m = _mass_terms(y[1], y[2], y[3], y[4], y[5], p_in, p_gy, psid, near)
    mu_t, mu_r = 0.0, 0.0
    for i in range(nr):
        mu_t += Cr[i] * y[6 + i]
        mu_r += Cr[i] * y[6 + nr + i]
    Mg = pto_torque(y[2], y[5], tau, pto)
    q0 = mx + dx - C * y[0] - mu_t - bv * y[3] - m[4]
    q1 = my + dy - C * y[1] - mu_r - bv * y[4] - m[5]
    q2 = -p_gy[5] * Mg - m[6]
    a00, a01, a11 = m[0], 0.0, m[1]
    if not trans:
        ud = _solve_tridiag3(a00, a01, a11, m[2], m[3], q0, q1, q2)
        return ud, m, mu_t, mu_r, Mg, dx, dy, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    Cs = args[17]
    m1, a15 = tp[TP_M1], tp[TP_A15]
    o11, o51, o33 = int(tp[TP_O11]), int(tp[TP_O51]), int(tp[TP_O33])
    mu_s = _dot_block(Cs, y, b + 4, o11, o51)  # the 11 and 15 blocks (adjacent)
    mu_n = _dot_block(Cs, y, b + 4, o51, o33)
    mu_z = _dot_block(Cs, y, b + 4, o33, int(tp[TP_NT]))
    # surge along the wave couples with alpha = -(g . u), g = (sin, -cos) of the direction
    gt, gr = sp[SP_DIR + 1], -sp[SP_DIR]
    fs, fz = inp[2 + N_KEEL + N_SIDE], inp[3 + N_KEEL + N_SIDE]
    r_s = fs + dfs - mu_s - tp[TP_K] * y[b]
    kk = a15 * a15 / m1
    h = mu_n + a15 * r_s / m1
    a00, a01, a11 = a00 - kk * gt * gt, a01 - kk * gt * gr, a11 - kk * gr * gr
    ud = _solve_tridiag3(a00, a01, a11, m[2], m[3], q0 + gt * h, q1 + gr * h, q2)
    sdd = (r_s + a15 * (gt * ud[0] + gr * ud[1])) / m1
    zdd = (fz + dfz - mu_z - tp[TP_C33] * y[b + 1]) / tp[TP_M3]
    return ud, m, mu_t, mu_r, Mg, dx, dy, (sdd, zdd, fs, fz, mu_s, mu_n, mu_z, dfs, dfz)


@numba.njit(cache=True)
def deriv(t, y, tau, args):
    """dy/dt (module doc layout) with the PTO command tau (N m); args: `pack`."""
    dy = np.empty_like(y)
    deriv_into(t, y, tau, args, sea_inputs(t, args[9], args[10], args[11], args[12], args[13]), dy)
    return dy


@kernel(forceinline=True)
def deriv_into(t, y, tau, args, inp, dy, near=None):
    """`deriv` into dy (n_state,) with the sea `sea_inputs` inp at t given (the RK4 step
    evaluates it once per stage time); no allocation, no temporaries."""
    p_gy, psid, Ar, Br, pto = args[1], args[2], args[5], args[6], args[8]
    bv = args[4]
    nr = Ar.shape[0]
    ud, m, mu_t, mu_r, Mg, drx, dry, tr = mechanics(t, y, tau, args, inp, near)
    mx, my = inp[0], inp[1]
    for i in range(3):
        dy[i] = y[3 + i]
        dy[3 + i] = ud[i]
    th_d, ro_d, ph_d = y[3], y[4], y[5]
    if nr == 4:  # the fit's order: `_radiation4`, the same sums unrolled
        _radiation4(y, dy, Ar, Br, th_d, ro_d)
    for i in range(nr if nr != 4 else 0):  # radiation states: x' = A x + B u (no BLAS call)
        at, ar = 0.0, 0.0
        for j in range(nr):
            at += Ar[i, j] * y[6 + j]
            ar += Ar[i, j] * y[6 + nr + j]
        dy[6 + i] = at + Br[i] * th_d
        dy[6 + nr + i] = ar + Br[i] * ro_d
    k = 6 + 2 * nr
    e_exc = mx * th_d + my * ro_d
    e_rad = mu_t * th_d + mu_r * ro_d
    e_drag = drx * th_d + dry * ro_d
    tp = args[14]
    if tp[TP_ON] != 0.0:
        k = _translation_rates(y, dy, k, ud, tr, args)
        sp = args[13]
        s_d, z_d = y[6 + 2 * nr + 2], y[6 + 2 * nr + 3]
        al_d = -(sp[SP_DIR + 1] * th_d - sp[SP_DIR] * ro_d)  # alpha' = -(g . u')
        e_exc += tr[2] * s_d + tr[3] * z_d
        e_rad += tr[4] * s_d + tr[5] * al_d + tr[6] * z_d
        e_drag += tr[7] * s_d + tr[8] * z_d
    nu = p_gy[5]
    P = nu * Mg * ph_d
    dy[k] = e_exc
    dy[k + 1] = e_rad
    dy[k + 2] = bv * (th_d * th_d + ro_d * ro_d) - e_drag
    dy[k + 3] = P
    dy[k + 4] = P * pto[4] if P >= 0.0 else P / pto[5]
    # rotor motors hold +-psi': torque Ja d/dt(w_g3) with w_g3 = sin(b) theta', b = rho + s phi
    pm = 0.0
    for j in range(int(nu)):
        sg = 1.0 - 2.0 * j
        cb, sb = (m[12], m[13]) if j == 0 else (m[14], m[15])
        pm += sg * (cb * (ro_d + sg * ph_d) * th_d + sb * ud[0])
    dy[k + 5] = p_gy[0] * pm * psid


@kernel(forceinline=True)
def _radiation4(y, dy, Ar, Br, th_d, ro_d):
    """`deriv_into`'s radiation states of a 4th-order fit (pitch at y[6:10], roll at y[10:14]),
    its loop's sums in its order, unrolled: 0.0 + sum_j A[i, j] x_j, then + B[i] u."""
    t0, t1, t2, t3 = y[6], y[7], y[8], y[9]
    r0, r1, r2, r3 = y[10], y[11], y[12], y[13]
    for i in range(4):
        a0, a1, a2, a3 = Ar[i, 0], Ar[i, 1], Ar[i, 2], Ar[i, 3]
        dy[6 + i] = (0.0 + a0 * t0 + a1 * t1 + a2 * t2 + a3 * t3) + Br[i] * th_d
        dy[10 + i] = (0.0 + a0 * r0 + a1 * r1 + a2 * r2 + a3 * r3) + Br[i] * ro_d


@kernel(forceinline=True)
def _block_rates(y, dy, o, As, Bs, lo, hi, v):
    """dy[o + i] = sum_j As[i, j] y[o + j] + Bs[i] v for the diagonal block lo <= i, j < hi
    (on views from 0: indices the compiler sees are >= 0, so no negative-index wraparound per
    element, which the offsets lo, o cost on every access)."""
    A, B, ys, ds = As[lo:hi, lo:hi], Bs[lo:hi], y[o + lo : o + hi], dy[o + lo : o + hi]
    if B.shape[0] == 4:  # the fits' order: the same sums, unrolled (no loop per 4 terms)
        y0, y1, y2, y3 = ys[0], ys[1], ys[2], ys[3]
        for i in range(4):
            ds[i] = B[i] * v + A[i, 0] * y0 + A[i, 1] * y1 + A[i, 2] * y2 + A[i, 3] * y3
        return
    for i in range(B.shape[0]):
        acc = B[i] * v
        for j in range(B.shape[0]):
            acc += A[i, j] * ys[j]
        ds[i] = acc


@kernel(forceinline=True)
def _dot_block(c, y, o, lo, hi):
    """sum_i c[i] y[o + i] over lo <= i < hi, in order from 0.0 (views, as `_block_rates`)."""
    cs, ys = c[lo:hi], y[o + lo : o + hi]
    acc = 0.0
    for i in range(cs.shape[0]):
        acc += cs[i] * ys[i]
    return acc


@kernel(forceinline=True)
def _translation_rates(y, dy, k, ud, tr, args):
    """The translation block's rates into dy (block at k = N_MECH + 2 nr: s, z, s', z', then
    the stacked radiation states x' = As x + Bs v with v = s' (11 and 51 blocks), alpha' (15)
    or z' (33)); returns the index of the energies after it."""
    sp, tp, As, Bs = args[13], args[14], args[15], args[16]
    b = k
    dy[b], dy[b + 1], dy[b + 2], dy[b + 3] = y[b + 2], y[b + 3], tr[0], tr[1]
    s_d, z_d = y[b + 2], y[b + 3]
    al_d = -(sp[SP_DIR + 1] * y[3] - sp[SP_DIR] * y[4])
    nt = int(tp[TP_NT])
    o15, o51, o33 = int(tp[TP_O15]), int(tp[TP_O51]), int(tp[TP_O33])
    _block_rates(y, dy, b + 4, As, Bs, 0, o15, s_d)  # K11: surge force from s'
    _block_rates(y, dy, b + 4, As, Bs, o15, o51, al_d)  # K15: surge force from alpha'
    _block_rates(y, dy, b + 4, As, Bs, o51, o33, s_d)  # K51: moment from s'
    _block_rates(y, dy, b + 4, As, Bs, o33, nt, z_d)  # K33: heave force from z'
    return b + 4 + nt


@kernel(forceinline=True)
def _stage_rhs(t, x, inp, args, out):
    """`deriv_into` in the RK4 template's form; inp = `sea_inputs` at t, args =
    (tau, deriv args, the step's start angles `near` of `_mass_terms`)."""
    deriv_into(t, x, args[0], args[1], inp, out, args[2])


_rk4 = make_rk4_given(_stage_rhs, inline=True)


@numba.njit(cache=True)
def rk4_steps(t, y, tau, dt, n, args):
    """n RK4 substeps of dt (s) from (t, y) with the PTO command tau held; returns y (new).
    args = (p_in, p_gy, psid, C, bv, Ar, Br, Cr, pto, om, cp, cr, dk, sp, tp, As, Bs, Cs) as
    `deriv` (`pack`).
    The stage loop is the one of `mf_envs.frames.kernels.make_rk4`."""
    y = y.copy()
    rk4_steps_into(t, y, tau, dt, n, args, rk4_work(y.shape[0]), np.empty((4, args[9].shape[0])))
    return y


@kernel
def rk4_steps_into(t, y, tau, dt, n, args, work, ph):
    """`rk4_steps` in place on y with caller-owned temporaries work = `rk4_work(n_state)` and
    ph (4, M) (M wave components; no allocation: the env's step calls it every control step).
    The sea is evaluated at t, t + dt/2, t + dt of every substep (as `make_rk4` does) from the
    components' phasors: cos/sin of w_i t once, then rotated by w_i dt/2 (`_advance_phasors`).
    Returns the sea (`sea_sum`) at the end time t + n dt and the last substep's start angles
    `near` of `_mass_terms` (NaNs if n = 0: libm), from which the end state's are near."""
    om, cp, cr, dk, sp = args[9], args[10], args[11], args[12], args[13]
    h = 0.5 * dt
    for i in range(om.shape[0]):
        ph[0, i], ph[1, i] = math.cos(om[i] * t), math.sin(om[i] * t)
        ph[2, i], ph[3, i] = math.cos(om[i] * h), math.sin(om[i] * h)
    i1 = sea_sum(ph, ramp(t, sp[1]), cp, cr, dk, sp)
    near = (math.nan, math.nan, math.nan, math.nan, math.nan, math.nan)
    for _ in range(n):
        i0 = i1
        # rho and phi at the substep's start: the stages' sin/cos from these (`_mass_terms`)
        ro, phi = y[1], y[2]
        near = (ro, math.cos(ro), math.sin(ro), phi, math.cos(phi), math.sin(phi))
        full = (tau, args, near)
        _advance_phasors(ph)
        ih = sea_sum(ph, ramp(t + h, sp[1]), cp, cr, dk, sp)
        _advance_phasors(ph)
        i1 = sea_sum(ph, ramp(t + dt, sp[1]), cp, cr, dk, sp)
        _rk4(t, y, dt, full, work, i0, ih, i1)
        dy = work[0]
        for i in range(y.shape[0]):
            y[i] += dy[i]
        t += dt
    return i1, near


def pack(p: FloatingParams, om: NDArray, cp: NDArray, cr: NDArray, dk: NDArray,
         sp: NDArray, tr: tuple) -> tuple:  # fmt: skip
    """The argument tuple of `deriv` / `rk4_steps` for params p, excitation (om, cp, cr), the
    sea's per-component loads dk (n, N_LOADS) and the sea parameters sp (SP_LEN,)
    (`sea_inputs`), and the translation (tp, As, Bs, Cs) (`translation_params`)."""
    return (p.inertia, p.gyro, float(p.psid), float(p.stiffness), float(p.viscous), p.Ar, p.Br,
            p.Cr, p.pto, om, cp, cr, dk, sp, *tr)  # fmt: skip


def drag_geometry(hull, drag_coefficient: float, ramp_seconds: float, direction: float) -> NDArray:
    """The sea parameters `sp` (SP_LEN,) of `sea_inputs` / `drag_loads` for a vertical
    cylinder hull (radius R, draft d, z_G from `hull`) and drag coefficient C_d (0 = off):
    - keel plate: N_KEEL nodes on a ring of radius r* = R (32 / (25 pi))^(1/3) at angles
      direction + j pi/3, each of area pi R^2 / N_KEEL, so that for a rigid rotation the ring
      reproduces the plate's integral of |x|^3 over the disc, 8 R^5 / 15 (the quadratic pitch
      damping K = 1/2 rho C_d 8 R^5 / 15 exactly in still water about the axis across the
      wave direction; about the other axis the ring gives 2.598 / 2.5, 3.9 % more);
    - side: N_SIDE Gauss-Legendre nodes over the draft on the axis, projected width 2R;
    - ramp time (s) of the incident wave, and the wave direction's cosine and sine."""
    sp = np.zeros(SP_LEN)
    sp[1] = ramp_seconds
    c, s = math.cos(direction), math.sin(direction)
    sp[SP_DIR], sp[SP_DIR + 1] = c, s
    if drag_coefficient <= 0.0:
        return sp
    R, d, zg, rho = float(hull.radius), float(hull.draft), float(hull.zg), float(hull.rho)
    if not (math.isfinite(R) and math.isfinite(d) and math.isfinite(zg)):
        raise ValueError("drag_coefficient: the hull has no radius/draft/zg (a user table "
                         "without geometry); quadratic drag needs them")  # fmt: skip
    sp[0] = 1.0
    ang = direction + np.arange(N_KEEL) * (2.0 * math.pi / N_KEEL)
    r = R * (32.0 / (25.0 * math.pi)) ** (1.0 / 3.0)
    sp[SP_CK : SP_CK + N_KEEL] = 0.5 * rho * drag_coefficient * math.pi * R * R / N_KEEL
    sp[SP_XK : SP_XK + N_KEEL] = r * np.cos(ang)
    sp[SP_YK : SP_YK + N_KEEL] = r * np.sin(ang)
    gl = np.array([-1.0, 1.0]) / math.sqrt(3.0)  # 2-point Gauss-Legendre on [-1, 1]
    sp[SP_CS : SP_CS + N_SIDE] = 0.5 * rho * drag_coefficient * 2.0 * R * d / N_SIDE
    sp[SP_ZS : SP_ZS + N_SIDE] = -0.5 * d * (1.0 + gl) - zg
    return sp


def drag_velocity_coefficients(sp: NDArray, hull, om: NDArray, amp: NDArray,
                               eps: NDArray) -> NDArray[np.complex128]:  # fmt: skip
    """dk (n, N_LOADS), its first N_KEEL + N_SIDE columns (the last two, the surge and heave
    forces, are `translation_loads`'): the incident wave's water velocity at the drag nodes is
    sum_i Re(dk[i, j] e^{-i w_i t}), linear deep-water kinematics (k = w^2 / g) of
    eta = sum a_i cos(k s - w_i t + eps_i): vertical w = a w e^{kz} sin(.) at the keel nodes
    (z = -draft), horizontal speed along the wave u = a w e^{kz} cos(.) at the side nodes
    (s = 0). Zeros when the drag is off."""
    om = np.asarray(om, dtype=float)
    dk = np.zeros((om.size, N_LOADS), dtype=complex)
    if sp[0] == 0.0 or om.size == 0:
        return dk
    k = om * om / float(hull.g)
    c = np.asarray(amp, dtype=float) * np.exp(1j * np.asarray(eps, dtype=float))
    cb, sb = sp[SP_DIR], sp[SP_DIR + 1]
    s = sp[SP_XK : SP_XK + N_KEEL] * cb + sp[SP_YK : SP_YK + N_KEEL] * sb
    zk = -float(hull.draft)
    dk[:, :N_KEEL] = (-1j * om * np.exp(k * zk) * c)[:, None] * np.exp(1j * k[:, None] * s)
    zs = sp[SP_ZS : SP_ZS + N_SIDE] + float(hull.zg)  # absolute depth of the side nodes
    dk[:, N_KEEL : N_KEEL + N_SIDE] = (om * c)[:, None] * np.exp(k[:, None] * zs)
    return dk


def translation_loads(dk: NDArray, three, om: NDArray, amp: NDArray, eps: NDArray) -> None:
    """dk's last two columns (in place): the surge force along the wave and the heave force
    per component, X_1(w) a e^{i eps} and X_3(w) a e^{i eps} (N), from the 3-dof table `three`
    (linear interpolation, 0 outside it)."""
    om = np.asarray(om, dtype=float)
    c = np.asarray(amp, dtype=float) * np.exp(1j * np.asarray(eps, dtype=float))
    for col, mode in ((N_KEEL + N_SIDE, 0), (N_KEEL + N_SIDE + 1, 1)):
        X = three.excitation[:, mode]
        Xi = np.interp(om, three.omega, X.real, 0.0, 0.0) + 1j * np.interp(
            om, three.omega, X.imag, 0.0, 0.0
        )
        dk[:, col] = Xi * c


@numba.njit(cache=True, inline="always")
def energy_index(args):
    """Index of the integrated energies in the state: after the mechanical state, the two
    rotational radiation copies and (when surge and heave are free) the translation block."""
    tp = args[14]
    k = N_MECH + 2 * args[5].shape[0]
    if tp[TP_ON] != 0.0:
        k += 4 + int(tp[TP_NT])
    return k


def mechanical_energy(p: FloatingParams, y: NDArray[np.float64], tp: NDArray | None = None,
                      direction: float = 0.0) -> float:  # fmt: skip
    """Kinetic + hydrostatic energy (J) of the mechanical state, with the rotor spin's constant
    1/2 Ja psi'^2 removed (the motor holds psi'; its work is E_motor); with the translation
    parameters tp (surge and heave free) also 1/2 M1 s'^2 + A15 s' alpha' + 1/2 M3 z'^2 and
    the mooring's and heave's springs."""
    M, _, spin, _ = mass_and_rhs(y[0:3], y[3:6], p.inertia, p.gyro, p.psid)
    u = y[3:6]
    kin = 0.5 * float(u @ M @ u) + p.gyro[0] * p.psid * spin
    e = kin + 0.5 * p.stiffness * float(y[0] ** 2 + y[1] ** 2)
    if tp is not None and tp[TP_ON] != 0.0:
        b = N_MECH + 2 * p.Ar.shape[0]
        s, z, sd, zd = y[b : b + 4]
        al_d = -(math.sin(direction) * y[3] - math.cos(direction) * y[4])
        e += 0.5 * tp[TP_M1] * sd * sd + tp[TP_A15] * sd * al_d + 0.5 * tp[TP_M3] * zd * zd
        e += 0.5 * tp[TP_K] * s * s + 0.5 * tp[TP_C33] * z * z
    return e


def gyro_moment(p: FloatingParams, y: NDArray[np.float64], accel: NDArray) -> NDArray:
    """Moment of the gyro unit on the hull along the (theta, rho) coordinates (N m, (2,)):
    minus the gimbal+rotor's B^T (J B u' + J B' u + w x h) rows of theta and rho, with the
    generator torque's reaction included through the rho row (the gimbal axis is e2)."""
    q, u = y[0:3], y[3:6]
    Mfull, v, _, gy = mass_and_rhs(q, u, p.inertia, p.gyro, p.psid)
    Mh, vh, _, _ = mass_and_rhs(q, u, p.inertia, np.zeros(6), 0.0)
    Mg_part = (Mfull - Mh) @ accel + gy
    return -Mg_part[:2]
