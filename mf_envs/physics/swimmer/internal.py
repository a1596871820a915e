"""The beam's algorithmic internal force and its tangent (`physics.beam.algorithmic.
assemble_algorithmic`, Simo & Tarnow 1992) evaluated without allocation: the shape functions
tabulated once per element and quadrature point, the 3 x 11 strain-displacement rows and the
element matrices in caller scratch, and the material tangent Bbar^T D B(b) summed over the
rows that are not structurally zero (the curvature row has psi entries only).

Same arithmetic as `assemble_algorithmic` with shift = 0, tangent on (tests/test_swimmer.py
compares the two to round-off); it exists because that function allocates small arrays at every
quadrature point and dominated the swimmer's Newton iteration (about 80 of 110 microseconds on 6
elements). Its home is `physics/beam` (not edited in issue 34): moving it there is a follow-up.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from mf_envs.physics.beam.algorithmic import _geo, _sinc_half
from mf_envs.physics.beam.banded import HALF_BW
from mf_envs.physics.beam.fused import quadrature_tables  # noqa: F401  (its home was here)
from mf_envs.physics.beam.element import N_GAUSS
from mf_envs.physics.serpentine.friction import LOC


@numba.njit(cache=True, nogil=True)
def make_work():
    """Scratch of `algorithmic_into`: two element dof vectors, fe, ke, bb, bt, dh."""
    return (np.empty(11), np.empty(11), np.empty(11), np.empty((11, 11)), np.zeros((3, 11)),
            np.zeros((3, 11)), np.empty((2, 3)))  # fmt: skip


@numba.njit(cache=True, nogil=True)
def _strains(de, t, off):
    """(z1', z2', psi, kappa) at a quadrature point from the element dofs de and the table row
    t (N_z' at t[0:4], N_psi at t[4:7], N_psi' at t[7:10])."""
    z1 = t[0] * de[0] + t[1] * de[1] + t[2] * de[2] + t[3] * de[3]
    z2 = t[0] * de[4] + t[1] * de[5] + t[2] * de[6] + t[3] * de[7]
    psi = t[4] * de[8] + t[5] * de[9] + t[6] * de[10]
    kap = t[7] * de[8] + t[8] * de[9] + t[9] * de[10]
    return z1, z2, psi, kap - off


@numba.njit(cache=True, nogil=True)
def _rows(t, a1, a2, pa, b1, b2, pb, bb, bt, dh):
    """Bbar, B(b) (3, 11) into bb, bt (zero where they are zero) and dh (2, 3)
    (`beam.algorithmic._bbar`). Returns (cos psi_b, sin psi_b)."""
    ca, sa, cb, sb = math.cos(pa), math.sin(pa), math.cos(pb), math.sin(pb)
    cbar, sbar = 0.5 * (ca + cb), 0.5 * (sa + sb)
    pm = 0.5 * (pa + pb)
    cm, sm = math.cos(pm), math.sin(pm)
    sig, dsig = _sinc_half(pb - pa)
    z1m, z2m = 0.5 * (a1 + b1), 0.5 * (a2 + b2)
    u1, u2 = -sm * z1m + cm * z2m, -cm * z1m - sm * z2m
    g1b, g2b = cb * b1 + sb * b2, -sb * b1 + cb * b2
    for k in range(4):
        dn = t[k]
        bb[0, k], bb[0, 4 + k] = cbar * dn, sbar * dn
        bb[1, k], bb[1, 4 + k] = -sbar * dn, cbar * dn
        bt[0, k], bt[0, 4 + k] = cb * dn, sb * dn
        bt[1, k], bt[1, 4 + k] = -sb * dn, cb * dn
    for k in range(3):
        npk = t[4 + k]
        bb[0, 8 + k], bb[1, 8 + k] = sig * u1 * npk, sig * u2 * npk
        bt[0, 8 + k], bt[1, 8 + k] = g2b * npk, -g1b * npk
        bb[2, 8 + k] = t[7 + k]
        bt[2, 8 + k] = t[7 + k]
    dh[0, 0], dh[0, 1] = -0.5 * sig * sm, 0.5 * sig * cm
    dh[1, 0], dh[1, 1] = -0.5 * sig * cm, -0.5 * sig * sm
    dh[0, 2] = 0.5 * dsig * u1 - 0.5 * sig * (cm * z1m + sm * z2m)
    dh[1, 2] = 0.5 * dsig * u2 - 0.5 * sig * (-sm * z1m + cm * z2m)
    return cb, sb


@numba.njit(cache=True, nogil=True)
def algorithmic_into(da, db, le, ksh_a, ksh_b, qw, stiff, theta, tab, work, p, ab):
    """Pbar(a, b) into p (n_dof,) and dPbar/db into the banded ab (21, n_dof), both overwritten
    (`beam.algorithmic.assemble_algorithmic` with shift = 0, tangent on, geo = 1): da, db the
    dofs at t_n, t_{n+1}; ksh_a, ksh_b kappa# (n_el, 4) [1/m]; qw, stiff the quadrature's
    weights and rigidities (`beam.element.quadrature`); theta the stress point; tab
    `quadrature_tables(le, qxi)`; work `make_work()`."""
    dea, deb, fe, ke, bb, bt, dh = work
    p[:] = 0.0
    ab[:, :] = 0.0
    sig = np.empty(3)
    for e in range(le.shape[0]):
        base = 6 * e
        for k in range(11):
            dea[k], deb[k] = da[base + LOC[k]], db[base + LOC[k]]
        fe[:] = 0.0
        ke[:, :] = 0.0
        for g in range(qw.shape[0]):
            t = tab[e, g]
            oa = ksh_a[e, g] if g < N_GAUSS else 0.0
            ob = ksh_b[e, g] if g < N_GAUSS else 0.0
            a1, a2, pa, ka = _strains(dea, t, oa)
            b1, b2, pb, kb = _strains(deb, t, ob)
            cb, sb = _rows(t, a1, a2, pa, b1, b2, pb, bb, bt, dh)
            ca, sa = math.cos(pa), math.sin(pa)
            w = qw[g] * le[e]
            e0 = theta * (cb * b1 + sb * b2 - 1.0) + (1.0 - theta) * (ca * a1 + sa * a2 - 1.0)
            e1 = theta * (-sb * b1 + cb * b2) + (1.0 - theta) * (-sa * a1 + ca * a2)
            sig[0] = stiff[g, 0] * e0
            sig[1] = stiff[g, 1] * e1
            sig[2] = stiff[g, 2] * (theta * kb + (1.0 - theta) * ka)
            for i in range(11):
                fe[i] += w * (bb[0, i] * sig[0] + bb[1, i] * sig[1] + bb[2, i] * sig[2])
            c0, c1, c2 = w * theta * stiff[g, 0], w * theta * stiff[g, 1], w * theta * stiff[g, 2]
            for i in range(11):
                x0, x1 = c0 * bb[0, i], c1 * bb[1, i]
                for j in range(11):
                    ke[i, j] += x0 * bt[0, j] + x1 * bt[1, j]
            for i in range(8, 11):
                x2 = c2 * bb[2, i]
                for j in range(8, 11):
                    ke[i, j] += x2 * bt[2, j]
            _geo(ke, w, sig[0], sig[1], t[0:4], t[4:7], dh, cb, sb, 1.0)
        for i in range(11):
            gi = base + LOC[i]
            p[gi] += fe[i]
            for j in range(11):
                gj = base + LOC[j]
                ab[HALF_BW + gi - gj, gj] += ke[i, j]
