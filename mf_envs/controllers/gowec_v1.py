"""Baselines for FloatingGOWEC-v0: PLL and square wave on the measured (floating) buoy motion,
and the matched linear PTO.

- `pll`, `bang_bang`: GOWEC-v0's controllers (`controllers.gowec`) unchanged: they read the same
  observation slots (gimbal encoder, buoy IMU rate w1) and the device's own rotor and gimbal
  (`env.unwrapped.model.inert`, `.psid`). On the floating buoy the rate they lock to is the
  buoy's actual motion, which the gyro's reaction changes.
- `linear_pto`: the classical impedance match. With the gimbal as a linear load
  Z_g = c + i (w I_g - k / w) the gyro presents H^2 / Z_g to the hull; matching it to the
  conjugate of the hull's pitch impedance Z_h = R + i X_h, R = B(w) + b_v (radiation + viscous),
  X_h = w (I + A(w)) - C / w, gives (n = gyro_units in parallel: load n H^2 / Z_g)

      c* = n H^2 R / |Z_h|^2,     k* = w^2 I_g - w n H^2 X_h / |Z_h|^2

  and the absorbed power |M_ex|^2 / (8 R). The gains are set once on the drive's inner loop
  (`env.unwrapped.set_pto`, evaluated every physics substep); the torque command is 0.
  It maximises *mechanical* power: the reactive power k phi phi' it circulates through the
  generator costs 1 - eta each way, so on a real drive it is not the best linear PTO.
- `efficient_pto` and `passive_damper`: the linear PTO (c, k) and the damper (c,
  with only the small centring spring k_c that keeps the gimbal from drifting to +-90 deg) that
  maximise the *net electrical* power eta P+ - P- / eta - rotor loss of the
  linearised device in the sea the env has just drawn (`net_electrical_power`: frequency-domain
  response of hull + gyro units to every wave component, the quadratic drag by stochastic
  (Lorentz) linearisation, the electrical power from the synthesised time signal of
  M_g phi'), maximised by scipy (Nelder-Mead over (log c, k); bounded scalar search for c).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mf_envs.controllers import register
from mf_envs.controllers.gowec import PLLController, SquareWaveController
from mf_envs.envs.gowec_v1.task import DECLARATION

ENV_ID = DECLARATION.env_id


def matched_pto(env: Any, period: float | None = None) -> tuple[float, float]:
    """(c*, k*) (N m s/rad, N m/rad) for the env's hull and gyro at `period` (default: the
    env's wave/peak period); module docstring."""
    raw = env.unwrapped
    w = 2.0 * math.pi / float(raw.wave_period if period is None else period)
    hull, p = raw.hull, raw.model.p
    A, B, _ = hull.at(w)
    R = B + p.viscous
    Xh = w * (raw.model.pitch_inertia() + A) - hull.stiffness / w
    H2 = raw.model.units * (p.gyro[0] * p.psid) ** 2  # n units in parallel: n H^2 / Z_g
    Ig = p.gyro[1] + p.gyro[3]
    Z2 = R * R + Xh * Xh
    return H2 * R / Z2, w * w * Ig - w * H2 * Xh / Z2


def _drag_k(raw: Any) -> float:
    """Still-water quadratic pitch damping K (N m s^2/rad^2) of the keel plate,
    1/2 rho C_d 8 R^5 / 15 (`sea.drag_geometry`), 0 with the drag off."""
    sp = raw.model.sp
    if sp[0] == 0.0:
        return 0.0
    return float(raw.model.drag_coefficient * 0.5 * raw.hull.rho * 8.0 * raw.hull.radius**5 / 15.0)


def linear_response(raw: Any, c: float, k: float) -> tuple[np.ndarray, np.ndarray]:
    """Complex amplitudes (e^{-i w t}) of the hull's pitch rate and one gimbal's rate (rad/s)
    at the env's wave components under the linear PTO (c, k), in the sea's e^{-i w t}
    convention: hull impedance Z_h = B + b - i (w (I + A) - C / w) with b the linear viscous
    plus the drag's stochastic linearisation sqrt(8 / pi) K sigma (regular sea:
    8 / (3 pi) K |theta'|), n units of load H^2 / Z_g, Z_g = c - i (w I_g - k / w)."""
    hull, p, wave = raw.hull, raw.model.p, raw.wave
    om = np.asarray(wave.omegas, dtype=float)
    X = raw.model.hull_excitation(om) * np.asarray(wave.amplitudes) * np.exp(1j * wave.phases)
    A = np.array([hull.at(float(w))[0] for w in om])
    B = np.array([hull.at(float(w))[1] for w in om])
    H = p.gyro[0] * p.psid
    Ig = p.gyro[1] + p.gyro[3]
    n = raw.model.units
    Zg = c - 1j * (om * Ig - k / om)
    K, b = _drag_k(raw), 0.0
    for _ in range(30):
        Zh = B + p.viscous + b - 1j * (om * (raw.model.pitch_inertia() + A) - hull.stiffness / om)
        th = X / (Zh + n * H * H / Zg)
        if om.size == 1:
            b_new = 8.0 / (3.0 * math.pi) * K * abs(th[0])
        else:
            b_new = math.sqrt(8.0 / math.pi) * K * math.sqrt(0.5 * float(np.sum(np.abs(th) ** 2)))
        if abs(b_new - b) <= 1e-6 * (b + 1.0):
            break
        b = 0.5 * (b + b_new)
    return th, H * th / Zg


MAX_LINEAR_GIMBAL = 0.8  # rad: gimbal swing the linearisation is trusted to (cos 0.8 = 0.70)
PITCH_MARGIN = 0.6  # predicted pitch kept below this fraction of the device's pitch_limit
CENTRING = 0.25  # minimum spring k >= CENTRING I_g w^2: without one a gimbal swinging ~1 rad
# drifts to +-pi/2, where the gyroscopic torque H theta' cos(phi) vanishes, and stays there


