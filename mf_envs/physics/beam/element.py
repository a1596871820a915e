"""The active three-node C1 beam element of Rios 2017, ch. 4 §4.7-4.8 (Eqs. 68-83, 104-106).

::

      node 1 (5 dofs)            mid node 3 (psi only)          node 2 (5 dofs)
      z1 z1' z2 z2' psi  o-------------------o-------------------o  z1 z1' z2 z2' psi
                         S = 0          S = L0/2            S = L0

* z_C(S) = (z1, z2): cubic Hermite in S with nodal values and nodal S-derivatives (Eq. 69), so the
  discretised curve of centroids is C1 across elements;
* psi(S): quadratic through the two end nodes and the mid node (Eq. 70);
* strains (Eq. 74, 75): gamma = R(psi)^T z_C' (gamma_1 - 1 axial, gamma_2 shear), kappa = psi';
* active constitutive law (Eqs. 51, 53): N1 = EA (gamma_1 - 1), N2 = GA_s gamma_2,
  M3 = EI (kappa - kappa#);
* internal force P = int B_T^T (N1, N2, M3) dS (Eqs. 78b, 80b), 4-point Gauss;
* consistent tangent K = int B_T^T D B_T dS + K_geo, where K_geo is the derivative of B_T at fixed
  stresses (derived below; B_T depends on psi and on gamma through its third column).

Element dof order (the seed's Eq. 71c): (z1^1, z1'^1, z1^2, z1'^2, z2^1, z2'^1, z2^2, z2'^2,
psi^1, psi^2, psi^3). Global layout: node j owns dofs 6j..6j+4 = (z1, z1', z2, z2', psi) and
element e's mid node owns dof 6e+5; n_dof = 6 n_el + 5 and the matrices are banded with
half-bandwidth 10. Banded storage follows scipy.linalg.solve_banded: ab[10 + i - j, j] = K[i, j].

Two elements share these kinematics and differ only in the quadrature (`quadrature`):

* "seed": everything by 4-point Gauss, as in the seed. Hermite z_C' is quadratic, while a bent
  inextensible, unsheared beam needs z_C' = (cos psi, sin psi): the axial and shear strains
  cannot vanish together with a curvature, the penalty EA, GA_s >> EI / L^2 then stiffens
  bending (membrane/shear locking: error ~ EA L^2 / EI at a fixed mesh).
* "sri" (default): selective reduced integration. Bending stays on 4-point Gauss; the axial and
  shear terms go to the 2-point rule, which only asks the strains to vanish at two points per
  element: 4 conditions on the element's 4 position/slope pairs, so a bent, unstretched,
  unsheared shape is representable (a circle under an end moment comes out exact to round-off
  at any EA) and the error no longer grows with slenderness. Why this choice: it keeps the
  dof layout, the C1 interpolation, the mass matrix, the banded solver and the consistent
  tangent (it is still the exact second derivative of a quadrature of the same energy), where
  a mixed or strain-based element would change all of them. The 2-point rule alone leaves one
  zero-energy mode per displacement component (every nodal slope z_C' offset alike: a pure
  Legendre-P2 strain, zero at both points), so a small share k = min(EA, SRI_STAB EI / l_e^2)
  of the axial and shear rigidity stays on the full rule. That stabilisation places the
  spurious pair at ~ 1.8 n_el^2 sqrt(SRI_STAB) times the first bending frequency (41x with 10
  elements) and costs an O(SRI_STAB h^2) error on the circle (4e-5 rad with 10 elements).

Geometric stiffness (derivation). With c = cos psi, s = sin psi, Nz' the Hermite derivatives and
Np the psi shape functions, the virtual strains are
    d gamma_1 = c dz1' + s dz2' + gamma_2 dpsi,   d gamma_2 = -s dz1' + c dz2' - gamma_1 dpsi.
Differentiating once more (stresses held fixed):
    D(d gamma_1) = (-s dz1' + c dz2') Dpsi + (-s Dz1' + c Dz2') dpsi - gamma_1 dpsi Dpsi,
    D(d gamma_2) = -(c dz1' + s dz2') Dpsi - (c Dz1' + s Dz2') dpsi - gamma_2 dpsi Dpsi,
so with a = (-s Nz', c Nz', 0), b = (c Nz', s Nz', 0), p = (0, 0, Np):
    K_geo = N1 (a p^T + p a^T - gamma_1 p p^T) - N2 (b p^T + p b^T + gamma_2 p p^T).
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs._jit import kernel
from mf_envs.physics.beam.banded import HALF_BW, N_BAND  # noqa: F401  (the band layout)

N_GAUSS = 4

# 4-point Gauss-Legendre on [0, 1]
_XI, _W = np.polynomial.legendre.leggauss(N_GAUSS)
GAUSS_XI = 0.5 * (_XI + 1.0)
GAUSS_W = 0.5 * _W


ELEMENTS = ("seed", "sri")
_XI2, _W2 = np.polynomial.legendre.leggauss(2)
GAUSS2_XI = 0.5 * (_XI2 + 1.0)
GAUSS2_W = 0.5 * _W2
# "sri": share of the axial/shear rigidity kept on the full rule, as a fraction of EI / l_e^2
SRI_STAB = 0.05


def quadrature(
    element: str, le: float, EA: float, GAs: float, EI: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Quadrature of an element of length le [m]: points xi (nq,), weights (nq,) on [0, 1] and
    the rigidities (nq, 3) = (EA [N], GA_s [N], EI [N m^2]) integrated at each point.

    "seed": every term by 4-point Gauss (the seed's element, Eq. 80b); it locks in membrane and
    shear as EA L^2 / EI grows. "sri": bending by 4-point Gauss; of the axial and shear
    rigidities only a stabilising part k = min(EA, SRI_STAB EI / le^2) (resp. GA_s) by 4 points,
    the rest by the 2-point rule (see the module docstring).
    """
    if element not in ELEMENTS:
        raise ValueError(f"element: must be one of {ELEMENTS}, got {element!r}")
    xi, w = GAUSS_XI.copy(), GAUSS_W.copy()
    stiff = np.tile([EA, GAs, EI], (N_GAUSS, 1)).astype(float)
    if element == "seed":
        return xi, w, stiff
    k_stab = SRI_STAB * EI / le**2
    ka, ks = min(EA, k_stab), min(GAs, k_stab)
    stiff[:, 0], stiff[:, 1] = ka, ks
    red = np.tile([EA - ka, GAs - ks, 0.0], (2, 1))
    return np.append(xi, GAUSS2_XI), np.append(w, GAUSS2_W), np.vstack([stiff, red])


