"""`Multibody`: the tree of rigid bodies of `mf_envs.physics.multibody` (equations in its
module doc, kernels in `multibody.kernels`): packing, matrices, energies, reactions and `step`."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import check_finite, check_nonnegative, check_shape, nonnegative_scalar
from mf_envs.frames.so3 import orthonormality_error
from mf_envs.physics.multibody import kernels as K
from mf_envs.physics.multibody.joints import Body, MBState


class Multibody:
    """A tree of rigid bodies in moving frames; see the module docstring for the equations."""

    def __init__(self, bodies: Sequence[Body], gravity: ArrayLike = (0.0, 0.0, 0.0)) -> None:
        if len(bodies) == 0:
            raise ValueError("bodies: need at least one body")
        self.bodies = tuple(bodies)
        self.names = [b.name for b in bodies]
        if len(set(self.names)) != len(self.names):
            raise ValueError(f"bodies: names must be unique, got {self.names}")
        self.index = {n: i for i, n in enumerate(self.names)}
        self.gravity = check_shape("gravity", gravity, (3,))
        self._build()

    # ------------------------------------------------------------------ assembly
    def _build(self) -> None:
        parent, jtype, Rpre, Rpost, spre, spost, axis, mass, inertia = self._joint_arrays()
        ndof = np.array([K.NU[t] for t in jtype], dtype=np.int64)
        nqs = np.array([K.NQ[t] for t in jtype], dtype=np.int64)
        uoff = np.concatenate([[0], np.cumsum(ndof)[:-1]]).astype(np.int64)
        qoff = np.concatenate([[0], np.cumsum(nqs)[:-1]]).astype(np.int64)
        self.nu, self.nq = int(ndof.sum()), int(nqs.sum())
        pres_joint = np.array([b.prescribed is not None for b in self.bodies])
        umask = np.zeros(self.nu, dtype=np.bool_)
        qmask = np.zeros(self.nq, dtype=np.bool_)
        for i in np.flatnonzero(pres_joint):
            umask[uoff[i] : uoff[i] + ndof[i]] = True
            qmask[qoff[i] : qoff[i] + nqs[i]] = True
        self._umask, self._qmask = umask, qmask
        self._no_pres = (np.zeros((3, self.nq)), np.zeros((3, self.nu)), np.zeros((3, self.nu)))
        self._pres_list = [
            (b.name, *self._slots_from(i, qoff, nqs, uoff, ndof), jtype[i], b.prescribed)
            for i, b in enumerate(self.bodies)
            if b.prescribed is not None
        ]
        self.free_slots = np.flatnonzero(~umask).astype(np.int64)
        self.prescribed_slots = np.flatnonzero(umask).astype(np.int64)
        self._arrays = dict(parent=parent, jtype=jtype, qoff=qoff, uoff=uoff, ndof=ndof, nqs=nqs)
        self.mass, self.inertia = mass, inertia
        self._topo = (
            parent,
            jtype,
            qoff,
            uoff,
            ndof,
            Rpre,
            spre,
            Rpost,
            spost,
            axis,
            mass,
            inertia,
            ~pres_joint,
            self.free_slots,
            self.prescribed_slots,
        )
        M = self.mass_matrix_blocks()
        if np.any(np.linalg.eigvalsh(M) < 0):
            raise ValueError("inertia: every body inertia must be positive semidefinite")

    def _joint_arrays(self) -> tuple[NDArray, ...]:
        """Per body, validated (errors name the body's field): parent index, joint type, the
        joint's pre/post rotations and offsets, its axis, mass and inertia."""
        nb = len(self.bodies)
        parent = np.full(nb, -1, dtype=np.int64)
        jtype = np.zeros(nb, dtype=np.int64)
        Rpre = np.tile(np.eye(3), (nb, 1, 1))
        Rpost = Rpre.copy()
        spre, spost, axis = np.zeros((nb, 3)), np.zeros((nb, 3)), np.zeros((nb, 3))
        mass, inertia = np.zeros(nb), np.zeros((nb, 3, 3))
        for i, b in enumerate(self.bodies):
            if b.parent is not None:
                if b.parent not in self.index or self.index[b.parent] >= i:
                    raise ValueError(
                        f"parent: body {b.name!r} needs a parent listed before it, got {b.parent!r}"
                    )
                parent[i] = self.index[b.parent]
            j = b.joint
            jtype[i] = j.kind
            spre[i] = check_shape(f"{b.name}.offset", j.offset, (3,))
            spost[i] = check_shape(f"{b.name}.child_offset", j.child_offset, (3,))
            for arr, val, nm in (
                (Rpre, j.rotation, "rotation"),
                (Rpost, j.child_rotation, "child_rotation"),
            ):
                if val is not None:
                    Rv = check_shape(f"{b.name}.{nm}", val, (3, 3))
                    if orthonormality_error(Rv) > 1e-9 or np.linalg.det(Rv) < 0:
                        raise ValueError(f"{b.name}.{nm}: must be a rotation matrix")
                    arr[i] = Rv
            axis[i] = j.axis_vector()
            mass[i] = nonnegative_scalar(f"{b.name}.mass", b.mass)
            inertia[i] = _inertia_matrix(f"{b.name}.inertia", b.inertia)
        return parent, jtype, Rpre, Rpost, spre, spost, axis, mass, inertia

    def mass_matrix_blocks(self) -> NDArray[np.float64]:
        """M (6 nb, 6 nb) = diag(m I3, J_C) per body (Eq. 56)."""
        nb = len(self.bodies)
        M = np.zeros((6 * nb, 6 * nb))
        for b in range(nb):
            M[6 * b : 6 * b + 3, 6 * b : 6 * b + 3] = self.mass[b] * np.eye(3)
            M[6 * b + 3 : 6 * b + 6, 6 * b + 3 : 6 * b + 6] = self.inertia[b]
        return M

    @staticmethod
    def _slots_from(i: int, qoff, nqs, uoff, ndof) -> tuple[slice, slice]:
        return (slice(qoff[i], qoff[i] + nqs[i]), slice(uoff[i], uoff[i] + ndof[i]))

    # ------------------------------------------------------------------ slots and state
    def slots(self, name: str) -> tuple[slice, slice]:
        """(q slice, u slice) of body `name`'s joint."""
        if name not in self.index:
            raise ValueError(f"name: unknown body {name!r}; bodies: {self.names}")
        i, a = self.index[name], self._arrays
        return (
            slice(a["qoff"][i], a["qoff"][i] + a["nqs"][i]),
            slice(a["uoff"][i], a["uoff"][i] + a["ndof"][i]),
        )

    def _pack_q(self, name: str, value: Any) -> NDArray[np.float64]:
        jt = self._arrays["jtype"][self.index[name]]
        if jt in (K.REVOLUTE, K.PRISMATIC):
            return check_finite(name, value).reshape(1)
        if jt == K.SPHERICAL:
            R = check_shape(name, value, (3, 3))
            if orthonormality_error(R) > 1e-8:
                raise ValueError(f"{name}: configuration must be a rotation matrix")
            return R.ravel()
        if jt == K.FREE:
            R, x = value
            return np.concatenate([self._pack_q_rot(name, R), check_shape(name, x, (3,))])
        return np.zeros(0)

    def _pack_q_rot(self, name: str, R: Any) -> NDArray[np.float64]:
        R = check_shape(name, R, (3, 3))
        if orthonormality_error(R) > 1e-8:
            raise ValueError(f"{name}: configuration must be a rotation matrix")
        return R.ravel()

    def _pack_u(self, name: str, value: Any) -> NDArray[np.float64]:
        _, us = self.slots(name)
        if isinstance(value, tuple) and len(value) == 2 and us.stop - us.start == 6:
            value = np.concatenate([np.ravel(value[0]), np.ravel(value[1])])
        return check_shape(name, np.ravel(np.asarray(value, dtype=float)), (us.stop - us.start,))

    def initial_state(
        self, t: float = 0.0, q: dict | None = None, u: dict | None = None
    ) -> MBState:
        """State at time t; q, u: {body name: joint configuration / velocity} (default zero /
        identity); prescribed joints are set from their prescription at t."""
        qv = np.zeros(self.nq)
        for b in self.bodies:
            if b.joint.kind in (K.SPHERICAL, K.FREE):
                qs, _ = self.slots(b.name)
                qv[qs.start : qs.start + 9] = np.eye(3).ravel()
        uv = np.zeros(self.nu)
        for name, val in (q or {}).items():
            qv[self.slots(name)[0]] = self._pack_q(name, val)
        for name, val in (u or {}).items():
            uv[self.slots(name)[1]] = self._pack_u(name, val)
        s = MBState(float(t), qv, uv)
        self._apply_prescription(s)
        return s

    def _prescribed_arrays(self, t: float) -> tuple[NDArray, NDArray, NDArray]:
        """Prescribed q, u, u' at time t in full-size arrays (other slots zero)."""
        q, u, ud = np.zeros(self.nq), np.zeros(self.nu), np.zeros(self.nu)
        for _name, qs, us, jt, f in self._pres_list:
            qq, uu, aa = f(t)
            if jt == K.FREE:
                q[qs] = np.concatenate([np.ravel(qq[0]), np.ravel(qq[1])])
                u[us] = np.concatenate([np.ravel(uu[0]), np.ravel(uu[1])])
                ud[us] = np.concatenate([np.ravel(aa[0]), np.ravel(aa[1])])
            else:
                q[qs], u[us], ud[us] = np.ravel(qq), np.ravel(uu), np.ravel(aa)
        if not (np.all(np.isfinite(q)) and np.all(np.isfinite(u)) and np.all(np.isfinite(ud))):
            raise ValueError(f"prescribed: a prescription returned a non-finite value at t={t}")
        return q, u, ud

    def _apply_prescription(self, s: MBState) -> NDArray[np.float64]:
        q, u, ud = self._prescribed_arrays(s.t)
        s.q[self._qmask] = q[self._qmask]
        s.u[self._umask] = u[self._umask]
        return ud

    # ------------------------------------------------------------------ quantities
    def coordinate(self, s: MBState, name: str) -> Any:
        """Joint configuration of `name`: float, R (3,3) or (R, x)."""
        qs, _ = self.slots(name)
        v = s.q[qs]
        jt = self._arrays["jtype"][self.index[name]]
        if jt in (K.REVOLUTE, K.PRISMATIC):
            return float(v[0])
        if jt == K.SPHERICAL:
            return v.reshape(3, 3).copy()
        if jt == K.FREE:
            return v[:9].reshape(3, 3).copy(), v[9:].copy()
        return None

    def velocity(self, s: MBState, name: str) -> Any:
        """Joint velocity of `name`: float (scalar joints) or array."""
        v = s.u[self.slots(name)[1]]
        return float(v[0]) if v.size == 1 else v.copy()

    def joint_forces(self, **forces: Any) -> NDArray[np.float64]:
        """tau (nu,) from {body name: generalized force on its joint coordinates}."""
        tau = np.zeros(self.nu)
        for name, val in forces.items():
            tau[self.slots(name)[1]] = self._pack_u(name, val)
        return tau

    def kinematics(self, s: MBState) -> tuple[NDArray, ...]:
        """R (nb,3,3), x (nb,3) body poses E^(b) (Eq. 7), B, B' (6 nb, nu), omega (nb,3)."""
        a = self._arrays
        t = self._topo
        return K.kinematics(
            s.q,
            s.u,
            a["parent"],
            a["jtype"],
            a["qoff"],
            a["uoff"],
            a["ndof"],
            t[5],
            t[6],
            t[7],
            t[8],
            t[9],
        )

    def poses(self, s: MBState) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """R (nb,3,3) body attitudes and x (nb,3) centre-of-mass positions (inertial, m)."""
        R, x, *_ = self.kinematics(s)
        return R, x

    def matrices(
        self, s: MBState, wrench: ArrayLike | None = None, tau: ArrayLike | None = None
    ) -> tuple[NDArray, NDArray, NDArray]:
        """(M*, N*, F*) (nu, nu), (nu, nu), (nu,) of Eqs. 73-75 at state s."""
        _, _, B, Bd, om = self.kinematics(s)
        w, tv = self._loads(wrench, tau)
        return K.reduced_matrices(B, Bd, om, self.mass, self.inertia, w, self.gravity, tv)

    def _loads(self, wrench: ArrayLike | None, tau: ArrayLike | None) -> tuple[NDArray, NDArray]:
        nb = len(self.bodies)
        w = np.zeros((nb, 6)) if wrench is None else check_shape("wrench", wrench, (nb, 6))
        tv = np.zeros(self.nu) if tau is None else check_shape("tau", tau, (self.nu,))
        return w, tv

    def accelerations(
        self, s: MBState, wrench: ArrayLike | None = None, tau: ArrayLike | None = None
    ) -> tuple[NDArray, NDArray]:
        """u' (nu,) and reactions lam (n_prescribed_slots,) at state s (Eq. 74)."""
        ud_p = self._prescribed_arrays(s.t)[2]
        w, tv = self._loads(wrench, tau)
        return K.dynamics(s.q, s.u, ud_p, self._topo, w, self.gravity, tv)

    def reactions(
        self, s: MBState, wrench: ArrayLike | None = None, tau: ArrayLike | None = None
    ) -> dict[str, Any]:
        """{prescribed body: generalized force its actuator supplies along its coordinates}."""
        _, lam = self.accelerations(s, wrench, tau)
        out: dict[str, Any] = {}
        k = 0
        for b in self.bodies:
            if b.prescribed is not None:
                n = self.slots(b.name)[1]
                n = n.stop - n.start
                out[b.name] = float(lam[k]) if n == 1 else lam[k : k + n].copy()
                k += n
        return out

    def kinetic_energy(self, s: MBState) -> float:
        """K = 1/2 u^T M* u (Eq. 55), J."""
        Ms, _, _ = self.matrices(s)
        return 0.5 * float(s.u @ Ms @ s.u)

    def potential_energy(self, s: MBState) -> float:
        """U = -sum m g . x_c (Eq. 57 for g = -9.81 e3), J."""
        _, x = self.poses(s)
        return -float(np.sum(self.mass * (x @ self.gravity)))

    def power(
        self, s: MBState, wrench: ArrayLike | None = None, tau: ArrayLike | None = None
    ) -> float:
        """Power of applied loads (not gravity) and of the prescribing actuators, W."""
        _, _, B, _, _ = self.kinematics(s)
        w, tv = self._loads(wrench, tau)
        _, lam = self.accelerations(s, w, tv)
        Xd = B @ s.u
        return float(Xd @ w.ravel() + s.u @ tv + s.u[self.prescribed_slots] @ lam)

    # ------------------------------------------------------------------ time stepping
    def step(
        self, s: MBState, dt: float, wrench: ArrayLike | None = None, tau: ArrayLike | None = None
    ) -> MBState:
        """Advance by dt (s) with loads held constant: RKMK order 4 (see module doc)."""
        w, tv = self._loads(wrench, tau)
        if self._pres_list:
            P = [self._prescribed_arrays(s.t + c * dt) for c in (0.0, 0.5, 1.0)]
            qP = np.stack([p[0] for p in P])
            uP = np.stack([p[1] for p in P])
            udP = np.stack([p[2] for p in P])
        else:  # nothing prescribed: the overlays are never read
            qP, uP, udP = self._no_pres
        q1, u1 = K.rkmk4_step(
            s.q,
            s.u,
            float(dt),
            qP,
            uP,
            udP,
            self._qmask,
            self._umask,
            self._topo,
            w,
            self.gravity,
            tv,
        )
        return MBState(s.t + dt, q1, u1)


def _inertia_matrix(name: str, value: Any) -> NDArray[np.float64]:
    arr = check_finite(name, value)
    if arr.shape == (3,):
        check_nonnegative(name, arr)
        return np.diag(arr)
    arr = check_shape(name, arr, (3, 3))
    if not np.allclose(arr, arr.T):
        raise ValueError(f"{name}: inertia matrix must be symmetric")
    return arr
