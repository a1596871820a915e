"""The hull's two tilt axes in the floating model: one block per axis from a BEM table.

`floating` turns the hull about pitch theta (e1) and roll rho (e2) (its module doc). An
axisymmetric hull (the cylinders) has one block for both: its pitch coefficients about G. A
hull with a sway/roll table (`three_dof`'s optional `transverse_*` fields: ISWEC's 15 x 8 m box)
has a roll block of its own: roll's A_inf, C44, radiation fit of B44 and rigid inertia, and
its wave moments come from the heading table.

Frames. The BEM table has x along the box's length (the head-wave direction), y across its
beam; the env's default sea travels along e2 (`wave_direction` pi/2) and its working tilt is
theta about e1. So the box lies with its length along e2: x_b = e2, y_b = -e1, z_b = e3, and
    theta = -(mode 5, pitch about y_b),   rho = mode 4 (roll about x_b),
    heading beta_b = direction - pi/2,
    M about e1 = -X5(beta_b) a,   M about e2 = X4(beta_b) a    (per component of amplitude a),
which for an axisymmetric X4(beta) = -X5(0) sin(beta), X5(beta) = X5(0) cos(beta) is
`sea.excitation_coefficients`' rule. Head seas (direction pi/2) give X4 = 0 by the xOz mirror.
SI units throughout.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from mf_envs.physics.gowec.hydro import HullCoefficients
from mf_envs.physics.gowec.hydro.checks import full_circle
from mf_envs.physics.gowec.hydro.radiation import RadiationFit
from mf_envs.physics.gowec.hydro.sea import interp_complex
from mf_envs.physics.gowec.hydro.three_dof import ThreeDofCoefficients

ROLL, PITCH = 3, 4  # modes 4 and 5 in the heading table (modes 1..5)


def _block(c: ThreeDofCoefficients, added, damping, excitation, a_inf: float, stiffness: float,
           inertia: float, label: str) -> HullCoefficients:  # fmt: skip
    """One tilt axis' block of a table as `HullCoefficients` (A_0 taken as the added inertia at
    the table's lowest frequency; negative near-zero damping at the table's high end, where the
    mesh no longer resolves it, clipped to 0)."""
    return HullCoefficients(
        omega=c.omega, added_mass=added, damping=np.maximum(damping, 0.0), excitation=excitation,
        added_mass_inf=float(a_inf), added_mass_zero=float(added[0]), stiffness=float(stiffness),
        inertia=float(inertia), mass=float(c.mass_matrix[0, 0]), rho=c.rho, g=c.g,
        radius=c.radius, draft=c.draft, zg=c.zg, name=f"{c.name} ({label})",
    )  # fmt: skip


def pitch_hull(c: ThreeDofCoefficients) -> HullCoefficients:
    """The pitch block (mode 5 about G) of a surge/heave/pitch table (`_block`)."""
    return _block(c, c.added_mass[:, 2, 2], c.damping[:, 2, 2], c.excitation[:, 2],
                  c.added_mass_inf[2, 2], c.hydrostatic_stiffness[2, 2], c.mass_matrix[2, 2],
                  "pitch")  # fmt: skip


def roll_hull(c: ThreeDofCoefficients | None) -> HullCoefficients | None:
    """The roll block (mode 4 about G) of a table with the sway/roll data (`_block`; its
    excitation X4 in beam seas, heading pi/2), None without that data."""
    if c is None or c.transverse_added_mass is None or c.heading_excitation is None:
        return None
    return _block(c, c.transverse_added_mass[:, 1, 1], c.transverse_damping[:, 1, 1],
                  c.heading_excitation[:, -1, ROLL], c.transverse_added_mass_inf[1, 1],
                  c.transverse_hydrostatic_stiffness[1, 1], c.transverse_mass_matrix[1, 1],
                  "roll")  # fmt: skip


def plan(c: ThreeDofCoefficients | None) -> tuple[float, float] | None:
    """(length, beam) (m) of a box table, None for a cylinder's or a pitch-only hull."""
    if c is None or not (math.isfinite(c.length) and math.isfinite(c.beam)):
        return None
    return float(c.length), float(c.beam)


def yaw_inertia(hull: HullCoefficients, c: ThreeDofCoefficients | None) -> float:
    """I_z (kg m^2) about G: a box's m (L^2 + B^2) / 12 (a solid box of the displaced mass, as
    its chosen pitch and roll gyration; chosen), else 1/2 m R^2 (R = 1 m if unknown); no added
    yaw inertia (yaw is held: I_z enters only through the hull's tilted body rates)."""
    lb = plan(c)
    if lb is not None:
        return hull.mass * (lb[0] ** 2 + lb[1] ** 2) / 12.0
    return 0.5 * hull.mass * (hull.radius if math.isfinite(hull.radius) else 1.0) ** 2


def stack_fits(pitch: RadiationFit, roll: RadiationFit) -> tuple[NDArray, NDArray, NDArray]:
    """(Ar (2, n, n), Br (2, n), Cr (2, n)) of `floating.FloatingParams` from the two axes'
    fits, n the larger order; the other is padded with inert states (A = -1 on the diagonal,
    B = C = 0: they start at 0 and stay there, and add nothing to mu)."""
    n = max(pitch.A.shape[0], roll.A.shape[0])
    Ar, Br, Cr = np.zeros((2, n, n)), np.zeros((2, n)), np.zeros((2, n))
    for i, f in enumerate((pitch, roll)):
        k = f.A.shape[0]
        Ar[i] = -np.eye(n)
        Ar[i, :k, :k] = f.A
        Br[i, :k], Cr[i, :k] = f.B[:, 0], f.C[0]
    return Ar, Br, Cr


def directional_excitation(c: ThreeDofCoefficients, omegas: NDArray,
                           direction: float) -> NDArray[np.complex128]:  # fmt: skip
    """(2, n) complex: the wave moments about e1 and e2 (N m per metre of amplitude) at each
    frequency of omegas (rad/s) for a sea travelling towards `direction` (rad from e1; module
    doc's frames): the heading table over the full circle (`checks.full_circle`), linear in the
    heading between its 10 deg steps, then linear in frequency (0 outside the table)."""
    beta, X = full_circle(c.headings, c.heading_excitation)
    b = (direction - 0.5 * math.pi) % (2.0 * math.pi)
    step = beta[1] - beta[0]
    i = int(b // step) % beta.size
    f = b / step - int(b // step)
    Xb = (1.0 - f) * X[:, i] + f * X[:, (i + 1) % beta.size]  # (n_table, 5)
    return np.stack([-interp_complex(omegas, c.omega, Xb[:, PITCH]),
                     interp_complex(omegas, c.omega, Xb[:, ROLL])])  # fmt: skip
