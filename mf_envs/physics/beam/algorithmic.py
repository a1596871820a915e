"""Algorithmic internal force of the energy-momentum scheme (Simo & Tarnow 1992, planar beam).

Between two configurations a = d_n and b = d_{n+1} the strains of every quadrature point change
by an exact discrete derivative (a discrete gradient at the strain level):

    gamma_b - gamma_a = Rbar^T (z'_b - z'_a) + G^T zbar' (psi_b - psi_a),
    Rbar = (R_a + R_b) / 2,  zbar' = (z'_a + z'_b) / 2,
    G = (R_b - R_a) / (psi_b - psi_a) = sinc((psi_b - psi_a) / 2) R'((psi_a + psi_b) / 2),

(kappa = psi' is linear in the dofs), i.e. eps_b - eps_a = Bbar (b - a) exactly. With the
stresses taken at the theta-point of the strains, sigma = D (theta eps_b + (1 - theta) eps_a
- eps#), the algorithmic force Pbar = int Bbar^T sigma dS does the work

    Pbar . (b - a) = W(b) - W(a) + (theta - 1/2) int (eps_b - eps_a)^T D (eps_b - eps_a) dS,

so theta = 1/2 conserves the stored energy exactly and theta > 1/2 dissipates (the generalized
energy-momentum method of Kuhl & Ramm 1999 takes theta = 1 - alpha_f). Pbar is symmetric in
(a, b) and Pbar(d, d) = P(d) (a second formulation of element.assemble_internal, tested).
A strain `shift` subtracted in the stresses carries the second-difference dissipation of the
"energy_momentum" scheme for rho_inf < 1 (dynamics.py).

The tangent is the exact derivative dPbar/db (not symmetric): the material part
Bbar^T D theta B(b) and the derivative of Bbar at fixed sigma (Rbar and G through psi_b, zbar'
through z'_b). Hand-written numba (as element.py) because it runs at every Newton iteration.
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.frames.kernels import rodrigues_coeffs
from mf_envs.physics.beam.element import HALF_BW, LOC, N_BAND, N_GAUSS, _shape_into


@numba.njit(cache=True)
def _sinc_half(delta):
    """sigma(x) = sin x / x and sigma'(x) = (cos x - sigma) / x at x = delta / 2 (series near 0).

    sigma is the Rodrigues coefficient a(x) of `mf_envs.frames.kernels.rodrigues_coeffs` (the
    planar rotation is its SO(2) restriction); only the derivative is formed here."""
    x = 0.5 * delta
    if abs(x) < 1e-3:
        x2 = x * x
        return 1.0 - x2 / 6.0 + x2 * x2 / 120.0, -x / 3.0 + x * x2 / 30.0
    sig = rodrigues_coeffs(x * x)[0]
    return sig, (np.cos(x) - sig) / x


@numba.njit(cache=True)
def _bbar(dnz, npsi, dnpsi, za, zb, pa, pb):
    """Rows (3, 11) of Bbar, B(b), and the derivatives of the psi entries of Bbar
    (dh (2, 3): d h_r / d(z1'_b, z2'_b, psi_b))."""
    bb, bt, dh = np.empty((3, 11)), np.empty((3, 11)), np.empty((2, 3))
    _, _, cb, sb = _bbar_into(dnz, npsi, dnpsi, za[0], za[1], zb[0], zb[1], pa, pb, bb, bt, dh)
    return bb, bt, dh, cb, sb


@numba.njit(cache=True)
def _bbar_into(dnz, npsi, dnpsi, za1, za2, zb1, zb2, pa, pb, bb, bt, dh):
    """`_bbar` into caller arrays bb, bt (3, 11), dh (2, 3) (no allocation); returns cos, sin
    of psi_a and of psi_b. za = (za1, za2), zb = (zb1, zb2): z' at a and b."""
    ca, sa, cb, sb = np.cos(pa), np.sin(pa), np.cos(pb), np.sin(pb)
    cbar, sbar = 0.5 * (ca + cb), 0.5 * (sa + sb)
    pm = 0.5 * (pa + pb)
    cm, sm = np.cos(pm), np.sin(pm)
    sig, dsig = _sinc_half(pb - pa)
    z1m, z2m = 0.5 * (za1 + zb1), 0.5 * (za2 + zb2)
    u1, u2 = -sm * z1m + cm * z2m, -cm * z1m - sm * z2m  # R'(pm)^T zbar'
    g1b, g2b = cb * zb1 + sb * zb2, -sb * zb1 + cb * zb2
    for k in range(8):
        bb[2, k] = 0.0
        bt[2, k] = 0.0
    for k in range(4):
        bb[0, k], bb[0, 4 + k] = cbar * dnz[k], sbar * dnz[k]
        bb[1, k], bb[1, 4 + k] = -sbar * dnz[k], cbar * dnz[k]
        bt[0, k], bt[0, 4 + k] = cb * dnz[k], sb * dnz[k]
        bt[1, k], bt[1, 4 + k] = -sb * dnz[k], cb * dnz[k]
    for k in range(3):
        bb[0, 8 + k], bb[1, 8 + k] = sig * u1 * npsi[k], sig * u2 * npsi[k]
        bt[0, 8 + k], bt[1, 8 + k] = g2b * npsi[k], -g1b * npsi[k]
        bb[2, 8 + k] = dnpsi[k]
        bt[2, 8 + k] = dnpsi[k]
    dh[0, 0], dh[0, 1] = -0.5 * sig * sm, 0.5 * sig * cm
    dh[1, 0], dh[1, 1] = -0.5 * sig * cm, -0.5 * sig * sm
    dh[0, 2] = 0.5 * dsig * u1 - 0.5 * sig * (cm * z1m + sm * z2m)
    dh[1, 2] = 0.5 * dsig * u2 - 0.5 * sig * (-sm * z1m + cm * z2m)
    return ca, sa, cb, sb


