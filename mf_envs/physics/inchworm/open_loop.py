"""Open-loop gaits of the driven inchworm (`drive.DrivenInchworm`) and their measurement.

Curvature commands (`cosine_gait`, the seed's; `square_gait`, bang-bang) with the grip of Eq. 102
on the realised actuation (`grip_for`), and the SMA wires' duty cycles (`heat_cool_gait`), each
run over whole cycles after a warm-up (`run_open_loop`, `run_duty_loop`) into `GaitMetrics`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from mf_envs.physics.inchworm.drive import DrivenInchworm

CommandFn = Callable[[float], np.ndarray]  # t [s] -> commanded kappa# (n,) [1/m]
DutyFn = Callable[[float], np.ndarray]  # t [s] -> duty cycles (n,) in [0, 1]


# ---------------------------------------------------------------------- open-loop gaits
def cosine_gait(amplitude: float, shape: np.ndarray, period: float) -> CommandFn:
    """The seed's gait in seconds: kappa#(S, t) = -a s(S) (1 + cos(2 pi t / T - pi)) / 2
    (Eqs. 101, 103 with the bookkeeping time 2 pi t / T); shape s (n,) = c1 + c2 S / L."""
    shape = np.asarray(shape, float)
    return lambda t: -0.5 * amplitude * shape * (1.0 + np.cos(2.0 * np.pi * t / period - np.pi))


def square_gait(amplitude: float, shape: np.ndarray, period: float, bias: float = 0.0) -> CommandFn:
    """Bang-bang command between two curl levels: -(b + a) s for the first half period, -b s
    for the second (b = bias >= 0, 0: release fully); the actuator's lag and rate limit shape
    the realised kappa#. A bias keeps the body arched, where the head-tail distance changes to
    first order with kappa# (near straight only to second order)."""
    shape = np.asarray(shape, float)

    def command(t: float) -> np.ndarray:
        phase = (t / period) % 1.0  # t = k dt: snap round-off at the switching instants
        phase = 0.0 if phase > 1.0 - 1e-9 else phase
        return -(bias + amplitude * float(phase < 0.5 - 1e-9)) * shape

    return command


def grip_for(driven: DrivenInchworm, command: np.ndarray, dt: float) -> str:
    """Eq. 102 on the realised actuation: the head grips while kappa# decreases over the next
    step (loading, neutral included), the tail while it increases; predicted by the lag."""
    if driven.lag is None:
        change = command - driven.kappa_ctrl
    else:
        change = driven.lag.trajectory(command, np.array([dt]))[0] - driven.lag.kappa
    return "head" if float(np.mean(change)) <= 0.0 else "tail"


@dataclass
class GaitMetrics:
    """Speed [body lengths / s], advance per cycle [body lengths], cost of transport
    E / (m_A g L * distance) [-], energy [J] and tail distance [m] over the measured cycles."""

    speed: float
    advance_per_cycle: float
    cost_of_transport: float
    energy: float
    distance: float


def _measure(
    driven: DrivenInchworm,
    step: Callable[[float], None],
    position: Callable[[], float],
    energy: Callable[[], float],
    period: float,
    dt: float,
    n_cycles: int,
    warmup_cycles: int,
) -> GaitMetrics:
    """step(t) for the control steps ending at t = k dt; `position` (m) and `energy` (J) read
    after warmup_cycles and again after n_cycles more: the metrics of those cycles."""
    n_warm = int(round(warmup_cycles * period / dt))
    n_meas = int(round(n_cycles * period / dt))
    x0 = e0 = 0.0
    for k in range(n_warm + n_meas):
        if k == n_warm:
            x0, e0 = position(), energy()
        step((k + 1) * dt)
    dist, spent = position() - x0, energy() - e0
    p, span = driven.sim.params, n_meas * dt
    weight = p.mass_per_length * p.gravity * p.length
    cot = spent / (weight * dist) if dist > 0.0 else float("inf")
    return GaitMetrics(dist / span / p.length, dist / p.length * period / span, cot, spent, dist)


def run_open_loop(
    driven: DrivenInchworm,
    command: CommandFn,
    period: float,
    dt: float,
    n_cycles: int = 2,
    warmup_cycles: int = 1,
) -> GaitMetrics:
    """Drive `driven` (already reset) with command(t) held over control steps of dt [s], the
    grip by `grip_for`; measure the tail over n_cycles after warmup_cycles."""

    def step(t: float) -> None:
        c = command(t)
        driven.step(c, grip_for(driven, c, dt), dt)

    def tail() -> float:
        return driven.sim.x_tail

    def energy() -> float:
        return driven.meter.input_energy

    return _measure(driven, step, tail, energy, period, dt, n_cycles, warmup_cycles)


# ---------------------------------------------------------------------- SMA duty gaits
def heat_cool_gait(
    t_heat: float, t_cool: float, n: int, duty_off: float = 0.0, lag: float = 0.0
) -> DutyFn:
    """Every wire group at duty 1 for t_heat [s], then at duty_off (0: the current off; > 0:
    kept warm) for t_cool [s]: the SMA inchworm's square wave (period t_heat + t_cool). lag: group
    j's square wave starts j lag periods after group 0's (0: all groups together; a heat wave
    along the body otherwise)."""
    period = t_heat + t_cool
    delays = lag * period * np.arange(n)

    def duty(t: float) -> np.ndarray:
        phase = (t - delays) % period
        phase = np.where(phase > period - 1e-9, 0.0, phase)  # snap round-off at the switches
        return np.where(phase < t_heat - 1e-9, 1.0, duty_off)

    return duty


def run_duty_loop(
    driven: DrivenInchworm,
    duty: DutyFn,
    period: float,
    dt: float,
    n_cycles: int = 2,
    warmup_cycles: int = 1,
) -> GaitMetrics:
    """`run_open_loop` for the SMA wires (`sma_wires`): duty(t) (a `heat_cool_gait`) held over
    control steps of dt [s], the head gripping while the wires are heated at duty 1, the tail
    otherwise (Eq. 102 on the command); the distance is the feet's midpoint's (a body still
    curling up over the warm-up does not count as crawling); the cost of transport is
    electrical."""

    def step(t: float) -> None:
        u = duty(t)
        driven.step(u, "head" if u[0] == 1.0 else "tail", dt)

    def middle() -> float:
        return 0.5 * (driven.sim.x_tail + driven.sim.x_head)

    def energy() -> float:
        return driven.electrical_energy

    return _measure(driven, step, middle, energy, period, dt, n_cycles, warmup_cycles)
