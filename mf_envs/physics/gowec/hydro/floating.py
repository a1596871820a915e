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
cancel those of the first, and Q_phi = -2 M_g. Each tilt axis has its own block (`axes`):
J_h = diag(I_1 + A_inf,1, I_2 + A_inf,2, I_z) (A_inf, the infinite-frequency added inertia,
rides with the hull; `bodies`), mu = radiation memory from the axis' state-space fit
x' = Ar x + Br q', mu = Cr x (`radiation.fit_radiation`), C the axis' hydrostatic stiffness
(Q above: C_theta theta, C_rho rho); an axisymmetric hull's roll block is its pitch block, a box
has a roll block of its own. M_x, M_y the wave excitation moments (`sea.excitation_coefficients`)
and an optional linear viscous damping b_v q' on each axis.
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
from mf_envs.frames.steppers import make_rk4_given, rk4_work
from mf_envs.physics.gowec.hydro.bodies import (  # noqa: F401 (mass_and_rhs: re-exported)
    _mass_terms,
    _solve_tridiag3,
    mass_and_rhs,
)
from mf_envs.physics.gowec.hydro.gimbal import gimbal_loads, stop_dissipation
from mf_envs.physics.gowec.hydro.radiation import block_rates, dot_block, radiation_rates4
from mf_envs.physics.gowec.hydro.sea import (
    N_KEEL,
    N_SIDE,
    SP_DIR,
    advance_phasors,
    drag_loads,
    ramp,
    sea_inputs,
    sea_sum,
)

N_MECH = 6
N_ENERGY = 6
N_SUPERVISOR = 1  # the supervisor's survival timer (s) after the energies (`gimbal.supervise`)


@dataclass(frozen=True)
class FloatingParams:
    """Packed numbers of the fast path (SI), per tilt axis (theta, rho) where two. inertia =
    (I_1 + A_inf,theta, I_z, I_2 + A_inf,rho) of the hull (kg m^2, `bodies`); gyro = (Ja, Jt,
    Jg1, Jg2, Jg3) kg m^2; psid rad/s; stiffness (C_theta, C_rho) (N m/rad); viscous b_v
    (N m s/rad); radiation (Ar (2, nr, nr), Br (2, nr), Cr (2, nr)), one fit per axis (the
    lower-order one padded with inert states, `axes.stack_fits`); pto = (c N m s/rad, k N m/rad,
    max torque N m, max power W, eta_generator, eta_motor, then the end stops, brake and
    supervisor of `gimbal.PTO_NAMES`)."""

    inertia: NDArray[np.float64]  # (3,)
    gyro: NDArray[np.float64]  # (Ja, Jt, Jg1, Jg2, Jg3, n_units)
    psid: float
    stiffness: NDArray[np.float64]  # (2,)
    viscous: float
    Ar: NDArray[np.float64]
    Br: NDArray[np.float64]
    Cr: NDArray[np.float64]
    pto: NDArray[np.float64]

    @property
    def n_state(self) -> int:
        """Without the translation block (`FloatingModel.n_state` adds it)."""
        return N_MECH + 2 * self.Ar.shape[1] + N_ENERGY + N_SUPERVISOR


# the translation parameters `tp` (TP_LEN,) (`translation_params`): on, M1 = m + A11_inf (kg),
# A15_inf (kg m, about G, symmetrised), mooring stiffness (N/m), M3 = m + A33_inf (kg), C33 (N/m),
# then the start of each radiation block in the stacked state (11 from s', 15 from alpha' to
# the surge force, 51 from s' to the moment, 33 from z') and the stacked order nt
TP_ON, TP_M1, TP_A15, TP_K, TP_M3, TP_C33, TP_O11, TP_O15, TP_O51, TP_O33, TP_NT = range(11)
TP_LEN = 11


