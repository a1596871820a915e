"""Muscle actuation of the serpentine beam as an active curvature kappa#(S, t) (Rios 2017 §4.5 II,
ch. 4 Eqs. 51-55: M_3 = EI (kappa - kappa#)).

Every gait here is a travelling wave with a ramp,

    kappa#(S, t) = r(t) a(S) sin(phi(S) - w t),   r(t) = min(1, t / t_ramp) (r = 1 if t_ramp = 0),

tabulated at the beam's Gauss points (a, phi: (n_el, 4)) so that the compiled time loop only
evaluates sines:

* `serpenoid`: Hirose's serpenoid curve, a constant, phi = 2 pi S / lambda (direction +1: the
  wave runs from S = 0 to S = L and the body crawls towards -S); direction -1 uses L - S, so the
  wave runs from the head S = L to the tail and the body advances towards +S.
* `elastica_muscles`: PyElastica's `MuscleTorques` (Gazzola et al. 2018) as a curvature. There,
  element k gets the couple +tau_k and element k - 1 the couple -tau_k at every interior
  junction k, tau(s) = beta(s) sin(w t - K s), s = 1 - S / L (the wave is indexed from the last
  element), beta the clamped cubic B-spline of the coefficients on [0, 1]. A couple pair across
  a junction is the virtual work sum_k tau_k (dpsi_k - dpsi_{k-1}), the discrete form of
  int M_a dpsi' dS with an active moment M_a = tau; in M_3 = EI (kappa - kappa#) that is
  kappa# = -tau / EI (sign: see `elastica_muscles`). The two differ only in how the moment is
  sampled (junctions vs Gauss points).
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np
from scipy.interpolate import BSpline

from mf_envs._validate import check_finite, check_nonnegative, check_positive


@dataclass(frozen=True)
class WaveGait:
    """a (n_el, 4) [1/m], phi (n_el, 4) [rad] at the Gauss points; w [rad/s]; ramp_time [s]."""

    amplitude: np.ndarray
    phase: np.ndarray
    omega: float
    ramp_time: float = 0.0

    def __post_init__(self) -> None:
        check_finite("amplitude", self.amplitude)
        check_finite("phase", self.phase)
        if np.shape(self.amplitude) != np.shape(self.phase):
            raise ValueError("phase: must have the shape of amplitude")
        check_finite("omega", self.omega)
        check_nonnegative("ramp_time", self.ramp_time)

    def kappa(self, t: float) -> np.ndarray:
        """kappa#(S_gauss, t) (n_el, 4) [1/m]."""
        out = np.empty(np.shape(self.amplitude))
        gait_kappa_into(self.amplitude, self.phase, self.omega, self.ramp_time, float(t), out)
        return out


def gait_for(gait: WaveGait | None, shape: tuple[int, int]) -> WaveGait:
    """The gait of a beam whose Gauss points are `shape` (n_el, 4): a passive one (zero
    amplitude) for None; ValueError naming `gait` if it is tabulated on another shape."""
    if gait is None:
        return WaveGait(np.zeros(shape), np.zeros(shape), 0.0)
    if np.shape(gait.amplitude) != shape:
        raise ValueError(f"gait: tabulated on {np.shape(gait.amplitude)}, the beam needs {shape}")
    return gait


def gait_tables(gait: WaveGait) -> tuple:
    """(a, phi, w, t_ramp) contiguous, the compiled run's `gait` (`stepping`)."""
    a, phi = (np.ascontiguousarray(x, float) for x in (gait.amplitude, gait.phase))
    return a, phi, float(gait.omega), float(gait.ramp_time)


@numba.njit(cache=True)
def gait_kappa_into(a, phi, w, t_ramp, t, out):
    """out = r(t) a sin(phi - w t) (module docstring)."""
    r = 1.0 if t_ramp <= 0.0 else min(1.0, t / t_ramp)
    for e in range(a.shape[0]):
        for g in range(a.shape[1]):
            out[e, g] = r * a[e, g] * np.sin(phi[e, g] - w * t)


def serpenoid(
    gauss_s: np.ndarray,
    amplitude: float,
    wavelength: float,
    period: float,
    direction: int = -1,
    ramp_time: float = 0.0,
) -> WaveGait:
    """kappa# = a sin(2 pi S / lambda - w t) (direction +1) or a sin(2 pi (L - S) / lambda - w t)
    written at the Gauss points gauss_s (n_el, 4) [m] (direction -1: the wave runs head (S = L)
    to tail, the body crawls towards +S). amplitude [1/m], wavelength [m], period [s]."""
    check_finite("amplitude", amplitude)
    check_positive("wavelength", wavelength)
    check_positive("period", period)
    if direction not in (1, -1):
        raise ValueError(f"direction: must be +1 or -1, got {direction!r}")
    s = np.asarray(gauss_s, float)
    length = float(np.max(s) + np.min(s))  # Gauss points are symmetric about L / 2
    x = s if direction == 1 else length - s
    k = 2.0 * np.pi / wavelength
    return WaveGait(np.full(s.shape, float(amplitude)), k * x, 2.0 * np.pi / period, ramp_time)


def elastica_spline(coefficients: np.ndarray) -> BSpline:
    """PyElastica's beta(s): clamped cubic B-spline of the coefficients, control points
    linspace(0, 1, n - 2) (`elastica.utils._bspline`, degree 3, no extrapolation)."""
    c = np.asarray(check_finite("coefficients", coefficients), float)
    if c.ndim != 1 or c.size < 4:
        raise ValueError(f"coefficients: need a 1-D array of >= 4 values, got shape {c.shape}")
    x = np.linspace(0.0, 1.0, c.size - 2)
    knots = np.concatenate([np.zeros(3), x, np.ones(3)])
    return BSpline(knots, c, 3, extrapolate=False)


def elastica_muscles(
    gauss_s: np.ndarray,
    length: float,
    bending_stiffness: float,
    coefficients: np.ndarray,
    wavelength: float,
    period: float,
    ramp_time: float,
) -> WaveGait:
    """PyElastica's MuscleTorques (module docstring) as kappa# at the Gauss points:
    kappa# = -beta(s) sin(w t - K s) / EI = beta(s) sin(K s - w t) / EI, s = 1 - S / L,
    K = 2 pi / wavelength (wavelength in units of L, as PyElastica's), w = 2 pi / period.

    The sign fixes the handedness only (a mirror image crawls at the same speed)."""
    check_positive("length", length)
    check_positive("bending_stiffness", bending_stiffness)
    check_positive("wavelength", wavelength)
    check_positive("period", period)
    s = 1.0 - np.asarray(gauss_s, float) / length
    beta = elastica_spline(coefficients)(s)
    k = 2.0 * np.pi / wavelength
    return WaveGait(beta / bending_stiffness, k * s, 2.0 * np.pi / period, ramp_time)
