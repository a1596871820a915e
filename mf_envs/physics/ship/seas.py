"""Seas met at a heading and a forward speed: encounter frequency, spreading, roll excitation.

Heading convention (Fossen 2011, *Handbook of Marine Craft Hydrodynamics and Motion Control*,
§10.2; Faltinsen 1990 ch. 2): beta is the angle from the ship's heading (its e_1, forward) to
the direction in which the waves TRAVEL, positive towards port (e_2):

    beta = 0 following sea,  pi/4 stern-quartering,  pi/2 beam sea (from starboard),
    3 pi/4 bow-quartering,  pi head sea.

A ship at speed U (m/s) meets a deep-water component of frequency w (rad/s), wavenumber
k = w^2 / g at the encounter frequency (the Doppler shift of the wave phase at x = U t)

    w_e = w - k U cos(beta) = w - w^2 U cos(beta) / g.

In a following or quartering sea w_e can be small or negative (the ship overtakes the waves);
it is kept signed (a negative w_e is the same wave seen running backwards).

Roll excitation: the Froude-Krylov moment of a narrow wall-sided hull in waves long against its
beam (the effective-wave-slope model of `wave_table` below, now with heading and length): the
waterplane tilts with the transverse wave slope d eta / d y averaged over the waterline length,

    M_4(t) = sum_i C44 r_eff k_i a_i sin(beta_i) L_i sin(w_e,i t - eps_i),
    L_i = sinc(k_i L_wl cos(beta_i) / 2),  sinc(x) = sin(x) / x,

with r_eff <= 1 the effective-slope coefficient (beam and depth attenuation, 1 for a narrow
hull) and L_wl the waterline length. The heave force rho g A_wp eta is averaged the same way
(times sinc(k_i B sin(beta_i) / 2) over the beam). A head or following sea (sin beta = 0)
excites no roll; at beta = pi/2 and U = 0 this is the beam-sea model of `wave_table` exactly.
This is an excitation model, not a strip-theory transfer function: no diffraction, no
radiation; the hull's roll damping and added inertia come from the `ShipParams`.

Short-crested seas: the directional spectrum S(w) D(theta) with the cos-2s spreading
D(theta) = Gamma(1 + s) / (sqrt(pi) Gamma(1/2 + s)) cos^(2s)(theta), |theta| <= pi/2
(DNV-RP-C205 (2010) Eq. 3.5.8 with n = 2s; its integral is 1), theta about the mean direction.
It is discretised with one random direction per frequency component (single-direction-per-
frequency method), drawn from D by inverse transform sampling, so the sum stays a Gaussian sea
without phase locking.

Beam-sea tables (`wave_table`, `regular_heave_force`; effect `irregular_waves` in the seed's
beam-sea scenes). Roll-moment model (effective wave slope, beam seas; Fossen 2011 §10.2 /
Faltinsen 1990 ch. 3):
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
from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import gammaln

from mf_envs._validate import (
    check_finite,
    check_int,
    check_nonnegative,
    check_positive,
    finite_scalar,
    positive_scalar,
)
from mf_envs.physics.constants import G
from mf_envs.physics.waves import jonswap_spectrum


def encounter_frequency(
    omega: ArrayLike, speed: float, heading: ArrayLike, g: float = G
) -> NDArray[np.float64]:
    """w_e = w - w^2 U cos(beta) / g (rad/s), signed (module doc); omega rad/s, speed m/s,
    heading beta rad (0 following, pi head)."""
    w = np.asarray(check_finite("omega", omega), dtype=np.float64)
    b = np.asarray(check_finite("heading", heading), dtype=np.float64)
    u = finite_scalar("speed", speed)
    return w - w * w * u * np.cos(b) / g


def sinc(x: ArrayLike) -> NDArray[np.float64]:
    """sin(x) / x with sinc(0) = 1 (numpy's normalised `np.sinc` at x / pi)."""
    return np.sinc(np.asarray(x, dtype=np.float64) / np.pi)


def spreading_density(theta: ArrayLike, s: float) -> NDArray[np.float64]:
    """cos-2s spreading D(theta) (1/rad), |theta| <= pi/2 about the mean direction (module doc)."""
    th = np.asarray(check_finite("theta", theta), dtype=np.float64)
    s = positive_scalar("spreading", s)
    c = math.exp(gammaln(1.0 + s) - gammaln(0.5 + s)) / math.sqrt(math.pi)
    inside = np.abs(th) <= 0.5 * math.pi
    return np.where(inside, c * np.abs(np.cos(np.where(inside, th, 0.0))) ** (2.0 * s), 0.0)


def sample_spreading(s: float, n: int, rng: np.random.Generator) -> NDArray[np.float64]:
    """n directions (rad, about the mean) drawn from the cos-2s density by inverse transform of
    its cumulative on a 4001-point grid (trapezoidal)."""
    grid = np.linspace(-0.5 * math.pi, 0.5 * math.pi, 4001)
    pdf = spreading_density(grid, s)
    cdf = np.concatenate(([0.0], np.cumsum(0.5 * (pdf[1:] + pdf[:-1]) * np.diff(grid))))
    return np.interp(rng.uniform(0.0, cdf[-1], n), cdf, grid)


@dataclass(frozen=True)
class SeaComponents:
    """A sea as harmonic components met by the ship: amplitudes a (n,) m, frequencies w (n,)
    rad/s (absolute), headings beta (n,) rad (module convention), phases eps (n,) rad."""

    amplitudes: NDArray[np.float64]
    omegas: NDArray[np.float64]
    headings: NDArray[np.float64]
    phases: NDArray[np.float64]

    def encounter(self, speed: float) -> NDArray[np.float64]:
        """Encounter frequencies w_e (n,) rad/s at ship speed (m/s)."""
        return encounter_frequency(self.omegas, speed, self.headings)


def jonswap_sea(
    hs: float,
    tp: float,
    heading: float,
    rng: np.random.Generator,
    n_components: int = 64,
    spreading: float | None = None,
    gamma: float = 3.3,
) -> SeaComponents:
    """A JONSWAP sea (`physics.waves.jonswap_spectrum`, m0 = Hs^2/16) met at mean heading beta.

    hs (m), tp (s); n_components equal bins over [0.2, 4] w_p, each at a random frequency inside
    its bin, a_i = sqrt(2 S(w_i) dw), phases uniform; spreading s of the cos-2s law (None:
    long-crested, every component at `heading`). All randomness from `rng`.
    """
    check_positive("hs", hs)
    check_positive("tp", tp)
    check_finite("heading", heading)
    n = check_int("n_components", n_components, low=1)
    wp = 2.0 * math.pi / tp
    edges = np.linspace(0.2 * wp, 4.0 * wp, n + 1)
    dw = edges[1] - edges[0]
    w = edges[:-1] + rng.uniform(0.0, 1.0, n) * dw
    a = np.sqrt(2.0 * jonswap_spectrum(w, hs, tp, gamma) * dw)
    eps = rng.uniform(0.0, 2.0 * math.pi, n)
    beta = np.full(n, float(heading))
    if spreading is not None:
        beta = beta + sample_spreading(spreading, n, rng)
    return SeaComponents(a, w, beta, eps)


def regular_sea(amplitude: float, period: float, heading: float, phase: float = 0.0):
    """One regular component eta = a cos(k x.n - w t + phase) (m, s, rad, rad)."""
    check_nonnegative("amplitude", amplitude)
    w = 2.0 * math.pi / positive_scalar("period", period)
    one = np.ones(1)
    return SeaComponents(amplitude * one, w * one, float(heading) * one, float(phase) * one)


def roll_moment_gains(
    sea: SeaComponents,
    roll_stiffness: float,
    length: float,
    r_eff: float = 1.0,
) -> NDArray[np.float64]:
    """m_i (n,) N m: roll-moment amplitude per component, C44 r_eff k a sin(beta) sinc(...)
    (module doc); roll_stiffness N m/rad, length L_wl m (0: a point hull)."""
    check_nonnegative("roll_stiffness", roll_stiffness)
    check_nonnegative("length", length)
    check_nonnegative("r_eff", r_eff)
    w, b = sea.omegas, sea.headings
    k = w * w / G
    lf = sinc(0.5 * k * length * np.cos(b))
    return roll_stiffness * r_eff * w * w / G * sea.amplitudes * np.sin(b) * lf


def heave_force_gains(
    sea: SeaComponents, heave_stiffness: float, length: float, beam: float
) -> NDArray[np.float64]:
    """f_i (n,) N: heave-force amplitude per component, rho g A_wp a L_i sinc(k B sin(beta)/2)."""
    check_nonnegative("heave_stiffness", heave_stiffness)
    k = sea.omegas**2 / G
    lf = sinc(0.5 * k * length * np.cos(sea.headings))
    bf = sinc(0.5 * k * beam * np.sin(sea.headings))
    return heave_stiffness * sea.amplitudes * lf * bf


def excitation_table(
    sea: SeaComponents,
    speed: float,
    roll_stiffness: float,
    heave_stiffness: float,
    length: float,
    beam: float,
    t_end: float,
    h: float,
    r_eff: float = 1.0,
) -> NDArray[np.float64]:
    """(N, 2) table [M_4 (N m), F_3 (N)] at t = 0, h, 2h, ... >= t_end (s) met at `speed` (m/s):
    M_4 = sum m_i sin(w_e,i t - eps_i), F_3 = sum f_i cos(w_e,i t - eps_i) (module doc), in the
    layout `kernels.table_value` reads."""
    check_positive("t_end", t_end)
    check_positive("h", h)
    we = sea.encounter(speed)
    m = roll_moment_gains(sea, roll_stiffness, length, r_eff)
    f = heave_force_gains(sea, heave_stiffness, length, beam)
    n = int(np.ceil(t_end / h)) + 2
    return _table_kernel(sea.amplitudes, we, sea.phases, m, f, float(h), n)


def regular_roll_moment(
    moment_amplitude: float, period: float, heading: float, speed: float, length: float
) -> tuple[float, float]:
    """(amplitude in N m, encounter frequency w_e in rad/s) of the roll moment of a regular wave
    whose beam-sea moment amplitude is M0 (N m): M0 sin(beta) sinc(k L cos(beta) / 2), met at
    w_e (module doc). period s, heading rad, speed m/s, length L_wl m."""
    sea = regular_sea(1.0, period, heading)
    k = float(sea.omegas[0]) ** 2 / G
    gain = math.sin(heading) * float(sinc(0.5 * k * length * math.cos(heading)))
    return finite_scalar("moment_amplitude", moment_amplitude) * gain, float(
        sea.encounter(speed)[0]
    )


# ---------------------------------------------------------------- beam-sea tables
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
