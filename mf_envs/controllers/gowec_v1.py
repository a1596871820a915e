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
  linearised device in the sea the env has just drawn (`LinearModel`: frequency-domain
  response of hull + gyro units to every wave component, the quadratic drag by stochastic
  (Lorentz) linearisation, the electrical power from the synthesised time signal of
  M_g phi'), inside the drive's limits and the swings the model is trusted to: a global grid
  search over (c, k) polished by a bounded scalar search on c (`pto_search`). The reactive
  setting is taken only where its prediction is positive and clearly above the damper's;
  the search's record (predicted power) is the controller's `prediction`. With a
  speed-dependent flywheel loss (the ISWEC-class device) `efficient_pto` also sets the
  **flywheel speed** per sea, as ISWEC does: the same search at each speed of a grid over the
  device's speed range (`speed_search`: H = J psi' and the loss change with it), the best
  kept, so a small sea runs a slower, cheaper flywheel. `passive_damper` keeps the flywheels
  at the rated speed the env was built with: a passive PTO, its damping set per sea and
  nothing else.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from mf_envs.controllers import register
from mf_envs.controllers.gowec import PLLController, SquareWaveController
from mf_envs.envs.gowec_v1.task import DECLARATION
from mf_envs.physics.gowec.hydro.devices import DEVICES
from mf_envs.physics.gowec.hydro.sea import N_KEEL, SP_CK, SP_YK

ENV_ID = DECLARATION.env_id


def matched_pto(
    env: Any, period: float | None = None, angular_momentum: float | None = None
) -> tuple[float, float]:
    """(c*, k*) (N m s/rad, N m/rad) for the env's hull and gyro at `period` (default: the
    env's wave/peak period) and a rotor of `angular_momentum` H (N m s; default the env's
    J psi'); module docstring."""
    raw = env.unwrapped
    w = 2.0 * math.pi / float(raw.wave_period if period is None else period)
    hull, p = raw.hull, raw.model.p
    A, B, _ = hull.at(w)
    R = B + p.viscous
    Xh = w * (raw.model.pitch_inertia() + A) - hull.stiffness / w
    H = p.gyro[0] * p.psid if angular_momentum is None else angular_momentum
    H2 = raw.model.units * H**2  # n units in parallel: n H^2 / Z_g
    Ig = p.gyro[1] + p.gyro[3]
    Z2 = R * R + Xh * Xh
    return H2 * R / Z2, w * w * Ig - w * H2 * Xh / Z2


def _drag_k(raw: Any) -> float:
    """Still-water quadratic pitch damping K (N m s^2/rad^2) of the keel plate,
    1/2 rho C_d 8 R^5 / 15 (`sea.drag_geometry`), 0 with the drag off; a box's (no radius),
    its keel nodes' sum of c |y|^3 about the pitch axis e1, 1/2 rho C_d B L^4 / 32."""
    sp = raw.model.sp
    if sp[0] == 0.0:
        return 0.0
    if not math.isfinite(raw.hull.radius):
        keel = slice(SP_CK, SP_CK + N_KEEL)
        return float(np.sum(sp[keel] * np.abs(sp[SP_YK : SP_YK + N_KEEL]) ** 3))
    return float(raw.model.drag_coefficient * 0.5 * raw.hull.rho * 8.0 * raw.hull.radius**5 / 15.0)


