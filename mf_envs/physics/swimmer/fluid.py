"""Fluid forces on a slender swimmer in the horizontal plane (Rios 2017 §4.5 I, Eq. 40 with the
distributed load n_hat(S, t) and m_hat_3 = 0): Taylor's resistive force (1952) and Lighthill's
reactive, elongated-body force (1960, 1971), as configuration- and velocity-dependent loads of the
C1 beam with their consistent tangents.

::

    y      water at rest, density rho
    |   tail S = 0  ~~~~~~~~~~~~~~~~~~~~>  head S = L
    +---- x        t = (cos psi, sin psi), n = (-sin psi, cos psi)
                   f(S) = resistive + reactive, plus Lighthill's force at the end
                   that trails (the tail when swimming head first)

At a point of the centreline with frame angle psi and velocity v (relative to the water at rest),
v_t = v . t, v_n = v . n:

* resistive (Taylor 1952, "Analysis of the swimming of long and narrow animals", Proc. R. Soc. A
  214: each element feels the force of a long straight cylinder at the same speed and
  inclination): f = -(g_t(v_t) t + g_n(v_n) n) with the quadratic law of a cylinder at high
  Reynolds number, g_n = 1/2 rho d C_N |v_n| v_n (cross-flow drag), g_t = 1/2 rho (pi d) C_T
  |v_t| v_t (skin friction on the wetted perimeter), or the linear (Stokes, resistive-force
  theory) law g_n = c_n v_n, g_t = c_t v_t. Consistent tangent (dt/dpsi = n, dn/dpsi = -t):
      df/dv = -(g_t' t t^T + g_n' n n^T),
      df/dpsi = -((g_t' v_n - g_n) t + (g_t - g_n' v_t) n).
* reactive (Lighthill 1960, J. Fluid Mech. 9; large-amplitude form Lighthill 1971, Proc. R. Soc.
  B 179): the water carried with a section has momentum P = m_a w n per length, w = v_n,
  m_a = rho pi d^2 / 4 (the added mass of a circular section); the body feels -dP/dt along the
  body plus, at the trailing edge (where the water streaming past the body leaves it), the
  momentum shed into the wake and the pressure on the plane there. At the tail (S = 0) when it
  trails (the body moves head first there, u > 0):
      F_tail = m_a (-u w n + w^2 t / 2),  u = v . t, w = v . n at S = 0,
      dF_tail/dv = m_a (-w n t^T - u n n^T + w t n^T),  dF_tail/dpsi = m_a (u^2 - w^2 / 2) n;
  at the head (S = L) when it trails (u < 0 there), the same term mirrored (S -> L - S turns t,
  n and w around): F_head = -m_a (-u w n + w^2 t / 2) at S = L. The leading edge sheds nothing.
  Which end trails is decided by the sign of u at each end, smoothly: the tail's term is
  weighted by sigma(u_tail), the head's by sigma(-u_head), sigma(x) = (1 + x / sqrt(x^2 +
  eps^2)) / 2 with eps = `Water.end_speed` (1 mm/s: a body swimming either way at more than a
  few mm/s sheds at one end only), and the weights' derivatives are in the tangent.
  Averaged over a period of a small-amplitude wave the force is Lighthill's mean thrust
  T = m_a / 2 < h_t^2 - U^2 h_x^2 >_tail (`theory.lighthill_thrust`). The -dP/dt term is an
  added mass on the normal direction that depends on psi; `kernels` puts it in the residual as
  (P(d_{n+1}, v_{n+1}) - P(d_n, v_n)) / dt, so body plus water momentum is conserved exactly
  when nothing else acts (`added_momentum` gives the nodal P and its derivatives).

* form drag (effect `form_drag` of the env): the drag of a gliding fish above the skin friction
  of the flat plate (pressure drag of the blunt head and the thickened boundary layer), lumped
  on the leading end as a point force along its axis, F = -k_f |u| u t, k_f = 1/2 rho C_F
  pi d^2 / 4 (C_F on the frontal area), at the head (S = L) while it leads (u > 0 there) and at
  the tail while the body backs (u < 0 there), blended by sigma(u_head), sigma(-u_tail) as the
  trailing-edge term. A straight body towed along its axis then feels -(k_t L + k_f) |u| u t
  exactly (sigma(u) + sigma(-u) = 1). C_F is derived from gliding fish (docs/eel.md): the total
  drag coefficient on the wetted area C_D measured on gliding fish, less the skin friction
  C_T, times the wetted / frontal area ratio 4 L / d: C_F = (C_D - C_T) 4 L / d. Tangent (h(u)
  = sigma |u| u, w = du/dpsi = v . n): dF/dv = -k_f h'(u) t t^T, dF/dpsi = -k_f (h' w t + h n).

Buoyancy: the body swims in a horizontal plane, gravity is normal to it, and a neutrally
buoyant body (density = rho) feels no net vertical load; the in-plane model has no buoyancy term.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs._validate import check_nonnegative, check_positive
from mf_envs.physics.beam.banded import HALF_BW
from mf_envs.physics.beam.element import GAUSS_W, N_GAUSS
from mf_envs.physics.beam.fused import shape_tables  # noqa: F401  (its home was here)
from mf_envs.physics.constants import RHO_FRESHWATER

# LOC: element dof -> offset from 6 e (Eq. 71c); _add_tangent: a point force's tangent
from mf_envs.physics.serpentine.friction import LOC, _add_tangent

RHO_WATER = RHO_FRESHWATER  # kg/m^3, the eel's water
# Taylor's quadratic law, frozen at the eel's Reynolds numbers (docs/eel.md): C_N the cross-flow
# drag coefficient of a circular cylinder at 1e3 < Re_d < 1e5; C_T the skin-friction coefficient
# on the wetted perimeter (laminar flat plate 1.328 / sqrt(Re_L) at Re_L = U L / nu ~ 6e4)
C_NORMAL = 1.1
C_TANGENTIAL = 0.0055
# form drag on the frontal area pi d^2 / 4 (module docstring), from the drag coefficient of gliding
# fish on their wetted area, 0.0075-0.0091 (Sagong, Jeon & Choi 2013, sailfish and swordfish at
# cruising Reynolds numbers; "comparable to tuna and pike"): their mid-range 0.0083 less C_T,
# times 4 L / d = 66.7 (d = 0.06 L): (0.0083 - 0.0055) x 66.7 = 0.19; the range gives 0.13-0.24
C_FORM = 0.19
# packed layout of `Water.packed()`
W_KN, W_KT, W_LINEAR, W_CN, W_CT, W_RESISTIVE, W_MA, W_TAIL, W_END_SPEED, W_KF = range(10)
END_SPEED = 1e-3  # m/s, the width of the smooth switch between the ends (module docstring)


@dataclass(frozen=True)
class Water:
    """The fluid laws (module docstring): water density rho [kg/m^3], body diameter d [m], Taylor's
    dimensionless C_N, C_T (quadratic law) or the linear coefficients c_n, c_t [N s/m^2] when
    `linear`; `resistive`, `reactive` switch the two forces (`tail`: Lighthill's trailing-edge
    term with the reactive force, at whichever end trails; `end_speed` [m/s] the width of the
    smooth switch between the ends); `form_drag` the leading end's form drag of frontal-area
    coefficient `c_form` (module docstring)."""

    density: float = RHO_WATER
    diameter: float = 0.012
    c_normal: float = C_NORMAL
    c_tangential: float = C_TANGENTIAL
    linear: bool = False
    linear_normal: float = 0.0
    linear_tangential: float = 0.0
    resistive: bool = True
    reactive: bool = True
    tail: bool = True
    end_speed: float = END_SPEED
    form_drag: bool = False
    c_form: float = C_FORM

    def __post_init__(self) -> None:
        check_positive("end_speed", self.end_speed)
        check_positive("density", self.density)
        check_positive("diameter", self.diameter)
        for name in ("c_normal", "c_tangential", "linear_normal", "linear_tangential", "c_form"):
            check_nonnegative(name, getattr(self, name))

    @property
    def added_mass(self) -> float:
        """m_a = rho pi d^2 / 4 [kg/m] (0 with the reactive force off)."""
        return self.density * math.pi * self.diameter**2 / 4.0 if self.reactive else 0.0

    @property
    def k_normal(self) -> float:
        """1/2 rho d C_N [kg/m^2]."""
        return 0.5 * self.density * self.diameter * self.c_normal

    @property
    def k_tangential(self) -> float:
        """1/2 rho pi d C_T [kg/m^2]."""
        return 0.5 * self.density * math.pi * self.diameter * self.c_tangential

    @property
    def k_form(self) -> float:
        """k_f = 1/2 rho C_F pi d^2 / 4 [kg/m] (0 with the form drag off)."""
        if not self.form_drag:
            return 0.0
        return 0.5 * self.density * self.c_form * math.pi * self.diameter**2 / 4.0

    def packed(self) -> np.ndarray:
        """The compiled layout (k_n, k_t, linear, c_n, c_t, resistive, m_a, tail, end_speed,
        k_f)."""
        return np.array(
            [
                self.k_normal,
                self.k_tangential,
                1.0 if self.linear else 0.0,
                self.linear_normal,
                self.linear_tangential,
                1.0 if self.resistive else 0.0,
                self.added_mass,
                1.0 if (self.tail and self.reactive) else 0.0,
                self.end_speed,
                self.k_form,
            ]
        )


@kernel(forceinline=True)
def _law(vel, k, c, linear):
    """g(vel) and g'(vel): k |vel| vel (quadratic) or c vel (linear)."""
    if linear:
        return c * vel, c
    return k * abs(vel) * vel, 2.0 * k * abs(vel)


