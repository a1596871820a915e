"""One contract for every env (issue 11/12): strict reset options, no RNG draw on a rejected reset,
episode_seconds, parameter errors naming the public argument, bounded substeps, the GOWEC reward
reference, Inchworm's solver failures, time as steps x dt, named observation layouts, docstring
sections, file sizes."""

from __future__ import annotations

import math
import re
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs.envs import available_env_ids, declaration
from mf_envs.envs.gyro_stabilizer import GyroStabilizerEnv
from mf_envs.physics.waves import G

ROOT = Path(__file__).resolve().parents[1]
ENV_IDS = available_env_ids()


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_unknown_reset_option_raises_naming_it(env_id):
    env = gym.make(env_id)
    with pytest.raises(ValueError, match="nonsense"):
        env.reset(seed=0, options={"nonsense": 1})


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_out_of_range_reset_option_raises_naming_it_and_draws_nothing(env_id):
    """A rejected reset leaves the generator as it was: the next reset is the one an env that
    never saw the rejected call makes."""
    env, ref = gym.make(env_id), gym.make(env_id)
    env.reset(seed=3)
    ref.reset(seed=3)
    for key, value in [*declaration(env_id).bad_reset_options, ("nonsense", 1)]:
        with pytest.raises(ValueError, match=key):
            env.reset(seed=99, options={key: value})
    np.testing.assert_array_equal(env.reset()[0], ref.reset()[0])


def test_gowec_reference_is_positive_for_every_direction_and_rotor_off():
    """P_ref = max(|Eq. 95|, 0.1 * 1/2 J3 max(|psi'|, 10 w) a k w^2), computed here by hand."""
    for theta in (-math.pi / 2, 0.0, 1.0, math.pi / 2, math.pi, -2.0):
        for speed in (523.6, -400.0, 0.0):
            u = gym.make("GOWEC-v0", wave_direction=theta, rotor_speed=speed).unwrapped
            J, a, T = u.params.rotor_inertia, u.wave_amplitude, u.wave_period
            w = 2 * math.pi / T
            eq95 = 0.5 * abs(speed) * J * a / G * w**4 * abs(math.sin(theta))
            floor = 0.1 * 0.5 * J * max(abs(speed), 10 * w) * a / G * w**4
            assert u.reference_power == pytest.approx(max(eq95, floor), rel=1e-12)
            assert u.reference_power > 0
    default = gym.make("GOWEC-v0").unwrapped
    assert default.reference_power == default.analytic_max_power()  # Eq. 95 exactly


@pytest.mark.parametrize("theta", [-math.pi / 2, 0.0, math.pi])
def test_gowec_reward_is_energy_over_the_reference(theta):
    """Harvesting (positive power) gives a positive reward for waves from any side; the reward
    is the step's energy over P_ref dt, finite also with the rotor off."""
    from mf_envs.controllers import make_baseline

    for speed in (523.6, 0.0):
        env = gym.make("GOWEC-v0", wave_direction=theta, rotor_speed=speed, n_periods=2)
        u = env.unwrapped
        ctrl = make_baseline(env)
        obs, _ = env.reset(seed=0)
        ctrl.reset()
        ret, energy = 0.0, 0.0
        for _ in range(u.max_episode_steps):
            obs, r, term, trunc, info = env.step(ctrl.predict(obs)[0])
            assert math.isfinite(r) and np.isfinite(obs).all()
            ret, energy = ret + r, energy + info["power"] * u.control_dt
            if term or trunc:
                break
        assert ret == pytest.approx(energy / (u.reference_power * u.control_dt), rel=1e-9)
        assert math.copysign(1, ret) == math.copysign(1, energy)
    env = gym.make("GOWEC-v0", wave_direction=-math.pi / 2)  # the case: PLL harvests
    ctrl = make_baseline(env)
    obs, _ = env.reset(seed=0)
    rets = []
    for _ in range(600):
        obs, r, *_ = env.step(ctrl.predict(obs)[0])
        rets.append(r)
    assert sum(rets) > 0


