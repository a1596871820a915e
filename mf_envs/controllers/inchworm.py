"""Open-loop inchworm gaits for Inchworm-v0, driven through the env's action interface.

* `seed_uniform`: uniform kappa#(t) = -kappa0 (1 + cos(2 pi t / T - pi)) / 2 (Rios 2017
  Eq. 101, bookkeeping time 2 pi t / T);
* `seed_linear`: kappa#(S, t) = -kappa0 (c1 + c2 S / L)(1 + cos(2 pi t / T - pi)) / 2, c1 = 0.2,
  c2 = 0.8 (Eq. 103);
* `tuned` (default, the strongest; on the SMA robot the fastest heat/cool wave): a bang-bang
  (square-wave) command between the curl levels -b and -(b + a) with period
  T, all three optimised for speed with scipy.optimize (brute grid, then Nelder-Mead, bounded)
  on the env's own physics; the actuator's lag and rate limit shape the realised kappa#. The
  bias b (an arched body) was added after PPO found that a small fast oscillation of an arched
  body outruns the square wave from straight (docs/inchworm.md).

Cycle period: with the env's actuator dynamics (`actuator_dynamics`), the seed gaits run at the
fastest cycle the actuator allows (`ActuatorParams.fastest_cycle`: peak commanded rate
pi kappa0 / T = rate limit, and T >= 2 pi tau), rounded up to whole control steps; without them
(the seed's scene) 40 steps per cycle as before. The grip follows Eq. 102 on the realised
kappa#: the head grips while it decreases (loading, neutral included), the tail while it
increases. The gaits predict the realised kappa# with their own copy of the actuator model
(synchronised with the env's actuator state at reset), so they stay open loop: the
observation is not used.
"""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache
from typing import Any

import numpy as np
from scipy.optimize import brute, minimize

from mf_envs._validate import check_int, check_positive, check_range, positive_scalar
from mf_envs.controllers import register
from mf_envs.envs.inchworm.task import DECLARATION
from mf_envs.physics.actuators.curvature import RateLimitedLag
from mf_envs.physics.actuators.sma import maker_times
from mf_envs.physics.inchworm import quasistatic as qs
from mf_envs.physics.inchworm.drive import make_driven
from mf_envs.physics.inchworm.open_loop import (
    CommandFn,
    cosine_gait,
    heat_cool_gait,
    run_duty_loop,
    run_open_loop,
    square_gait,
)

ENV_ID = DECLARATION.env_id

SEED_STEPS_PER_CYCLE = 40  # the seed's scene (no actuator dynamics)
WARMUP_SECONDS = 1.5  # the tuning's warm-up: the actuator's full range takes 1 s (rate limit)
WIRE_WARMUP_SECONDS = 10.0  # the SMA wires' warm-up: a kept-warm wire settles in ~3 cycles


class OpenLoopGait:
    """Open-loop command kappa#(t) at the control points with Eq. 102 grips (module docstring)."""

    def __init__(self, env: Any, command: CommandFn, period: float) -> None:
        self.base = env.unwrapped
        self.max_curvature = float(self.base.max_curvature)
        self.dt = float(self.base.control_dt)
        self.command = command
        self.period = positive_scalar("period", period)
        self.steps_per_cycle = max(1, int(round(self.period / self.dt)))  # for reporting
        self.switching = bool(self.base.switching)
        act = self.base.actuator
        self.lag = RateLimitedLag(act, self.base.n_ctrl) if act is not None else None
        self.reset()

    def reset(self) -> None:
        self.k = 0
        self.kappa_now = np.array(self.base.driven.kappa_ctrl, float)  # realised, at reset
        if self.lag is not None:
            self.lag.reset(self.kappa_now)

    def kappa(self, k: int) -> np.ndarray:
        """Commanded kappa# at the control points [1/m] after k steps."""
        return self.command(k * self.dt)

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        del obs, deterministic  # open loop
        c = self.kappa(self.k + 1)
        self.k += 1
        if self.lag is None:
            change = c - self.kappa_now
            self.kappa_now = c
        else:
            before = self.lag.kappa.copy()
            change = self.lag.advance(c, self.dt) - before
        a = 2.0 * c / -self.max_curvature - 1.0
        if self.switching:  # Eq. 102 on the realised kappa# (neutral counted as loading)
            a = np.append(a, 1.0 if float(np.mean(change)) <= 0.0 else -1.0)
        return np.clip(a, -1.0, 1.0).astype(np.float32), None