@kernel(forceinline=True)
def resistive_scalars(v1, v2, psi, law):
    """`resistive_point` as scalars: (f1, f2, df/dv row-major (4), df/dpsi (2))."""
    c, s = math.cos(psi), math.sin(psi)
    vt = c * v1 + s * v2
    vn = -s * v1 + c * v2
    lin = law[W_LINEAR] > 0.0
    gt, dgt = _law(vt, law[W_KT], law[W_CT], lin)
    gn, dgn = _law(vn, law[W_KN], law[W_CN], lin)
    o3 = -(dgt - dgn) * c * s
    at = dgt * vn - gn  # df/dpsi = -(at t + an n)
    an = gt - dgn * vt
    return (-(gt * c - gn * s), -(gt * s + gn * c), -(dgt * c * c + dgn * s * s), o3, o3,
            -(dgt * s * s + dgn * c * c), -(at * c - an * s), -(at * s + an * c))  # fmt: skip


@numba.njit(cache=True, nogil=True)
def resistive_point(v1, v2, psi, law, out):
    """Taylor's line force at a point: out[0:2] = f [N/m], out[2:6] = df/dv (row-major 2x2)
    [N s/m^2], out[6:8] = df/dpsi [N/m] (module docstring)."""
    f = resistive_scalars(v1, v2, psi, law)
    for k in range(8):
        out[k] = f[k]


