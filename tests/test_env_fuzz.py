"""Property-based fuzz of every env (hypothesis): constructor kwargs, reset options and action
sequences drawn from valid, extreme and wrong-typed values.

The contract (docs/api.md, issue 12): the only exceptions an env may raise are ValueError or
TypeError whose message names the offending argument (a kwarg, an option key, or `action`); no
call takes more than 10 s; every observation and reward returned is finite (a blown-up state ends
the episode with info["numerical_failure"], never a NaN). A fast profile runs in the normal suite;
the `slow` profile draws >= 300 examples per env.
"""

from __future__ import annotations

import math
import time
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs.envs.gowec.env import AVAILABLE_EFFECTS as GOWEC_EFFECTS
from mf_envs.physics.inchworm import INCHWORM_EFFECTS
from mf_envs.physics.inchworm.drive import DRIVE_EFFECTS
from mf_envs.physics.ship.model import SHIP_EFFECTS

MAX_SECONDS = 10.0
FAST, SLOW = 30, 300

# values any numeric kwarg may get: extremes and wrong types next to the sane range
WILD = st.one_of(
    st.sampled_from([0.0, -1.0, 1e-300, 1e308, -1e308, math.nan, math.inf, -math.inf, 1e17]),
    st.sampled_from([True, False, None, "abc", "1.5", [1.0, 2.0], (), {}]),
    st.integers(-(2**70), 2**70),
    st.floats(allow_nan=True, allow_infinity=True),
)


def _num(lo: float, hi: float) -> st.SearchStrategy[Any]:
    """Mostly a sane value in [lo, hi] (log-uniform when both ends are positive), sometimes wild."""
    if lo > 0:
        sane = st.floats(math.log(lo), math.log(hi)).map(math.exp)
    else:
        sane = st.floats(lo, hi)
    return _mostly(sane)


def _mostly(sane: st.SearchStrategy[Any]) -> st.SearchStrategy[Any]:
    """`sane` 19 times in 20, else a wild value (so that most scenes get past make)."""
    return st.integers(0, 19).flatmap(lambda i: WILD if i == 0 else sane)


def _effects(available: Any) -> st.SearchStrategy[Any]:
    """None, a subset of the available effects, or (1 in 20) a bad value."""
    names = sorted(available)
    valid = st.one_of(
        st.none(), st.lists(st.sampled_from(names), max_size=len(names), unique=True).map(tuple)
    )
    bad = st.sampled_from(["bogus", ("gravity", 3), 7])
    return st.integers(0, 19).flatmap(lambda i: bad if i == 0 else valid)


KWARGS: dict[str, dict[str, st.SearchStrategy[Any]]] = {
    "GOWEC-v0": {
        "rotor_inertia": _num(1.0, 200.0),
        "rotor_speed": st.one_of(st.just(0.0), _num(-1000.0, 1000.0)),
        "wave_amplitude": _num(0.05, 5.0),
        "wave_period": _num(2.0, 20.0),
        "wave_direction": _num(-7.0, 7.0),
        "max_generator_torque": _num(100.0, 1e6),
        "max_gimbal_rate": _num(1.0, 100.0),
        "steps_per_period": _mostly(st.integers(4, 400)),
        "physics_dt": _num(1e-4, 0.1),
        "n_components": _mostly(st.integers(1, 32)),
        "buoy_radius": st.one_of(st.none(), _num(0.1, 10.0)),
        "gimbal_inertia": _mostly(st.tuples(*[st.floats(0, 50)] * 3)),
        "episode_seconds": st.one_of(st.none(), _num(0.1, 100.0)),
        "effects": _effects(GOWEC_EFFECTS),
    },
    "GyroStabilizer-v0": {
        "ship_inertia": st.one_of(st.none(), _mostly(st.tuples(*[_num(1e3, 1e6)] * 3))),
        "n_gyros": _mostly(st.integers(0, 3)),
        "rotor_inertia": _num(0.5, 100.0),
        "rotor_speed": _num(-2000.0, 2000.0),
        "wave_moment_amplitude": _num(-1e5, 1e5),
        "wave_period": st.one_of(st.none(), _num(1.0, 30.0)),
        "roll_stiffness": st.one_of(st.none(), _num(0.0, 1e6)),
        "roll_damping": st.one_of(st.none(), _num(0.0, 1e5)),
        "max_precession_rate": _num(0.1, 10.0),
        "max_gimbal_angle": _num(0.1, 3.0),
        "control_dt": _num(0.005, 0.5),
        "physics_dt": st.one_of(st.none(), _num(1e-3, 0.1)),
        "servo_time_constant": _num(0.005, 1.0),
        "gimbal_drive": st.sampled_from(["servo", "torque", "magic"]),
        "max_gimbal_torque": _num(0.0, 1e5),
        "gimbal_damping": _num(0.0, 1e3),
        "episode_seconds": _num(0.1, 60.0),
        "effects": _effects(SHIP_EFFECTS),
    },
    "Inchworm-v0": {
        "length": _num(0.1, 1.0),
        "height": _num(0.003, 0.03),
        "youngs_modulus": _num(1e8, 1e10),
        "mass_per_length": _num(0.05, 2.0),
        "n_elements": _mostly(st.integers(2, 16)),
        "max_curvature": _num(1.0, 20.0),
        "n_control_points": _mostly(st.integers(2, 5)),
        "effort_weight": _num(0.0, 1.0),
        "increment_factor": _num(1.0, 10.0),
        "reset_noise_scale": _num(0.0, 1.0),
        "physics_dt": _num(0.01, 0.1),
        "actuator_time_constant": _num(0.01, 2.0),
        "actuator_rate_limit": _num(0.5, 100.0),
        "grip_time_constant": _num(0.01, 1.0),
        "friction_coefficients": _mostly(st.tuples(*[st.floats(0.0, 2.0)] * 4)),
        "effects": _effects({**INCHWORM_EFFECTS, **DRIVE_EFFECTS}),
    },
}
OPTIONS: dict[str, dict[str, st.SearchStrategy[Any]]] = {
    "GOWEC-v0": {
        "gimbal_angle": _num(-20.0, 20.0),
        "gimbal_rate": _num(-5.0, 5.0),
        "wave_phase": _num(-20.0, 20.0),
        "nonsense": st.just(1),
    },
    "GyroStabilizer-v0": {
        "roll": _num(-2.0, 2.0),
        "roll_rate": _num(-1.0, 1.0),
        "gimbal_angle": _num(-3.0, 3.0),
        "wave_phase": _num(-10.0, 10.0),
        "nonsense": st.just(1),
    },
    "Inchworm-v0": {
        "x_tail": _num(-1e6, 1e6),
        "kappa": _mostly(st.lists(st.floats(-15.0, 0.0), min_size=2, max_size=4)),
        "nonsense": st.just(1),
    },
}
STEPS = {"GOWEC-v0": 20, "GyroStabilizer-v0": 20, "Inchworm-v0": 3}


