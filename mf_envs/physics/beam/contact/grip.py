"""Feet that must grip to anchor: a regularised friction law with an engagement
threshold, a small quasi-static two-foot model to test it, and the quasi-static model's error.

Why: in quasi-static Coulomb friction (`friction`, `stick_slip`) the foot with the lower holding
limit slips and the other holds, however small the difference; with anisotropic sliding
coefficients two never-gripping feet then ratchet at full speed (grips between 0.38
and 0.62 crawl as fast as gripping ones).

Law (force on a foot of normal load N moving at v, direction s = sign v):

    F(v) = -N [ mu_s v / sqrt(v^2 + v_s^2) + phi(g) (mu_grip(s) - mu_s) v / sqrt(v^2 + v_g^2) ]

* below the threshold g_th the pad slides on its smooth face: isotropic coefficient mu_s
  (SLIDE_MU = 0.1, the released foot of `friction.FrictionParams`, made direction-free), with a
  creep range: the force grows with speed up to |v| ~ v_s (regularisation; v_s = 50 mm/s, our
  choice, of the order of the fast gait's foot speeds, 0.02 m per 0.1 s step) - so two
  non-gripping feet share a length change in proportion to their forces instead of one
  anchoring;
* the grip adds phi(g) (mu_grip(s) - mu_s), phi the C1 smoothstep from 0 at g_th to 1 at
  g_th + width (defaults 0.7, 0.2): no anchoring below g_th, full grip above g_th + width, and
  a 1 % change of g moves phi by at most 1.5 % / width; the grip's regularisation v_g = 10 mm/s
  (a fully gripping foot creeps ~3 % of the stroke in the 1 s, 20 mm test cycle).
Measured in the two-foot model (tests/test_grip.py): advance per cycle relative to one foot
gripping, with the other foot at g_th - 1 %: 0 at g_th - 1 %, 9 % at g_th + 1 %, 32 % at
g_th + 2 %, 84 % at g_th + 5 %, 100 % at g_th + width.
Both terms are odd and increasing in v, so the two-foot force balance has one solution.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from mf_envs._validate import check_fields, check_nonnegative, check_positive

SLIDE_MU = 0.1


@dataclass(frozen=True)
class GripLaw:
    """threshold and width of the engagement ramp; mu_slide (isotropic, below the threshold);
    gripping coefficients forward (+x) / backward (-x); regularisation speeds [m/s]."""

    threshold: float = 0.7
    width: float = 0.2
    mu_slide: float = SLIDE_MU
    grip_forward: float = 0.6
    grip_backward: float = 1.0
    v_slide: float = 0.05
    v_grip: float = 0.01

    def __post_init__(self) -> None:
        check_nonnegative("threshold", self.threshold)
        check_positive("width", self.width)
        if self.threshold + self.width > 1.0:
            raise ValueError(f"threshold: threshold + width must be <= 1, got {self}")
        # a coefficient 0: frictionless
        check_fields(self, nonnegative=("mu_slide", "grip_forward", "grip_backward"))
        check_fields(self, positive=("v_slide", "v_grip"))
        if min(self.grip_forward, self.grip_backward) < self.mu_slide:
            raise ValueError("grip_forward: gripping coefficients must not be below mu_slide")

    def kernel_args(self) -> np.ndarray:
        """(threshold, width, mu_slide, grip_forward, grip_backward, v_slide, v_grip), the
        layout of the compiled law (`grip_feet.foot_force`)."""
        return np.array([self.threshold, self.width, self.mu_slide, self.grip_forward,
                         self.grip_backward, self.v_slide, self.v_grip])  # fmt: skip

    def grip_fraction(self, g: float) -> float:
        """phi(g): C1 smoothstep, 0 at and below the threshold, 1 at threshold + width."""
        x = min(max((g - self.threshold) / self.width, 0.0), 1.0)
        return x * x * (3.0 - 2.0 * x)

    def force(self, v: float, g: float, normal: float) -> float:
        """Ground force [N] on a foot moving at v [m/s] with engagement g, normal load [N]."""
        mu_g = self.grip_forward if v > 0 else self.grip_backward
        slide = self.mu_slide * v / math.hypot(v, self.v_slide)
        grip = self.grip_fraction(g) * (mu_g - self.mu_slide) * v / math.hypot(v, self.v_grip)
        return -max(normal, 0.0) * (slide + grip)


@dataclass(frozen=True)
class GripFeetParams:
    """Two feet with the law `law` whose engagement follows its command with the time constants
    engage_time, release_time [s] (exact first-order response, `friction.grip_response`)."""

    law: GripLaw = GripLaw()
    engage_time: float = 0.5
    release_time: float = 0.5

    def __post_init__(self) -> None:
        check_fields(self, label="grip_time_constant", positive=("engage_time", "release_time"))


def split_velocity(law: GripLaw, rate: float, g_tail: float, g_head: float, normal) -> float:
    """Tail velocity [m/s] when the head-tail distance changes at `rate` [m/s] (head velocity
    = tail + rate) and the feet's forces balance (quasi-static, no other horizontal load)."""
    n_t, n_h = normal

    def balance(v_t):
        return law.force(v_t, g_tail, n_t) + law.force(v_t + rate, g_head, n_h)

    if rate == 0.0:
        return 0.0
    lo, hi = -abs(rate), abs(rate)
    return brentq(balance, lo, hi, xtol=1e-15, rtol=1e-13)


