"""Gyroscopic ocean wave energy converter (GOWEC): gimbal equation fast path and power.

Rios 2017, ch. 3 Sec. 3.2 (Eqs. 76-97). One gyroscope of the dual unit (the power of the device is
twice the numbers here, Sec. 3.2.3):

         wave -> buoy (1) rocks, omega^(1) prescribed by the wave slope (Eqs. 77-78, 90-93)
        +--------------------------------+
        |   gimbal (2): free about e2^(1), angle phi, generator torque M_g opposes phi'
        |     +-----------+
        |     |  rotor (3) spins about e3^(2) at the prescribed rate psi' (motor)
        |     +-----------+
        +--------------------------------+

With the buoy rotation prescribed, Lagrange's equation for phi is exact (the gimbal/rotor centre
of mass on the gimbal axis). Gimbal-frame buoy rates O1 = cos(phi) w1 - sin(phi) w3,
O3 = sin(phi) w1 + cos(phi) w3; rotor inertias Jt (transverse), Ja (axial); gimbal (Jg1, Jg2, Jg3):

    (Jg2 + Jt)(phi'' + w2') - (Jg3 - Jg1 - Jt) O1 O3 - Ja (O3 + psi') O1 + M_g = 0

For a thin disk (Jt = Ja/2), no gimbal inertia and w2 = w3 = 0 (Eq. 79) this is

    Ja { 1/2 phi'' - 1/4 w1^2 sin(2 phi) - w1 psi' cos(phi) } + M_g = 0        (Eq. 81)

(the seed's Eq. 80 has + w1^2/4 sin(2 phi); Eq. 81 and Lagrange have the minus sign). With the
rotor off (psi' = 0) phi = 0 is unstable: the gimbal turns toward +-90 deg. `gowec_engine` checks
this fast path against the general multibody engine. Power P = M_g phi' (Eq. 82, positive =
harvested); with phi = w t locked to the wave the mean is Eq. 86/95; the ceiling over all gimbal
motions is 4/pi times that (a square-wave sin(phi)).
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numba
import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import check_finite, check_nonnegative, check_positive, check_shape
from mf_envs.physics.waves import BREAKING_STEEPNESS, G, WaveField, disk_average_factor

SQUARE_WAVE_GAIN = 4.0 / math.pi  # ceiling / Eq. 86 (docs/design.md)
RPM = 2.0 * math.pi / 60.0

# Seakeeper gyro stabilizers (ch. 3 Table 3-1): model -> (rotor rpm, angular momentum N m s,
# spool-up (rotor) power consumption W)
SEAKEEPER: dict[str, tuple[float, float, float]] = {
    "3DC": (6400.0, 3000.0, 900.0),
    "5": (10700.0, 5000.0, 2000.0),
    "9": (9000.0, 9000.0, 2000.0),
    "16": (6130.0, 16000.0, 3000.0),
    "26": (5000.0, 26000.0, 3000.0),
    "35": (5150.0, 35000.0, 5000.0),
}


@dataclass(frozen=True)
class GOWECParams:
    """Inertias (kg m^2) and rotor speed (rad/s) of one gyroscope of the GOWEC.

    Defaults: Seakeeper 26 (Table 3-1: H = 26000 N m s at 5000 rpm, so Ja = H / psi'), thin disk
    (Jt = Ja/2, Eq. 79), gimbal inertia about its axes `gimbal_inertia` (used when the
    `gimbal_inertia` effect is on).
    """

    rotor_inertia: float = 26000.0 / (5000.0 * RPM)  # Ja = J3^(3), kg m^2
    rotor_speed: float = 5000.0 * RPM  # psi', rad/s
    rotor_transverse_inertia: float | None = None  # Jt = J1^(3) = J2^(3); None = Ja/2
    gimbal_inertia: tuple[float, float, float] = (5.0, 5.0, 5.0)  # (Jg1, Jg2, Jg3), kg m^2

    def __post_init__(self) -> None:
        check_positive("rotor_inertia", self.rotor_inertia)
        check_finite("rotor_speed", self.rotor_speed)
        if self.rotor_transverse_inertia is not None:
            check_positive("rotor_transverse_inertia", self.rotor_transverse_inertia)
        check_nonnegative(
            "gimbal_inertia", check_shape("gimbal_inertia", self.gimbal_inertia, (3,))
        )

    @property
    def transverse(self) -> float:
        """Jt (kg m^2): rotor inertia about a diameter."""
        r = self.rotor_transverse_inertia
        return 0.5 * self.rotor_inertia if r is None else float(r)

    @property
    def angular_momentum(self) -> float:
        """H = Ja psi' (N m s)."""
        return self.rotor_inertia * self.rotor_speed


# ---------------------------------------------------------------------- fast path kernels
@numba.njit(cache=True)
def buoy_rates(t, amp, om, eps, k, cth, sth, two_d):
    """Body rates w (3,) and w' (3,) of the wave-slope buoy R = rot_x(b1) rot_y(b2).

    b1 = d eta/d x2, b2 = -d eta/d x1 at the origin (waves.WaveField); two_d = False keeps
    only b1 (rocking about e1 alone, as in Eq. 94). k (n,) are the SLOPE wavenumbers
    k_i F(k_i r) (`WaveField.slope_wavenumbers`: slope averaged over the buoy waterplane).
    """
    w = np.zeros(3)
    wd = np.zeros(3)
    buoy_rates_into(t, amp, om, eps, k, cth, sth, two_d, w, wd)
    return w, wd


@numba.njit(cache=True)
def buoy_rates_into(t, amp, om, eps, k, cth, sth, two_d, w, wd):
    """`buoy_rates` writing into the caller's w (3,) and w' (3,) (no allocation in the RK4 loop)."""
    g0 = 0.0
    g1 = 0.0
    g2 = 0.0
    g3 = 0.0
    for i in range(amp.shape[0]):
        arg = -om[i] * t + eps[i]
        ak = amp[i] * k[i]
        sa, ca = math.sin(arg), math.cos(arg)
        g0 -= ak * sa
        g1 += ak * om[i] * ca
        g2 += ak * om[i] * om[i] * sa
        g3 -= ak * om[i] ** 3 * ca
    b1d, b1dd = sth * g1, sth * g2
    if not two_d:
        w[0], w[1], w[2] = b1d, 0.0, 0.0
        wd[0], wd[1], wd[2] = b1dd, 0.0, 0.0
        return
    b2, b2d, b2dd = -cth * g0, -cth * g1, -cth * g2
    c2, s2 = math.cos(b2), math.sin(b2)
    w[0] = b1d * c2
    w[1] = b2d
    w[2] = b1d * s2
    wd[0] = b1dd * c2 - b1d * s2 * b2d
    wd[1] = b2dd
    wd[2] = b1dd * s2 + b1d * c2 * b2d


@numba.njit(cache=True)
def gimbal_accel(phi, phid, w, wd, Mg, Ja, Jt, Jg1, Jg2, Jg3, psid):
    """phi'' (rad/s^2) from the general gimbal equation (module doc; Eq. 81 as special case)."""
    c, s = math.cos(phi), math.sin(phi)
    O1 = c * w[0] - s * w[2]
    O3 = s * w[0] + c * w[2]
    drive = (Jg3 - Jg1 - Jt) * O1 * O3 + Ja * (O3 + psid) * O1
    return (drive - Mg) / (Jg2 + Jt) - wd[1]


@numba.njit(cache=True)
def fast_step(t, phi, phid, Mg, dt, n, inert, psid, amp, om, eps, k, cth, sth, two_d):
    """n RK4 substeps of length dt with the generator torque Mg (N m) held.

    inert = (Ja, Jt, Jg1, Jg2, Jg3). Returns (phi, phi', harvested energy int M_g phi' dt (J),
    buoy rates w1, w2, w3 (rad/s) and the wave elevation at the origin (m) at the end).
    """
    Ja, Jt, Jg1, Jg2, Jg3 = inert[0], inert[1], inert[2], inert[3], inert[4]
    energy = 0.0
    w = np.empty(3)
    wd = np.empty(3)
    for _ in range(n):
        buoy_rates_into(t, amp, om, eps, k, cth, sth, two_d, w, wd)
        a1 = gimbal_accel(phi, phid, w, wd, Mg, Ja, Jt, Jg1, Jg2, Jg3, psid)
        buoy_rates_into(t + 0.5 * dt, amp, om, eps, k, cth, sth, two_d, w, wd)
        p2, v2 = phi + 0.5 * dt * phid, phid + 0.5 * dt * a1
        a2 = gimbal_accel(p2, v2, w, wd, Mg, Ja, Jt, Jg1, Jg2, Jg3, psid)
        p3, v3 = phi + 0.5 * dt * v2, phid + 0.5 * dt * a2
        a3 = gimbal_accel(p3, v3, w, wd, Mg, Ja, Jt, Jg1, Jg2, Jg3, psid)
        buoy_rates_into(t + dt, amp, om, eps, k, cth, sth, two_d, w, wd)
        p4, v4 = phi + dt * v3, phid + dt * a3
        a4 = gimbal_accel(p4, v4, w, wd, Mg, Ja, Jt, Jg1, Jg2, Jg3, psid)
        # energy = Mg * (change of phi), exact for the held torque
        dphi = dt / 6.0 * (phid + 2.0 * v2 + 2.0 * v3 + v4)
        energy += Mg * dphi
        phi += dphi
        phid += dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4)
        t += dt
    buoy_rates_into(t, amp, om, eps, k, cth, sth, two_d, w, wd)
    eta = 0.0
    for i in range(amp.shape[0]):
        eta += amp[i] * math.cos(-om[i] * t + eps[i])
    return phi, phid, energy, w[0], w[1], w[2], eta