@pytest.mark.parametrize(
    ("env_id", "kwargs", "name"),
    [
        ("GOWEC-v0", {"wave_period": 1e308}, "wave_period"),
        ("GOWEC-v0", {"wave_direction": 100.0}, "wave_direction"),
        ("GOWEC-v0", {"physics_dt": 1e-82}, "physics_dt"),
        ("GOWEC-v0", {"physics_dt": 1e-6}, "physics_dt"),  # 2e4 substeps of a 0.02 s step
        ("GOWEC-v0", {"rotor_speed": "fast"}, "rotor_speed"),
        ("GOWEC-v0", {"rotor_speed": "500"}, "rotor_speed"),
        ("GOWEC-v0", {"wave_amplitude": True}, "wave_amplitude"),
        ("GOWEC-v0", {"gimbal_inertia": [1.0, 2.0]}, "gimbal_inertia"),
        ("GOWEC-v0", {"n_periods": 2, "episode_seconds": 10.0}, "episode_seconds"),
        ("GyroStabilizer-v0", {"control_dt": 1e30}, "control_dt"),
        ("GyroStabilizer-v0", {"servo_time_constant": 1e-9}, "servo_time_constant"),
        ("GyroStabilizer-v0", {"ship_inertia": 1e6}, "ship_inertia"),
        ("GyroStabilizer-v0", {"ship_inertia": [1e5, 1e5]}, "ship_inertia"),
        ("GyroStabilizer-v0", {"max_gimbal_torque": -1.0}, "max_gimbal_torque"),
        ("GyroStabilizer-v0", {"rotor_inertia": "9.5"}, "rotor_inertia"),
        ("GyroStabilizer-v0", {"n_gyros": True}, "n_gyros"),
        ("GyroStabilizer-v0", {"episode_seconds": "30"}, "episode_seconds"),
        ("Inchworm-v0", {"youngs_modulus": 40, "length": 25}, "length"),
        ("Inchworm-v0", {"youngs_modulus": 1e3}, "youngs_modulus"),  # sags without equilibrium
        ("Inchworm-v0", {"reset_noise_scale": 3.0}, "reset_noise_scale"),
        ("Inchworm-v0", {"reset_noise_scale": 1e16}, "reset_noise_scale"),
        ("Inchworm-v0", {"height": 1e-4, "increment_factor": 1.0}, "increment_factor"),
        ("Inchworm-v0", {"soil": "lava"}, "soil"),
    ],
)
def test_bad_parameter_raises_naming_the_public_argument(env_id, kwargs, name):
    with pytest.raises(ValueError, match=name):
        gym.make(env_id, **kwargs)


def test_inchworm_episode_length_from_one_argument():
    """`max_episode_steps` and `episode_seconds` given to the env together must give the same
    steps; gym.make's `max_episode_steps` is its TimeLimit (tests/test_env_limits.py)."""
    from mf_envs.envs.inchworm import InchwormEnv

    with pytest.raises(ValueError, match="episode_seconds=1.0 is 10 control steps"):
        InchwormEnv(max_episode_steps=5, episode_seconds=1.0)
    assert InchwormEnv(max_episode_steps=5).max_episode_steps == 5
    assert InchwormEnv(max_episode_steps=10, episode_seconds=1.0).max_episode_steps == 10
    env = gym.make("Inchworm-v0", max_episode_steps=5)
    assert env.spec.max_episode_steps == 5 and env.unwrapped.max_episode_steps == 400


def test_inchworm_full_noise_resets_and_steps():
    env = gym.make("Inchworm-v0", reset_noise_scale=1.0)
    obs, _ = env.reset(seed=1)
    assert env.observation_space.contains(obs)
    obs, r, *_ = env.step(env.action_space.sample())
    assert np.isfinite(obs).all() and math.isfinite(r)