class LinearModel:
    """The linearised device in the sea the env has just drawn: frequency-domain response of
    the hull's pitch and the gyro units to every wave component under a linear PTO (c, k), the
    synthesised time signals over one period (regular sea) or 20 min (irregular), and the
    predicted net electrical power and excursions (`predict`). The sea's hydrodynamic
    coefficients and the synthesis matrix are computed once per sea."""

    def __init__(self, raw: Any) -> None:
        hull, p, wave = raw.hull, raw.model.p, raw.wave
        self.raw = raw
        self.om = om = np.asarray(wave.omegas, dtype=float)
        amp = np.asarray(wave.amplitudes) * np.exp(1j * wave.phases)
        self.X = raw.model.hull_excitation(om) * amp
        coef = np.array([hull.at(float(w))[:2] for w in om])
        self.A, self.B = coef[:, 0], coef[:, 1]
        self.speed, self.H = p.psid, p.gyro[0] * p.psid
        self.loss = raw.rotor_loss_power()
        self.Ig = p.gyro[1] + p.gyro[3]
        self.n = raw.model.units
        self.K = _drag_k(raw)
        span = 2.0 * math.pi / om[0] if om.size == 1 else 1200.0
        t = np.linspace(0.0, span, 256 if om.size == 1 else 4000, endpoint=False)
        wt = np.outer(om, t)  # Re(z e^{-i w t}) = Re z cos(w t) + Im z sin(w t): one real product
        self.e = np.ascontiguousarray(np.vstack([np.cos(wt), np.sin(wt)]))  # (2 n, samples)
        self.q = 1.0 if om.size == 1 else 0.99  # the excursions' peak: the 99th percentile
        self.Zs, self.Zc, X1 = raw.model.surge_coupling(om)  # surge along the wave, coupled
        self.X = self.X - self.Zc * (X1 * amp) / self.Zs  # the surge's share out of pitch

    def at_speed(self, speed: float) -> LinearModel:
        """This model with the flywheels at `speed` (rad/s): H = J psi' and the running loss
        at that speed (`GOWECV1Env.rotor_loss_power`); the sea's coefficients are kept."""
        self.speed = float(speed)
        self.H = self.raw.model.p.gyro[0] * self.speed
        self.loss = self.raw.rotor_loss_power(self.speed)
        return self

    def response(self, c: Any, k: Any) -> tuple[np.ndarray, np.ndarray]:
        """Complex amplitudes (e^{-i w t}) of the hull's pitch rate and one gimbal's rate
        (rad/s) under the linear PTO (c, k) (scalars, or arrays (m,) of m settings: then
        (m, n_components)), in the sea's e^{-i w t} convention: hull impedance
        Z_h = B + b - i (w (I + A) - C / w) with b the linear viscous plus the drag's stochastic
        linearisation sqrt(8 / pi) K sigma (regular sea: 8 / (3 pi) K |theta'|), n units of
        load H^2 / Z_g, Z_g = c - i (w I_g - k / w); with surge free (the 3-dof table) the
        surge-pitch coupling Z_c = B15 - i w A15 eliminated through the surge impedance
        Z_s = B11 - i (w (m + A11) - K_mooring / w): Z_h - Z_c^2 / Z_s and X5 - Z_c X1 / Z_s."""
        raw, om, H = self.raw, self.om, self.H
        scalar = np.ndim(c) == 0
        c = np.atleast_1d(np.asarray(c, float))[:, None]
        k = np.broadcast_to(np.atleast_1d(np.asarray(k, float))[:, None], c.shape)
        Zg = c - 1j * (om * self.Ig - k / om)
        Zr = (
            self.B
            + raw.model.p.viscous
            - 1j * (om * (raw.model.pitch_inertia() + self.A) - raw.hull.stiffness / om)
            - self.Zc * self.Zc / self.Zs
        )  # surge eliminated (zero without surge)
        b = np.zeros((c.shape[0], 1))
        for _ in range(30):
            th = self.X / (Zr + b + self.n * H * H / Zg)
            if om.size == 1:
                b_new = 8.0 / (3.0 * math.pi) * self.K * np.abs(th)
            else:
                sigma = np.sqrt(0.5 * np.sum(np.abs(th) ** 2, axis=1, keepdims=True))  # RMS
                b_new = math.sqrt(8.0 / math.pi) * self.K * sigma
            if np.all(np.abs(b_new - b) <= 1e-6 * (b + 1.0)):
                break
            b = 0.5 * (b + b_new)
        ph = H * th / Zg
        return (th[0], ph[0]) if scalar else (th, ph)

    def predict(self, c: float, k: float) -> dict[str, float]:
        """The prediction under (c, k): `net_W`, the mean net electrical power (W) of n units'
        M_g phi' = (c phi' + k phi) phi' (generator efficiency when positive, 1 / motor
        efficiency when negative, less the rotor loss at the model's speed), and `excess`, the
        largest of the peak torque, power, gimbal swing and hull tilt over the drive's limits,
        MAX_LINEAR_GIMBAL and PITCH_MARGIN x the survival tilt (<= 1: inside them all);
        `speed`, the flywheels' (rad/s)."""
        return self.predict_many(np.array([c]), np.array([k]))[0]

    def predict_many(self, c: np.ndarray, k: np.ndarray) -> list[dict[str, float]]:
        """`predict` of each setting (c[i], k[i]) (arrays (m,)), computed together."""
        raw, om = self.raw, self.om
        th, ph = self.response(c, k)
        z = np.concatenate([ph, ph / (-1j * om), th / (-1j * om)])  # rates to angles
        rate, angle, pitch = np.split(np.hstack([z.real, z.imag]) @ self.e, 3)  # (m, samples)
        torque = c[:, None] * rate + k[:, None] * angle
        P = self.n * torque * rate
        el = np.where(P > 0.0, P * raw.eta_g, P / raw.eta_m)
        q = self.q
        excess = np.max(
            [np.quantile(np.abs(torque), q, axis=1) / raw.max_generator_torque,
             np.quantile(np.abs(torque * rate), q, axis=1) / max(raw.max_generator_power, 1e-9),
             np.quantile(np.abs(angle), q, axis=1) / MAX_LINEAR_GIMBAL,
             np.quantile(np.abs(pitch), q, axis=1) / (PITCH_MARGIN * raw.pitch_limit)],
            axis=0,
        )  # fmt: skip
        net = np.mean(el, axis=1) - self.loss
        return [{"c": float(ci), "k": float(ki), "net_W": float(n), "excess": float(x),
                 "speed": self.speed} for ci, ki, n, x in zip(c, k, net, excess)]  # fmt: skip


