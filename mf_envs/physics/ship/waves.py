"""Wave roll moment and heave force on the hull from an irregular sea (effect `irregular_waves`).

Roll-moment model (effective wave slope, beam seas; Fossen 2011 §10.2 / Faltinsen 1990 ch. 3):
a ship whose beam is small against the wave length feels the local wave slope alpha(t) as a
tilt of the waterplane, so the Froude-Krylov roll moment is the hydrostatic stiffness times an
effective slope

    M_4(t) = C44 r_eff alpha(t),   alpha(t) = sum_i k_i a_i sin(w_i t - eps_i),  k_i = w_i^2 / g,

with r_eff <= 1 the effective-slope coefficient (1 for a narrow hull). The heave force of a long
wave is F_3(t) = rho g A_wp eta(t), eta(t) = sum_i a_i cos(w_i t - eps_i). These are the
elevation and the slope d eta / d x2 at the ship (x = 0) of `waves.WaveField`
(eta = sum a cos(k x2 - w t + eps)). A regular wave of moment amplitude M0 is the
one-component case with a = M0 / (C44 r_eff k).

The components (a_i, w_i, eps_i) come from `mf_envs.physics.waves.IrregularSea(...).components`
(a JONSWAP or Pierson-Moskowitz sea seeded by a numpy Generator). The moment is tabulated once
per episode so a step costs one interpolation, whatever the number of components.
"""

from __future__ import annotations

import math

import numba
import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import check_finite, check_nonnegative, check_positive
from mf_envs.physics.constants import G


def wave_table(
    amplitudes: ArrayLike,
    omegas: ArrayLike,
    phases: ArrayLike,
    roll_stiffness: float,
    heave_stiffness: float,
    t_end: float,
    h: float,
    r_eff: float = 1.0,
) -> NDArray[np.float64]:
    """(N, 2) table [M_4 (N m), F_3 (N)] sampled at t = 0, h, 2h, ... >= t_end (module doc).

    amplitudes (m), omegas (rad/s), phases (rad): (n,) wave components; roll_stiffness C44
    (N m/rad); heave_stiffness rho g A_wp (N/m); h: sampling step (s).
    """
    a = check_nonnegative("amplitudes", amplitudes).ravel()
    w = check_positive("omegas", omegas).ravel()
    eps = check_finite("phases", phases).ravel()
    if not (a.shape == w.shape == eps.shape):
        raise ValueError("amplitudes: amplitudes, omegas and phases must have the same length")
    check_nonnegative("roll_stiffness", roll_stiffness)
    check_nonnegative("heave_stiffness", heave_stiffness)
    check_positive("t_end", t_end)
    check_positive("h", h)
    check_nonnegative("r_eff", r_eff)
    n = int(np.ceil(t_end / h)) + 2
    return _table_kernel(
        a, w, eps, roll_stiffness * r_eff * w * w / G * a, heave_stiffness * a, float(h), n
    )


@numba.njit(cache=True)
def _table_kernel(a, w, eps, cm, cf, h, n):
    """sum_i cm_i sin(w_i t_j - eps_i), sum_i cf_i cos(w_i t_j - eps_i) at t_j = j h: each
    harmonic advanced by the rotation exp(i w h) (no trig per sample; round-off ~ n eps)."""
    out = np.zeros((n, 2))
    for k in range(a.shape[0]):
        zr, zi = math.cos(eps[k]), -math.sin(eps[k])
        rr, ri = math.cos(w[k] * h), math.sin(w[k] * h)
        for j in range(n):
            out[j, 0] += cm[k] * zi
            out[j, 1] += cf[k] * zr
            zr, zi = zr * rr - zi * ri, zr * ri + zi * rr
    return out


def regular_heave_force(
    moment_amplitude: float,
    period: float,
    roll_stiffness: float,
    heave_stiffness: float,
    r_eff: float = 1.0,
) -> float:
    """Heave force amplitude (N) of the regular wave whose roll moment amplitude is M0 (module
    doc: a = M0 / (C44 r_eff k), F = rho g A_wp a); 0 without roll stiffness."""
    if roll_stiffness <= 0.0 or r_eff <= 0.0:
        return 0.0
    k = (2.0 * np.pi / period) ** 2 / G
    return float(heave_stiffness * abs(moment_amplitude) / (roll_stiffness * r_eff * k))
