"""The SMA wire groups of an inchworm body (effect `sma_wires`): their power and the wire state
that holds a given kappa#, for `drive.DrivenInchworm` and its kernels."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mf_envs.physics.actuators.sma import SMAWireParams
from mf_envs.physics.inchworm import quasistatic as qs


@dataclass(frozen=True)
class SMAWires:
    """The wire groups of an SMA-driven body: one group per control point, each of `params`
    (its n_wires, a length of body / control points), at a lever arm under the neutral axis such
    that a fully contracted group holds kappa# = -kappa_full [1/m] (kappa_full = the recovery
    strain / lever arm)."""

    params: SMAWireParams
    kappa_full: float
    n_groups: int

    @property
    def group_power(self) -> float:
        """Electrical power [W] of one group at duty 1 (rated current)."""
        p = self.params
        return p.current**2 * p.resistance_per_length * p.length * p.n_wires

    @property
    def power_per_length(self) -> float:
        """Joule power per length of one wire at duty 1 [W/m]."""
        return self.params.current**2 * self.params.resistance_per_length

    def state_for(self, kappa_ctrl: np.ndarray) -> np.ndarray:
        """SMA state (5, n) of groups at rest holding kappa# (n,) [1/m] in [-kappa_full, 0]:
        at ambient (xi = 1) for kappa# = 0, else warm on the heating branch at the temperature
        whose martensite fraction is 1 + kappa# / kappa_full (a wire heated to there)."""
        a = self.params.alloy
        xi = np.clip(1.0 + np.asarray(kappa_ctrl, float) / self.kappa_full, 0.0, 1.0)
        out = np.empty((5, len(xi)))
        t_amb = self.params.ambient
        temp = (
            a.austenite_start
            + (a.austenite_finish - a.austenite_start) * np.arccos(2.0 * xi - 1.0) / np.pi
        )
        out[qs.SMA_T] = np.where(xi >= 1.0, t_amb, temp)
        out[qs.SMA_XI] = xi
        out[qs.SMA_DIR] = np.where(xi >= 1.0, -1.0, 1.0)  # sma_kernels COOLING / HEATING
        out[qs.SMA_TR] = t_amb
        out[qs.SMA_XIR] = 1.0
        return out

    def kernel_args(self) -> tuple:
        """((hp, cap, T_amb), (As, Af, Ms, Mf, L/c), power per length [W/m], kappa_full,
        group power [W])."""
        thermal, tt = self.params.kernel_args()
        return thermal, tt, self.power_per_length, self.kappa_full, self.group_power