def linear_response(raw: Any, c: float, k: float) -> tuple[np.ndarray, np.ndarray]:
    """`LinearModel.response` in the env's current sea."""
    return LinearModel(raw).response(c, k)


MAX_LINEAR_GIMBAL = 0.8  # rad: the gimbal's 99th-percentile swing the linearisation is trusted
# to (cos 0.8 = 0.70; 46 deg, inside the 70 deg stops; docs/gowec_v1.md: why not 0.6)
PITCH_MARGIN = 0.75  # predicted peak tilt kept below this fraction of the survival tilt
CENTRING = 0.25  # minimum spring k >= CENTRING I_g w^2: without one a gimbal swinging ~1 rad
# drifts to +-pi/2, where the gyroscopic torque H theta' cos(phi) vanishes, and stays there
REACTIVE_GAIN = 1.1  # the reactive PTO only where it is predicted > 10 % above the damper


def net_electrical_power(raw: Any, c: float, k: float) -> float:
    """Predicted mean net electrical power (W) of the linearised device under (c, k) in the
    env's current sea (`LinearModel.predict`)."""
    return LinearModel(raw).predict(c, k)["net_W"]


def centring_stiffness(raw: Any) -> float:
    """k_c = CENTRING I_g w^2 (N m/rad) at the sea's (peak) frequency."""
    p = raw.model.p
    w = 2.0 * math.pi / float(raw.wave_period)
    return CENTRING * (p.gyro[1] + p.gyro[3]) * w * w


def _best(cands: list[dict[str, float]]) -> dict[str, float]:
    """The candidate of the highest predicted net power among those inside the limits
    (excess <= 1); with none inside, the one of the least excess (the gentlest on the device)."""
    inside = [r for r in cands if r["excess"] <= 1.0]
    if inside:
        return max(inside, key=lambda r: r["net_W"])
    return min(cands, key=lambda r: r["excess"])