class WireGait:
    """Open-loop duty cycles of the SMA wire groups (`sma_wires`) with Eq. 102 grips
    on the wires' predicted kappa#: the gait keeps its own copy of the wires' state (the env's
    own kernel, synchronised at reset) and advances it with the duties it commands, so it stays
    open loop (the observation is not used).

    `duty(t, kappa_now, model)` -> duties (n,) in [0, 1]; `model(duty)` predicts kappa# (n,)
    [1/m] after one step from the gait's copy without changing it."""

    def __init__(
        self, env: Any, duty: Callable, period: float, curling: Callable | None = None
    ) -> None:
        self.curling = curling
        self.base = env.unwrapped
        self.dt = float(self.base.control_dt)
        self.duty_fn = duty
        self.period = positive_scalar("period", period)
        self.steps_per_cycle = max(1, int(round(self.period / self.dt)))
        self.switching = bool(self.base.switching)
        self.wires = self.base.scene.wires
        self.reset()

    def reset(self) -> None:
        self.k = 0
        self.sma = np.array(self.base.driven.sma, float)
        self.kappa_now = np.array(self.base.driven.kappa_ctrl, float)

    def model(self, duty: np.ndarray, advance: bool = False) -> np.ndarray:
        """kappa# [1/m] after one step at `duty` (the gait's copy advanced when `advance`)."""
        thermal, tt, p_full, k_full, _g = self.wires.kernel_args()
        work = self.sma if advance else self.sma.copy()
        out = np.empty(len(duty))
        qs.sma_advance(work, np.asarray(duty, float), self.dt, thermal, tt, p_full, k_full, out)
        return out

    def predict(self, obs: np.ndarray, deterministic: bool = True) -> tuple[np.ndarray, None]:
        del obs, deterministic  # open loop
        self.k += 1
        duty = np.clip(np.asarray(self.duty_fn(self.k * self.dt, self.kappa_now, self.model),
                                  float), 0.0, 1.0)  # fmt: skip
        kappa = self.model(duty, advance=True)
        change, self.kappa_now = kappa - self.kappa_now, kappa
        a = 2.0 * duty - 1.0
        if self.switching:  # Eq. 102: the head grips while the body curls
            if self.curling is not None:  # by the gait's phase (the wires lag the command)
                head = bool(self.curling(self.k * self.dt))
            else:  # on the predicted kappa# (neutral counted as loading)
                head = float(np.mean(change)) <= 0.0
            a = np.append(a, 1.0 if head else -1.0)
        return np.clip(a, -1.0, 1.0).astype(np.float32), None


def wire_cycle(env: Any) -> float:
    """The fastest seed-gait cycle of the wires [s]: their contraction time at the rated
    current plus their relaxation time in still air (`sma.maker_times`)."""
    t_c, t_r = maker_times(env.unwrapped.scene.wires.params)
    return t_c + t_r


def tracking_duty(target: CommandFn) -> Callable:
    """Duties that bring each group's predicted kappa# closest to target(t) (n,) [1/m] after
    the step: bisection on the duty (kappa# after a step is monotone in it); cooling cannot
    be commanded, so a target above the wire's relaxation gives duty 0."""

    def duty(t: float, kappa_now: np.ndarray, model: Callable) -> np.ndarray:
        goal = np.asarray(target(t), float)
        lo, hi = np.zeros(len(goal)), np.ones(len(goal))
        for _ in range(12):  # kappa# decreases (curls more) with the duty
            mid = 0.5 * (lo + hi)
            more = model(mid) > goal  # not curled enough: more heat
            lo, hi = np.where(more, mid, lo), np.where(more, hi, mid)
        return 0.5 * (lo + hi)

    return duty


