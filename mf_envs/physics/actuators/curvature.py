"""Curvature actuator of the active beam: its dynamics and actuation power (Rios 2017 §4.4.3,
Eqs. 53-55).

The seed prescribes kappa#(S, t) directly (Eqs. 101, 103): any rate is allowed. A real actuator
has its own dynamics between the commanded curvature u and the realised kappa#. Here, at every
control point independently (all rates in 1/(m s), curvatures in 1/m):

    d kappa# / dt = clip((u - kappa#) / tau, -r, r),                                (A1)

a first-order lag of time constant tau [s] whose rate is saturated at r (a rate limiter on the
lag's output, the usual model of a slew-limited first-order actuator). For a command u held over
a step (zero-order hold) (A1) has the exact solution used by `RateLimitedLag`: while
|u - kappa#| > r tau the curvature moves linearly at the rate r towards u, from then on
u - kappa# decays as exp(-t / tau). It is exact at any dt, never overshoots u and never exceeds
r. Hand-written: scipy/python-control offer linear systems, not this saturated flow.

Defaults: shape-memory-alloy (SMA) wires embedded in the body, the seed's own robot (Wang et
al. 2014, Bioinspir. Biomim. 9 046006, cited by the seed as [34]: SMA wires in PDMS, stride about
a third of the body length, top speed 3.6 mm/s). Numbers taken from Dynalloy, "Technical
Characteristics of Flexinol Actuator Wires" (F1140 Rev I.2, section 3, cycle time): a thin
(0.1-0.15 mm) wire contracts in about 1 s at its rated current and relaxes in about 1 s in
still air. We read that as (i) the full actuation range kappa0# = 13 1/m swept in no less than
1 s: r = 13 1/(m s), and (ii) a 95 % settling time 3 tau of about 1 s: tau = 0.3 s (corner
frequency 1 / (2 pi tau) = 0.53 Hz). These are order-of-magnitude figures for the actuator
class, not a fit to one robot; pass your own through `ActuatorParams`.

Generic in the robot: the actuated curvature lives at control points along any active beam
(`kappa_at_gauss` carries it to the Gauss points); the inchworm's drive
(`mf_envs.physics.inchworm.drive`) is one user. The compiled forms are in `kernels`.

Power (sign convention): the stored energy U = int (N1^2/EA + N2^2/GA_s + M3^2/EI) / 2 dS with
M3 = EI (kappa - kappa#) (Eq. 53) changes at the rate dU/dt = int (N1 g1' + N2 g2' + M3
(kappa' - kappa#')) dS, and the first three terms are the power of the loads (gravity, supports,
feet, minus d(kinetic energy)/dt with inertia) by the principle of virtual work (Eq. 79). Hence

    dU/dt = P_loads - int M3 (d kappa#/dt) dS,

so the mechanical power the actuator delivers to the body is

    P_act = - int_0^L M3(S, t) (d kappa#/dt)(S, t) dS  [W],                          (A2)

positive when the actuator does work on the body (curling against gravity, against a gripping
foot or a friction force). Loss model: the actuators cannot take energy back (an SMA wire or a
pneumatic chamber does not regenerate), so negative mechanical work is dissipated in the
actuator, and the energy drawn is E_in = int max(P_act, 0) dt / efficiency. efficiency = 1 (the
default) reports the positive mechanical work; SMA wires convert only a few per cent of their
electrical heat into work, so an `efficiency` of ~0.01-0.05 models their input energy.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from mf_envs._validate import check_fields, check_positive
from mf_envs.physics.actuators import kernels
from mf_envs.physics.beam import GAUSS_W, BeamModel

SMA_TIME_CONSTANT = 0.3  # tau [s]: 3 tau ~ 1 s relaxation of a thin Flexinol wire in still air
SMA_RATE_LIMIT = 13.0  # r [1/(m s)]: the seed's full range kappa0# = 13 1/m in ~1 s


@dataclass(frozen=True)
class ActuatorParams:
    """First-order lag tau [s] with rate limit r [1/(m s)] (A1); efficiency in (0, 1] of the
    no-regeneration loss model (A2). Defaults: SMA wires (module docstring)."""

    time_constant: float = SMA_TIME_CONSTANT
    rate_limit: float = SMA_RATE_LIMIT
    efficiency: float = 1.0
    name: str = "SMA wire (Flexinol-class)"

    def __post_init__(self) -> None:
        check_fields(self, label="actuator_{}", positive=("time_constant", "rate_limit"))
        check_positive("efficiency", self.efficiency)
        if self.efficiency > 1.0:
            raise ValueError(f"efficiency: must be <= 1, got {self.efficiency}")

    @property
    def corner_frequency(self) -> float:
        """Bandwidth of the lag, 1 / (2 pi tau) [Hz]."""
        return 1.0 / (2.0 * np.pi * self.time_constant)

    def fastest_cycle(self, amplitude: float) -> float:
        """Shortest period [s] of the seed's cosine gait kappa# = -a (1 + cos(2 pi t / T)) / 2
        (Eqs. 101, 103 with peak |kappa#| = amplitude [1/m]) that the actuator follows: the
        commanded peak rate pi a / T may not exceed r, and the cycle may not be faster than the
        lag's corner frequency (T >= 2 pi tau)."""
        check_positive("amplitude", amplitude)
        return max(np.pi * float(amplitude) / self.rate_limit, 2.0 * np.pi * self.time_constant)


def rate_limited_lag(
    kappa: np.ndarray, u: np.ndarray, t: np.ndarray | float, tau: float, rate: float
) -> np.ndarray:
    """Exact solution of (A1) from kappa (n,) under the held command u (n,) [1/m] at the time t
    [s] (-> (n,)) or the times t (m,) or (m, 1) (-> (m, n)), t >= 0: the compiled
    `kernels.lag_at` (the linear phase lasts (|u - kappa| - r tau) / r, then the gap decays
    as exp(-t / tau))."""
    kappa, u = np.asarray(kappa, float).reshape(-1), np.asarray(u, float).reshape(-1)
    t = np.asarray(t, float)
    out = np.empty((t.size, kappa.size))
    for j, tj in enumerate(t.reshape(-1)):
        kernels.lag_at(kappa, u, float(tj), tau, rate, out[j])
    return out[0] if t.ndim == 0 else out


class RateLimitedLag:
    """Per-control-point actuator state kappa# (n,) [1/m] obeying (A1) with ActuatorParams."""

    def __init__(self, params: ActuatorParams, n: int) -> None:
        self.params = params
        self.kappa = np.zeros(int(n))
        self.command = np.zeros(int(n))

    def reset(self, kappa: np.ndarray) -> None:
        """At rest at kappa (n,) [1/m] (command = kappa)."""
        self.kappa = np.array(kappa, float).reshape(self.kappa.shape)
        self.command = self.kappa.copy()

    def trajectory(self, u: np.ndarray, times: np.ndarray) -> np.ndarray:
        """kappa# (m, n) [1/m] at the times (m,) [s] after the present under the command u (n,),
        without changing the state."""
        p = self.params
        times = np.asarray(times, float)[:, None]
        return rate_limited_lag(self.kappa, u, times, p.time_constant, p.rate_limit)

    def rate(self, kappa: np.ndarray | None = None, u: np.ndarray | None = None) -> np.ndarray:
        """d kappa#/dt (n,) [1/(m s)] of (A1) at kappa under u (default: the present state)."""
        kappa = self.kappa if kappa is None else kappa
        u = self.command if u is None else u
        p = self.params
        return np.clip((u - kappa) / p.time_constant, -p.rate_limit, p.rate_limit)

    def advance(self, u: np.ndarray, dt: float) -> np.ndarray:
        """Hold the command u (n,) [1/m] for dt [s]; returns the new kappa# (n,)."""
        u = np.asarray(u, float).reshape(self.kappa.shape)
        self.kappa = self.trajectory(u, np.array([dt]))[0]
        self.command = u.copy()
        return self.kappa.copy()


def kappa_at_gauss(S_ctrl: np.ndarray, values: np.ndarray, gauss_S: np.ndarray) -> np.ndarray:
    """Piecewise-linear interpolation of control-point curvatures (n_ctrl,) to the Gauss points."""
    return np.interp(gauss_S, S_ctrl, values)


def bending_moment(model: BeamModel, d: np.ndarray, kappa_sharp: np.ndarray) -> np.ndarray:
    """M3 = EI (kappa - kappa#) (Eq. 53) at the Gauss points (n_el, 4) [N m]."""
    return model.params.EI * (model.gauss_fields(d)["kappa"] - kappa_sharp)


def integrate_along(model: BeamModel, f_gp: np.ndarray) -> float:
    """int_0^L f dS of a field given at the Gauss points (n_el, 4) (4-point Gauss-Legendre)."""
    return float(np.sum(model.le[:, None] * GAUSS_W[None, :] * f_gp))


def actuation_power(
    model: BeamModel, d: np.ndarray, kappa_sharp: np.ndarray, kappa_rate: np.ndarray
) -> float:
    """P_act = -int M3 (d kappa#/dt) dS [W] (A2) at the configuration d with the actuation
    kappa_sharp and its rate kappa_rate, both (n_el, 4) at the Gauss points."""
    return -integrate_along(model, bending_moment(model, d, kappa_sharp) * kappa_rate)


def increment_work(
    model: BeamModel, d0: np.ndarray, d1: np.ndarray, k0: np.ndarray, k1: np.ndarray
) -> float:
    """Actuation work [J] over one increment kappa# k0 -> k1 (n_el, 4), configuration d0 -> d1:
    the time integral of (A2) by the trapezoidal rule in the increment, -int M_mid (k1 - k0) dS
    with M_mid the mean of M3 at both ends (second order in the increment size); the compiled
    `kernels.increment_work`."""
    k0, k1 = np.ascontiguousarray(k0, float), np.ascontiguousarray(k1, float)
    return float(kernels.increment_work(d0, d1, k0, k1, model.params.EI, model.le))


@dataclass
class EnergyMeter:
    """Accumulates actuation work: `positive` (J, what the actuators deliver), `net` (J) and the
    input energy `positive / efficiency` (no regeneration, module docstring)."""

    efficiency: float = 1.0
    positive: float = 0.0
    net: float = 0.0

    def add(self, work: float) -> None:
        self.net += work
        self.positive += max(work, 0.0)

    def add_totals(self, positive: float, net: float) -> None:
        """Add a step's summed positive and net work [J] (the compiled step sums them)."""
        self.net += float(net)
        self.positive += float(positive)

    @property
    def input_energy(self) -> float:
        return self.positive / self.efficiency
