"""Numba kernels of the moving-frame multibody engine (Rios 2017, ch. 3 Eqs. 5-75).

Arrays, not objects: the tree is encoded by `mf_envs.physics.multibody.Multibody` as

    parent (nb,) int      parent body index, -1 = the inertial frame (bodies in tree order)
    jtype  (nb,) int      FIXED, REVOLUTE, PRISMATIC, SPHERICAL, FREE
    qoff, uoff (nb,) int  offsets of each joint's slots in q (configuration) and u (velocities)
    Rpre, Rpost (nb,3,3); spre, spost (nb,3); axis (nb,3)   constant joint geometry
    mass (nb,), inertia (nb,3,3)  body mass (kg) and inertia about the centre of mass (body frame)

The relative frame connection of body b (ch. 3 Eq. 6) is

    E^(b/p)(q) = [[Rpre, spre], [0, 1]] . [[Rj(q), xj(q)], [0, 1]] . [[Rpost, spost], [0, 1]]

with the joint part (Rj, xj): revolute exp(q hat(axis)), prismatic (I, q axis), spherical (R, 0),
free (R, x). Joint velocities u_j give omega_j = S_w u_j (joint angular velocity, hat(omega_j) =
Rj^T dRj/dt) and dxj/dt = S_v u_j. Configuration slots: revolute/prismatic 1 (q), spherical 9
(R row-major), free 12 (R, x); velocity slots 1, 1, 3 (omega), 6 (v, omega).

B (6 nb, nu): rows 6b..6b+2 = inertial velocity of the centre of mass of body b, rows
6b+3..6b+5 = body-frame angular velocity (the seed's ordering of Eq. 48), X' = B u (Eq. 49).
"""

from __future__ import annotations

import numba
import numpy as np

from mf_envs.frames.kernels import dexpinv_right, exp_so3, hat
from mf_envs.frames.steppers import make_rk4, rk4_work

FIXED, REVOLUTE, PRISMATIC, SPHERICAL, FREE = 0, 1, 2, 3, 4
NQ = (0, 1, 1, 9, 12)  # configuration slots per joint type
NU = (0, 1, 1, 3, 6)  # velocity slots per joint type


@numba.njit(cache=True)
def _mm(A, B):
    """A @ B by loops (small matrices: avoids the BLAS call overhead of numba's @)."""
    n, k = A.shape
    m = B.shape[1]
    C = np.zeros((n, m))
    for i in range(n):
        for p in range(k):
            a = A[i, p]
            if a != 0.0:
                for j in range(m):
                    C[i, j] += a * B[p, j]
    return C


@numba.njit(cache=True)
def _mv(A, v):
    """A @ v by loops."""
    n, k = A.shape
    out = np.zeros(n)
    for i in range(n):
        acc = 0.0
        for p in range(k):
            acc += A[i, p] * v[p]
        out[i] = acc
    return out


@numba.njit(cache=True)
def _joint_parts(jt, axis, q, qo, nd):
    """Rj, xj, S_w (3, nd), S_v (3, nd) of one joint."""
    Rj = np.eye(3)
    xj = np.zeros(3)
    Sw = np.zeros((3, nd))
    Sv = np.zeros((3, nd))
    if jt == REVOLUTE:
        Rj = exp_so3(axis * q[qo])
        Sw[:, 0] = axis
    elif jt == PRISMATIC:
        xj = axis * q[qo]
        Sv[:, 0] = axis
    elif jt == SPHERICAL:
        Rj = q[qo : qo + 9].copy().reshape((3, 3))
        Sw[:, :] = np.eye(3)
    elif jt == FREE:
        Rj = q[qo : qo + 9].copy().reshape((3, 3))
        xj = q[qo + 9 : qo + 12].copy()
        Sv[:, 0:3] = np.eye(3)
        Sw[:, 3:6] = np.eye(3)
    return Rj, xj, Sw, Sv


