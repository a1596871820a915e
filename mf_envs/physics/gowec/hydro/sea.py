"""The sea of the floating GOWEC's fast path: the wave components' excitation moments, the water's
velocity at the Morison drag nodes, the surge and heave forces, the incident wave's start-up ramp
and the quadratic drag loads (Rios 2017 ch. 3's excitation moments; Morison drag relative to
the incident wave's water), as numba kernels that `floating`'s RK4 step inlines, and the
Python-side tables they read (`drag_geometry`, `drag_velocity_coefficients`,
`translation_loads`).
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numpy.typing import NDArray

from mf_envs._jit import kernel


def excitation_coefficients(
    X: NDArray[np.complex128], amplitudes: NDArray, phases: NDArray, direction: float
) -> tuple[NDArray[np.complex128], NDArray[np.complex128]]:
    """Complex moment coefficients (N m) c_i such that M(t) = sum Re(c_i e^{-i w_i t}) about e1
    (pitch) and e2 (roll) for components eta = a_i cos(k x.n - w_i t + eps_i) travelling in
    `direction` (rad from x1). X (n,) is an axisymmetric hull's pitch excitation (about y, wave
    along +x) at w_i: the moment about e2 is X cos(direction) and about e1 -X sin(direction);
    or X (2, n) the moments about e1 and e2 at that direction already (`axes`, a box)."""
    if np.ndim(X) == 2:
        return tuple(np.asarray(x) * np.asarray(amplitudes) * np.exp(1j * np.asarray(phases))
                     for x in X)  # fmt: skip
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
def advance_phasors(ph):
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


def drag_geometry(hull, drag_coefficient: float, ramp_seconds: float, direction: float,
                  plan: tuple[float, float] | None = None) -> NDArray:  # fmt: skip
    """The sea parameters `sp` (SP_LEN,) of `sea_inputs` / `drag_loads` for a vertical
    cylinder hull (radius R, draft d, z_G from `hull`) and drag coefficient C_d (0 = off):
    - keel plate: N_KEEL nodes on a ring of radius r* = R (32 / (25 pi))^(1/3) at angles
      direction + j pi/3, each of area pi R^2 / N_KEEL, so that for a rigid rotation the ring
      reproduces the plate's integral of |x|^3 over the disc, 8 R^5 / 15 (the quadratic pitch
      damping K = 1/2 rho C_d 8 R^5 / 15 exactly in still water about the axis across the
      wave direction; about the other axis the ring gives 2.598 / 2.5, 3.9 % more);
    - side: N_SIDE Gauss-Legendre nodes over the draft on the axis, projected width 2R;
    - ramp time (s) of the incident wave, and the wave direction's cosine and sine.
    A box (plan = (length L, beam B) m, its length along e2: `axes`): the keel nodes at the
    body-fixed angles pi/2 + j pi/3 on the ellipse of semi-axes a along e2 and b along e1,
    a^3 = N L^3 / (32 S_c), b^3 = N B^3 / (32 S_s) (S_c, S_s the sums of |cos|^3, |sin|^3 of
    j pi/3), each of area L B / N: the plate's integrals of |y|^3 (B L^4 / 32) and of |x|^3
    (L B^4 / 32) exactly, so both axes' still-water quadratic damping; the side's width the
    one facing the wave, B |sin| + L |cos| of the direction (chosen)."""
    sp = np.zeros(SP_LEN)
    sp[1] = ramp_seconds
    c, s = math.cos(direction), math.sin(direction)
    sp[SP_DIR], sp[SP_DIR + 1] = c, s
    if drag_coefficient <= 0.0:
        return sp
    R, d, zg, rho = float(hull.radius), float(hull.draft), float(hull.zg), float(hull.rho)
    if not ((plan is not None or math.isfinite(R)) and math.isfinite(d) and math.isfinite(zg)):
        raise ValueError("drag_coefficient: the hull has no radius/draft/zg (a user table "
                         "without geometry); quadratic drag needs them")  # fmt: skip
    sp[0] = 1.0
    gl = np.array([-1.0, 1.0]) / math.sqrt(3.0)  # 2-point Gauss-Legendre on [-1, 1]
    sp[SP_ZS : SP_ZS + N_SIDE] = -0.5 * d * (1.0 + gl) - zg
    half = 0.5 * rho * drag_coefficient
    if plan is not None:
        L, B = plan
        j = np.arange(N_KEEL) * (2.0 * math.pi / N_KEEL)
        a = L * (N_KEEL / (32.0 * np.sum(np.abs(np.cos(j)) ** 3))) ** (1.0 / 3.0)
        b = B * (N_KEEL / (32.0 * np.sum(np.abs(np.sin(j)) ** 3))) ** (1.0 / 3.0)
        sp[SP_CK : SP_CK + N_KEEL] = half * L * B / N_KEEL
        sp[SP_XK : SP_XK + N_KEEL] = b * np.cos(0.5 * math.pi + j)
        sp[SP_YK : SP_YK + N_KEEL] = a * np.sin(0.5 * math.pi + j)
        sp[SP_CS : SP_CS + N_SIDE] = half * (B * abs(s) + L * abs(c)) * d / N_SIDE
        return sp
    ang = direction + np.arange(N_KEEL) * (2.0 * math.pi / N_KEEL)
    r = R * (32.0 / (25.0 * math.pi)) ** (1.0 / 3.0)
    sp[SP_CK : SP_CK + N_KEEL] = half * math.pi * R * R / N_KEEL
    sp[SP_XK : SP_XK + N_KEEL] = r * np.cos(ang)
    sp[SP_YK : SP_YK + N_KEEL] = r * np.sin(ang)
    sp[SP_CS : SP_CS + N_SIDE] = half * 2.0 * R * d / N_SIDE
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
        dk[:, col] = interp_complex(om, three.omega, three.excitation[:, mode]) * c


def interp_complex(w: NDArray, omega: NDArray, X: NDArray) -> NDArray[np.complex128]:
    """X (complex, tabulated at omega) at the frequencies w, linear in its real and imaginary
    parts, 0 outside the table."""
    return np.interp(w, omega, X.real, 0.0, 0.0) + 1j * np.interp(w, omega, X.imag, 0.0, 0.0)
