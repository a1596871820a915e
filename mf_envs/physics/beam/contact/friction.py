"""Anisotropic Coulomb friction of a contact on the ground, with engagement dynamics (Rios 2017
§4.5 III, §4.10): the friction law shared by every body resting on the ground by friction (the
two feet of `feet`; a belly in sliding contact along the beam).

* engagement g in [0, 1] of a contact (0 released, 1 gripping) follows the command g_c in
  {0, 1} with first-order dynamics, dg/dt = (g_c - g) / tau_g (tau_g = engage or release time
  constant), solved exactly (`grip_response`); so |dg/dt| <= 1 / tau_g at all times;
* friction coefficient, anisotropic (different for slipping forward, +x, and backward, -x, like
  the directional hooks of a caterpillar's prolegs or a snake's belly scales):
  mu(g, s) = mu_slide(s) + g (mu_grip(s) - mu_slide(s)), s = +1 forward, -1 backward
  (`friction_coefficient`);
* holding limit F_hold = mu(g, s) max(N, 0) (Coulomb, equal static and kinetic coefficients),
  N the normal load (`holding_limit`).

`FrictionParams` holds the coefficients; the compiled functions take them in the layout
mu4 = (grip_forward, grip_backward, slide_forward, slide_backward).
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from mf_envs._validate import check_fields

FORWARD, BACKWARD = 1, -1


@dataclass(frozen=True)
class FrictionParams:
    """Coulomb coefficients (dimensionless) of a gripping (g = 1) and a released (g = 0) foot for
    slipping forward (+x) and backward (-x); engage/release time constants [s].

    Defaults (our choice, order of magnitude of polymer films on a dry surface): gripping foot
    0.6 forward / 1.0 backward (a directional pad that resists being pushed back), released
    smooth foot 0.1 / 0.15. Time constants 0.2 s: the seed's robot switches feet by warping the
    foot sections with transverse SMA wires, the same ~1 s-class wires as the body (3 tau ~ the
    0.5-1 s wire response, see `mf_envs.physics.actuators`).
    """

    grip_forward: float = 0.6
    grip_backward: float = 1.0
    slide_forward: float = 0.1
    slide_backward: float = 0.15
    engage_time: float = 0.2
    release_time: float = 0.2

    def __post_init__(self) -> None:
        coefficients = ("grip_forward", "grip_backward", "slide_forward", "slide_backward")
        check_fields(self, label="friction_coefficients['{}']", nonnegative=coefficients)
        check_fields(self, label="grip_time_constant", positive=("engage_time", "release_time"))

    @property
    def coefficients(self) -> np.ndarray:
        """(grip_forward, grip_backward, slide_forward, slide_backward), the compiled layout."""
        return np.array(
            [self.grip_forward, self.grip_backward, self.slide_forward, self.slide_backward]
        )

    def mu(self, g: float, direction: int) -> float:
        """Friction coefficient of a foot with engagement g slipping in `direction` (+1/-1):
        mu_slide + g (mu_grip - mu_slide)."""
        return friction_coefficient(self.coefficients, float(g), int(direction))

    def holding_limit(self, g: float, direction: int, normal: float) -> float:
        """F_hold = mu(g, direction) max(N, 0) [N] (normal load N [N], positive pressing)."""
        return holding_limit(self.coefficients, float(g), int(direction), float(normal))


@numba.njit(cache=True)
def friction_coefficient(mu4, g, direction):
    """Friction coefficient of a foot with engagement g slipping towards direction (+1/-1);
    mu4 = (grip_forward, grip_backward, slide_forward, slide_backward)."""
    if direction == FORWARD:
        return mu4[2] + g * (mu4[0] - mu4[2])
    return mu4[3] + g * (mu4[1] - mu4[3])


@numba.njit(cache=True)
def holding_limit(mu4, g, direction, normal):
    """Holding limit F_hold = mu max(N, 0) [N]."""
    return friction_coefficient(mu4, g, direction) * max(normal, 0.0)


@numba.njit(cache=True)
def grip_response(g, command, t, engage, release, out):
    """Exact engagement (2,) at time t [s] from g under the held command (0/1)."""
    for k in range(2):
        tau = engage if command[k] > g[k] else release
        out[k] = command[k] + (g[k] - command[k]) * np.exp(-t / tau)