@numba.njit(cache=True)
def kinematics(q, u, parent, jtype, qoff, uoff, ndof, Rpre, spre, Rpost, spost, axis):
    """Body poses, B, dB/dt and body angular velocities by the relative-connection recursion.

    Returns R (nb,3,3) and x (nb,3) (E^(b) = E^(p) E^(b/p), Eq. 7), B and Bdot (6 nb, nu)
    (Eqs. 49-50 and their time rate along the motion u), omega (nb,3) body frame (Eq. 37).
    Recursion for body b with parent p, relative rotation Rr and offset s (parent frame):
      omega_b = Rr^T omega_p + Rpost^T omega_j,   v_b = v_p + R_p (hat(omega_p) s + s')   (Eq. 36)
    """
    nb = parent.shape[0]
    nu = u.shape[0]
    R = np.zeros((nb, 3, 3))
    x = np.zeros((nb, 3))
    om = np.zeros((nb, 3))
    B = np.zeros((6 * nb, nu))
    Bd = np.zeros((6 * nb, nu))
    for b in range(nb):
        jt, nd, uo = jtype[b], ndof[b], uoff[b]
        Rj, xj, Sw, Sv = _joint_parts(jt, axis[b], q, qoff[b], nd)
        Rr = _mm(_mm(Rpre[b], Rj), Rpost[b])
        s = spre[b] + _mv(Rpre[b], xj + _mv(Rj, spost[b]))
        Hs = hat(spost[b])
        RjHs = _mm(Rj, Hs)
        G = _mm(Rpre[b], Sv - _mm(RjHs, Sw))
        uj = u[uo : uo + nd].copy()
        wj = _mv(Sw, uj)
        RpostT = np.ascontiguousarray(Rpost[b].T)
        w_rel = _mv(RpostT, wj)
        sd = _mv(G, uj)
        Gd = -_mm(_mm(_mm(Rpre[b], Rj), _mm(hat(wj), Hs)), Sw)
        p = parent[b]
        if p < 0:
            Rp = np.eye(3)
            xp = np.zeros(3)
            wp = np.zeros(3)
            Jwp = np.zeros((3, nu))
            Jvp = np.zeros((3, nu))
            Jwdp = np.zeros((3, nu))
            Jvdp = np.zeros((3, nu))
        else:
            Rp = R[p]
            xp = x[p]
            wp = om[p]
            Jvp = B[6 * p : 6 * p + 3]
            Jwp = B[6 * p + 3 : 6 * p + 6]
            Jvdp = Bd[6 * p : 6 * p + 3]
            Jwdp = Bd[6 * p + 3 : 6 * p + 6]
        R[b] = _mm(Rp, Rr)
        x[b] = xp + _mv(Rp, s)
        RrT = np.ascontiguousarray(Rr.T)
        Hsh = hat(s)
        RpHs = _mm(Rp, Hsh)
        Jw = _mm(RrT, Jwp)
        Jv = Jvp - _mm(RpHs, Jwp)
        Jwd = -_mm(hat(w_rel), Jw) + _mm(RrT, Jwdp)
        RpWp = _mm(Rp, hat(wp))
        Jvd = Jvdp - _mm(_mm(RpWp, Hsh) + _mm(Rp, hat(sd)), Jwp) - _mm(RpHs, Jwdp)
        if nd > 0:
            Jw[:, uo : uo + nd] += _mm(RpostT, Sw)
            Jv[:, uo : uo + nd] += _mm(Rp, G)
            Jvd[:, uo : uo + nd] += _mm(RpWp, G) + _mm(Rp, Gd)
        B[6 * b : 6 * b + 3] = Jv
        B[6 * b + 3 : 6 * b + 6] = Jw
        Bd[6 * b : 6 * b + 3] = Jvd
        Bd[6 * b + 3 : 6 * b + 6] = Jwd
        om[b] = _mv(Jw, u)
    return R, x, B, Bd, om