def _scene(env_id: str) -> st.SearchStrategy[tuple[dict, dict, int]]:
    kw = st.fixed_dictionaries({}, optional=KWARGS[env_id])
    opts = st.fixed_dictionaries({}, optional=OPTIONS[env_id])
    return st.tuples(kw, opts, st.integers(0, 2**31 - 1))


def _timed(fn, what: str):
    t0 = time.perf_counter()
    out = fn()
    elapsed = time.perf_counter() - t0
    assert elapsed < MAX_SECONDS, f"{what} took {elapsed:.1f} s"
    return out


def _named(exc: Exception, names: list[str]) -> None:
    assert isinstance(exc, (ValueError, TypeError)), repr(exc)
    assert any(n in str(exc) for n in names), f"{exc!r} names none of {names}"


def check_scene(env_id: str, kwargs: dict, options: dict, seed: int) -> None:
    """One fuzz example: make, reset and step; only named ValueError/TypeError, all finite."""
    try:
        env = _timed(lambda: gym.make(env_id, disable_env_checker=True, **kwargs), "make")
    except Exception as exc:  # noqa: BLE001 - the contract is what is checked
        _named(exc, list(kwargs))
        return
    try:
        obs, _ = _timed(lambda: env.reset(seed=seed, options=options), "reset")
    except Exception as exc:  # noqa: BLE001
        _named(exc, [*options, "options", *kwargs])
        obs, _ = _timed(lambda: env.reset(seed=seed), "reset without options")
    assert np.isfinite(obs).all() and env.observation_space.contains(obs)
    rng = np.random.default_rng(seed)
    for _ in range(STEPS[env_id]):
        action = rng.uniform(-1.5, 1.5, env.action_space.shape).astype(np.float32)
        obs, r, term, trunc, info = _timed(lambda a=action: env.step(a), "step")
        assert np.isfinite(obs).all() and math.isfinite(r), info
        if term or trunc:
            obs, _ = _timed(lambda: env.reset(), "reset")
            assert np.isfinite(obs).all()
    env.close()


def _fuzz(env_id: str, n: int):
    @settings(
        max_examples=n,
        deadline=None,
        derandomize=True,
        database=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )
    @given(_scene(env_id))
    def run(scene):
        check_scene(env_id, *scene)

    return run


@pytest.mark.parametrize("env_id", list(KWARGS))
def test_fuzz_fast(env_id):
    _fuzz(env_id, FAST if env_id != "Inchworm-v0" else FAST // 2)()


@pytest.mark.slow
@pytest.mark.parametrize("env_id", list(KWARGS))
def test_fuzz_slow(env_id):
    _fuzz(env_id, SLOW)()