def pto_search(
    raw: Any, passive: bool = False, model: LinearModel | None = None
) -> dict[str, float]:
    """The linear PTO of the highest predicted net electrical power inside the limits
    (`LinearModel.predict`), by a global grid search over the gains, polished by a bounded
    scalar search on c around the grid's best: c on 41 log-spaced values from c* / 300 to the
    larger of 300 c* and 10 H (c* the mechanical match's, `matched_pto`), k = k_c + s (k_c
    the centring spring, `centring_stiffness`; s on 12 values from 0 to 4 (|k*| + c* w));
    `passive`: k = k_c only
    (the damper). The reactive PTO is kept only where its prediction is positive and
    REACTIVE_GAIN x above the damper's (the model is linear and the reactive branch the one it
    predicts least well); otherwise, and wherever the prediction is negative, the damper's
    setting. `model`: the sea's `LinearModel` (default: a new one at the env's flywheel speed).
    Returns the chosen record: c, k, net_W (the prediction), excess, speed, passive_W (the
    damper's prediction)."""
    from scipy.optimize import minimize_scalar

    model = LinearModel(raw) if model is None else model
    c0, k0 = matched_pto(raw, angular_momentum=model.H)
    c0 = max(c0, 1.0)
    kc = centring_stiffness(raw)
    # up to at least 10 H, where the gimbal all but locks (phi' = H theta' / c): far from the
    # hull's resonance c* is small, and the damping that keeps the swing inside its limits lies
    # decades above it
    cs = np.geomspace(c0 / 300.0, max(c0 * 300.0, 10.0 * abs(model.H)), 41)

    def polish(r: dict[str, float]) -> dict[str, float]:
        k = r["k"]

        def cost(x: float) -> float:
            q = model.predict(math.exp(x), k)
            return -q["net_W"] + 1e9 * max(q["excess"] - 1.0, 0.0)

        res = minimize_scalar(
            cost,
            bounds=(math.log(r["c"]) - 0.2, math.log(r["c"]) + 0.2), method="bounded",
            options={"xatol": 1e-3},
        )  # fmt: skip
        p = model.predict(math.exp(res.x), k)
        return p if p["excess"] <= max(r["excess"], 1.0) and p["net_W"] >= r["net_W"] else r

    damper = polish(_best(model.predict_many(cs, np.full(cs.size, kc))))
    best = damper
    if not passive:
        ks = abs(k0) + c0 * 2.0 * math.pi / float(raw.wave_period)
        grid = [r for s in np.linspace(0.0, 4.0, 12)[1:] * ks
                for r in model.predict_many(cs, np.full(cs.size, kc + s))]  # fmt: skip
        reactive = polish(_best(grid + [damper]))
        gain = reactive["net_W"] - damper["net_W"]
        if (reactive["excess"] <= 1.0 and reactive["net_W"] > 0.0
                and gain > (REACTIVE_GAIN - 1.0) * abs(damper["net_W"])):  # fmt: skip
            best = reactive
    return dict(best, k=float(best["k"]), passive_W=damper["net_W"])


SPEEDS = 9  # the speed schedule's grid: geometric over the device's speed range
REFINE = 3  # bisections of the speed where the limits bind between two grid speeds


def scheduled_speeds(raw: Any) -> np.ndarray:
    """The flywheel speeds (rad/s) the schedule chooses among: SPEEDS values, geometric between
    the device's `rotor_speed_range`, with the sign of the env's spin; only the current speed
    when the loss is a fixed figure (`rotor_loss` given: slowing down would save nothing),
    the rotor is off, or the device has no speed range; only the slowest in a sea beyond the
    operating range (met in survival from the reset: no power to make, only the loss)."""
    psid = float(raw.model.psid)
    lo, hi = DEVICES[raw.device].rotor_speed_range
    if raw.rotor_loss is not None or psid == 0.0 or not 0.0 < lo < hi < math.inf:
        return np.array([psid])
    if raw.survival_at_reset() > 0.0:  # a sea beyond the range: the PTO stays unloaded
        return np.array([math.copysign(lo, psid)])  # the slowest, cheapest speed
    return math.copysign(1.0, psid) * np.geomspace(lo, hi, SPEEDS)


