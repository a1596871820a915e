"""Bekker/Janosi ground contact of a beam (Rios 2017 §4.5; the inchworm's `terrain` effect).

The line loads of `mf_envs.physics.terrain.TerrainContact` (Eq. 56 pressure-sinkage, Eq. 57
shear-slip) act at the Gauss points of the C1 beam. Approximation: the bottom surface point is
taken as the centroid shifted down by h/2 (z_bottom = z_C - h/2, exact for a flat-lying body;
in the curled parts the contact is at the feet, which stay nearly flat); the load acts on the
curve of centroids (no distributed couple). The nodal force is Eq. 81b and its derivative enters
the Newton tangent: dF/dd = int N_z^T (dn/dz) N_z dS.

Grip: `anchor` picks which half of the body grips ("head": S >= L/2, "tail": S < L/2); that
half has the soil's full shear strength, the other half slides on a slick surface (friction
angle tan(phi) x `SLICK_FACTOR`, no cohesion). anchor None (the default): the whole body has
the soil's strength. So the grip comes out of the contact law, not a kinematic constraint. (The
seed's robot switches which foot holds by warping its leg sections, rough PI film vs smooth
PDMS, §4.10: the inchworm sets `anchor` with `anchor_switching` + `terrain`.)

The soil models themselves (`mf_envs.physics.terrain`) know nothing of beams; this module is
their beam side, next to the beam's other ground contacts.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from mf_envs.physics.beam import fields
from mf_envs.physics.beam.solver import BeamModel
from mf_envs.physics.terrain import SlipState, TerrainContact, soil

SLICK_FACTOR = 0.05  # tan(phi) multiplier of the sliding foot (smooth PDMS), cohesion off


class BeamTerrain:
    """Contact of a beam model with flat ground at z = 0; holds the committed slip history."""

    def __init__(
        self, model: BeamModel, height: float, width: float, soil_name: str = "dry_sand"
    ) -> None:
        self.model = model
        self.half_h = 0.5 * height
        base = soil(soil_name)
        slick = dataclasses.replace(
            base,
            cohesion=0.0,
            friction_angle=float(np.arctan(SLICK_FACTOR * np.tan(base.friction_angle))),
            name=base.name + " (slick)",
        )
        self.grip = TerrainContact(base, width)
        self.slick = TerrainContact(slick, width)
        self.head_side = (model.gauss_S >= 0.5 * model.params.length).ravel()
        self.anchor: str | None = None  # None: the whole body grips
        self.slip = SlipState.at_rest(
            model.gauss_fields(model.straight())["position"][..., 0].ravel()
        )
        self._trial = self.slip

    def reset(self, d: np.ndarray) -> None:
        x = self.model.gauss_fields(d)["position"][..., 0].ravel()
        self.slip = SlipState.at_rest(x)
        self._trial = self.slip

    def translate(self, dx: float) -> None:
        """Shift the slip references by dx [m] (the beam's local origin moved by -dx)."""
        self.slip = SlipState(self.slip.j, self.slip.x_ref + dx)
        self._trial = SlipState(self._trial.j, self._trial.x_ref + dx)

    def _gripping(self) -> np.ndarray:
        if self.anchor is None:
            return np.ones_like(self.head_side)
        return self.head_side if self.anchor == "head" else ~self.head_side

    def loads(self, d: np.ndarray, v: np.ndarray):
        """extra-load callback for `newton`: (F (n_dof,), dF/dd banded, None)."""
        pos = self.model.gauss_fields(d)["position"]
        x, z = pos[..., 0].ravel(), pos[..., 1].ravel() - self.half_h
        a = self.grip.loads(x, z, self.slip)
        b = self.slick.loads(x, z, self.slip)
        g = self._gripping()
        pick = {
            k: np.where(g, getattr(a, k), getattr(b, k))
            for k in ("fx", "fz", "dfx_dx", "dfx_dz", "dfz_dz")
        }
        self._trial = a.slip  # same slip for both (it only depends on x and contact)
        shape = self.model.gauss_S.shape
        n_gp = np.stack([pick["fx"], pick["fz"]], axis=-1).reshape(*shape, 2)
        dn = np.zeros((*shape, 2, 2))
        dn[..., 0, 0] = pick["dfx_dx"].reshape(shape)
        dn[..., 0, 1] = pick["dfx_dz"].reshape(shape)
        dn[..., 1, 1] = pick["dfz_dz"].reshape(shape)
        f = self.model.distributed(n_gp)
        return f, fields.assemble_line_stiffness(self.model.le, dn), None

    def commit(self, d: np.ndarray) -> None:
        """Accept the slip history of the converged configuration d."""
        self.loads(d, np.zeros_like(d))
        self.slip = self._trial

    def in_contact(self, d: np.ndarray) -> np.ndarray:
        """(n_el, 4) bool: Gauss points touching the ground."""
        z = self.model.gauss_fields(d)["position"][..., 1] - self.half_h
        return z < 0.0