@kernel(forceinline=True)
def mechanics(t, y, tau, args, inp, near=None):
    """The mechanical part of `deriv` at (t, y) with the sea `sea_inputs` inp at t:
    (u' (3), the mass terms of `_mass_terms`, radiation moments mu_t, mu_r (N m), M_g (N m),
    drag moments (dx, dy) (N m), translation tr = (s'', z'' (m/s^2), surge and heave
    excitation (N), surge radiation force mu_11 + mu_15 (N), the moment mu_51 about the axis
    across the wave (N m), heave radiation force mu_33 (N), surge and heave drag (N)); tr is
    zeros when surge and heave are held (`translation` module doc below), and the gimbal's
    brake and end-stop torques (M_b, tau_s) (N m, `gimbal.gimbal_loads`: M_g is 0 and the
    brake on in survival, the state's supervisor timer > 0). near: as `_mass_terms`."""
    p_in, p_gy, psid, C, bv, Ar, _, Cr, pto = args[:9]
    sp, tp = args[13], args[14]
    mx, my = inp[0], inp[1]
    nr = Ar.shape[1]
    trans = tp[TP_ON] != 0.0
    b = N_MECH + 2 * nr  # translation block: s, z, s', z', stacked radiation states
    s_d, z_d = (y[b + 2], y[b + 3]) if trans else (0.0, 0.0)
    dx, dy, dfs, dfz = drag_loads(y[3], y[4], s_d, z_d, inp, sp)
    m = _mass_terms(y[1], y[2], y[3], y[4], y[5], p_in, p_gy, psid, near)
    mu_t, mu_r = 0.0, 0.0
    for i in range(nr):
        mu_t += Cr[0, i] * y[6 + i]
        mu_r += Cr[1, i] * y[6 + nr + i]
    Mg, Mb, Ms = gimbal_loads(y[2], y[5], tau, pto, y[energy_index(args) + N_ENERGY] > 0.0)
    q0 = mx + dx - C[0] * y[0] - mu_t - bv * y[3] - m[4]
    q1 = my + dy - C[1] * y[1] - mu_r - bv * y[4] - m[5]
    q2 = p_gy[5] * (Ms - Mg - Mb) - m[6]
    a00, a01, a11 = m[0], 0.0, m[1]
    if not trans:
        ud = _solve_tridiag3(a00, a01, a11, m[2], m[3], q0, q1, q2)
        return ud, m, mu_t, mu_r, Mg, dx, dy, (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0), \
            (Mb, Ms)  # fmt: skip
    Cs = args[17]
    m1, a15 = tp[TP_M1], tp[TP_A15]
    o11, o51, o33 = int(tp[TP_O11]), int(tp[TP_O51]), int(tp[TP_O33])
    mu_s = dot_block(Cs, y, b + 4, o11, o51)  # the 11 and 15 blocks (adjacent)
    mu_n = dot_block(Cs, y, b + 4, o51, o33)
    mu_z = dot_block(Cs, y, b + 4, o33, int(tp[TP_NT]))
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
    return ud, m, mu_t, mu_r, Mg, dx, dy, (sdd, zdd, fs, fz, mu_s, mu_n, mu_z, dfs, dfz), \
        (Mb, Ms)  # fmt: skip


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
    nr = Ar.shape[1]
    ud, m, mu_t, mu_r, Mg, drx, dry, tr, gl = mechanics(t, y, tau, args, inp, near)
    mx, my = inp[0], inp[1]
    for i in range(3):
        dy[i] = y[3 + i]
        dy[3 + i] = ud[i]
    th_d, ro_d, ph_d = y[3], y[4], y[5]
    if nr == 4:  # the fit's order: `radiation_rates4`, the same sums unrolled
        radiation_rates4(y, dy, Ar, Br, th_d, ro_d)
    for i in range(nr if nr != 4 else 0):  # radiation states: x' = A x + B u (no BLAS call)
        at, ar = 0.0, 0.0
        for j in range(nr):
            at += Ar[0, i, j] * y[6 + j]
            ar += Ar[1, i, j] * y[6 + nr + j]
        dy[6 + i] = at + Br[0, i] * th_d
        dy[6 + nr + i] = ar + Br[1, i] * ro_d
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
    # dissipated: viscous, drag, and the gimbals' survival brake and end-stop cushions
    gimbal = nu * (gl[0] * ph_d + stop_dissipation(y[2], ph_d, gl[1], pto))
    dy[k + 2] = bv * (th_d * th_d + ro_d * ro_d) - e_drag + gimbal
    dy[k + 3] = P
    dy[k + 4] = P * pto[4] if P >= 0.0 else P / pto[5]
    # rotor motors hold +-psi': torque Ja d/dt(w_g3) with w_g3 = sin(b) theta', b = rho + s phi
    pm = 0.0
    for j in range(int(nu)):
        sg = 1.0 - 2.0 * j
        cb, sb = (m[12], m[13]) if j == 0 else (m[14], m[15])
        pm += sg * (cb * (ro_d + sg * ph_d) * th_d + sb * ud[0])
    dy[k + 5] = p_gy[0] * pm * psid
    dy[k + N_ENERGY] = 0.0  # the supervisor's timer: stepped once per control step


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
    block_rates(y, dy, b + 4, As, Bs, 0, o15, s_d)  # K11: surge force from s'
    block_rates(y, dy, b + 4, As, Bs, o15, o51, al_d)  # K15: surge force from alpha'
    block_rates(y, dy, b + 4, As, Bs, o51, o33, s_d)  # K51: moment from s'
    block_rates(y, dy, b + 4, As, Bs, o33, nt, z_d)  # K33: heave force from z'
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
    components' phasors: cos/sin of w_i t once, then rotated by w_i dt/2 (`advance_phasors`).
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
        advance_phasors(ph)
        ih = sea_sum(ph, ramp(t + h, sp[1]), cp, cr, dk, sp)
        advance_phasors(ph)
        i1 = sea_sum(ph, ramp(t + dt, sp[1]), cp, cr, dk, sp)
        _rk4(t, y, dt, full, work, i0, ih, i1)
        dy = work[0]
        for i in range(y.shape[0]):
            y[i] += dy[i]
        t += dt
    return i1, near


def pack(p: FloatingParams, om: NDArray, cp: NDArray, cr: NDArray, dk: NDArray, sp: NDArray,
         tr: tuple) -> tuple:  # fmt: skip
    """The argument tuple of `deriv` / `rk4_steps` for params p, excitation (om, cp, cr), the
    sea's per-component loads dk (n, N_LOADS) and the sea parameters sp (SP_LEN,)
    (`sea_inputs`), and the translation (tp, As, Bs, Cs) (`translation_params`)."""
    return (p.inertia, p.gyro, float(p.psid), p.stiffness, float(p.viscous), p.Ar, p.Br,
            p.Cr, p.pto, om, cp, cr, dk, sp, *tr)  # fmt: skip


@numba.njit(cache=True, inline="always")
def energy_index(args):
    """Index of the integrated energies in the state: after the mechanical state, the two
    tilt axes' radiation states and (when surge and heave are free) the translation block."""
    tp = args[14]
    k = N_MECH + 2 * args[5].shape[1]
    if tp[TP_ON] != 0.0:
        k += 4 + int(tp[TP_NT])
    return k