@numba.njit(cache=True, nogil=True)
def tail_force(v1, v2, psi, m_a, out):
    """Lighthill's force at the tail (module docstring): out[0:2] = F [N], out[2:6] = dF/dv
    (row-major) [N s/m], out[6:8] = dF/dpsi [N]."""
    c, s = math.cos(psi), math.sin(psi)
    u = c * v1 + s * v2
    w = -s * v1 + c * v2
    a = 0.5 * w * w
    out[0] = m_a * (u * w * s + a * c)
    out[1] = m_a * (-u * w * c + a * s)
    # dF/dv = m_a (-w n t^T - u n n^T + w t n^T), t = (c, s), n = (-s, c)
    out[2] = m_a * (w * s * c - u * s * s - w * c * s)
    out[3] = m_a * (w * s * s + u * s * c + w * c * c)
    out[4] = m_a * (-w * c * c + u * c * s - w * s * s)
    out[5] = m_a * (-w * c * s - u * c * c + w * s * c)
    g = m_a * (u * u - a)
    out[6] = -g * s
    out[7] = g * c


@numba.njit(cache=True, nogil=True)
def _gather(d, v, base, de, ve):
    """The element dofs (Eq. 71c order) of d and v from global index 6 e = base into de, ve."""
    for k in range(11):
        de[k] = d[base + LOC[k]]
        ve[k] = v[base + LOC[k]]


@numba.njit(cache=True, nogil=True)
def _gauss_point(de, ve, nz, npsi):
    """Velocity (v1, v2) and frame angle psi at a Gauss point of an element."""
    v1 = nz[0] * ve[0] + nz[1] * ve[1] + nz[2] * ve[2] + nz[3] * ve[3]
    v2 = nz[0] * ve[4] + nz[1] * ve[5] + nz[2] * ve[6] + nz[3] * ve[7]
    psi = npsi[0] * de[8] + npsi[1] * de[9] + npsi[2] * de[10]
    return v1, v2, psi