class SeedGait(OpenLoopGait):
    """Eqs. 101/103: kappa# = -kappa0 (c1 + c2 S / L) (1 + cos(2 pi t / T - pi)) / 2."""

    def __init__(
        self,
        env: Any,
        kappa0: float | None = None,
        c1: float = 1.0,
        c2: float = 0.0,
        steps_per_cycle: int | None = None,
    ) -> None:
        base = env.unwrapped
        max_k = float(base.max_curvature)
        self.kappa0 = max_k if kappa0 is None else float(kappa0)
        check_positive("kappa0", self.kappa0)
        peak = self.kappa0 * max(abs(c1), abs(c1 + c2))
        if peak > max_k * (1 + 1e-12):
            raise ValueError("kappa0: the gait exceeds the env's max_curvature")
        if steps_per_cycle is None:
            steps_per_cycle = SEED_STEPS_PER_CYCLE
            if base.actuator is not None:  # the fastest cycle the actuator allows
                fastest = base.actuator.fastest_cycle(peak)
                steps_per_cycle = max(2, int(np.ceil(fastest / base.control_dt - 1e-9)))
        shape = c1 + c2 * base.S_ctrl / base.params.length
        n = check_int("steps_per_cycle", steps_per_cycle, low=2)
        period = n * base.control_dt
        super().__init__(env, cosine_gait(self.kappa0, shape, period), period)


def seed_wire_gait(env: Any, c1: float, c2: float, steps_per_cycle: int | None = None):
    """The seed's gait (Eqs. 101/103, peak kappa0# = max_curvature) on the SMA wires: duties
    tracking it (`tracking_duty`) at the wires' fastest cycle (`wire_cycle`, rounded up to
    whole control steps) unless steps_per_cycle is given."""
    base = env.unwrapped
    dt = base.control_dt
    if steps_per_cycle is None:
        steps_per_cycle = max(2, int(np.ceil(wire_cycle(env) / dt - 1e-9)))
    n = check_int("steps_per_cycle", steps_per_cycle, low=2)
    shape = c1 + c2 * base.S_ctrl / base.params.length
    if base.max_curvature * max(abs(c1), abs(c1 + c2)) > base.max_curvature * (1 + 1e-12):
        raise ValueError("c1: the gait exceeds the env's max_curvature")
    period = n * dt
    target = cosine_gait(base.max_curvature, shape, period)

    def curling(t: float) -> bool:  # the commanded kappa# decreases over the step
        return float(np.mean(target(t) - target(t - dt))) <= 0.0

    return WireGait(env, tracking_duty(target), period, curling)


def seed_uniform(env: Any, **params: Any):
    """Eq. 101: uniform actuation curvature (on the SMA wires: tracked by the duties)."""
    if env.unwrapped.sma:
        return seed_wire_gait(env, 1.0, 0.0, params.get("steps_per_cycle"))
    return SeedGait(env, c1=1.0, c2=0.0, **params)


def seed_linear(env: Any, c1: float = 0.2, c2: float = 0.8, **params: Any):
    """Eq. 103: actuation growing linearly from tail to head."""
    if env.unwrapped.sma:
        return seed_wire_gait(env, c1, c2, params.get("steps_per_cycle"))
    return SeedGait(env, c1=c1, c2=c2, **params)


# the validation gait (docs/inchworm.md): the wires heated at their rated current until the
# model's wire has contracted (maker's test, 2.9 s for the 0.15 mm HT wire at 0.4 A), then
# cooled for the maker's still-air relaxation time (1.2 s, Dynalloy F1140)
VALIDATION_HEAT, VALIDATION_COOL = 2.9, 1.2