def advance_per_cycle(
    law: GripLaw, stroke: float, period: float, grips, normal=(0.2, 0.2), n: int = 400
) -> float:
    """Net advance [m] of the mid-point of two feet over one cycle of the head-tail distance
    l(t) = l0 - stroke (1 - cos(2 pi t / T)) / 2 (contracting, then extending), by the
    midpoint rule in n steps. grips(phase) -> (g_tail, g_head), phase = t / T in [0, 1)."""
    dt = period / n
    x_t = x_h = 0.0
    for k in range(n):
        t = (k + 0.5) * dt
        rate = -stroke * math.pi / period * math.sin(2.0 * math.pi * t / period)
        g_t, g_h = grips(t / period)
        v_t = split_velocity(law, rate, g_t, g_h, normal)
        x_t += v_t * dt
        x_h += (v_t + rate) * dt
    return 0.5 * (x_t + x_h)


def inchworm_grips(on: float = 1.0, off: float = 0.0):
    """The inchworm's schedule: head grips while the body contracts (first half), tail while it
    extends (Rios 2017 Eq. 102), at engagements `on` / `off`."""
    return lambda phase: (off, on) if phase < 0.5 else (on, off)


def foot_acceleration(x: np.ndarray, dt: float) -> float:
    """Smallest peak acceleration [m/s^2] consistent with a foot's positions x (n+1,) [m] at
    equal substeps over a step dt [s] with the foot at rest at the step's start and end (the
    quasi-static premise): the larger of the rest-to-rest bound 4 |x_n - x_0| / dt^2 (bang-bang
    is the least-acceleration rest-to-rest move) and the velocity changes between samples."""
    x = np.asarray(x, float)
    check_positive("dt", dt)
    if x.ndim != 1 or x.size < 2:
        raise ValueError(f"x: needs at least 2 positions, got shape {x.shape}")
    h = dt / (x.size - 1)
    v = np.concatenate([[0.0], np.diff(x) / h, [0.0]])
    a_samples = np.max(np.abs(np.diff(v))) / h
    return max(4.0 * abs(x[-1] - x[0]) / dt**2, float(a_samples))


def quasi_static_error(x: np.ndarray, dt: float, mass: float, friction_force: float) -> float:
    """Inertia force m a (a = `foot_acceleration`) over the friction force that holds or drags
    the foot [N]: the quasi-static model neglects the former; values near or above 1 mean the
    step's motion is not quasi-static (to be reported as info['quasi_static_error'])."""
    check_positive("mass", mass)
    check_positive("friction_force", friction_force)
    return mass * foot_acceleration(x, dt) / friction_force
