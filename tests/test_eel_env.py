"""Eel-v0 beyond the shared contract: the muscles' rate limit, a body in vacuum cannot move its
centre of mass (momentum), the anguilliform wave swims head first and the heading controller
turns towards the target, the render's force arrows, and (slow) the tuned gaits' slip ratio."""

from __future__ import annotations

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs.controllers import make_baseline
from mf_envs.controllers.eel import EFFICIENT, FAST, gait_stats
from mf_envs.envs.eel import render


def _run(env, ctrl, steps, options=None, seed=0):
    obs, info = env.reset(seed=seed, options=options)
    ctrl.reset()
    infos = [info]
    for _ in range(steps):
        obs, _, term, trunc, info = env.step(ctrl.predict(obs)[0])
        infos.append(info)
        assert not term
    return obs, infos


def test_command_moves_at_most_the_muscle_rate_per_step():
    env = gym.make("Eel-v0", max_curvature_rate=300.0)
    env.reset(seed=1)
    base = env.unwrapped
    limit = 300.0 * base.control_dt
    prev = base.cmd.copy()
    for k in range(20):
        a = np.where(np.arange(base.n_ctrl) % 2 == k % 2, 1.0, -1.0).astype(np.float32)
        _, _, _, _, info = env.step(a)
        change = info["kappa_command"] - prev
        assert np.max(np.abs(change)) <= limit * (1 + 1e-12)
        assert np.max(np.abs(change)) == pytest.approx(limit)  # the full swing is rate-limited
        prev = info["kappa_command"]


def test_body_in_vacuum_keeps_its_centre_of_mass():
    """effects=(): no water, so no external force: an actuated body starting at rest keeps its
    centre of mass where it was (linear momentum 0) whatever the muscles do."""
    env = gym.make("Eel-v0", effects=(), numerical_damping=0.0, physics_dt=0.005)
    obs, info = env.reset(seed=2)
    x0 = np.array([info["x"], info["y"]])
    rng = np.random.default_rng(0)
    for _ in range(30):
        _, _, term, _, info = env.step(rng.uniform(-0.3, 0.3, 7).astype(np.float32))
        assert not term
    drift = np.hypot(info["x"] - x0[0], info["y"] - x0[1])
    assert drift < 1e-9 * env.unwrapped.scene.length
    assert np.max(np.abs(env.unwrapped.state[1])) > 1e-2  # the body did move


def test_anguilliform_wave_swims_head_first():
    env = gym.make("Eel-v0")
    ctrl = make_baseline(env, "wave")
    _, infos = _run(env, ctrl, 150, {"heading": 0.0, "kappa": np.zeros(7)})
    speed = np.mean([i["speed"] for i in infos[50:]])
    assert speed > 0.5 * env.unwrapped.scene.length  # > 0.5 L/s along +x (the head's side)
    terms = infos[-1]["reward_terms"]
    assert terms["progress"] > 0.0 > terms["effort"]


def test_heading_controller_turns_towards_the_target():
    env = gym.make("Eel-v0")
    ctrl = make_baseline(env, "heading")
    _, infos = _run(env, ctrl, 250, {"heading": 2.0, "kappa": np.zeros(7)})
    err = [abs(np.angle(np.exp(1j * i["heading"]))) for i in infos]
    assert np.mean(err[-25:]) < 0.5 * err[0]


def test_render_draws_the_fluid_force_arrows():
    env = gym.make("Eel-v0", render_mode="rgb_array")
    ctrl = make_baseline(env, "wave")
    _run(env, ctrl, 20, {"heading": 0.0, "kappa": np.zeros(7)})
    frame = env.render()
    assert frame.dtype == np.uint8 and frame.ndim == 3
    red = np.all(np.abs(frame.astype(int) - render.FORCE) < 40, axis=-1)
    assert red.sum() > 50
    forces = env.unwrapped.water_forces()
    assert np.all(np.isfinite(forces)) and np.max(np.abs(forces[:, 2:])) > 0.0


@pytest.mark.slow
@pytest.mark.parametrize("params", [FAST, EFFICIENT])
def test_tuned_gaits_slip_below_one(params):
    """Thrust needs a body wave faster than the body (Lighthill's mean thrust vanishes at U = c):
    the tuned gaits' slip U / c lies in (0.5, 1); measured 0.85 (fast), 0.65 (efficient)."""
    stats = gait_stats(gym.make("Eel-v0"), params)
    assert 0.5 < stats["slip"] < 1.0
    assert 0.0 < stats["froude"] < 1.0