@numba.njit(cache=True, nogil=True)
def _end_into(d, v, base, sign, law, f, ab, cd, cv, pf):
    """The trailing-edge term at the node whose dofs start at `base` (sign +1: the tail, -1:
    the head), weighted by sigma(sign u) (module docstring), added to f and, with its tangent
    (cd dF/dd + cv dF/dv), to the band ab; pf (8,) is scratch. Returns its power [W]."""
    v1, v2, psi = v[base], v[base + 2], d[base + 4]
    tail_force(v1, v2, psi, law[W_MA], pf)
    c, s = math.cos(psi), math.sin(psi)
    u = c * v1 + s * v2
    x, eps = sign * u, law[W_END_SPEED]
    r = math.sqrt(x * x + eps * eps)
    g = sign * 0.5 * (1.0 + x / r)  # the head's term: the tail's formula, opposite sign
    dg_du = 0.5 * eps * eps / (r * r * r)  # sign * sigma'(x) * dx/du, with dx/du = sign
    f[base] += g * pf[0]
    f[base + 2] += g * pf[1]
    if cd != 0.0 or cv != 0.0:
        du_dv = (c, s)
        du_dpsi = -s * v1 + c * v2
        for ci in range(2):
            fi = dg_du * pf[ci]
            for cj in range(2):
                dfdv = g * pf[2 + 2 * ci + cj] + fi * du_dv[cj]
                ab[HALF_BW + 2 * ci - 2 * cj, base + 2 * cj] += cv * dfdv
            ab[HALF_BW + 2 * ci - 4, base + 4] += cd * (g * pf[6 + ci] + fi * du_dpsi)
    return g * (pf[0] * v1 + pf[1] * v2)


@numba.njit(cache=True, nogil=True)
def _form_into(d, v, base, sign, k_f, eps, f, ab, cd, cv):
    """The form drag at the node whose dofs start at `base` (sign +1: the head, -1: the tail),
    weighted by sigma(sign u) (module docstring), added to f and, with its tangent (cd dF/dd +
    cv dF/dv), to the band ab. Returns its power [W]."""
    v1, v2, psi = v[base], v[base + 2], d[base + 4]
    c, s = math.cos(psi), math.sin(psi)
    u = c * v1 + s * v2
    x = sign * u
    r = math.sqrt(x * x + eps * eps)
    g = 0.5 * (1.0 + x / r)
    h = g * abs(u) * u
    f[base] -= k_f * h * c
    f[base + 2] -= k_f * h * s
    if cd != 0.0 or cv != 0.0:
        dh = 0.5 * eps * eps / (r * r * r) * sign * abs(u) * u + 2.0 * g * abs(u)
        w = -s * v1 + c * v2  # du/dpsi
        t = (c, s)
        nrm = (-s, c)
        for ci in range(2):
            for cj in range(2):
                ab[HALF_BW + 2 * ci - 2 * cj, base + 2 * cj] -= cv * k_f * dh * t[ci] * t[cj]
            ab[HALF_BW + 2 * ci - 4, base + 4] -= cd * k_f * (dh * w * t[ci] + h * nrm[ci])
    return -k_f * h * u


@numba.njit(cache=True, nogil=True)
def tail_into(d, v, law, f, ab, cd, cv):
    """The end forces at (d, v): Lighthill's trailing-edge force (if on) at whichever end
    trails and the form drag (if on) at whichever end leads (module docstring), added to f,
    cd dF/dd + cv dF/dv to the band ab (cd = cv = 0: no tangent). Returns their power [W]."""
    power = 0.0
    head = d.shape[0] - 5  # the last node (n_dof = 6 n_el + 5): its z1, z2, psi at +0, +2, +4
    if law[W_KF] > 0.0:
        eps = law[W_END_SPEED]
        power += _form_into(d, v, head, 1.0, law[W_KF], eps, f, ab, cd, cv)
        power += _form_into(d, v, 0, -1.0, law[W_KF], eps, f, ab, cd, cv)
    if law[W_TAIL] <= 0.0:
        return power
    pf = np.empty(8)
    power += _end_into(d, v, 0, 1.0, law, f, ab, cd, cv, pf)  # node 0: z1, z2, psi = d[0, 2, 4]
    return power + _end_into(d, v, head, -1.0, law, f, ab, cd, cv, pf)


@numba.njit(cache=True, nogil=True)
def assemble_water(d, v, le, nzt, npt, law, f, ab, cd, cv):
    """Add the nodal force of Taylor's resistive law (if on) and the end forces (`tail_into`)
    at configuration d and dof velocities v (n_dof,) to f (n_dof,), and cd dF/dd + cv dF/dv to
    the banded ab (21, n_dof) (cd = cv = 0: no tangent). nzt, npt: `shape_tables(le)`; law:
    `Water.packed()`. Returns the power [W]."""
    power = tail_into(d, v, law, f, ab, cd, cv)
    if law[W_RESISTIVE] != 0.0:
        power += _line_load(0, d, v, le, nzt, npt, law, 0.0, f, ab, cd, cv)
    return power