@numba.njit(cache=True)
def reduced_matrices(B, Bd, om, mass, inertia, wrench, gravity, tau):
    """M* = B^T M B, N* = B^T (M B' + D M B), F* = B^T Q + tau (ch. 3 Eqs. 73-75).

    wrench (nb, 6): applied force (inertial frame, N) at the centre of mass and moment (body
    frame, N m) on each body; gravity (3,) inertial m/s^2 adds m g to the force; tau (nu,)
    generalized forces on the joint coordinates (joint torques, N m / N).
    """
    nb = mass.shape[0]
    nu = B.shape[1]
    Ms = np.zeros((nu, nu))
    Ns = np.zeros((nu, nu))
    Fs = tau.copy()
    for b in range(nb):
        Jv = B[6 * b : 6 * b + 3]
        Jw = B[6 * b + 3 : 6 * b + 6]
        Jvd = Bd[6 * b : 6 * b + 3]
        Jwd = Bd[6 * b + 3 : 6 * b + 6]
        m = mass[b]
        Jb = inertia[b]
        JJw = _mm(Jb, Jw)
        JvT = np.ascontiguousarray(Jv.T)
        JwT = np.ascontiguousarray(Jw.T)
        Ms += m * _mm(JvT, Jv) + _mm(JwT, JJw)
        Ns += m * _mm(JvT, Jvd) + _mm(JwT, _mm(Jb, Jwd) + _mm(hat(om[b]), JJw))
        Fs += _mv(JvT, wrench[b, 0:3] + m * gravity) + _mv(JwT, wrench[b, 3:6].copy())
    return Ms, Ns, Fs


@numba.njit(cache=True)
def accelerations(Ms, Ns, Fs, u, ud_pres, free, pres):
    """Solve M*_ff u'_f = F*_f - (N* u)_f - M*_fp u'_p; reactions lam_p = (M* u' + N* u - F*)_p.

    free, pres: index arrays of the free and prescribed velocity slots; ud_pres (nu,) holds the
    prescribed accelerations in the `pres` slots. Returns u' (nu,) and lam (n_pres,): the
    generalized forces the prescribing actuators must add along the prescribed coordinates.
    """
    nu = u.shape[0]
    ud = np.zeros(nu)
    for i in pres:
        ud[i] = ud_pres[i]
    r = Fs - _mv(Ns, u) - _mv(Ms, ud)
    nf = free.shape[0]
    if nf > 0:
        A = np.empty((nf, nf))
        rhs = np.empty(nf)
        for a in range(nf):
            rhs[a] = r[free[a]]
            for c in range(nf):
                A[a, c] = Ms[free[a], free[c]]
        sol = np.linalg.solve(A, rhs)
        for a in range(nf):
            ud[free[a]] = sol[a]
    res = _mv(Ms, ud) + _mv(Ns, u) - Fs
    lam = np.empty(pres.shape[0])
    for a in range(pres.shape[0]):
        lam[a] = res[pres[a]]
    return ud, lam


@numba.njit(cache=True)
def retract(q0, z, jtype, qoff, uoff, free_joint):
    """q0 (+) z: local coordinates z (nu,) of the free joints applied to q0 (R0 exp(theta))."""
    q = q0.copy()
    for b in range(jtype.shape[0]):
        if not free_joint[b]:
            continue
        jt, qo, uo = jtype[b], qoff[b], uoff[b]
        if jt == REVOLUTE or jt == PRISMATIC:
            q[qo] = q0[qo] + z[uo]
        elif jt == SPHERICAL or jt == FREE:
            th = z[uo : uo + 3].copy() if jt == SPHERICAL else z[uo + 3 : uo + 6].copy()
            Rn = _mm(q0[qo : qo + 9].copy().reshape((3, 3)), exp_so3(th))
            q[qo : qo + 9] = Rn.ravel()
            if jt == FREE:
                q[qo + 9 : qo + 12] = q0[qo + 9 : qo + 12] + z[uo : uo + 3]
    return q