@numba.njit(cache=True)
def _geo(ke, w, n1, n2, dnz, npsi, dh, cb, sb, geo):
    """Add w * d(Bbar^T sigma)/db at fixed sigma (times geo) to the element matrix ke."""
    for k in range(4):
        # z rows: Rbar depends on psi_b
        r1 = 0.5 * (n1 * -sb + n2 * -cb) * dnz[k]
        r2 = 0.5 * (n1 * cb + n2 * -sb) * dnz[k]
        for m in range(3):
            ke[k, 8 + m] += geo * w * r1 * npsi[m]
            ke[4 + k, 8 + m] += geo * w * r2 * npsi[m]
    for m in range(3):  # psi rows: h depends on z'_b and psi_b
        for k in range(4):
            ke[8 + m, k] += geo * w * npsi[m] * (n1 * dh[0, 0] + n2 * dh[1, 0]) * dnz[k]
            ke[8 + m, 4 + k] += geo * w * npsi[m] * (n1 * dh[0, 1] + n2 * dh[1, 1]) * dnz[k]
        for j in range(3):
            ke[8 + m, 8 + j] += geo * w * npsi[m] * (n1 * dh[0, 2] + n2 * dh[1, 2]) * npsi[j]


@numba.njit(cache=True)
def assemble_algorithmic(da, db, le, ksh_a, ksh_b, qxi, qw, stiff, theta, shift, tangent, geo):
    """Pbar(a, b) (n_dof,), banded dPbar/db (21, n_dof) and the elastic strain increments
    e(b) - e(a) (n_el, nq, 3) at the quadrature points (module docstring).

    da, db: (n_dof,) dofs at t_n and t_{n+1}; ksh_a, ksh_b: kappa# (n_el, 4) [1/m] there;
    qxi, qw, stiff: the element quadrature (element.quadrature); theta: stress point in [0, 1];
    shift: (n_el, nq, 3) strains subtracted in the stresses, sigma = D (e_theta - shift);
    geo: factor on the geometric part (2 with a = b, theta = 1 gives the static tangent).
    """
    nd = da.shape[0]
    p = np.empty(nd)
    ab = np.zeros((N_BAND, nd))
    de = np.empty((le.shape[0], qxi.shape[0], 3))
    assemble_algorithmic_into(
        da, db, le, ksh_a, ksh_b, (qxi, qw, stiff), theta, shift, tangent, geo, p, ab, de,
        algorithmic_scratch(),
    )  # fmt: skip
    return p, ab, de


@numba.njit(cache=True)
def algorithmic_scratch():
    """Scratch of `assemble_algorithmic_into`: element dofs at a and b, element force and
    matrix, stresses, Bbar, B(b), dh, shape functions (N_z, N_z', N_psi, N_psi')."""
    return (
        np.empty(11), np.empty(11), np.empty(11), np.empty((11, 11)), np.empty(3),
        np.empty((3, 11)), np.empty((3, 11)), np.empty((2, 3)), np.empty(4), np.empty(4),
        np.empty(3), np.empty(3),
    )  # fmt: skip


