"""Baseline controllers for GOWEC-v0: a phase-locked loop, the seed's fixed rate, a square wave.

All three share one structure: a phase estimate theta of the measured buoy rate w1 = A cos(theta),
a gimbal reference phi_ref = shape(theta) and a torque loop that makes phi follow it:

    M_g = drive(phi, w) + Kp wrap(phi - phi_ref) + Kd (phi' - phi_ref')          (N m)

drive(phi, w) = (Jg3 - Jg1 - Jt) O1 O3 + Ja (O3 + psi') O1 is the measured gyroscopic moment of
the gimbal equation (env docstring); cancelling it leaves J_eff e'' = -Kp e - Kd e'. The device
knows its own rotor and gimbal (read from `env.unwrapped.model`) and the nominal sea period;
the wave phase is never read -- it is estimated from the IMU rate w1 in the observation.

- `pll`: SOGI-PLL. A second-order generalized integrator tuned at the estimated
  frequency w^ turns w1 into an in-phase/quadrature pair (x1, x2) ~ A (cos th, sin th); the
  phase detector e = (x2 cos th^ - x1 sin th^) / A ~ sin(th - th^) drives a PI loop filter,
  th^' = w^ = w0 + Kp e + Ki int e. phi_ref = sign(H) th^, the locking of Eq. 86.
  Design (python-control, `design_pll` -> `PLLDesign`): loop L(s) = (Kp s + Ki)/s^2 *
  1/(tau s + 1), tau = 2/(k w0) the SOGI envelope lag, Kp = 2 zeta wn, Ki = wn^2, wn = w0/4,
  zeta = 0.8, k = sqrt 2. At the default T = 6 s (w0 = 1.047 rad/s): gain crossover 0.40 rad/s,
  phase margin 39 deg (the SOGI lag limits it; zeta = 1.2 only reaches 43 deg), gain margin inf,
  closed-loop bandwidth 0.68 rad/s, i.e. lock within ~3 wave periods; all scale with w0.
  Torque loop (`design_torque_loop`): PD on J_eff e'' with ZOH at the control step, bandwidth
  w_t = min(max(3 w0, 2 sqrt(H A / J_eff)), 0.35 / dt) -- it must beat the gyroscopic stiffness
  H A of the gimbal; default 17.5 rad/s at dt = 0.02 s, discrete phase margin 37 deg.
- `fixed_rate`: the seed's phi = 2 pi t / T at the nominal period (Fig. 3-4); the phase is fitted
  once by least squares over the first nominal period, then never corrected.
- `bang_bang` (default, the strongest): the PLL phase with a staircase reference that dwells at
  phi = +-90 deg and flips
  through 0/180 deg when w1 peaks, so sin(phi) ~ sign(sin th): the 4/pi ceiling of docs/design.md.
  The flip half-width delta (rad of wave phase) is chosen so that the torque stays under
  `torque_fraction` of the limit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import control as ct
import numpy as np

from mf_envs.controllers import register
from mf_envs.envs.gowec.spec import OBS
from mf_envs.envs.gowec.task import DECLARATION
from mf_envs.physics.waves import G, disk_average_factor

ENV_ID = DECLARATION.env_id

SOGI_GAIN = math.sqrt(2.0)
_SIN, _COS = OBS.index("sin_gimbal_angle"), OBS.index("cos_gimbal_angle")
_RATE, _BUOY = OBS.index("gimbal_rate"), OBS.slice("buoy_rates")
_W1 = _BUOY.start  # w1, the first buoy rate (roll of the buoy about e1)


@dataclass(frozen=True)
class PLLDesign:
    """Loop numbers of the PLL (rad/s, deg) computed with python-control."""

    wn: float
    zeta: float
    kp: float
    ki: float
    crossover: float
    phase_margin: float
    gain_margin: float
    bandwidth: float


def design_pll(w0: float, zeta: float = 0.8, ratio: float = 0.25) -> PLLDesign:
    """PI loop filter for the SOGI-PLL at the nominal wave frequency w0 (rad/s)."""
    wn = ratio * w0
    kp, ki = 2.0 * zeta * wn, wn * wn
    tau = 2.0 / (SOGI_GAIN * w0)
    L = ct.tf([kp, ki], [1.0, 0.0, 0.0]) * ct.tf([1.0], [tau, 1.0])
    gm, pm, _, wcp = ct.margin(L)
    bw = ct.bandwidth(ct.feedback(L, 1))
    return PLLDesign(wn, zeta, kp, ki, float(wcp), float(pm), float(gm), float(bw))


def design_torque_loop(J: float, dt: float, w_t: float, zeta: float = 0.9) -> tuple[float, ...]:
    """PD gains for J e'' = -Kp e - Kd e' with ZOH at dt; returns (Kp, Kd, discrete PM deg)."""
    kp, kd = J * w_t**2, 2.0 * zeta * J * w_t
    P = ct.c2d(ct.tf([1.0], [J, 0.0, 0.0]), dt, "zoh")
    z = ct.tf([1.0, 0.0], [1.0], dt)
    C = kp + kd * (z - 1) / (dt * z)
    _, pm, _, _ = ct.margin(C * P)
    return kp, kd, float(pm)