class GimbalModel:
    """The fast path: the scalar gimbal equation driven by a wave field (numba RK4).

    effects: `gyroscopic` (psi' != 0), `gimbal_inertia` (general inertias; off = Eq. 79: thin
    disk, massless gimbal), `buoy_rocking` (off = still buoy), `wave_2d` (both slope angles; off
    = rocking about e1 only, Eq. 94).
    """

    def __init__(self, params: GOWECParams, wave: WaveField, effects: frozenset[str]) -> None:
        self.params, self.wave, self.effects = params, wave, frozenset(effects)
        Ja = params.rotor_inertia
        if "gimbal_inertia" in self.effects:
            self.inert = np.array([Ja, params.transverse, *params.gimbal_inertia], dtype=float)
        else:
            self.inert = np.array([Ja, 0.5 * Ja, 0.0, 0.0, 0.0])
        self.psid = params.rotor_speed if "gyroscopic" in self.effects else 0.0
        rock = "buoy_rocking" in self.effects
        self._amp, self._om = wave.amplitudes, wave.omegas
        self._eps, self._k = wave.phases, wave.slope_wavenumbers  # k F(k r), waterplane mean
        # a still buoy: zero slope projections (the elevation is still computed)
        self._cth = math.cos(wave.direction) if rock else 0.0
        self._sth = math.sin(wave.direction) if rock else 0.0
        self._two_d = "wave_2d" in self.effects

    def with_phases(self, phases: ArrayLike) -> GimbalModel:
        """This model on the same wave components with other phases (rad): what a reset needs,
        without rebuilding the response factors (a shallow copy; arrays are not written)."""
        w = self.wave
        phases = np.asarray(phases, dtype=np.float64)
        wave = WaveField(w.amplitudes, w.omegas, phases, w.wavenumbers, w.direction, w.buoy_radius)
        model = copy.copy(self)
        model.wave, model._eps = wave, wave.phases
        return model

    def step(
        self, t: float, phi: float, phid: float, Mg: float, dt: float, n: int = 1
    ) -> tuple[float, ...]:
        """(phi, phi', energy J, w1, w2, w3, eta) after n substeps of dt (s) with the generator
        torque Mg (N m); w (rad/s) buoy rates and eta (m) the elevation (0 without rocking)."""
        return fast_step(
            t,
            phi,
            phid,
            Mg,
            dt,
            n,
            self.inert,
            self.psid,
            self._amp,
            self._om,
            self._eps,
            self._k,
            self._cth,
            self._sth,
            self._two_d,
        )

    def rates(self, t: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Buoy body rates w (3,) rad/s and w' (3,) rad/s^2 at time t."""
        return buoy_rates(
            t, self._amp, self._om, self._eps, self._k, self._cth, self._sth, self._two_d
        )

    def accel(self, t: float, phi: float, phid: float, Mg: float) -> float:
        w, wd = self.rates(t)
        i = self.inert
        return gimbal_accel(phi, phid, w, wd, Mg, i[0], i[1], i[2], i[3], i[4], self.psid)


# ---------------------------------------------------------------------- power (Eqs. 82-96)
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
