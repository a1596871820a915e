"""Belly friction of a serpentine body lying on the ground plane (Rios 2017 §4.5 II; the law of
Hu, Nirody, Scott & Shelley 2009 and of PyElastica's anisotropic plane; Saito et al. 2002).

The beam lies in the ground plane (x, y); gravity is normal to it, so the normal load per unit
length is p = m_A g (a flat body on flat ground). At a point of the body with heading psi,
tangent t = (cos psi, sin psi), normal n = (-sin psi, cos psi) and velocity v, the line force is

* anisotropic Coulomb ("friction"):  f = -p [mu_t (u . t) t + mu_n (u . n) n],
  mu_t = mu_forward if v . t > 0 else mu_backward, mu_n = mu_lateral, u = v / |v| the unit slip
  (Hu et al. 2009, Eq. 2.3; PyElastica `RodPlaneContactWithAnisotropicFriction` splits its unit
  total slip velocity the same way). Regularised below the slip speed v_eps:
  u = v phi(|v| / v_eps) / |v|, phi(r) = r (2 - r) for r < 1 and 1 beyond, so the law is exact
  Coulomb for |v| >= v_eps and viscous, f = -2 p A v / v_eps, at vanishing slip; phi is C1 at
  r = 1 (g(|v|) = phi / |v| has the derivative -1 / v_eps^2 from both sides).
* viscous ("viscous_ground"): f = -(c_t (v . t) t + c_n (v . n) n), c [N s / m^2] (the
  viscous ground of Saito et al. 2002 and of the resistive-force snakes);
* rigid-body drag of PyElastica's analytical damper (for the side-by-side check only):
  f = -nu_v m_A v, line couple m = -c_w psi_dot.

Writing f = -p g(|v|) A(psi) v with A = mu_t t t^T + mu_n n n^T, the consistent tangent is
    df/dv = -p [g A + g'(|v|) (A v) v^T / |v|],   df/dpsi = -p g (mu_t - mu_n)(n (t.v) + t (n.v))
(mu_t is constant on each side of v . t = 0, where its term (u . t) vanishes, so f is
continuous there). `assemble_ground` integrates these at the 4 Gauss points (Eq. 81b) into the
nodal force and its banded derivatives with respect to the displacement and velocity dofs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs._validate import check_fields, check_positive
from mf_envs.physics.beam.banded import HALF_BW
from mf_envs.physics.beam.element import GAUSS_W, GAUSS_XI, N_GAUSS, _shape_into

LOC = np.array([0, 1, 6, 7, 2, 3, 8, 9, 4, 10, 5])  # element dof -> offset from 6 e (Eq. 71c)


@dataclass(frozen=True)
class BellyFriction:
    """Ground law (module docstring). Coulomb coefficients (dimensionless) forward (+t),
    backward (-t), lateral (n); slip_speed v_eps [m/s]; viscous coefficients [N s/m^2] used when
    `viscous` is True (then the Coulomb part is off); drag nu_v [1/s] and couple c_w [N s]."""

    mu_forward: float = 0.1
    mu_backward: float = 0.15
    mu_lateral: float = 0.2
    slip_speed: float = 1e-4
    viscous: bool = False
    c_tangential: float = 0.0
    c_normal: float = 0.0
    drag_rate: float = 0.0
    couple_damping: float = 0.0

    def __post_init__(self) -> None:
        coefficients = ("mu_forward", "mu_backward", "mu_lateral", "c_tangential", "c_normal")
        check_fields(self, nonnegative=(*coefficients, "drag_rate", "couple_damping"))
        check_positive("slip_speed", self.slip_speed)

    @property
    def active(self) -> bool:
        """False if the law's force is identically zero (every coefficient of it is 0): the
        time loop then skips the ground assembly (an effect that is off costs nothing)."""
        coeffs = (
            (self.c_tangential, self.c_normal)
            if self.viscous
            else (self.mu_forward, self.mu_backward, self.mu_lateral)
        )
        return any(c > 0.0 for c in (*coeffs, self.drag_rate, self.couple_damping))

    def packed(self) -> np.ndarray:
        """The compiled layout (mu_f, mu_b, mu_n, v_eps, viscous, c_t, c_n, nu_v, c_w, active)."""
        return np.array(
            [
                self.mu_forward,
                self.mu_backward,
                self.mu_lateral,
                self.slip_speed,
                1.0 if self.viscous else 0.0,
                self.c_tangential,
                self.c_normal,
                self.drag_rate,
                self.couple_damping,
                1.0 if self.active else 0.0,
            ]
        )


@kernel(forceinline=True)
def slip_factor(speed, v_eps):
    """g = phi(|v| / v_eps) / |v| and dg/d|v| (module docstring)."""
    if speed >= v_eps:
        return 1.0 / speed, -1.0 / (speed * speed)
    return (2.0 - speed / v_eps) / v_eps, -1.0 / (v_eps * v_eps)


@kernel(forceinline=True)
def ground_point(v1, v2, psi, p, law):
    """`point_force` as scalars: (f1, f2, df/dv row-major (4), df/dpsi (2))."""
    c, s = np.cos(psi), np.sin(psi)
    vt = c * v1 + s * v2
    vn = -s * v1 + c * v2
    if law[4] > 0.0:
        mt, mn, gain, dg = law[5], law[6], 1.0, 0.0
    else:
        mt = law[0] if vt > 0.0 else law[1]
        mn = law[2]
        speed = np.sqrt(v1 * v1 + v2 * v2)
        gain, dg = slip_factor(speed, law[3])
        gain *= p
        dg = dg * p / speed if speed > 0.0 else 0.0
    # A v and A
    av1 = mt * vt * c - mn * vn * s
    av2 = mt * vt * s + mn * vn * c
    a11 = mt * c * c + mn * s * s
    a12 = (mt - mn) * c * s
    a22 = mt * s * s + mn * c * c
    return (
        -gain * av1, -gain * av2,
        -(gain * a11 + dg * av1 * v1), -(gain * a12 + dg * av1 * v2),
        -(gain * a12 + dg * av2 * v1), -(gain * a22 + dg * av2 * v2),
        -gain * (mt - mn) * (-s * vt + c * vn), -gain * (mt - mn) * (c * vt + s * vn),
    )  # fmt: skip


@numba.njit(cache=True)
def point_force(v1, v2, psi, p, law, out):
    """Line force of the ground at a point: out[0:2] = f [N/m], out[2:6] = df/dv (row-major
    2x2) [N s/m^2], out[6:8] = df/dpsi [N/m]; p = normal load per length [N/m]."""
    f = ground_point(v1, v2, psi, p, law)
    for k in range(8):
        out[k] = f[k]


@numba.njit(cache=True)
def assemble_ground(d, v, le, p, m_a, law, f, ab, cd, cv):
    """Add the nodal force of the ground (module docstring) at configuration d and dof
    velocities v to f (n_dof,), and cd dF/dd + cv dF/dv to the banded ab (21, n_dof) (pass
    cd = cv = 0 for no tangent). p: normal load per length [N/m]; m_a: mass per length [kg/m]
    (for the drag); law: `BellyFriction.packed()`. Returns the power of the force [W]."""
    ne = le.shape[0]
    de = np.empty(11)
    ve = np.empty(11)
    pf = np.empty(8)
    nz, dnz, npsi, dnpsi = np.empty(4), np.empty(4), np.empty(3), np.empty(3)
    nu_v, c_w = law[7], law[8]
    power = 0.0
    for e in range(ne):
        base = 6 * e
        for k in range(11):
            de[k] = d[base + LOC[k]]
            ve[k] = v[base + LOC[k]]
        for g in range(N_GAUSS):
            _shape_into(GAUSS_XI[g], le[e], nz, dnz, npsi, dnpsi)
            w = GAUSS_W[g] * le[e]
            v1 = nz[0] * ve[0] + nz[1] * ve[1] + nz[2] * ve[2] + nz[3] * ve[3]
            v2 = nz[0] * ve[4] + nz[1] * ve[5] + nz[2] * ve[6] + nz[3] * ve[7]
            psi = npsi[0] * de[8] + npsi[1] * de[9] + npsi[2] * de[10]
            w3 = npsi[0] * ve[8] + npsi[1] * ve[9] + npsi[2] * ve[10]
            point_force(v1, v2, psi, p, law, pf)
            pf[0] -= nu_v * m_a * v1
            pf[1] -= nu_v * m_a * v2
            pf[2] -= nu_v * m_a
            pf[5] -= nu_v * m_a
            mc = -c_w * w3
            power += w * (pf[0] * v1 + pf[1] * v2 + mc * w3)
            for i in range(4):
                f[base + LOC[i]] += w * nz[i] * pf[0]
                f[base + LOC[4 + i]] += w * nz[i] * pf[1]
            for i in range(3):
                f[base + LOC[8 + i]] += w * npsi[i] * mc
            if cd == 0.0 and cv == 0.0:
                continue
            _add_tangent(ab, base, w, nz, npsi, pf, c_w, cd, cv)
    return power


@numba.njit(cache=True)
def _add_tangent(ab, base, w, nz, npsi, pf, c_w, cd, cv):
    """ab += cd dF/dd + cv dF/dv of one Gauss point (weight w)."""
    for ci in range(2):
        for i in range(4):
            gi = base + LOC[4 * ci + i]
            for cj in range(2):
                c = cv * w * nz[i] * pf[2 + 2 * ci + cj]
                for j in range(4):
                    gj = base + LOC[4 * cj + j]
                    ab[HALF_BW + gi - gj, gj] += c * nz[j]
            c = cd * w * nz[i] * pf[6 + ci]
            for j in range(3):
                gj = base + LOC[8 + j]
                ab[HALF_BW + gi - gj, gj] += c * npsi[j]
    for i in range(3):
        gi = base + LOC[8 + i]
        for j in range(3):
            gj = base + LOC[8 + j]
            ab[HALF_BW + gi - gj, gj] -= cv * w * c_w * npsi[i] * npsi[j]