def n_dof(n_elements: int) -> int:
    """Global number of dofs: 5 per end node, 1 per mid node."""
    return 6 * n_elements + 5


def element_dofs(n_elements: int) -> np.ndarray:
    """(n_el, 11) int: global dof of each element dof in the seed's order (Eq. 71c)."""
    e = 6 * np.arange(n_elements)[:, None]
    local = np.array([0, 1, 6, 7, 2, 3, 8, 9, 4, 10, 5])
    return e + local[None, :]


@numba.njit(cache=True)
def _shape(xi: float, le: float):
    """Hermite values/S-derivatives (4,), psi values/S-derivatives (3,) at xi = S/L0.

    Eqs. 69-70 and 73, 75."""
    nz = np.empty(4)
    dnz = np.empty(4)
    npsi = np.empty(3)
    dnpsi = np.empty(3)
    _shape_into(xi, le, nz, dnz, npsi, dnpsi)
    return nz, dnz, npsi, dnpsi


@kernel(forceinline=True)
def _shape_into(xi, le, nz, dnz, npsi, dnpsi):
    """`_shape` into caller arrays (no allocation in the assembly loops)."""
    nz[0] = 1.0 - 3.0 * xi**2 + 2.0 * xi**3
    nz[1] = le * xi * (xi - 1.0) ** 2
    nz[2] = xi**2 * (3.0 - 2.0 * xi)
    nz[3] = le * xi**2 * (xi - 1.0)
    dnz[0] = (-6.0 * xi + 6.0 * xi**2) / le
    dnz[1] = (xi - 1.0) * (3.0 * xi - 1.0)
    dnz[2] = (6.0 * xi - 6.0 * xi**2) / le
    dnz[3] = xi * (3.0 * xi - 2.0)
    npsi[0] = (2.0 * xi - 1.0) * (xi - 1.0)
    npsi[1] = xi * (2.0 * xi - 1.0)
    npsi[2] = 4.0 * xi * (1.0 - xi)
    dnpsi[0] = (4.0 * xi - 3.0) / le
    dnpsi[1] = (4.0 * xi - 1.0) / le
    dnpsi[2] = (4.0 - 8.0 * xi) / le