class _GimbalTracker:
    """Shared torque loop and SOGI-PLL (see module docstring)."""

    def __init__(
        self,
        env: Any,
        period: float | None = None,
        bandwidth_ratio: float = 3.0,
        feedforward: bool = True,
    ) -> None:
        raw = env.unwrapped
        self.dt = raw.control_dt
        self.T0 = float(raw.wave_period if period is None else period)
        if not (self.T0 > 0 and math.isfinite(self.T0)):
            raise ValueError(f"period: must be > 0, got {period!r}")
        self.w0 = 2.0 * math.pi / self.T0
        self.m_max = raw.max_generator_torque
        self.inert = np.asarray(raw.model.inert, dtype=float)
        self.psid = float(raw.model.psid)
        self.sign = 1.0 if self.psid * self.inert[0] >= 0 else -1.0
        Ja, Jt, _, Jg2, _ = self.inert
        self.J = Jg2 + Jt
        # the gyroscopic stiffness H A / J sets the fastest gimbal motion; A from Eq. 78 at the
        # nominal wave of the env (a / g w^3), times the buoy's waterplane-averaging factor F(k r)
        H = abs(self.inert[0] * self.psid)
        F = abs(float(disk_average_factor(self.w0**2 / G * raw.buoy_radius)))
        A = raw.wave_amplitude / G * self.w0**3 * F
        w_t = min(max(bandwidth_ratio * self.w0, 2.0 * math.sqrt(H * A / self.J)), 0.35 / self.dt)
        self.kp, self.kd, self.torque_pm = design_torque_loop(self.J, self.dt, w_t)
        self.feedforward = feedforward
        self.pll = design_pll(self.w0)
        self.reset()

    def reset(self) -> None:
        self.x = np.zeros(2)  # SOGI states (in-phase, quadrature)
        self.th = 0.0
        self.w_hat = self.w0
        self.integ = 0.0
        self.k = 0
        self.phi_unwrapped: float | None = None

    # -------------------------------------------------------------- phase estimation
    def _sogi_pll(self, w1: float) -> None:
        """One step of the SOGI (trapezoidal) and the PI phase loop."""
        w, dt, k = self.w_hat, self.dt, SOGI_GAIN
        A = np.array([[-k * w, -w], [w, 0.0]])
        b = np.array([k * w, 0.0])
        Minv = np.linalg.inv(np.eye(2) - 0.5 * dt * A)
        self.x = Minv @ ((np.eye(2) + 0.5 * dt * A) @ self.x + dt * b * w1)
        amp = math.hypot(self.x[0], self.x[1])
        self.th_cur = self.th
        if amp < 1e-9:
            self.th += self.w_hat * dt
            return
        # the trapezoidal SOGI lags by half a step: compare with th - w dt / 2
        th_meas = self.th - 0.5 * w * dt
        e = (self.x[1] * math.cos(th_meas) - self.x[0] * math.sin(th_meas)) / amp
        self.integ += e * dt
        self.w_hat = min(
            max(self.w0 + self.pll.kp * e + self.pll.ki * self.integ, 0.5 * self.w0), 2.0 * self.w0
        )
        self.th += self.w_hat * dt

    def _phase(self, obs: np.ndarray) -> tuple[float, float]:
        """(theta, theta') of the wave at the time of `obs`; subclasses override."""
        self._sogi_pll(float(obs[_W1]))
        return self.th_cur, self.w_hat

    def _shape(self, th: float, thd: float) -> tuple[float, float, float]:
        """(phi_ref, phi_ref', phi_ref'') for wave phase th; locking: phi = th."""
        return th, thd, 0.0

    # -------------------------------------------------------------- torque loop
    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        obs = np.asarray(obs, dtype=float)
        s, c, phid = obs[_SIN], obs[_COS], obs[_RATE]
        w = obs[_BUOY]
        phi = math.atan2(s, c)
        w1 = float(w[0])
        th, thd = self._phase(obs)
        ref, refd, refdd = self._shape(th, thd)
        ref, refd, refdd = self.sign * ref, self.sign * refd, self.sign * refdd
        err = math.remainder(phi - ref, 2.0 * math.pi)
        Mg = self.kp * err + self.kd * (phid - refd) - self.J * refdd
        if self.feedforward:
            # gyroscopic drive predicted at the middle of the hold interval: phi + phi' dt/2,
            # w1 + w1' dt/2 with w1' = -w^ x2 from the SOGI quadrature signal
            Ja, Jt, Jg1, _, Jg3 = self.inert
            pm = phi + 0.5 * self.dt * phid
            s, c = math.sin(pm), math.cos(pm)
            w1m = w1 - 0.5 * self.dt * self.w_hat * self.x[1]
            O1 = c * w1m - s * w[2]
            O3 = s * w1m + c * w[2]
            Mg += (Jg3 - Jg1 - Jt) * O1 * O3 + Ja * (O3 + self.psid) * O1
        self.k += 1
        a = np.clip(Mg / self.m_max, -1.0, 1.0)
        return np.array([a], dtype=np.float32), None


