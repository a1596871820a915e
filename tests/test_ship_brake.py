"""Hydraulic precession brake (ship.brake) against analytic truth and its documented bounds.

Truths: passivity of the brake law (tau_b a' <= 0 for every command), the exact penetration
v sqrt(J_g / k_s) of an undamped cushion hit at rate v, and, integrating a gimbal driven by a
prescribed roll rate under bang-bang, chattering and random valve commands (20 seeds each), the
bounds the design derives (module doc of ship.brake): rate cap within 10 %, penetration below
the cushion's travel, roll and gimbal-axis mount moments below their bounds, no NaN.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import pytest

from mf_envs.physics.ship import brake as BR
from mf_envs.physics.ship.seakeeper import SEAKEEPER_7000

H = SEAKEEPER_7000.angular_momentum  # 7016 N m s
JG = 1.5 * SEAKEEPER_7000.rotor_inertia  # gimbal J2 = rotor J3, plus the rotor's J1 = J3 / 2
P_MAX = 0.5  # design roll rate, rad/s
PARAMS = BR.BrakeParams.design(H, JG, P_MAX, q_range=(0.0, 2.0))
B = PARAMS.pack()

# command modes of the harness
BANG, CHATTER, RANDOM, STEADY = 0, 1, 2, 3


@numba.njit(cache=False)
def _simulate(B, h, jg, dt, n, amps, omegas, phases, mode, useq, udt, a0, ad0):
    """RK4 of the gimbal a'' = (h p cos a + tau_b + tau_s) / jg with the roll rate
    p(t) = sum amps sin(omegas t + phases) (STEADY: p = amps[0]) and the valve command of
    `mode`; returns the extremes (|a'|, |a|, roll moment, gimbal-axis moment, brake power,
    NaN count)."""
    a, ad = a0, ad0
    out = np.zeros(6)
    u = 0.0
    for i in range(n):
        t = i * dt
        if mode == BANG:
            u = 1.0 if a * ad > 0.0 else 0.0
        elif mode == CHATTER:
            u = float(i % 2)
        elif mode == RANDOM:
            u = useq[int(t / udt) % useq.shape[0]]
        else:
            u = 0.0
        ka = np.zeros(4)
        kv = np.zeros(4)
        for s in range(4):
            f = 0.0 if s == 0 else (0.5 if s < 3 else 1.0)
            ts = t + f * dt
            if s == 0:
                x, v = a, ad
            else:
                x, v = a + f * dt * ka[s - 1], ad + f * dt * kv[s - 1]
            p = amps[0]
            if mode != STEADY:
                p = 0.0
                for j in range(amps.shape[0]):
                    p += amps[j] * math.sin(omegas[j] * ts + phases[j])
            acc, tb, tst = BR.gimbal_accel(x, v, u, p, h, jg, B)
            ka[s], kv[s] = v, acc
            out[2] = max(out[2], abs(h * v * math.cos(x)))
            out[3] = max(out[3], abs(tb + tst))
            out[4] = max(out[4], tb * v)
        a += dt / 6.0 * (ka[0] + 2.0 * ka[1] + 2.0 * ka[2] + ka[3])
        ad += dt / 6.0 * (kv[0] + 2.0 * kv[1] + 2.0 * kv[2] + kv[3])
        if not (math.isfinite(a) and math.isfinite(ad)):
            out[5] += 1.0
            break
        out[0] = max(out[0], abs(ad))
        out[1] = max(out[1], abs(a))
    return out


def _run(seed: int, mode: int, t_end: float = 8.0):
    rng = np.random.default_rng(seed)
    w = rng.uniform(0.2, 1.0, 3)
    amps = P_MAX * w / w.sum()  # |p| <= p_max
    omegas = 2.0 * math.pi / rng.uniform(2.5, 8.0, 3)
    phases = rng.uniform(0.0, 2.0 * math.pi, 3)
    if mode == STEADY:
        amps = np.array([P_MAX * rng.choice([-1.0, 1.0])])
    useq = rng.uniform(-0.5, 1.5, 4096)  # random commands, also outside [0, 1] (clipped)
    dt = 0.5 * PARAMS.stable_dt(JG)
    a0 = rng.uniform(-1.0, 1.0)
    return _simulate(B, H, JG, dt, int(t_end / dt), amps, omegas, phases, mode, useq, 0.01, a0, 0.0)


def test_brake_is_passive_for_every_command():
    for u in np.linspace(-0.5, 1.5, 21):
        for ad in np.linspace(-5.0, 5.0, 201):
            assert BR.brake_torque(u, ad, B) * ad <= 0.0
    # the law itself: below the cap c(u) a' + q(u) a'^2, clipped u, relief
    c = PARAMS.c_min + 0.3 * (PARAMS.c_max - PARAMS.c_min)
    q = PARAMS.q_min + 0.3 * (PARAMS.q_max - PARAMS.q_min)
    assert BR.brake_torque(0.3, 0.01, B) == pytest.approx(-(c + q * 0.01) * 0.01, rel=1e-12)
    assert BR.brake_torque(2.0, -0.01, B) == BR.brake_torque(1.0, -0.01, B)
    assert BR.brake_torque(1.0, 4.0, B) == -PARAMS.relief_torque
    a = PARAMS.rate_cap * 1.02  # above the cap, u = 0: c_min a' + k_cap (a' - r_cap)
    want = PARAMS.c_min * a + PARAMS.cap_resistance * (a - PARAMS.rate_cap)
    assert BR.brake_torque(0.0, a, B) == pytest.approx(-min(want, PARAMS.relief_torque))


def test_undamped_cushion_penetration_is_exact():
    """No brake, no gyro, no cushion damping: a gimbal hitting the stop at v penetrates
    v sqrt(J_g / k_s) (energy) and leaves at -v."""
    p = BR.BrakeParams(0.0, 0.0, 10.0, 1.0, 1e9, PARAMS.stop_stiffness, 0.0, 0.2)
    b = p.pack()
    v = 1.5
    dt = 0.02 * p.stable_dt(JG)
    n = int(0.05 / dt)
    out = _simulate(
        b,
        0.0,
        JG,
        dt,
        n,
        np.zeros(1),
        np.zeros(1),
        np.zeros(1),
        STEADY,
        np.zeros(1),
        1.0,
        p.stop_angle - 1e-3,
        v,
    )
    pen = out[1] - p.stop_angle
    assert pen == pytest.approx(v * math.sqrt(JG / p.stop_stiffness), rel=1e-4)
    assert out[0] == pytest.approx(v, rel=1e-6)  # energy kept: no rate above v


@pytest.mark.parametrize("mode", [BANG, CHATTER, RANDOM, STEADY])
def test_bounds_hold_over_seeds(mode):
    cap = PARAMS.rate_cap
    for seed in range(20):
        out = _run(seed, mode)
        assert out[5] == 0.0, f"NaN, seed {seed}"
        assert out[0] <= 1.10 * cap, f"rate {out[0]:.3f} > 1.1 cap, seed {seed}"
        assert out[1] < PARAMS.stop_angle + PARAMS.max_penetration, f"travel, seed {seed}"
        assert out[2] <= (1.0 + BR.CAP_OVERSHOOT) * H * cap * (1 + 1e-9), f"roll M, {seed}"
        assert out[3] <= PARAMS.relief_torque + PARAMS.stop_moment_bound, f"axis M, {seed}"
        assert out[4] <= 0.0, f"the brake motored, seed {seed}"


def test_steady_heel_reaches_the_stop_and_design_is_used():
    """A steady roll rate at p_max (a turn) drives the gimbal onto the cushion at the capped
    rate: the cap and the cushion are exercised, not idle."""
    out = _run(0, STEADY)
    assert out[1] > PARAMS.stop_angle
    assert out[0] > 0.9 * PARAMS.rate_cap


def test_bad_inputs_raise_naming_parameter():
    with pytest.raises(ValueError, match="c_max"):
        BR.BrakeParams(2.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.1)
    with pytest.raises(ValueError, match="rate_cap"):
        BR.BrakeParams(0.0, 1.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.1)
    with pytest.raises(ValueError, match="max_penetration"):
        BR.BrakeParams(0.0, 1.0, 1.0, 1.0, 1.0, 1.0, 0.0, 0.6)
    with pytest.raises(ValueError, match="design_roll_rate"):
        BR.BrakeParams.design(H, JG, 0.0)