def shape_functions(xi: float, le: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Public view of the shape functions: (N_z (4,), N_z' (4,), N_psi (3,), N_psi' (3,))."""
    return _shape(float(xi), float(le))


# one point's shape functions in a row of 16 (`_shape_row`): N_z, N_z', N_psi, N_psi' at
# these offsets (the gaps keep the blocks aligned)
SH_NZ, SH_DNZ, SH_NPSI, SH_DNPSI = 0, 4, 8, 12
SH_LEN = 16
# element dof k sits at global dof 6 e + LOC[k] (Eq. 71c); LOC_INV the other way round
LOC = (0, 1, 6, 7, 2, 3, 8, 9, 4, 10, 5)
LOC_INV = (0, 1, 4, 5, 8, 10, 2, 3, 6, 7, 9)


@kernel(forceinline=True)
def _shape_row(xi, le, sh):
    """`_shape` into a row sh (SH_LEN,) at the SH_* offsets (no allocation)."""
    _shape_into(
        xi, le, sh[SH_NZ : SH_NZ + 4], sh[SH_DNZ : SH_DNZ + 4], sh[SH_NPSI : SH_NPSI + 3],
        sh[SH_DNPSI : SH_DNPSI + 3],
    )  # fmt: skip


@kernel(forceinline=True)
def _shape_table(xis, le, shp, le_tab):
    """Rows of shape functions (`_shape_row`) at the local points xis (n,) into shp (n, SH_LEN)
    for an element of length le, unless the table already holds them (le == le_tab: they
    depend on the element only through its length; the values, hence the bits, are those of
    `_shape`). Returns le, the length the table now holds (start with le_tab = nan)."""
    if le != le_tab:
        for q in range(xis.shape[0]):
            _shape_row(xis[q], le, shp[q])
    return le


@kernel(forceinline=True)
def _point_strains(de, sh):
    """psi, kappa, cos psi, sin psi, gamma_1, gamma_2 at a point from the 11 element dofs and
    the shape functions there (a `_shape_row`) (Eqs. 74, 75)."""
    z, n, k = SH_DNZ, SH_NPSI, SH_DNPSI
    dz1 = sh[z] * de[0] + sh[z + 1] * de[1] + sh[z + 2] * de[2] + sh[z + 3] * de[3]
    dz2 = sh[z] * de[4] + sh[z + 1] * de[5] + sh[z + 2] * de[6] + sh[z + 3] * de[7]
    psi = sh[n] * de[8] + sh[n + 1] * de[9] + sh[n + 2] * de[10]
    kap = sh[k] * de[8] + sh[k + 1] * de[9] + sh[k + 2] * de[10]
    c = np.cos(psi)
    s = np.sin(psi)
    g1 = c * dz1 + s * dz2
    g2 = -s * dz1 + c * dz2
    return psi, kap, c, s, g1, g2


@kernel(forceinline=True)
def kappa_at(d, base, le, xi):
    """kappa = psi' [1/m] at local xi of the element of length le whose first global dof is
    `base` (the expression of `_point_strains` with the psi shape functions of `_shape`,
    without the rest of the point)."""
    dn0 = (4.0 * xi - 3.0) / le
    dn1 = (4.0 * xi - 1.0) / le
    dn2 = (4.0 - 8.0 * xi) / le
    return dn0 * d[base + 4] + dn1 * d[base + 10] + dn2 * d[base + 5]


@numba.njit(cache=True)
def assemble_internal(d, le, kappa_sharp, qxi, qw, stiff, with_tangent):
    """Internal force P (n_dof,) and banded tangent (21, n_dof) (Eqs. 78b, 80b + K_geo above).

    d: (n_dof,) global dofs [m, -, rad]; le: (n_el,) element lengths [m];
    kappa_sharp: (n_el, 4) actuation curvature kappa# at the 4 Gauss points [1/m];
    qxi, qw, stiff: the element's quadrature (`quadrature`): points (nq,) in [0, 1], weights
    (nq,) and the rigidities (nq, 3) = (EA [N], GA_s [N], EI [N m^2]) carried by each point;
    the first 4 points are the 4-point Gauss rule (kappa# lives there).
    Returns (P, ab, energy): P in N (z dofs) / N m (z', psi dofs), ab = dP/dd banded,
    energy = stored elastic energy [J].
    """
    nd = d.shape[0]
    p = np.empty(nd)
    ab = np.empty((N_BAND, nd))
    energy = assemble_into(d, le, kappa_sharp, qxi, qw, stiff, with_tangent, p, ab)
    return p, ab, energy


@kernel(forceinline=True)
def _element_point(de, sh, w, ea, gas, ei, ksh, fe, ke, with_tangent, u, v):
    """Add one quadrature point's force and tangent to the element's fe (11,), ke (11, 11)
    (upper triangle), exploiting the structure of B_T: with u = (c Nz', s Nz') and
    v = (-s Nz', c Nz') on the 8 z dofs and Np, Np' on the 3 psi dofs,
        B_T rows = (u, g2 Np), (v, -g1 Np), (0, Np'),  a = (v, 0),  b = (u, 0),  p = (0, Np),
    so K = ea B1 B1^T + gas B2 B2^T + ei B3 B3^T + K_geo reduces to the blocks
        zz: ea u u^T + gas v v^T = [[A, B], [B, C]] (x) Nz' Nz'^T, A = ea c^2 + gas s^2,
            B = (ea - gas) c s, C = ea s^2 + gas c^2,
        z-psi: (alpha u + beta v) Np^T,  alpha = ea g2 - N2,  beta = N1 - gas g1,
        psi-psi: (ea g2^2 + gas g1^2 - N1 g1 - N2 g2) Np Np^T + ei Np' Np'^T.
    sh: the point's shape functions (`_shape_row`); u, v (8,) scratch. Returns the point's
    stored energy [J]."""
    psi, kap, c, s, g1, g2 = _point_strains(de, sh)
    n1 = ea * (g1 - 1.0)
    n2 = gas * g2
    m3 = ei * (kap - ksh)
    for k in range(4):
        dk = sh[SH_DNZ + k]
        u[k] = c * dk
        u[4 + k] = s * dk
        v[k] = -s * dk
        v[4 + k] = c * dk
    for i in range(8):
        fe[i] += w * (u[i] * n1 + v[i] * n2)
    for k in range(3):
        fe[8 + k] += w * (sh[SH_NPSI + k] * (g2 * n1 - g1 * n2) + sh[SH_DNPSI + k] * m3)
    if with_tangent:
        wea, wgas = w * ea, w * gas
        # zz = wea u u^T + wgas v v^T = [[A, B], [B, C]] (x) Nz' Nz'^T
        a_, b_, c_ = wea * c * c + wgas * s * s, (wea - wgas) * c * s, wea * s * s + wgas * c * c
        for i in range(4):
            di = sh[SH_DNZ + i]
            for j in range(4):
                dd = di * sh[SH_DNZ + j]
                ke[i, 4 + j] += b_ * dd
                if j >= i:
                    ke[i, j] += a_ * dd
                    ke[4 + i, 4 + j] += c_ * dd
        alpha = w * (ea * g2 - n2)
        beta = w * (n1 - gas * g1)
        for i in range(8):
            zi = alpha * u[i] + beta * v[i]
            for k in range(3):
                ke[i, 8 + k] += zi * sh[SH_NPSI + k]
        gpp = w * (ea * g2 * g2 + gas * g1 * g1 - n1 * g1 - n2 * g2)
        wei = w * ei
        for i in range(3):
            npi, dpi = sh[SH_NPSI + i], sh[SH_DNPSI + i]
            for j in range(i, 3):
                ke[8 + i, 8 + j] += gpp * npi * sh[SH_NPSI + j] + wei * dpi * sh[SH_DNPSI + j]
    return 0.5 * w * (n1 * (g1 - 1.0) + n2 * g2 + m3 * (kap - ksh))


@kernel(forceinline=True)
def _element(d, e, le_e, kappa_sharp, qw, stiff, shp, de, fe, ke, uv, with_tangent, energy):
    """Element e's force into fe (11,) and, with_tangent, its upper-triangle tangent into ke
    (11, 11), its dofs into de (11,); shp: the shape table of its quadrature at its length.
    Returns energy plus the element's stored energy, point by point [J]."""
    base = 6 * e
    for k in range(11):
        de[k] = d[base + LOC[k]]
    fe[:] = 0.0
    if with_tangent:
        ke[:, :] = 0.0
    for g in range(qw.shape[0]):
        ksh = kappa_sharp[e, g] if g < N_GAUSS else 0.0
        w = qw[g] * le_e
        energy += _element_point(
            de, shp[g], w, stiff[g, 0], stiff[g, 1], stiff[g, 2], ksh, fe, ke, with_tangent,
            uv[0], uv[1],
        )  # fmt: skip
    return energy


@numba.njit(cache=True)
def assemble_into(d, le, kappa_sharp, qxi, qw, stiff, with_tangent, p, ab):
    """`assemble_internal` into caller arrays p (n_dof,) and ab (21, n_dof) (overwritten; ab
    untouched without the tangent); returns the stored energy [J]. Allocation-light: the
    Newton loops of the quasi-static solver call it every iteration."""
    ne = le.shape[0]
    p[:] = 0.0
    if with_tangent:
        ab[:, :] = 0.0
    energy = 0.0
    de, fe = np.empty(11), np.empty(11)
    ke = np.empty((11, 11))
    uv = np.empty((2, 8))
    shp = np.empty((qxi.shape[0], SH_LEN))
    le_tab = np.nan
    for e in range(ne):
        le_tab = _shape_table(qxi, le[e], shp, le_tab)
        energy = _element(d, e, le[e], kappa_sharp, qw, stiff, shp, de, fe, ke, uv,
                          with_tangent, energy)  # fmt: skip
        base = 6 * e
        for i in range(11):
            p[base + LOC[i]] += fe[i]
        if with_tangent:
            for i in range(11):
                gi = base + LOC[i]
                for j in range(i, 11):
                    gj = base + LOC[j]
                    ab[HALF_BW + gi - gj, gj] += ke[i, j]
                    if j != i:
                        ab[HALF_BW + gj - gi, gi] += ke[i, j]
    return energy


@numba.njit(cache=True)
def forces_at_into(d, le, kappa_sharp, qxi, qw, stiff, dofs, out):
    """The internal force P at the global dofs `dofs` (k ints: an array or a tuple) into out
    (k,): the bits of `assemble_into`'s P there (the same element contributions added in the
    same order), but only the elements holding those dofs are evaluated (e.g. the two end
    elements for the ground reactions at the feet)."""
    out[:] = 0.0
    de, fe = np.empty(11), np.empty(11)
    ke = np.empty((11, 11))
    uv = np.empty((2, 8))
    shp = np.empty((qxi.shape[0], SH_LEN))
    le_tab = np.nan
    for e in range(le.shape[0]):
        base = 6 * e
        hit = False
        for m in range(len(dofs)):
            hit = hit or base <= dofs[m] <= base + 10
        if not hit:
            continue
        le_tab = _shape_table(qxi, le[e], shp, le_tab)
        _element(d, e, le[e], kappa_sharp, qw, stiff, shp, de, fe, ke, uv, False, 0.0)
        for m in range(len(dofs)):
            off = dofs[m] - base
            if 0 <= off <= 10:
                out[m] += fe[LOC_INV[off]]


@numba.njit(cache=True)
def actuation_load_into(le, qxi, qw, stiff, dk, out):
    """dP/dkappa# . dk into out (n_dof,): the change of the internal force per unit change of
    the actuation curvature along dk (n_el, 4) [1/m] at the Gauss points. kappa# enters P only
    through M3 = EI (kappa - kappa#) on the psi dofs, so P is affine in kappa# and this does
    not depend on the configuration: -int EI Np'^T dk dS (the bending row of Eq. 80b)."""
    out[:] = 0.0
    shp = np.empty((qxi.shape[0], SH_LEN))
    le_tab = np.nan
    for e in range(le.shape[0]):
        le_tab = _shape_table(qxi, le[e], shp, le_tab)
        base = 6 * e
        for g in range(N_GAUSS):
            m = -qw[g] * le[e] * stiff[g, 2] * dk[e, g]
            for k in range(3):
                out[base + LOC[8 + k]] += m * shp[g, SH_DNPSI + k]