def net_electrical_power(raw: Any, c: float, k: float) -> float:
    """Predicted mean net electrical power (W) of the linearised device under (c, k)
    (`linear_response`): n units' M_g phi' = (c phi' + k phi) phi' synthesised over one period
    (regular sea) or 20 min (irregular), generator efficiency when positive, 1 / motor
    efficiency when negative, less the rotor loss. Gains whose torque, power, gimbal swing or
    hull pitch would exceed the drive's limits, MAX_LINEAR_GIMBAL or PITCH_MARGIN x the pitch
    limit (peaks; irregular seas: 99th percentiles) are scored down by the excess."""
    th, ph = linear_response(raw, c, k)
    om = np.asarray(raw.wave.omegas, dtype=float)
    span = 2.0 * math.pi / om[0] if om.size == 1 else 1200.0
    t = np.linspace(0.0, span, 256 if om.size == 1 else 4000, endpoint=False)
    e = np.exp(-1j * np.outer(t, om))
    rate = (e @ ph).real
    angle = (e @ (ph / (-1j * om))).real
    pitch = (e @ (th / (-1j * om))).real
    torque = c * rate + k * angle
    P = raw.model.units * torque * rate
    el = np.where(P > 0.0, P * raw.eta_g, P / raw.eta_m)
    net = float(np.mean(el)) - raw.rotor_loss_power()
    q = 1.0 if om.size == 1 else 0.99  # irregular: the 99th percentile
    excess = max(
        np.quantile(np.abs(torque), q) / raw.max_generator_torque,
        np.quantile(np.abs(torque * rate), q) / max(raw.max_generator_power, 1e-9),
        np.quantile(np.abs(angle), q) / MAX_LINEAR_GIMBAL,
        np.quantile(np.abs(pitch), q) / (PITCH_MARGIN * raw.pitch_limit),
    )
    if excess > 1.0:
        net -= (excess - 1.0) * (abs(net) + raw.rotor_loss_power() + 1.0) * 10.0
    return net


def centring_stiffness(raw: Any) -> float:
    """k_c = CENTRING I_g w^2 (N m/rad) at the sea's (peak) frequency."""
    p = raw.model.p
    w = 2.0 * math.pi / float(raw.wave_period)
    return CENTRING * (p.gyro[1] + p.gyro[3]) * w * w


def efficient_pto(raw: Any, passive: bool = False) -> tuple[float, float]:
    """(c, k) maximising `net_electrical_power`, started from the mechanical match
    (`matched_pto`); k >= the centring spring k_c (`centring_stiffness`); `passive`: the damper
    c alone with k = k_c."""
    from scipy.optimize import minimize, minimize_scalar

    c0, k0 = matched_pto(raw)
    c0 = max(c0, 1.0)
    kc = centring_stiffness(raw)
    if passive:
        r = minimize_scalar(lambda x: -net_electrical_power(raw, math.exp(x), kc),
                            bounds=(math.log(c0) - 5.0, math.log(c0) + 5.0), method="bounded",
                            options={"xatol": 1e-3})  # fmt: skip
        return math.exp(r.x), kc
    # k = k_c + ks x^2 >= k_c > 0 (a negative gimbal spring destabilises the gimbal)
    ks = abs(k0) + c0 * 2.0 * math.pi / float(raw.wave_period)  # scale of k
    r = minimize(
        lambda x: -net_electrical_power(raw, math.exp(x[0]), kc + x[1] ** 2 * ks),
        np.array([math.log(c0), math.sqrt(max(k0 - kc, 0.0) / ks)]),
        method="Nelder-Mead",
        options={"xatol": 1e-3, "fatol": 1.0, "maxiter": 300},
    )
    best = (math.exp(r.x[0]), float(kc + r.x[1] ** 2 * ks))
    cp, _ = efficient_pto(raw, passive=True)  # never worse than the damper
    if net_electrical_power(raw, cp, kc) > net_electrical_power(raw, *best):
        return cp, kc
    return best


class EfficientPTOController:
    """The linear PTO optimised for net electrical power in the sea of the last reset
    (`efficient_pto`); `passive=True` the best pure damper. Gains set on the drive at reset."""

    def __init__(self, env: Any, passive: bool = False) -> None:
        self.env, self.passive = env, passive
        self.c, self.k = 0.0, 0.0

    def reset(self) -> None:
        self.c, self.k = efficient_pto(self.env.unwrapped, self.passive)
        self.env.unwrapped.set_pto(self.c, self.k)

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return np.zeros(1, dtype=np.float32), None


class PassiveDamperController(EfficientPTOController):
    """The best pure damper (k = 0) for net electrical power (`efficient_pto`)."""

    def __init__(self, env: Any) -> None:
        super().__init__(env, passive=True)


class LinearPTOController:
    """Sets the matched (c*, k*) on the drive at reset; commands zero extra torque."""

    def __init__(self, env: Any, period: float | None = None) -> None:
        self.env = env
        self.c, self.k = matched_pto(env, period)
        self.reset()

    def reset(self) -> None:
        self.env.unwrapped.set_pto(self.c, self.k)

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return np.zeros(1, dtype=np.float32), None


register(ENV_ID, "pll", PLLController)
register(ENV_ID, "bang_bang", SquareWaveController)
register(ENV_ID, "linear_pto", LinearPTOController)
register(ENV_ID, "efficient_pto", EfficientPTOController, default=True)  # the strongest
register(ENV_ID, "passive_damper", PassiveDamperController)