def test_wave_action_mode_swims_as_the_wave_baseline():
    """action_mode="wave" with the constant action of the `wave` baseline's (a, lambda / L, T)
    makes the same kappa# as the baseline in the curvature mode (up to the float32 rounding of
    the actions): the same swimming speed."""
    from mf_envs.controllers.eel import WAVE
    from mf_envs.envs.eel.build import WAVE_FREQUENCY, WAVE_WAVELENGTH

    base = gym.make("Eel-v0")
    _, ref = _run(base, make_baseline(base, "wave"), 150, {"heading": 0.0, "kappa": np.zeros(7)})
    env = gym.make("Eel-v0", action_mode="wave")
    assert env.action_space.shape == (3,)
    a, lam, period = WAVE
    u = np.array([a / 50.0, (lam - WAVE_WAVELENGTH[0]) / np.ptp(WAVE_WAVELENGTH),
                  (1.0 / period - WAVE_FREQUENCY[0]) / np.ptp(WAVE_FREQUENCY)])  # fmt: skip
    action = (2.0 * u - 1.0).astype(np.float32)
    env.reset(seed=0, options={"heading": 0.0, "kappa": np.zeros(7)})
    infos = [env.step(action)[-1] for _ in range(150)]
    got = np.mean([i["speed"] for i in infos[50:]])
    want = np.mean([i["speed"] for i in ref[51:]])
    assert want > 0.1
    assert got == pytest.approx(want, rel=1e-3)


def test_a_body_too_light_for_its_entrained_water_is_refused_by_name():
    with pytest.raises(ValueError, match=r"^density: must be >= 0.25 x water_density"):
        gym.make("Eel-v0", density=10.0)
    with pytest.raises(ValueError, match="density"):
        gym.make("Eel-v0", density=100.0, water_density=1025.0)


@pytest.mark.parametrize("pattern", ["random", "alternate", "hold"])
def test_the_lightest_allowed_body_survives_bang_bang_strokes(pattern):
    """Reactive force only (no drag to damp anything), density at the lower bound: 400 steps of
    bang-bang curvature commands (random per point, all switching every 5 steps, held then
    reversed) end in no numerical failure."""
    env = gym.make("Eel-v0", density=250.0, effects=("reactive",))
    env.reset(seed=0)
    rng = np.random.default_rng(1)
    shape = env.action_space.shape
    failures = 0
    for k in range(400):
        if pattern == "random":
            a = np.where(rng.random(shape) < 0.5, -1.0, 1.0)
        elif pattern == "alternate":
            a = np.full(shape, 1.0 if (k // 5) % 2 else -1.0)
        else:
            a = np.full(shape, 1.0 if k < 200 else -1.0)
        _, _, term, trunc, info = env.step(a.astype(np.float32))
        failures += bool(info["numerical_failure"])
        if term or trunc:
            env.reset(seed=k + 1)
    assert failures == 0


def _coast(env, seed):
    """Swim the default controller 5 s, command a straight body and coast: the distance along
    the track from 0.5 s after the stop (the body straight) while the speed falls by e [m]."""
    base = env.unwrapped
    _run(env, make_baseline(env), 250, seed=seed)
    xy, speed = [], []
    for _ in range(200):
        env.step(np.zeros(base.action_space.shape, np.float32))
        xy.append(base._body[:2].copy())
        speed.append(np.hypot(base._body[2], base._body[3]))
    xy, speed = np.array(xy), np.array(speed)
    path = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))])
    i0, goal = 25, speed[25] / np.e
    i1 = int(np.argmax(speed < goal))
    assert i1 > i0
    frac = (speed[i1 - 1] - goal) / (speed[i1 - 1] - speed[i1])
    return path[i1 - 1] + frac * (path[i1] - path[i1 - 1]) - path[i0]