def heat_cool(
    env: Any,
    t_heat: float = VALIDATION_HEAT,
    t_cool: float = VALIDATION_COOL,
    duty_off: float = 0.0,
    lag: float = 0.0,
    grip_shift: float = 0.0,
) -> WireGait:
    """Square wave of the SMA wires (`open_loop.heat_cool_gait`): every group at duty 1 for
    t_heat [s], then at duty_off for t_cool [s], group j lag periods after group 0; Eq. 102
    grips: the head grips while group 0 is heated, grip_shift periods later (0: in phase).
    Defaults: the validation timing, the groups together."""
    base = env.unwrapped
    if not base.sma:
        raise ValueError("effects: heat_cool drives the SMA wires; the scene has no 'sma_wires'")
    check_positive("t_heat", t_heat)
    check_positive("t_cool", t_cool)
    if not 0.0 <= duty_off <= 1.0:
        raise ValueError(f"duty_off: must lie in [0, 1], got {duty_off}")
    lag = check_range("lag", lag, -1.0, 1.0)
    shift = check_range("grip_shift", grip_shift, -1.0, 1.0)
    fn = heat_cool_gait(float(t_heat), float(t_cool), base.n_ctrl, float(duty_off), lag)
    period = float(t_heat + t_cool)
    # the head grips while the wires are heated, the tail while they cool (Eq. 102 on the
    # command: the wires' kappa# follows it with the thermal lag)
    gait = WireGait(env, lambda t, _k, _m: fn(t), period,
                    lambda t: bool(fn(t - shift * period)[0] == 1.0))  # fmt: skip
    gait.t_heat, gait.t_cool, gait.duty_off = float(t_heat), float(t_cool), float(duty_off)
    return gait


# `_tune_wires` on the default robot (t_heat s, t_cool s, keep-warm duty): the brute force takes
# minutes, so its result is stored (the default baseline must be cheap to make);
# tests/test_inchworm_sma.py::test_stored_tuned_gait_is_the_brute_force_optimum re-runs it (slow)
TUNED_SMA = (2.0, 1.1, 0.0)


@lru_cache(maxsize=1)
def _default_config() -> tuple:
    import gymnasium as gym

    env = gym.make(ENV_ID)
    try:
        return env.unwrapped.drive_config()
    finally:
        env.close()


@lru_cache(maxsize=8)
def _tune_wires(config: tuple) -> tuple[float, float, float, float]:
    """(t_heat [s], t_cool [s], duty_off, speed [L/s]) of the fastest `heat_cool_gait` of the
    SMA robot configured by `config` (`drive_config()`): scipy.optimize.brute over heating
    times 0.5-4 s (0.5 s apart), cooling times 0.2-2 s (0.3 s apart) and keep-warm duties 0,
    0.15, 0.3,
    each from the robot at rest, the speed of the feet's midpoint over two cycles after a
    warm-up of at least two cycles and WIRE_WARMUP_SECONDS (the wires' periodic state)."""
    cfg = dict(config)
    dt = cfg.pop("control_dt")
    cfg.pop("max_curvature")
    n = cfg["n_control_points"]

    def neg_speed(x: np.ndarray) -> float:
        t_heat, t_cool, off = float(x[0]), float(x[1]), float(x[2])
        if t_heat <= 0.0 or t_cool <= 0.0 or not 0.0 <= off < 1.0:
            return 0.0
        driven = make_driven(**cfg)
        driven.reset(np.zeros(n))
        period = t_heat + t_cool
        warm = max(2, int(np.ceil(WIRE_WARMUP_SECONDS / period)))
        m = run_duty_loop(driven, heat_cool_gait(t_heat, t_cool, n, off), period, dt, 2, warm)
        return -m.speed

    grid = (slice(0.5, 4.01, 0.5), slice(0.2, 2.01, 0.3), slice(0.0, 0.31, 0.15))
    x, fval, _grid, _jout = brute(neg_speed, grid, finish=None, full_output=True)
    return float(x[0]), float(x[1]), float(x[2]), float(-fval)


