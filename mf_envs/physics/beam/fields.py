"""Mass, distributed loads, ground stiffness and field evaluation of the C1 beam element
(`beam.element`: the element, its dof layout and shape functions; Eqs. 68-83 of ch. 4).

- `assemble_mass`: the consistent mass matrix (banded), translational and rotary inertia;
- `assemble_distributed`: the load vector of a distributed force and moment given at the Gauss
  points (Eq. 40's n_hat, m_hat);
- `assemble_line_stiffness`: the banded stiffness of a distributed spring on z_C (ground contact);
- `evaluate_fields`, `centerline_into`: positions, angle, curvature and strains at given points.
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.physics.beam.banded import HALF_BW, N_BAND
from mf_envs.physics.beam.element import (
    GAUSS_W,
    GAUSS_XI,
    LOC,
    N_GAUSS,
    SH_LEN,
    _point_strains,
    _shape,
    _shape_table,
)


@numba.njit(cache=True)
def assemble_mass(le, m_a, j3):
    """Consistent mass matrix, banded (21, n_dof) (Eqs. 83, 104-106), by 4-point Gauss (exact).

    m_a: mass per reference length [kg/m]; j3: rotary inertia per length J_3C [kg m].
    """
    ne = le.shape[0]
    nd = 6 * ne + 5
    ab = np.zeros((N_BAND, nd))
    for e in range(ne):
        base = 6 * e
        me = np.zeros((11, 11))
        for g in range(N_GAUSS):
            nz, dnz, npsi, dnpsi = _shape(GAUSS_XI[g], le[e])
            w = GAUSS_W[g] * le[e]
            for i in range(4):
                for j in range(4):
                    me[i, j] += w * m_a * nz[i] * nz[j]
                    me[4 + i, 4 + j] += w * m_a * nz[i] * nz[j]
            for i in range(3):
                for j in range(3):
                    me[8 + i, 8 + j] += w * j3 * npsi[i] * npsi[j]
        for i in range(11):
            for j in range(11):
                gi = base + LOC[i]
                gj = base + LOC[j]
                ab[HALF_BW + gi - gj, gj] += me[i, j]
    return ab


@numba.njit(cache=True)
def assemble_distributed(le, n_gp, m_gp):
    """Nodal force of distributed loads (Eq. 81b): n_gp (n_el, 4, 2) inertial-frame line force
    [N/m] and m_gp (n_el, 4) line couple [N m/m] at the Gauss points -> (n_dof,)."""
    ne = le.shape[0]
    nd = 6 * ne + 5
    f = np.zeros(nd)
    for e in range(ne):
        base = 6 * e
        for g in range(N_GAUSS):
            nz, dnz, npsi, dnpsi = _shape(GAUSS_XI[g], le[e])
            w = GAUSS_W[g] * le[e]
            for k in range(4):
                f[base + LOC[k]] += w * nz[k] * n_gp[e, g, 0]
                f[base + LOC[4 + k]] += w * nz[k] * n_gp[e, g, 1]
            for k in range(3):
                f[base + LOC[8 + k]] += w * npsi[k] * m_gp[e, g]
    return f


@numba.njit(cache=True)
def evaluate_fields(d, le, xis):
    """Position (n_el, n_xi, 2), psi, kappa, gamma_1, gamma_2 (n_el, n_xi) at local xis."""
    ne = le.shape[0]
    nx = xis.shape[0]
    pos = np.empty((ne, nx, 2))
    psi_o = np.empty((ne, nx))
    kap_o = np.empty((ne, nx))
    g1_o = np.empty((ne, nx))
    g2_o = np.empty((ne, nx))
    de = np.empty(11)
    shp = np.empty((nx, SH_LEN))
    le_tab = np.nan
    for e in range(ne):
        le_tab = _shape_table(xis, le[e], shp, le_tab)
        for k in range(11):
            de[k] = d[6 * e + LOC[k]]
        for q in range(nx):
            sh = shp[q]
            psi, kap, c, s, g1, g2 = _point_strains(de, sh)
            pos[e, q, 0] = sh[0] * de[0] + sh[1] * de[1] + sh[2] * de[2] + sh[3] * de[3]  # N_z
            pos[e, q, 1] = sh[0] * de[4] + sh[1] * de[5] + sh[2] * de[6] + sh[3] * de[7]
            psi_o[e, q] = psi
            kap_o[e, q] = kap
            g1_o[e, q] = g1
            g2_o[e, q] = g2
    return pos, psi_o, kap_o, g1_o, g2_o


@numba.njit(cache=True)
def assemble_line_stiffness(le, dn_gp):
    """Banded (21, n_dof) derivative of the nodal force of configuration-dependent line loads:
    dn_gp (n_el, 4, 2, 2) = d n_i / d z_j [N/m^2] at the Gauss points (n acting at z_C), i.e.
    dF/dd = int N_z^T (dn/dz) N_z dS (Eq. 81b differentiated)."""
    ne = le.shape[0]
    nd = 6 * ne + 5
    ab = np.zeros((N_BAND, nd))
    for e in range(ne):
        base = 6 * e
        for g in range(N_GAUSS):
            nz, dnz, npsi, dnpsi = _shape(GAUSS_XI[g], le[e])
            w = GAUSS_W[g] * le[e]
            for ci in range(2):
                for cj in range(2):
                    c = w * dn_gp[e, g, ci, cj]
                    if c == 0.0:
                        continue
                    for i in range(4):
                        gi = base + LOC[4 * ci + i]
                        for j in range(4):
                            gj = base + LOC[4 * cj + j]
                            ab[HALF_BW + gi - gj, gj] += c * nz[i] * nz[j]
    return ab


@numba.njit(cache=True)
def centerline_into(d, x_origin, le, xis, out):
    """The curve of centroids at the local xis of every element and the last node, x shifted
    by x_origin [m], into out (n_el len(xis) + 1, 2) [m] (`BeamModel.centerline`)."""
    pos = evaluate_fields(d, le, xis)[0]
    ne, nx = pos.shape[0], pos.shape[1]
    for e in range(ne):
        for q in range(nx):
            out[e * nx + q, 0] = pos[e, q, 0] + x_origin
            out[e * nx + q, 1] = pos[e, q, 1]
    last = evaluate_fields(d[d.shape[0] - 11 :], le[ne - 1 :], np.ones(1))[0]
    out[ne * nx, 0] = last[0, 0, 0] + x_origin
    out[ne * nx, 1] = last[0, 0, 1]
