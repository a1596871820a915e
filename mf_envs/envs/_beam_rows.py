"""The compiled configuration and pieces the beam robots' rows share (`Serpentine-v0` on the
ground, `Eel-v0` in water; their `rows.py` hold the step and the observation): `Cfg`, packed by
`pack_cfg`; the centre-of-mass kernel `body_state`; the map of control-point curvatures to the
Gauss points `to_gauss`; the observation's curvature slots `observe_curvature`."""

from __future__ import annotations

from collections import namedtuple
from typing import Any

import numba
import numpy as np

from mf_envs.physics.beam import element as el
from mf_envs.physics.serpentine.stepping import Body

# report of a step: ok (1/0), actuation energy [J], Newton iterations, com before (x, y) [m],
# the muscles' signed (net) work [J]
REP_OK, REP_ENERGY, REP_ITER, REP_X0, REP_Y0, REP_NET = range(6)
N_REPORT = 6
# the Newton settings: the step test |dd| / u_scale < 1e-6 (or the next correction predicted
# below 1e-9 in the quadratic phase) leaves ~1e-9; at most 2^6 sub-steps
TOLERANCE, MAX_ITER, MAX_HALVINGS = 1e-6, 12, 6

Cfg = namedtuple("Cfg", "body interp nz npsi ce cxi max_curvature n_sub length target h robot")
Cfg.__doc__ = """A beam robot's compiled configuration: body the time loop's
`physics.serpentine.stepping.Body`; interp (4 n_el, n) the control points' curvatures to the
Gauss points (`serpentine.build.interpolation`); nz, npsi (4, 4), (4, 3) the shape functions
at the Gauss points; ce, cxi (n,) the control points' elements and local coordinates;
max_curvature [1/m] the action scale; n_sub physics steps of h [s] per control step; length
[m]; target [rad] the target direction; robot the robot's own settings (its `rows.py`)."""


def pack_cfg(scene: Any, model: Any, steps: tuple[int, float], target: float, body: tuple,
         robot: tuple) -> Cfg:  # fmt: skip
    """The `Cfg` of a scene on its `BeamModel`: steps = (physics steps per control step,
    physics_dt [s]); body = (quad, load, th, damping) of the model's `Body` (the Newton settings
    above, EI from the scene); robot as `Cfg.robot`."""
    from mf_envs.envs.serpentine.build import control_points, interpolation

    p, le = scene.params, model.le
    quad, load, th, damping = body
    nz = np.array([el.shape_functions(x, le[0])[0] for x in el.GAUSS_XI])
    npsi = np.array([el.shape_functions(x, le[0])[2] for x in el.GAUSS_XI])
    ce, cxi = control_points(p.length, scene.n_ctrl, model.n_elements)
    return Cfg(
        Body(model.mass, le, quad, load, th, TOLERANCE, MAX_ITER, MAX_HALVINGS, p.EI,
             float(damping)),
        interpolation(model.gauss_S, p.length, scene.n_ctrl), nz, npsi, ce, cxi,
        scene.max_curvature, int(steps[0]), p.length, float(target), float(steps[1]), robot,
    )  # fmt: skip


@numba.njit(cache=True, nogil=True)
def body_state(d, v, le, nz, npsi, out):
    """out = (x_com, y_com [m], vx_com, vy_com [m/s], mean frame angle [rad]) (4-point Gauss,
    uniform m_A, as `SnakeHistory.com`)."""
    for k in range(5):
        out[k] = 0.0
    length = 0.0
    for e in range(le.shape[0]):
        b = 6 * e
        for g in range(4):
            w = el.GAUSS_W[g] * le[e]
            for i in range(4):
                out[0] += w * nz[g, i] * d[b + el.LOC[i]]
                out[1] += w * nz[g, i] * d[b + el.LOC[4 + i]]
                out[2] += w * nz[g, i] * v[b + el.LOC[i]]
                out[3] += w * nz[g, i] * v[b + el.LOC[4 + i]]
            for i in range(3):
                out[4] += w * npsi[g, i] * d[b + el.LOC[8 + i]]
        length += le[e]
    for k in range(5):
        out[k] /= length


@numba.njit(cache=True, nogil=True)
def to_gauss(interp, c0, c1, k0, k1):
    """kappa# at the Gauss points (n_el, 4) of the control points' c0 and c1 (n,) [1/m], linear
    in S between them (interp as `Cfg.interp`), into k0 and k1."""
    n = c0.shape[0]
    for e in range(k0.shape[0]):
        for g in range(4):
            a, b = 0.0, 0.0
            for j in range(n):
                a += interp[4 * e + g, j] * c0[j]
                b += interp[4 * e + g, j] * c1[j]
            k0[e, g], k1[e, g] = a, b


@numba.njit(cache=True, nogil=True)
def observe_curvature(d, cmd, cfg, gap, out):
    """The observation's curvature slots: kappa L at the n control points into out[:n], the
    command cmd (n,) over max_curvature into out[n + gap:2 n + gap] (the robot's own slots
    between them)."""
    le, ce, cxi, length = cfg.body.le, cfg.ce, cfg.cxi, cfg.length
    n = cmd.shape[0]
    for j in range(n):
        out[j] = el.kappa_at(d, 6 * ce[j], le[ce[j]], cxi[j]) * length
        out[n + gap + j] = cmd[j] / cfg.max_curvature


@numba.njit(cache=True, nogil=True)
def open_report(d, v, cfg, body, rep, acc):
    """The start of a control step: the body state (`body_state`) into body (5,), the centre of
    mass before it into the report, the work sums acc (2,) zeroed."""
    body_state(d, v, cfg.body.le, cfg.nz, cfg.npsi, body)
    rep[REP_X0], rep[REP_Y0] = body[0], body[1]
    acc[0], acc[1] = 0.0, 0.0


@numba.njit(cache=True, nogil=True)
def close_report(rep, ok, acc, total):
    """The end of a control step: ok (1/0), the muscles' positive and signed work acc (2,) [J]
    and the Newton iterations into the report."""
    rep[REP_OK], rep[REP_ENERGY], rep[REP_ITER], rep[REP_NET] = ok, acc[0], total, acc[1]