@numba.njit(cache=True)
def assemble_algorithmic_into(
    da, db, le, ksh_a, ksh_b, quad, theta, shift, tangent, geo, p, ab, de, scr
):
    """`assemble_algorithmic` into p (n_dof,), ab (21, n_dof) (overwritten; ab untouched
    without tangent) and de (n_el, >= nq, 3), with the scratch `algorithmic_scratch()`: no
    allocation, the same arithmetic (hence the same bits); quad = (qxi, qw, stiff)."""
    qxi, qw, stiff = quad
    ne, nq = le.shape[0], qxi.shape[0]
    nd = da.shape[0]
    dea, deb, fe, ke, sig, bb, bt, dh, nz, dnz, npsi, dnpsi = scr
    for i in range(nd):
        p[i] = 0.0
    if tangent:
        for k in range(N_BAND):
            for i in range(nd):
                ab[k, i] = 0.0
    for e in range(ne):
        for k in range(11):
            dea[k], deb[k] = da[6 * e + LOC[k]], db[6 * e + LOC[k]]
        fe[:] = 0.0
        ke[:, :] = 0.0
        for g in range(nq):
            _shape_into(qxi[g], le[e], nz, dnz, npsi, dnpsi)
            a1 = dnz[0] * dea[0] + dnz[1] * dea[1] + dnz[2] * dea[2] + dnz[3] * dea[3]
            a2 = dnz[0] * dea[4] + dnz[1] * dea[5] + dnz[2] * dea[6] + dnz[3] * dea[7]
            pa = npsi[0] * dea[8] + npsi[1] * dea[9] + npsi[2] * dea[10]
            ka = dnpsi[0] * dea[8] + dnpsi[1] * dea[9] + dnpsi[2] * dea[10]
            b1 = dnz[0] * deb[0] + dnz[1] * deb[1] + dnz[2] * deb[2] + dnz[3] * deb[3]
            b2 = dnz[0] * deb[4] + dnz[1] * deb[5] + dnz[2] * deb[6] + dnz[3] * deb[7]
            pb = npsi[0] * deb[8] + npsi[1] * deb[9] + npsi[2] * deb[10]
            kb = dnpsi[0] * deb[8] + dnpsi[1] * deb[9] + dnpsi[2] * deb[10]
            ca, sa, cb, sb = _bbar_into(dnz, npsi, dnpsi, a1, a2, b1, b2, pa, pb, bb, bt, dh)
            ea0 = ca * a1 + sa * a2 - 1.0
            ea1 = -sa * a1 + ca * a2
            ea2 = ka
            eb0 = cb * b1 + sb * b2 - 1.0
            eb1 = -sb * b1 + cb * b2
            eb2 = kb
            if g < N_GAUSS:
                ea2 -= ksh_a[e, g]
                eb2 -= ksh_b[e, g]
            w = qw[g] * le[e]
            de[e, g, 0] = eb0 - ea0
            de[e, g, 1] = eb1 - ea1
            de[e, g, 2] = eb2 - ea2
            sig[0] = stiff[g, 0] * (theta * eb0 + (1.0 - theta) * ea0 - shift[e, g, 0])
            sig[1] = stiff[g, 1] * (theta * eb1 + (1.0 - theta) * ea1 - shift[e, g, 1])
            sig[2] = stiff[g, 2] * (theta * eb2 + (1.0 - theta) * ea2 - shift[e, g, 2])
            for i in range(11):
                fe[i] += w * (bb[0, i] * sig[0] + bb[1, i] * sig[1] + bb[2, i] * sig[2])
            if tangent:
                # the material part sum_r Bbar_ri D_r B_rj; the bending row r = 2 of Bbar and B
                # is exactly zero outside the psi dofs (8..10), where its term is skipped (an
                # exact zero added: the same bits)
                s0, s1, s2 = stiff[g, 0], stiff[g, 1], stiff[g, 2]
                for i in range(11):
                    for j in range(11):
                        kij = 0.0
                        kij += bb[0, i] * s0 * bt[0, j]
                        kij += bb[1, i] * s1 * bt[1, j]
                        if i >= 8 and j >= 8:
                            kij += bb[2, i] * s2 * bt[2, j]
                        ke[i, j] += w * theta * kij
                _geo(ke, w, sig[0], sig[1], dnz, npsi, dh, cb, sb, geo)
        for i in range(11):
            gi = 6 * e + LOC[i]
            p[gi] += fe[i]
            if tangent:
                for j in range(11):
                    ab[HALF_BW + gi - 6 * e - LOC[j], 6 * e + LOC[j]] += ke[i, j]
