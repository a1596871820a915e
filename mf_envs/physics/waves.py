"""Linear (Airy) ocean waves: dispersion, energy, power, wave-slope buoy rocking, irregular seas.

Rios 2017, ch. 3 Eqs. 12-19 (dispersion, velocities, energy, power per metre of crest), Eqs. 77-78
and 89-93 (a buoy that rocks with the wave slope), Eq. 97 (breaking limit). SI units throughout;
the inertial frame has x3 up and the still water surface at x3 = 0 (ch. 3 Fig. 3-1).

    eta(x1, x2, t) = sum_i a_i cos(k_i (x1 cos(theta) + x2 sin(theta)) - w_i t + eps_i)   (Eq. 89)

theta is the direction of travel measured from x1 (theta = pi/2: head-on along x2, Eq. 76).
The buoy attitude follows the surface normal: R = rot_x(beta1) rot_y(beta2) with
beta1 = d eta/d x2 (Eq. 90) and beta2 = -d eta/d x1. (The seed's Eq. 91 writes +d eta/d x1; its
sign is immaterial for the power, which only involves omega_1, but the minus sign is what tilts
e3 onto the surface normal (-eta_x1, -eta_x2, 1).)

Finite buoy (not in the seed): a buoy of waterplane radius r does not follow waves shorter than
itself. We model its attitude as following the wave slope AVERAGED over its circular waterplane.
The slope of a plane wave a cos(k n.x - w t + eps) is itself a plane wave, and the mean of
exp(i k n.x) over a disk of radius r is (polar coordinates, Bessel's integral J0, then
int_0^q s J0(s) ds = q J1(q))

    (1 / (pi r^2)) int_0^r int_0^2pi exp(i k rho cos(t)) rho dt drho = 2 J1(k r) / (k r)

(the Airy/circular-aperture factor), so every component's slope (hence the buoy angles, rates
and accelerations) is scaled by F(k r) = 2 J1(k r)/(k r), -> 1 for k r -> 0 (point buoy, the
seed's Eqs. 77-78, 90-93; `buoy_radius = 0`). F ~ (k r)^(-3/2) for large k r, which makes the
slope-rate spectrum w^2 (k F)^2 S(w) integrable: without it (deep water, S ~ w^-5) it grows ~ w
and the buoy rates of an irregular sea depend on the spectral cut-off.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.special import j1

from mf_envs._validate import (
    check_finite,
    check_int,
    check_nonnegative,
    check_positive,
    nonnegative_scalar,
    positive_scalar,
)
from mf_envs.physics.constants import RHO_SEAWATER, G  # G re-exported: waves.G (ch. 3 Eq. 15)

BREAKING_STEEPNESS = 1.0 / (24.0 * math.pi)  # a/(g T^2) at a 30 deg crest slope (Eq. 97: 0.01326)


# ---------------------------------------------------------------------- dispersion (Eqs. 13-14)
def wavenumber(omega: ArrayLike, depth: float = math.inf, g: float = G) -> NDArray[np.float64]:
    """k (rad/m) solving w^2 = g k tanh(k D) (Eq. 13), vectorised over omega (rad/s).

    Start from the explicit approximation of Fenton & McKee (1990), then Newton to round-off.
    depth = inf gives the deep-water k = w^2/g.
    """
    w = check_positive("omega", omega)
    if not (isinstance(depth, (int, float)) and depth > 0 and not math.isnan(depth)):
        raise ValueError(f"depth: must be > 0 (inf = deep water), got {depth!r}")
    k0 = w * w / g
    if math.isinf(depth):
        return k0
    x0 = k0 * depth
    y = x0 / np.tanh(x0**0.75) ** (2.0 / 3.0)  # y = k D
    for _ in range(50):
        th = np.tanh(y)
        f = y * th - x0
        df = th + y * (1.0 - th * th)
        dy = f / df
        y = y - dy
        if np.all(np.abs(dy) <= 1e-15 * np.maximum(y, 1e-300)):
            break
    return y / depth


def wavelength(period: ArrayLike, depth: float = math.inf, g: float = G) -> NDArray[np.float64]:
    """lambda = 2 pi / k (m) for the period T (s) (Eq. 13); deep water: g T^2 / (2 pi)."""
    T = check_positive("period", period)
    return 2.0 * np.pi / wavenumber(2.0 * np.pi / T, depth, g)


def phase_velocity(omega: ArrayLike, depth: float = math.inf, g: float = G) -> NDArray[np.float64]:
    """c_p = w / k (m/s) (Eq. 13)."""
    return check_positive("omega", omega) / wavenumber(omega, depth, g)


def group_velocity(omega: ArrayLike, depth: float = math.inf, g: float = G) -> NDArray[np.float64]:
    """c_g = dw/dk = c_p/2 (1 + 2kD / sinh(2kD)) (m/s) (Eq. 14); deep water c_p/2."""
    k = wavenumber(omega, depth, g)
    cp = check_positive("omega", omega) / k
    if math.isinf(depth):
        return 0.5 * cp
    x = 2.0 * k * depth
    ratio = np.where(x < 700.0, x / np.sinh(np.minimum(x, 700.0)), 0.0)
    return 0.5 * cp * (1.0 + ratio)


# ---------------------------------------------------------------------- energy and power (15-19)
def energy_density(amplitude: ArrayLike, rho: float = RHO_SEAWATER, g: float = G) -> NDArray:
    """E = rho g a^2 / 2 (J/m^2) per unit horizontal area of a harmonic wave (Eq. 15)."""
    a = check_finite("amplitude", amplitude)
    return 0.5 * rho * g * a * a


def amplitude_from_hs(hs: ArrayLike) -> NDArray[np.float64]:
    """Equivalent harmonic amplitude a = Hs / (2 sqrt 2) (m) (Eq. 16)."""
    return np.asarray(check_positive("hs", hs)) / (2.0 * math.sqrt(2.0))


def energy_density_hs(hs: ArrayLike, rho: float = RHO_SEAWATER, g: float = G) -> NDArray:
    """E = rho g Hs^2 / 16 (J/m^2) (Eq. 17)."""
    h = check_positive("hs", hs)
    return rho * g * h * h / 16.0


def power_per_metre(
    hs: ArrayLike,
    period: ArrayLike,
    depth: float = math.inf,
    rho: float = RHO_SEAWATER,
    g: float = G,
) -> NDArray[np.float64]:
    """P = E c_g (W per metre of crest) with E from Hs (Eqs. 17-18)."""
    T = check_positive("period", period)
    return energy_density_hs(hs, rho, g) * group_velocity(2.0 * np.pi / T, depth, g)


def deep_water_power_per_metre(
    hs: ArrayLike, period: ArrayLike, rho: float = RHO_SEAWATER, g: float = G
) -> NDArray[np.float64]:
    """P = rho g^2 Hs^2 T / (64 pi) (W/m), ~0.48 Hs^2 T kW/m (Eq. 19)."""
    h, T = check_positive("hs", hs), check_positive("period", period)
    return rho * g * g * h * h * T / (64.0 * math.pi)


def breaking_amplitude(period: ArrayLike, g: float = G) -> NDArray[np.float64]:
    """Largest deep-water amplitude before breaking, a = g T^2 / (24 pi) (m) (Eq. 97).

    From the 120 deg limiting crest angle: slope a k <= pi/6 with k = 4 pi^2 / (g T^2), i.e.
    a / (g T^2) <= 1/(24 pi) = 0.013263 (the seed's 0.01326).
    """
    T = check_positive("period", period)
    return BREAKING_STEEPNESS * g * T * T


# ---------------------------------------------------------------------- spectra
def pierson_moskowitz_spectrum(omega: ArrayLike, hs: float, tp: float) -> NDArray[np.float64]:
    """One-sided Pierson-Moskowitz S(w) (m^2 s/rad) by Hs (m) and peak period Tp (s).

    S = 5/16 Hs^2 wp^4 w^-5 exp(-5/4 (wp/w)^4), wp = 2 pi / Tp; its m0 = Hs^2 / 16 exactly
    (DNV-RP-C205 Eq. 3.5.5.1).
    """
    w = np.asarray(check_finite("omega", omega))
    check_positive("hs", hs)
    check_positive("tp", tp)
    wp = 2.0 * math.pi / tp
    out = np.zeros_like(w, dtype=np.float64)
    pos = w > 0
    r = wp / w[pos]
    out[pos] = 5.0 / 16.0 * hs * hs * r**4 / w[pos] * np.exp(-1.25 * r**4)
    return out


@lru_cache(maxsize=64)
def _jonswap_norm(gamma: float) -> float:
    """1 / integral of the unit-Hs, unit-wp JONSWAP shape (so that m0 = Hs^2/16 exactly)."""

    from scipy.integrate import quad  # here: importing scipy.integrate costs every env ~0.5 s

    def shape(x: float) -> float:
        return float(_jonswap_shape(np.array([x]), 1.0, gamma)[0])

    m0, _ = quad(shape, 0.0, np.inf, limit=400, points=None)
    return (1.0 / 16.0) / m0


def _jonswap_shape(omega: NDArray, wp: float, gamma: float) -> NDArray[np.float64]:
    w = omega
    out = np.zeros_like(w, dtype=np.float64)
    pos = w > 0
    r = wp / w[pos]
    sigma = np.where(w[pos] <= wp, 0.07, 0.09)
    peak = gamma ** np.exp(-0.5 * ((w[pos] - wp) / (sigma * wp)) ** 2)
    out[pos] = 5.0 / 16.0 * r**4 / w[pos] * np.exp(-1.25 * r**4) * peak
    return out


def jonswap_spectrum(omega: ArrayLike, hs: float, tp: float, gamma: float = 3.3) -> NDArray:
    """One-sided JONSWAP S(w) (m^2 s/rad): Pierson-Moskowitz times gamma^exp(-(w-wp)^2 /
    (2 sigma^2 wp^2)), sigma = 0.07 (w <= wp) / 0.09, scaled so that m0 = Hs^2/16 exactly
    (DNV-RP-C205 3.5.5; its A_gamma = 1 - 0.287 ln(gamma) is the approximate scaling).
    """
    w = np.asarray(check_finite("omega", omega), dtype=np.float64)
    check_positive("hs", hs)
    check_positive("tp", tp)
    check_positive("gamma", gamma)
    wp = 2.0 * math.pi / tp
    # shape(w; wp) = shape(w/wp; 1) / wp, so the normalisation depends on gamma only
    return hs * hs * _jonswap_norm(float(gamma)) * _jonswap_shape(w, wp, gamma)


# ---------------------------------------------------------------------- finite buoy response
def disk_average_factor(kr: ArrayLike) -> NDArray[np.float64]:
    """F = 2 J1(k r) / (k r) (dimensionless): the mean of a plane wave's slope over a disk of
    radius r, relative to the slope at the centre (module doc). kr = k r >= 0 (k rad/m, r m);
    F(0) = 1 (series 1 - (kr)^2/8 + ... below 1e-4)."""
    x = np.asarray(check_nonnegative("kr", kr), dtype=np.float64)
    small = x < 1e-4
    xs = np.where(small, 1.0, x)
    return np.where(small, 1.0 - x * x / 8.0, 2.0 * j1(xs) / xs)


# ---------------------------------------------------------------------- wave fields
@dataclass(frozen=True)
class WaveField:
    """Long-crested sum of harmonics (Eq. 89): amplitudes a (m), omegas w (rad/s), phases eps
    (rad), wavenumbers k (rad/m), direction theta (rad from x1; pi/2 = head-on along x2),
    buoy_radius r (m) of the waterplane over which the buoy averages the slope (0 = point buoy).
    """

    amplitudes: NDArray[np.float64]
    omegas: NDArray[np.float64]
    phases: NDArray[np.float64]
    wavenumbers: NDArray[np.float64]
    direction: float = math.pi / 2
    buoy_radius: float = 0.0

    def __post_init__(self) -> None:
        check_nonnegative("buoy_radius", self.buoy_radius)

    @property
    def slope_response(self) -> NDArray[np.float64]:
        """F_i = 2 J1(k_i r)/(k_i r) (n,): waterplane-averaged / point slope of each component."""
        return disk_average_factor(self.wavenumbers * self.buoy_radius)

    @property
    def slope_wavenumbers(self) -> NDArray[np.float64]:
        """k_i F_i (n,) rad/m: the buoy angles are sum a_i k_i F_i (...) (Eqs. 90-93 averaged)."""
        return self.wavenumbers * self.slope_response

    @property
    def components(self) -> tuple[NDArray, NDArray, NDArray]:
        """(amplitudes (n,) m, omegas (n,) rad/s, phases (n,) rad)."""
        return self.amplitudes, self.omegas, self.phases

    def _arg(self, t: ArrayLike, x1: ArrayLike, x2: ArrayLike) -> NDArray[np.float64]:
        t, x1, x2 = (np.asarray(v, dtype=np.float64)[..., None] for v in (t, x1, x2))
        c, s = math.cos(self.direction), math.sin(self.direction)
        return self.wavenumbers * (x1 * c + x2 * s) - self.omegas * t + self.phases

    def elevation(self, t: ArrayLike, x: ArrayLike = 0.0, x2: ArrayLike = 0.0) -> NDArray:
        """eta (m) at time t (s) and point (x, x2) (m) (Eq. 89); broadcasts t, x, x2."""
        return np.sum(self.amplitudes * np.cos(self._arg(t, x, x2)), axis=-1)

    def slope_angles(self, t: ArrayLike) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """(beta1, beta1', beta1'', beta2, ...) at the origin: beta1 = d eta/d x2 (Eq. 90),
        beta2 = -d eta/d x1 (see module doc). Returns (b1, b1d, b1dd), (b2, b2d, b2dd) stacked
        as an array (2, 3, ...). Slopes are averaged over the buoy waterplane (`slope_response`)."""
        arg = self._arg(t, 0.0, 0.0)
        ak = self.amplitudes * self.slope_wavenumbers
        sa, ca = np.sin(arg), np.cos(arg)
        w = self.omegas
        # d eta / d(n . x) = -a k sin(arg); time derivatives: d arg/dt = -w
        g0 = -np.sum(ak * sa, axis=-1)
        g1 = np.sum(ak * w * ca, axis=-1)
        g2 = np.sum(ak * w * w * sa, axis=-1)
        c, s = math.cos(self.direction), math.sin(self.direction)
        return np.array([[s * g0, s * g1, s * g2], [-c * g0, -c * g1, -c * g2]])

    def buoy_motion(self, t: float) -> tuple[NDArray, NDArray, NDArray]:
        """Buoy attitude R = rot_x(beta1) rot_y(beta2) (3,3), body rates omega (3,) rad/s and
        omega' (3,) rad/s^2 (Eqs. 77-78, 90-93 with the exact rates of this parameterisation)."""
        (b1, b1d, b1dd), (b2, b2d, b2dd) = self.slope_angles(t)
        return buoy_rotation(b1, b1d, b1dd, b2, b2d, b2dd)


def buoy_rotation(b1: float, b1d: float, b1dd: float, b2: float, b2d: float, b2dd: float):
    """R = rot_x(b1) rot_y(b2), omega = R^T R' (body) and omega' for given angle histories."""
    c1, s1, c2, s2 = math.cos(b1), math.sin(b1), math.cos(b2), math.sin(b2)
    Rx = np.array([[1.0, 0, 0], [0, c1, -s1], [0, s1, c1]])
    Ry = np.array([[c2, 0, s2], [0, 1.0, 0], [-s2, 0, c2]])
    # omega = Ry^T (b1d e1) + b2d e2 = (b1d c2, b2d, b1d s2)
    w = np.array([b1d * c2, b2d, b1d * s2])
    wd = np.array([b1dd * c2 - b1d * s2 * b2d, b2dd, b1dd * s2 + b1d * c2 * b2d])
    return Rx @ Ry, w, wd


def regular_wave(
    amplitude: float,
    period: float,
    direction: float = math.pi / 2,
    depth: float = math.inf,
    phase: float = 0.0,
    buoy_radius: float = 0.0,
) -> WaveField:
    """A single harmonic, eta = a cos(k x.n - w t + phase) (Eqs. 76, 89); buoy_radius (m) of the
    slope-averaging waterplane (0 = point buoy)."""
    check_positive("amplitude", amplitude)
    T = positive_scalar("period", period)
    check_finite("direction", direction)
    w = np.array([2.0 * math.pi / T])
    return WaveField(
        np.array([float(amplitude)]),
        w,
        np.array([float(phase)]),
        wavenumber(w, depth),
        float(direction),
        nonnegative_scalar("buoy_radius", buoy_radius),
    )


class IrregularSea(WaveField):
    """Random-phase irregular sea from a one-sided spectrum (long-crested).

    spectrum_fn(omega, hs, tp) -> S (m^2 s/rad), e.g. `jonswap_spectrum`; n_components equal
    bins over [w_lo, w_hi] = [0.2, 4] wp (or `omega_range`), each harmonic at a random frequency
    inside its bin (avoids the repeat period 2 pi / dw), amplitude a_i = sqrt(2 S(w_i) dw) and
    phase uniform in [0, 2 pi) -- both drawn from `rng` (a numpy Generator) for reproducibility.
    The default upper bound 4 wp is where JONSWAP (gamma = 3.3) falls to 1e-3 of its peak
    (4.02 wp); with a finite `buoy_radius` (m) the buoy rates converge well below it (the
    slope-rate spectrum w^2 (k F)^2 S decays like w^-5), with a point buoy they do not.
    """

    def __init__(
        self,
        spectrum_fn: Callable[..., NDArray],
        hs: float,
        tp: float,
        n_components: int,
        rng: np.random.Generator,
        direction: float = math.pi / 2,
        depth: float = math.inf,
        omega_range: tuple[float, float] | None = None,
        buoy_radius: float = 0.0,
    ) -> None:
        check_positive("hs", hs)
        check_positive("tp", tp)
        n = check_int("n_components", n_components, low=1)
        if not isinstance(rng, np.random.Generator):
            raise ValueError(f"rng: expected a numpy.random.Generator, got {type(rng).__name__}")
        wp = 2.0 * math.pi / tp
        lo, hi = omega_range if omega_range is not None else (0.2 * wp, 4.0 * wp)
        check_positive("omega_range", (lo, hi))
        if hi <= lo:
            raise ValueError(f"omega_range: need lo < hi, got {(lo, hi)}")
        edges = np.linspace(lo, hi, n + 1)
        dw = edges[1] - edges[0]
        w = edges[:-1] + rng.uniform(0.0, 1.0, n) * dw
        a = np.sqrt(2.0 * spectrum_fn(w, hs, tp) * dw)
        eps = rng.uniform(0.0, 2.0 * math.pi, n)
        r = nonnegative_scalar("buoy_radius", buoy_radius)
        super().__init__(a, w, eps, wavenumber(w, depth), float(direction), r)
        object.__setattr__(self, "hs", float(hs))
        object.__setattr__(self, "tp", float(tp))