@kernel(forceinline=True)
def added_scalars(v1, v2, psi, m_a):
    """`added_point` as scalars: (P (2), dP/dv row-major (4), dP/dpsi (2))."""
    c, s = math.cos(psi), math.sin(psi)
    vt = c * v1 + s * v2
    wn = -s * v1 + c * v2
    return (-m_a * wn * s, m_a * wn * c, m_a * s * s, -m_a * s * c, -m_a * s * c, m_a * c * c,
            m_a * (vt * s - wn * c), m_a * (-vt * c - wn * s))  # fmt: skip


@numba.njit(cache=True, nogil=True)
def added_point(v1, v2, psi, m_a, out):
    """The entrained water's momentum at a point: out[0:2] = P = m_a w n [kg/s], out[2:6] =
    dP/dv = m_a n n^T (row-major) [kg/m], out[6:8] = dP/dpsi = m_a (-v_t n - w t)."""
    f = added_scalars(v1, v2, psi, m_a)
    for k in range(8):
        out[k] = f[k]


@numba.njit(cache=True, nogil=True)
def _line_load(kind, d, v, le, nzt, npt, law, m_a, f, ab, cd, cv):
    """f += int N_z^T q dS and ab += cd dF/dd + cv dF/dv (cd = cv = 0: no tangent) of the point
    law q at the 4 Gauss points (Eq. 81b): kind 0 Taylor's force (`resistive_point`, law),
    kind 1 the water's momentum (`added_point`, m_a). Returns int q . v dS."""
    de = np.empty(11)
    ve = np.empty(11)
    pf = np.empty(8)
    acc = 0.0
    for e in range(le.shape[0]):
        base = 6 * e
        _gather(d, v, base, de, ve)
        for g in range(N_GAUSS):
            nz, npsi = nzt[e, g], npt[e, g]
            w = GAUSS_W[g] * le[e]
            v1, v2, psi = _gauss_point(de, ve, nz, npsi)
            if kind == 0:
                resistive_point(v1, v2, psi, law, pf)
            else:
                added_point(v1, v2, psi, m_a, pf)
            acc += w * (pf[0] * v1 + pf[1] * v2)
            for i in range(4):
                f[base + LOC[i]] += w * nz[i] * pf[0]
                f[base + LOC[4 + i]] += w * nz[i] * pf[1]
            if cd != 0.0 or cv != 0.0:
                _add_tangent(ab, base, w, nz, npsi, pf, 0.0, cd, cv)
    return acc


@numba.njit(cache=True, nogil=True)
def added_momentum(d, v, le, nzt, npt, m_a, p, ab, cd, cv):
    """Nodal momentum of the entrained water p = int N_z^T m_a w n dS (n_dof,) (set, not added)
    at (d, v), and cd dp/dd + cv dp/dv added to the banded ab (cd = cv = 0: no tangent).
    Returns the water's kinetic energy int m_a w^2 / 2 dS [J] (P . v = m_a w^2)."""
    for i in range(p.shape[0]):
        p[i] = 0.0
    if m_a == 0.0:
        return 0.0
    return 0.5 * _line_load(1, d, v, le, nzt, npt, p, m_a, p, ab, cd, cv)  # law unused: p


@numba.njit(cache=True, nogil=True)
def point_forces(d, v, le, nzt, npt, law, out):
    """Resistive line force (ignoring the switches) at the Gauss points for drawing: out
    (n_el * 4, 4) rows (x, y, f_x, f_y) [m, N/m]."""
    de = np.empty(11)
    ve = np.empty(11)
    pf = np.empty(8)
    for e in range(le.shape[0]):
        base = 6 * e
        _gather(d, v, base, de, ve)
        for g in range(N_GAUSS):
            nz, npsi = nzt[e, g], npt[e, g]
            v1, v2, psi = _gauss_point(de, ve, nz, npsi)
            resistive_point(v1, v2, psi, law, pf)
            r = 4 * e + g
            out[r, 0] = nz[0] * de[0] + nz[1] * de[1] + nz[2] * de[2] + nz[3] * de[3]
            out[r, 1] = nz[0] * de[4] + nz[1] * de[5] + nz[2] * de[6] + nz[3] * de[7]
            out[r, 2], out[r, 3] = pf[0], pf[1]