@lru_cache(maxsize=8)
def _tune(config: tuple, max_evals: int) -> tuple[float, float, float, float]:
    """(period [s], amplitude [1/m], bias [1/m], speed [L/s]) of the fastest two-level
    square-wave gait (`square_gait`: -(b + a) for half a period, -b for the other) of the env
    configured by `config` (its `drive_config()`: make_driven's arguments + control_dt,
    max_curvature), from a straight body at rest, speed over one cycle after a warm-up of at
    least one cycle and `WARMUP_SECONDS` (time to reach the arched posture): a grid
    (scipy.optimize.brute: 8 log-spaced periods from 2 control steps to twice the seed gait's
    period, 4 amplitudes, 3 biases; a + b > max_curvature scores 0) then a bounded Nelder-Mead
    polish (<= max_evals runs)."""
    cfg = dict(config)
    dt, max_k = cfg.pop("control_dt"), cfg.pop("max_curvature")
    shape = np.ones(cfg["n_control_points"])

    def neg_speed(x: np.ndarray) -> float:  # x = (log period [log s], amplitude, bias [1/m])
        period, amp, bias = float(np.exp(x[0])), float(x[1]), float(x[2])
        if amp + bias > max_k * (1 + 1e-12) or amp <= 0.0 or bias < 0.0:
            return 0.0  # outside the actuation range: no gait
        driven = make_driven(**cfg)
        driven.reset(np.zeros(len(shape)))
        warm = max(1, int(np.ceil(WARMUP_SECONDS / period)))
        m = run_open_loop(driven, square_gait(amp, shape, period, bias), period, dt, 1, warm)
        return -m.speed

    act = cfg["actuator"] if "actuator_dynamics" in cfg["effects"] else None
    start = act.fastest_cycle(max_k) if act is not None else SEED_STEPS_PER_CYCLE * dt
    lo, hi = np.log(2 * dt), np.log(2.0 * start)
    grid = (
        slice(lo, hi + 1e-9, (hi - lo) / 7),
        slice(0.25 * max_k, 1.0001 * max_k, 0.25 * max_k),
        slice(0.0, 0.51 * max_k, 0.25 * max_k),
    )
    x0 = brute(neg_speed, grid, finish=None)
    res = minimize(
        neg_speed,
        x0=x0,
        method="Nelder-Mead",
        bounds=[(lo, hi), (0.05 * max_k, max_k), (0.0, 0.95 * max_k)],
        options={"xatol": 0.02, "fatol": 1e-4, "maxfev": max_evals},
    )
    return float(np.exp(res.x[0])), float(res.x[1]), float(res.x[2]), float(-res.fun)


def tuned(
    env: Any,
    period: float | None = None,
    amplitude: float | None = None,
    bias: float | None = None,
    max_evals: int = 30,
) -> OpenLoopGait:
    """Two-level square-wave gait (`square_gait`) with period [s], amplitude [1/m] and curl
    bias [1/m] optimised for speed on the env's physics (`_tune`, cached per configuration;
    a few minutes on the defaults) unless all three are given."""
    base = env.unwrapped
    if base.sma:  # the SMA robot's square wave of duties
        cfg = base.drive_config()
        t_heat, t_cool, off = TUNED_SMA if cfg == _default_config() else _tune_wires(cfg)[:3]
        return heat_cool(env, t_heat, t_cool, off)
    if period is None or amplitude is None or bias is None:
        t_opt, a_opt, b_opt, _ = _tune(base.drive_config(), max_evals)
        period = t_opt if period is None else period
        amplitude = a_opt if amplitude is None else amplitude
        bias = b_opt if bias is None else bias
    check_positive("period", period)
    check_positive("amplitude", amplitude)
    if bias < 0.0:
        raise ValueError(f"bias: must be >= 0 (a curl level, 1/m), got {bias}")
    if amplitude + bias > base.max_curvature * (1 + 1e-12):
        raise ValueError("amplitude: amplitude + bias exceeds the env's max_curvature")
    shape = np.ones(base.n_ctrl)
    command = square_gait(float(amplitude), shape, float(period), float(bias))
    gait = OpenLoopGait(env, command, float(period))
    gait.amplitude, gait.bias = float(amplitude), float(bias)
    return gait


register(ENV_ID, "seed_uniform", seed_uniform)
register(ENV_ID, "seed_linear", seed_linear)
register(ENV_ID, "tuned", tuned, default=True)  # the fastest on the default robot
register(ENV_ID, "heat_cool", heat_cool)