@numba.njit(cache=True)
def local_rate(z, u, jtype, uoff, free_joint):
    """dz/dt of the local coordinates (RKMK): u for scalars and translations, J_r^-1 omega."""
    dz = np.zeros(z.shape[0])
    for b in range(jtype.shape[0]):
        if not free_joint[b]:
            continue
        jt, uo = jtype[b], uoff[b]
        if jt == REVOLUTE or jt == PRISMATIC:
            dz[uo] = u[uo]
        elif jt == SPHERICAL:
            dz[uo : uo + 3] = dexpinv_right(z[uo : uo + 3].copy(), u[uo : uo + 3].copy())
        elif jt == FREE:
            dz[uo : uo + 3] = u[uo : uo + 3]
            dz[uo + 3 : uo + 6] = dexpinv_right(
                z[uo + 3 : uo + 6].copy(), u[uo + 3 : uo + 6].copy()
            )
    return dz


@numba.njit(cache=True)
def dynamics(q, u, ud_pres, topo, wrench, gravity, tau):
    """u' (nu,) and reactions lam (n_pres,) at (q, u): Eq. 74 solved for the free slots."""
    parent, jtype, qoff, uoff, ndof, Rpre, spre, Rpost, spost, axis, mass, inertia = topo[:12]
    free, pres = topo[13], topo[14]
    R, x, B, Bd, om = kinematics(
        q, u, parent, jtype, qoff, uoff, ndof, Rpre, spre, Rpost, spost, axis
    )
    Ms, Ns, Fs = reduced_matrices(B, Bd, om, mass, inertia, wrench, gravity, tau)
    return accelerations(Ms, Ns, Fs, u, ud_pres, free, pres)


@numba.njit(cache=True)
def _overlay(base, over, mask):
    out = base.copy()
    for i in range(base.shape[0]):
        if mask[i]:
            out[i] = over[i]
    return out


@numba.njit(cache=True)
def _stage_inputs(t, args):
    """Index k = 0, 1, 2 of the prescribed-slot samples at t, t + dt/2, t + dt (t from 0)."""
    return int(round(2.0 * t / args[0]))


@numba.njit(cache=True)
def _stage_rhs(t, x, k, args, out):
    """(dz/dt, du/dt) of x = (z, u) at stage k into out: RKMK in local coordinates q = q0 (+) z."""
    dt, q, qP, uP, udP, qmask, umask, topo, wrench, gravity, tau = args
    jtype, qoff, uoff, free_joint = topo[1], topo[2], topo[3], topo[12]
    nu = x.shape[0] // 2
    zs, us = x[:nu], _overlay(x[nu:], uP[k], umask)
    qs = _overlay(retract(q, zs, jtype, qoff, uoff, free_joint), qP[k], qmask)
    ud, _ = dynamics(qs, us, udP[k], topo, wrench, gravity, tau)
    out[:nu] = local_rate(zs, us, jtype, uoff, free_joint)
    out[nu:] = ud


_rk4 = make_rk4(_stage_rhs, _stage_inputs)


@numba.njit(cache=True)
def rkmk4_step(q, u, dt, qP, uP, udP, qmask, umask, topo, wrench, gravity, tau):
    """One Runge-Kutta-Munthe-Kaas step of order 4 on the configuration manifold.

    Free joints: the frames RK4 stepper on (z, u) with z the local coordinates of q = q0 (+) z
    (rotations R0 exp(hat(theta)), ch. 2 Rodrigues), dz/dt from `local_rate`. Prescribed slots are
    overwritten at the stage times t, t + dt/2, t + dt by qP[k], uP[k], udP[k] (k = 0, 1, 2).
    Wrench and tau are held over the step (zero-order hold). Returns (q_new, u_new).
    """
    jtype, qoff, uoff, free_joint = topo[1], topo[2], topo[3], topo[12]
    nu = u.shape[0]
    x = np.zeros(2 * nu)
    x[nu:] = u
    args = (dt, q, qP, uP, udP, qmask, umask, topo, wrench, gravity, tau)
    work = rk4_work(2 * nu)
    _rk4(0.0, x, dt, args, work)
    dx = work[0]
    q1 = _overlay(retract(q, dx[:nu], jtype, qoff, uoff, free_joint), qP[2], qmask)
    u1 = _overlay(u + dx[nu:], uP[2], umask)
    return q1, u1