def speed_search(raw: Any) -> dict[str, float]:
    """The flywheel speed and linear PTO of the highest predicted net electrical power inside
    the limits: `pto_search` at each of `scheduled_speeds` on the sea's linear model (H = J psi'
    and the running loss at each speed), the best kept (`_best`); where the next slower grid
    speed predicts more but breaks a limit, REFINE bisections (geometric) between the two keep
    the best inside the limits; otherwise REFINE rounds of the geometric midpoints on either
    side of the best close in on the optimum between the grid's speeds (the predicted power is
    not concave in the speed, so the grid alone left up to 15 % of it in a small sea). ISWEC
    sets its flywheel speed with the PTO per sea state (module doc). Returns `pto_search`'s
    record with `speed` (rad/s)."""
    model = LinearModel(raw)

    def at(speed: float) -> dict[str, float]:
        return pto_search(raw, model=model.at_speed(speed))

    def between(x: float, w: float) -> float:  # the geometric mean of two speeds of one sign
        return math.copysign(math.sqrt(x * w), w)

    grid = [at(float(w)) for w in scheduled_speeds(raw)]
    best = _best(grid)
    i = next(j for j, r in enumerate(grid) if r is best)
    if best["excess"] > 1.0 or len(grid) == 1:  # nothing inside the limits, or one speed
        return best
    if i > 0 and grid[i - 1]["net_W"] > best["net_W"]:
        # the limits bind between the grid's speeds: bisect towards the slower one
        lo, hi = grid[i - 1]["speed"], best["speed"]
        for _ in range(REFINE):
            mid = between(lo, hi)
            r = at(mid)
            if r["excess"] <= 1.0:
                best, hi = (r if r["net_W"] > best["net_W"] else best), mid
            else:
                lo = mid
        return best
    # the optimum between the grid's speeds: REFINE rounds of the geometric midpoints on either
    # side of the best, the bracket closing on the better one (inside the limits); at an end of
    # the range that side's bracket is the best speed itself
    a, b = grid[max(i - 1, 0)]["speed"], grid[min(i + 1, len(grid) - 1)]["speed"]
    for _ in range(REFINE):
        w = best["speed"]
        tried = [at(between(x, w)) for x in (a, b) if x != w]
        better = [r for r in tried if r["excess"] <= 1.0 and r["net_W"] > best["net_W"]]
        if better:
            best = max(better, key=lambda r: r["net_W"])
            a, b = (a, w) if abs(best["speed"]) < abs(w) else (w, b)
        else:
            a, b = between(a, w), between(b, w)
    return best


class EfficientPTOController:
    """The linear PTO and flywheel speed optimised for net electrical power in the sea of the
    last reset (`speed_search`). Gains and speed set on the drive at reset; `prediction` holds
    the search's record (predicted net power, W) to set beside the realised one."""

    def __init__(self, env: Any) -> None:
        self.env = env
        self.c, self.k = 0.0, 0.0
        self.prediction: dict[str, float] = {}

    def reset(self) -> None:
        self._apply(speed_search(self.env.unwrapped))

    def _apply(self, prediction: dict[str, float]) -> None:
        raw = self.env.unwrapped
        self.prediction = prediction
        self.c, self.k = prediction["c"], prediction["k"]
        raw.set_rotor_speed(prediction["speed"])
        raw.set_pto(self.c, self.k)

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        return np.zeros(1, dtype=np.float32), None


class PassiveDamperController(EfficientPTOController):
    """A passive PTO: the best pure damper (k = the centring spring) for net electrical power
    (`pto_search`, passive) with the flywheels at the speed the env was built with (the
    device's rated `rotor_speed`), nothing scheduled but the damping per sea. `efficient_pto`
    is this damper plus what an ISWEC-style drive adds: the flywheel speed chosen per sea and
    a spring where the model predicts one pays."""

    def reset(self) -> None:
        raw = self.env.unwrapped
        raw.set_rotor_speed(float(raw.model.gyro.rotor_speed))
        self._apply(pto_search(raw, passive=True))  # its record's speed: the rated one


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