def test_inchworm_reward_is_exact_far_from_the_origin():
    """The progress term is computed in local coordinates: the same crawl at x_tail = 1e6 m
    scores what it scores at 0 (x_tail - x_tail_old there would lose 1e-10 m per step)."""
    rewards, progress = [], []
    for x0 in (0.0, 1e6):
        env = gym.make("Inchworm-v0")
        env.reset(seed=0, options={"x_tail": x0})
        rng = np.random.default_rng(1)
        steps = [env.step(rng.uniform(-1, 1, 4)) for _ in range(12)]
        rewards.append([s[1] for s in steps])
        progress.append([s[4]["reward_terms"]["progress"] for s in steps])
    np.testing.assert_allclose(rewards[0], rewards[1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(progress[0], progress[1], rtol=0, atol=1e-12)
    assert max(abs(r) for r in progress[0]) > 1e-4  # the first step moves the tail (1.9e-4 L)


@pytest.mark.parametrize(
    ("env_id", "kwargs", "steps"),
    [
        ("GOWEC-v0", {"episode_seconds": 0.3}, 15),
        ("GyroStabilizer-v0", {"episode_seconds": 0.3}, 6),
        ("Inchworm-v0", {"episode_seconds": 0.5}, 5),
    ],
)
def test_episode_seconds_and_time_is_steps_times_dt(env_id, kwargs, steps):
    env = gym.make(env_id, **kwargs)
    u = env.unwrapped
    assert u.max_episode_steps == steps
    env.reset(seed=0)
    for k in range(1, steps + 1):
        *_, trunc, info = env.step(np.zeros(env.action_space.shape, np.float32))
        assert info["time"] == k * u.control_dt  # exact: no accumulated round-off
        assert trunc == (k == steps)


def test_long_stabilizer_episode_length_follows_episode_seconds():
    """A 1e4 s episode (200 001 steps with accumulated time): 200 000 now, from gym.make with
    episode_seconds alone."""
    env = gym.make("GyroStabilizer-v0", episode_seconds=1e4)
    assert env.unwrapped.max_episode_steps == 200_000
    assert GyroStabilizerEnv(episode_seconds=1e4).max_episode_steps == 200_000
    assert gym.make("GOWEC-v0").unwrapped.max_episode_steps == 20 * 300  # n_periods default


SECTIONS = (
    "Description",
    "Action Space",
    "Observation Space",
    "Rewards",
    "Starting State",
    "Episode End",
    "Arguments",
    "Version History",
)


@pytest.mark.parametrize("env_id", ENV_IDS)
def test_docstring_sections_and_observation_table_follow_the_layout(env_id):
    env = gym.make(env_id)
    doc = type(env.unwrapped).__doc__
    heads = re.findall(r"^\s*## (.+)$", doc, flags=re.M)
    assert tuple(heads) == SECTIONS
    section = doc.split("## Observation Space")[1].split("## Rewards")[0]
    lines = [r.strip() for r in section.splitlines() if r.strip().startswith("| ")]
    rows = [r.split("|")[2].strip() for r in lines]
    layout = env.unwrapped.obs_layout  # every env's named layout (an instance's for the inchworm)
    assert tuple(rows[1:]) == layout.names  # header row first
    assert env.observation_space.shape == (layout.size,)
    sized = any("n" in r.split("|")[1] for r in lines[1:])  # slots written in n (the inchworm)
    if not sized:
        assert layout.table() in "\n".join(line.strip() for line in doc.splitlines())


def test_no_literal_observation_slots_outside_the_layouts():
    pattern = re.compile(r"\bobs\[\s*(:\s*,\s*)?-?\d")
    offenders = []
    for folder in ("mf_envs/controllers", "mf_envs/envs"):
        for path in (ROOT / folder).rglob("*.py"):
            for n, line in enumerate(path.read_text().splitlines(), 1):
                if pattern.search(line):
                    offenders.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert not offenders, offenders


def test_env_files_are_short():
    for path in (ROOT / "mf_envs/envs").rglob("*.py"):
        n = len(path.read_text().splitlines())
        assert n <= 350, f"{path.relative_to(ROOT)} has {n} lines"


ENV_FILES = {"__init__.py", "env.py", "task.py", "spec.py", "build.py", "rows.py", "vector.py",
             "render.py"}  # fmt: skip


def test_every_env_package_has_the_same_files():
    """One env shape (docs/adding_an_env.md): the same modules with the same roles in every
    `mf_envs/envs/<env>/`."""
    for pkg in sorted(p for p in (ROOT / "mf_envs/envs").iterdir() if (p / "env.py").is_file()):
        files = {p.name for p in pkg.glob("*.py")}
        assert files == ENV_FILES, f"{pkg.name}: {sorted(files ^ ENV_FILES)}"
