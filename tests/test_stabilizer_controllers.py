"""Baselines of GyroStabilizer-v0: roll reduction at resonance, LQR design, seed excitations."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401
from mf_envs.controllers import baseline_kinds, make_baseline
from mf_envs.envs.gyro_stabilizer.spec import OBS
from mf_envs.physics.ship import (
    RPM,
    SEED_EFFECTS,
    GimbalDrive,
    pack_params,
    seed_test_hull,
    simulate,
)

ENV_ID = "GyroStabilizer-v0"
SETTLE = 10.0  # s of transient left out of the RMS


def rms_roll(kwargs: dict, kind: str | None, seeds=(0, 1)) -> tuple[float, float]:
    """Mean RMS roll after SETTLE s over seeds, and the largest |gimbal angle|."""
    out, peak = [], 0.0
    for seed in seeds:
        env = gym.make(ENV_ID, **kwargs)
        obs, _ = env.reset(seed=seed)
        ctrl = None if kind is None else make_baseline(env, kind)
        rolls, done = [], False
        while not done:
            a = np.zeros(1, np.float32) if ctrl is None else ctrl.predict(obs)[0]
            obs, _, term, trunc, info = env.step(a)
            done = term or trunc
            if info["time"] > SETTLE:
                rolls.append(info["roll"])
            peak = max(peak, abs(info["gimbal_angle"]))
        out.append(float(np.sqrt(np.mean(np.square(rolls)))))
    return float(np.mean(out)), peak


def rotor_off(kwargs: dict) -> dict:
    eff = set(gym.make(ENV_ID, **kwargs).unwrapped.effects) - {"gyroscopic"}
    return {**kwargs, "effects": tuple(sorted(eff))}


# the default yacht + Seakeeper 9 (tuning scene) and a larger boat + Seakeeper 16 (not tuned on)
SCENES = {
    "yacht18t_sk9": {},
    "boat28t_sk16": dict(
        ship_inertia=(9.0e4, 3.0e5, 3.3e5),
        roll_stiffness=3.0e5,
        roll_damping=1.1e4,
        rotor_inertia=16000 / (6130 * RPM),
        gimbal_inertia=20.0,
        rotor_speed=6130 * RPM,
        wave_moment_amplitude=1.5e4,
    ),
}


@pytest.mark.parametrize("scene", sorted(SCENES))
def test_pid_and_lqr_cut_rms_roll_75_percent_at_resonance(scene):
    kwargs = SCENES[scene]
    env = gym.make(ENV_ID, **kwargs).unwrapped
    assert env.capacity() < 1.0
    assert env.wave_period == pytest.approx(env.ship.natural_roll_period(True))
    off, _ = rms_roll(rotor_off(kwargs), None)
    assert off > 0.1  # the yacht really rolls (> 5.7 deg RMS) without the gyro
    for kind in ("pid", "lqr"):
        on, gimbal_peak = rms_roll(kwargs, kind)
        assert 1.0 - on / off >= 0.75, (kind, on, off)
        assert gimbal_peak <= env.max_gimbal_angle + 1e-3


def test_lqr_gain_and_poles():
    env = gym.make(ENV_ID)
    ctrl = make_baseline(env, "lqr")
    assert ctrl.gain.shape == (1, 5)  # roll, roll rate, phi, phi', drive-loop integral
    np.testing.assert_allclose(
        np.sort_complex(np.linalg.eigvals(ctrl.A - ctrl.B @ ctrl.gain)),
        np.sort_complex(ctrl.poles),
        rtol=1e-8,
    )
    assert np.all(ctrl.poles.real < 0)
    # open loop: the roll mode is lightly damped (zeta ~ 0.04); LQR damps it strongly
    ol = np.linalg.eigvals(ctrl.A)
    zeta_ol = min(-p.real / abs(p) for p in ol if abs(p.imag) > 0)
    zeta_cl = min(-p.real / abs(p) for p in ctrl.poles if abs(p) > 0)
    assert zeta_ol < 0.06 and zeta_cl > 0.5
    # linearisation is exact at 0: A[1, 3] = -n H / J_eff
    m = ctrl.m
    assert ctrl.A[1, 3] == pytest.approx(-m.nh / m.j_eff)


@pytest.mark.parametrize("env_id", [ENV_ID, "GyroStabilizer-JONSWAP-v0"])
def test_tuned_and_scheduled_lqr_close_stable_loops(env_id):
    """Both gains of the default (the tuned LQR and the schedule's roll-rate weighting) and
    every blend the schedule uses close stable loops A - B K on the linearised plant."""
    ctrl = make_baseline(gym.make(env_id))
    assert type(ctrl).__name__ == "ScheduledLQR"
    for s in np.linspace(0.0, 1.0, 21):  # the schedule's blends (s = 0, 1: the two designs)
        eig = np.linalg.eigvals(ctrl.A - ctrl.B @ (ctrl.gain + s * (ctrl.gain_high - ctrl.gain)))
        assert np.all(eig.real < 0.0), (s, eig)
    assert not np.allclose(ctrl.gain, ctrl.gain_high)


@pytest.mark.parametrize("ratio, high", [(0.6, True), (1.0, False), (1.6, False)])
def test_the_schedule_measures_the_period_of_a_sinusoidal_roll(ratio, high):
    """Fed a sinusoidal roll of period T (and its exact rate), the schedule's measured mean
    zero-crossing period 2 pi sqrt(<r^2>/<r'^2>) tends to T, and it takes the high-frequency
    gains only below 0.75 of the natural roll period."""
    ctrl = make_baseline(gym.make(ENV_ID), "scheduled_lqr")
    period = ratio * ctrl.t_n
    w, dt = 2.0 * np.pi / period, ctrl.m.dt
    for k in range(int(240.0 / dt)):
        t = k * dt
        obs = np.array([0.05 * np.sin(w * t), 0.05 * w * np.cos(w * t), 0, 0, 0, 0], np.float32)
        ctrl.predict(obs)
    assert ctrl.period == pytest.approx(period, rel=0.02)
    assert ctrl.high is high


def test_kinds_registered():
    # the default (the strongest) first
    assert baseline_kinds(ENV_ID) == [
        "scheduled_lqr", "continuous", "lqr", "pid", "rate", "sinusoidal"
    ]  # fmt: skip
    with pytest.raises(ValueError, match="period"):
        make_baseline(gym.make(ENV_ID), "sinusoidal", period=-1.0)


def test_fig_3_9_continuous_equals_sinusoidal_at_half_pi():
    """Fig. 3-9: Eq. 118 and Eq. 119 with a = pi/2 give the same roll-rate peaks and zeros."""
    ship, gyro = seed_test_hull()
    T = 10.0
    runs = {}
    for mode in ("continuous", "sinusoidal"):
        drive = GimbalDrive(mode, amplitude=math.pi / 2, frequency=1.0 / T)
        runs[mode] = simulate(pack_params(ship, gyro, 2, SEED_EFFECTS, drive), 2 * T, 0.01)
    c, s = runs["continuous"].omega[:, 0], runs["sinusoidal"].omega[:, 0]
    assert np.abs(c).max() == pytest.approx(np.abs(s).max(), rel=1e-3)
    quarter = [int(round(k * T / 4 / 0.01)) for k in (1, 2, 3, 4)]
    np.testing.assert_allclose(c[quarter], s[quarter], atol=1e-3 * np.abs(c).max())
    # roll rate in antiphase with the gimbal ANGLE (J w1 = -2 H sin phi), a quarter period after
    # the gimbal rate (the seed's Fig. 3-9 text says "out of phase by pi" with the rate)
    assert np.corrcoef(runs["sinusoidal"].phi, s)[0, 1] < -0.99
    assert abs(np.corrcoef(runs["sinusoidal"].phi_rate, s)[0, 1]) < 0.01


def test_seed_excitation_controllers_follow_eqs_118_119():
    env = gym.make(ENV_ID, effects=("gyroscopic",), max_precession_rate=5.0, wave_period=8.0)
    obs, _ = env.reset(seed=0, options={"roll": 0.0, "roll_rate": 0.0})
    ctrl = make_baseline(env, "sinusoidal", amplitude=0.6)
    for _ in range(80):  # 4 s = half a period
        obs, *_ = env.step(ctrl.predict(obs)[0])
    # phi = 0.6 sin(2 pi t / 8) -> at t = 4 s back to ~0 after peaking at 0.6 (servo lag 0.05 s)
    assert abs(obs[OBS.index("gimbal_angle")]) < 0.05
    env.reset(seed=0)
    ctrl = make_baseline(env, "continuous", amplitude=math.pi / 2)
    for _ in range(80):
        obs, *_ = env.step(ctrl.predict(obs)[0])
    assert ctrl.predict(obs)[0][0] * 5.0 == pytest.approx(4 * (math.pi / 2) / 8.0)