class PLLController(_GimbalTracker):
    """SOGI phase-locked loop on the buoy rate + torque loop (module docstring)."""


class FixedRateController(_GimbalTracker):
    """phi = 2 pi t / T0 + phase (Fig. 3-4): phase fitted over the first nominal period only."""

    def reset(self) -> None:
        super().reset()
        self.samples: list[tuple[float, float]] = []
        self.alpha: float | None = None
        self.phi0: float | None = None

    def _phase(self, obs: np.ndarray) -> tuple[float, float]:
        self._sogi_pll(float(obs[_W1]))  # only for the quadrature signal of the feed-forward
        t = self.k * self.dt
        if self.alpha is None:
            if self.phi0 is None:
                self.phi0 = math.atan2(obs[_SIN], obs[_COS]) * self.sign
            self.samples.append((t, float(obs[_W1])))
            if t + 0.5 * self.dt >= self.T0:  # one nominal period seen: fit w1 = R cos(w t - a)
                tt, yy = np.array(self.samples).T
                X = np.stack([np.cos(self.w0 * tt), np.sin(self.w0 * tt)], axis=1)
                cc, dd = np.linalg.lstsq(X, yy, rcond=None)[0]
                self.alpha = math.atan2(dd, cc)
            else:
                return self.phi0 + self.w0 * t, self.w0
        return self.w0 * t - self.alpha, self.w0


class SquareWaveController(_GimbalTracker):
    """Staircase phi_ref: dwell at +-90 deg, flip while w1 peaks (the 4/pi ceiling)."""

    def __init__(
        self, env: Any, torque_fraction: float = 0.8, delta: float | None = None, **kw: Any
    ) -> None:
        if not 0 < torque_fraction <= 1:
            raise ValueError(f"torque_fraction: must be in (0, 1], got {torque_fraction!r}")
        self.torque_fraction = torque_fraction
        self.delta_fixed = delta
        super().__init__(env, **kw)

    def _delta(self) -> float:
        """Flip half-width (rad of wave phase): J phi''_max + H A <= fraction * limit."""
        if self.delta_fixed is not None:
            return self.delta_fixed
        H = abs(self.inert[0] * self.psid)
        amp = math.hypot(self.x[0], self.x[1])
        room = self.torque_fraction * self.m_max - H * amp
        # h(x) = (3x - x^3)/2 gives phi''_max = (pi/2)(3) w^2 / delta^2
        need = 1.5 * math.pi * self.J * self.w_hat**2
        return min(max(math.sqrt(need / room) if room > 0 else 1.0, 0.05), 1.2)

    def _shape(self, th: float, thd: float) -> tuple[float, float, float]:
        d = self._delta()
        n = round(th / math.pi)
        x = (th - n * math.pi) / d
        if abs(x) >= 1.0:
            return n * math.pi + math.copysign(0.5 * math.pi, x), 0.0, 0.0
        h = 0.5 * (3 * x - x**3)
        hd = 1.5 * (1 - x * x) / d
        hdd = -3.0 * x / (d * d)
        return (
            n * math.pi + 0.5 * math.pi * h,
            0.5 * math.pi * hd * thd,
            (0.5 * math.pi * hdd * thd * thd),
        )


register(ENV_ID, "pll", PLLController)
register(ENV_ID, "fixed_rate", FixedRateController)
# the strongest (1.2714 of Eq. 95 against the 4/pi square-wave ceiling): the default
register(ENV_ID, "bang_bang", SquareWaveController, default=True)