@pytest.mark.parametrize("drag_form", [0.13, 0.24])
def test_coasting_distance_is_the_cited_drag_coefficients(drag_form):
    """After the muscles stop, the eel coasts while its speed falls by e the distance
    M / b = `theory.coasting_distance(1, 1/e, M, 0, b)` of M dV/dt = -b V^2, b = k_t L + k_f:
    the drag of a gliding fish (docs/eel.md) at the ends of the cited range of the form-drag
    coefficient, to 0.5 %; without the form drag the eel coasts the skin friction's longer
    M / (k_t L)."""
    from mf_envs.physics.swimmer.theory import coasting_distance

    env = gym.make("Eel-v0", drag_form=drag_form, episode_seconds=100.0)
    scene = env.unwrapped.scene
    mass, water, length = scene.body_mass, scene.water, scene.length
    b = water.k_tangential * length + water.k_form
    want = coasting_distance(1.0, 1.0 / np.e, mass, 0.0, b)
    assert _coast(env, seed=21) == pytest.approx(want, rel=5e-3)
    bare = gym.make("Eel-v0", effects=("resistive", "reactive"), episode_seconds=100.0)
    skin = coasting_distance(1.0, 1.0 / np.e, mass, 0.0, water.k_tangential * length)
    assert _coast(bare, seed=21) == pytest.approx(skin, rel=5e-3)
    assert want < 0.75 * skin


@pytest.mark.parametrize("seed", [3, 4])
def test_muscle_power_stays_within_its_limit_under_bang_bang_strokes(seed):
    """Effect `muscle_power` (default): the muscles' positive power of every control step
    (actuation energy / control_dt) stays within 1 % of muscle_power_density x
    muscle_mass_fraction x body mass (0.249 W), where the same strokes without the limit reach
    several times it; nothing fails."""
    rng = np.random.default_rng(seed)
    actions = rng.choice([-1.0, 1.0], size=(200, 7)).astype(np.float32)
    powers = {}
    for effects in (None, ("resistive", "reactive", "form_drag")):
        env = gym.make("Eel-v0", effects=effects)
        env.reset(seed=seed)
        base = env.unwrapped
        out = []
        for a in actions:
            _, _, term, _, info = env.step(a)
            assert not term
            out.append(info["actuation_energy"] / base.control_dt)
        powers[effects is None] = np.array(out)
    cap = 22.0 * 0.5 * env.unwrapped.scene.body_mass
    assert np.max(powers[True]) <= 1.01 * cap
    assert np.max(powers[False]) > 3.0 * cap
    assert np.mean(powers[True] > 0.95 * cap) > 0.2  # the limit binds on many steps


def test_a_muscle_power_limit_above_the_need_changes_nothing():
    """The `heading` baseline needs at most 0.22 W (docs/eel.md): with a limit of 100x that the
    run is bit for bit the run without the effect."""
    runs = []
    for kw in ({"muscle_power_density": 4400.0}, {"effects": ("resistive", "reactive",
                                                             "form_drag")}):  # fmt: skip
        env = gym.make("Eel-v0", **kw)
        obs, infos = _run(env, make_baseline(env), 100, seed=2)
        runs.append(obs)
    assert np.array_equal(runs[0], runs[1])


def test_kinematics_of_a_run_follow_the_commanded_wave():
    """`gait_kinematics` on the `eel` gait (a, lambda / L, T) = EEL: the tail beats at the
    commanded 1 / T (to 0.5 %), the body's wave runs at the commanded lambda within 5 % (the
    body is not the command: it lags and bends under the water's load), V = f lambda, slip =
    U / V below one, St = f 2 A / U; the speed is gait_stats' over the same window (1 %)."""
    from mf_envs.controllers.eel import EEL, gait_kinematics

    env = gym.make("Eel-v0", episode_seconds=20.0)
    k = gait_kinematics(env, "eel", seconds=6.0, warmup=3.0, seed=4)
    length = env.unwrapped.scene.length
    assert k["frequency"] == pytest.approx(1.0 / EEL[2], rel=5e-3)
    assert k["wavelength"] == pytest.approx(EEL[1] * length, rel=5e-2)
    assert k["wave_speed"] == pytest.approx(k["frequency"] * k["wavelength"], rel=1e-12)
    assert 0.5 < k["slip"] < 1.0
    assert k["strouhal"] == pytest.approx(k["frequency"] * 2 * k["amplitude"] / k["speed"])
    assert k["froude_lighthill"] == pytest.approx(0.5 * (1 + k["slip"]))
    stats = gait_stats(gym.make("Eel-v0"), EEL, seconds=6.0, warmup=3.0, seed=4)
    assert k["speed"] == pytest.approx(stats["speed"], rel=1e-2)
