"""GOWEC power (Rios 2017 ch. 3 Eqs. 82-96): generator and gyroscopic power, the analytic
maxima, the detuned mean, Seakeeper net power and the Fig. 3-5 power map."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import check_finite, check_nonnegative, check_positive
from mf_envs.physics.gyros import SEAKEEPER
from mf_envs.physics.waves import BREAKING_STEEPNESS, G, disk_average_factor

SQUARE_WAVE_GAIN = 4.0 / math.pi  # ceiling / Eq. 86 (docs/design.md)


def generator_power(Mg: ArrayLike, phid: ArrayLike) -> NDArray[np.float64]:
    """P = M_g phi' (W, positive = harvested) (Eq. 82)."""
    return np.asarray(Mg, dtype=float) * np.asarray(phid, dtype=float)


def gyroscopic_power(w1: ArrayLike, phi: ArrayLike, phid: ArrayLike, H: float) -> NDArray:
    """P_g = H w1 cos(phi) phi' (W), the gyroscopic part of Eq. 82 (Eqs. 83, 94)."""
    return H * np.asarray(w1) * np.cos(phi) * np.asarray(phid)


def analytic_max_power(
    rotor_inertia: float,
    rotor_speed: float,
    amplitude: float,
    period: float,
    direction: float = math.pi / 2,
    g: float = G,
    buoy_radius: float = 0.0,
) -> float:
    """(P_g)max = 1/2 |psi'| J3 (a/g) (2 pi/T)^4 sin(theta) |F(k r)| (W) (Eq. 95; Eq. 86 at
    theta = pi/2), k = (2 pi/T)^2 / g.

    The mean power with phi = 2 pi t / T locked to a deep-water regular wave, one gyroscope.
    F = 2 J1(k r)/(k r) is the waterplane-averaged slope response of a buoy of radius r (m)
    (`waves.disk_average_factor`): Eq. 95 of the buoy's actual slope amplitude a k |F|.
    buoy_radius = 0 (point buoy) is the seed's Eq. 95 exactly.
    """
    check_positive("rotor_inertia", rotor_inertia)
    check_finite("rotor_speed", rotor_speed)
    check_positive("amplitude", amplitude)
    check_positive("period", period)
    check_finite("direction", direction)
    check_nonnegative("buoy_radius", buoy_radius)
    F = abs(float(disk_average_factor((2.0 * math.pi / period) ** 2 / g * buoy_radius)))
    return (
        F
        * 0.5
        * abs(rotor_speed)
        * rotor_inertia
        * (amplitude / g)
        * (2.0 * math.pi / period) ** 4
        * math.sin(direction)
    )


def analytic_max_power_from_angle(
    rotor_inertia: float, rotor_speed: float, beta0: float, period: float
) -> float:
    """(P_g)max = 1/2 |psi'| J3 beta0 (2 pi / T)^2 (W) for buoy rocking beta0 sin(wt) (Eq. 88)."""
    check_positive("rotor_inertia", rotor_inertia)
    check_positive("period", period)
    return 0.5 * abs(rotor_speed) * rotor_inertia * abs(beta0) * (2.0 * math.pi / period) ** 2


def detuned_mean_power(
    eps: ArrayLike, period: float, scale: float = 1.0, t_end: float | None = None, n: int = 20001
) -> NDArray[np.float64]:
    """Mean of Eq. 96 over [0, t_end]: the gimbal turns at 2 pi/T while the wave has T + eps.

    P = scale * 2 * (2 pi/T) cos(2 pi t/(T + eps)) cos(2 pi t/T) normalised so that eps = 0 gives
    `scale` (Eq. 86). The seed's Fig. 3-4 uses T = 4 s; t_end (default 20 T) sets how much of the
    beat the average covers (the loss grows with t_end, Fig. 3-4 shows ~20% at 1%).
    """
    e = np.atleast_1d(np.asarray(eps, dtype=float))
    t_end = 20.0 * period if t_end is None else t_end
    t = np.linspace(0.0, t_end, n)
    vals = np.cos(2 * math.pi * t[None, :] / (period + e[:, None])) * np.cos(
        2 * math.pi * t[None, :] / period
    )
    return scale * 2.0 * np.trapezoid(vals, t, axis=1) / t_end


# ---------------------------------------------------------------------- Seakeeper (Sec. 3.2.10)
def seakeeper_net_power(
    model: str,
    amplitude: ArrayLike,
    period: ArrayLike,
    efficiency: float = 0.8,
    direction: float = math.pi / 2,
    g: float = G,
) -> NDArray[np.float64]:
    """Net electrical power (W) of one Seakeeper unit: efficiency x Eq. 86 - spool-up power.

    Eq. 86 with |psi'| J3 = H (Table 3-1); 80% generator efficiency (Sec. 3.2.10). Negative
    values mean the rotor costs more than the gimbal harvests (the black regions of Fig. 3-5).
    """
    if model not in SEAKEEPER:
        raise ValueError(f"model: one of {sorted(SEAKEEPER)}, got {model!r}")
    _, H, spool = SEAKEEPER[model]
    a = check_positive("amplitude", amplitude)
    T = check_positive("period", period)
    P = 0.5 * H * (a / g) * (2.0 * np.pi / T) ** 4 * math.sin(direction)
    return efficiency * P - spool


def power_map(
    model: str, heights: ArrayLike, periods: ArrayLike, efficiency: float = 0.8
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """Fig. 3-5: net power (W) over wave height H = 2a (m, rows) x period T (s, columns), and the
    mask of unbroken waves a / (g T^2) <= 0.01326 (Eq. 97)."""
    Hh = np.asarray(check_positive("heights", heights))[:, None]
    T = np.asarray(check_positive("periods", periods))[None, :]
    P = seakeeper_net_power(model, 0.5 * Hh, T, efficiency)
    ok = 0.5 * Hh / (G * T * T) <= BREAKING_STEEPNESS
    return P, np.broadcast_to(ok, P.shape)
