"""Serpentine-v0 against independent truth (the contract tests cover the API): the physics
model's own time loop for the same gait, momentum, the discrete energy balance, the start shape
and the heading controller."""

from __future__ import annotations

import inspect
import math

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs.benchmarks.accuracy.serpentine import env_speed
from mf_envs.controllers import make_baseline
from mf_envs.envs.serpentine.env import SerpentineEnv
from mf_envs.physics.beam.algorithmic import assemble_algorithmic
from mf_envs.physics.beam.banded import band_matvec
from mf_envs.physics.serpentine import Serpentine, serpenoid

ENV_ID = "Serpentine-v0"
SPEED_TOLERANCE = 0.05  # relative speed error the default discretisation is chosen to hold


def _rest(env, heading=0.0):
    u = env.unwrapped
    return env.reset(seed=0, options={"heading": heading, "kappa": np.zeros(u.n_ctrl)})


def test_serpenoid_speed_equals_the_physics_models_simulate():
    """The env driven through its actions (kappa# sampled at 25 control points, linear in S and
    in t) vs `Serpentine.simulate` with the continuous serpenoid on the same rod and ground:
    same speed over 4-10 s (measured ratio 0.99x, the rest is the sampling). Both with the
    body's Kelvin-Voigt damping, the muscles without their lag (the model has none)."""
    dt, a, lam, period, ramp = 0.01, 20.0, 0.35, 2.0, 1.0
    env = gym.make(ENV_ID, n_control_points=25, control_dt=dt, physics_dt=dt, max_curvature=25.0,
                   effects=("friction",), max_episode_steps=2000)  # fmt: skip
    u = env.unwrapped
    model = Serpentine(u.scene.params, u.scene.ground, material_damping=u.scene.material_damping)
    model.gait = serpenoid(model.model.gauss_S, a, lam, period, direction=-1, ramp_time=ramp)
    hist = model.simulate(10.0, dt, every=1, tol=1e-10)
    ref = hist.mean_speed(4.0, 10.0)
    _rest(env)
    s = np.linspace(0.0, u.scene.length, u.n_ctrl)
    com = {}
    for k in range(1, 1001):
        t = k * dt
        kappa = (
            min(1.0, t / ramp)
            * a
            * np.sin(2 * np.pi * (u.scene.length - s) / lam - 2 * np.pi * t / period)
        )
        *_, info = env.step((kappa / u.max_curvature).astype(np.float32))
        if k in (400, 1000):
            com[k] = np.array([info["x"], info["y"]])
    speed = np.linalg.norm(com[1000] - com[400]) / 6.0
    assert ref > 0.02  # it crawls (m/s)
    assert speed == pytest.approx(ref, rel=0.02)


def test_frictionless_body_keeps_its_centre_of_mass_under_any_action():
    env = gym.make(ENV_ID, effects=())
    _, info0 = env.reset(seed=3)
    rng = np.random.default_rng(0)
    moved = 0.0
    for _ in range(40):
        *_, info = env.step(rng.uniform(-1, 1, env.action_space.shape).astype(np.float32))
        assert not info["numerical_failure"]
        moved = max(moved, math.hypot(info["x"] - info0["x"], info["y"] - info0["y"]))
    assert moved < 1e-9  # m: linear momentum is conserved by the scheme (started at rest)
    assert np.max(np.abs(env.unwrapped.state[1])) > 1e-3  # while the body did move


def test_actuation_energy_closes_the_discrete_energy_balance():
    """One physics step per control step: the muscles' net work is dKE + dU + D - W_ground,
    with KE from the mass matrix, U the beam's stored energy, D the body's Kelvin-Voigt
    dissipation (tau / dt) int deps^T C deps dS and W_ground the ground force at the step's end
    (theta = 1) times the displacement: the scheme's exact balance (default effects: the muscles
    lag their command)."""
    env = gym.make(ENV_ID, control_dt=0.01, physics_dt=0.01, max_episode_steps=2000)  # 20 s
    u = env.unwrapped
    m = u.model
    tau = u.scene.material_damping
    assert tau > 0.0
    zero = np.zeros((m.n_elements, 4))

    def dissipation(d0, d1):
        qxi, qw, stiff = m.quad
        de = assemble_algorithmic(d0, d1, m.le, zero, zero, qxi, qw, stiff, 0.5,
                                  np.zeros((m.n_elements, len(qxi), 3)), False, 1.0)[2]  # fmt: skip
        w = qw[None, :] * m.le[:, None]
        return tau / u.physics_dt * float(np.einsum("eg,gr,egr->", w, stiff, de**2))

    interp = u.cfg.interp
    model = Serpentine(u.scene.params, u.scene.ground)
    env.reset(seed=1)
    ctrl = make_baseline(env, "serpenoid")

    def energy():
        d, v = u.state
        return 0.5 * v @ band_matvec(m.mass, v) + m.elastic_energy(
            d, (interp @ u.cmd).reshape(-1, 4)
        )

    checked = 0
    obs = None
    for k in range(120):
        e0, d0 = energy(), u.state[0].copy()
        obs, *_, info = env.step(ctrl.predict(obs)[0])
        if k < 3:  # the jump from the start noise splits the steps (the balance is per substep;
            continue  # at 10 ms no later step is split: measured)
        f, _ = model.ground_force(*u.state)
        balance = energy() - e0 + dissipation(d0, u.state[0]) - f @ (u.state[0] - d0)
        assert info["actuation_net_work"] == pytest.approx(balance, rel=1e-6, abs=1e-10)
        # positive work per (sub)step: at least the net work, equal when no step was split
        assert info["actuation_energy"] >= max(balance, 0.0) - 1e-10
        checked += balance > 1e-6
    assert checked > 20


def test_start_shape_has_the_asked_curvature_heading_and_rest():
    env = gym.make(ENV_ID)
    u = env.unwrapped
    kappa = np.linspace(-3.0, 4.0, u.n_ctrl)
    obs, info = env.reset(seed=0, options={"heading": 0.5, "kappa": kappa})
    lay = u.obs_layout
    np.testing.assert_allclose(obs[lay.slice("curvature")], kappa * u.scene.length, atol=2e-3)
    assert math.hypot(info["x"], info["y"]) < 1e-6
    np.testing.assert_array_equal(obs[lay.slice("velocity")], 0.0)
    mean_psi = np.mean(u.model.fields(u.state[0], 32)["psi"])
    assert mean_psi == pytest.approx(0.5, abs=2e-3)


def _travel_direction(env, kind, heading, seconds=24.0):
    obs, info = _rest(env, heading)
    ctrl = make_baseline(env, kind)
    track = []
    for _ in range(round(seconds / env.unwrapped.control_dt)):
        obs, *_, info = env.step(ctrl.predict(obs)[0])
        track.append((info["x"], info["y"]))
    tail = np.array(track[-len(track) // 4 :])
    dx, dy = tail[-1] - tail[0]
    return math.atan2(dy, dx)


def test_heading_controller_turns_the_snake_toward_the_target():
    env = gym.make(ENV_ID, episode_seconds=30.0, max_episode_steps=600)
    start = 1.2  # rad off the target direction (+x)
    open_loop = _travel_direction(env, "tuned", start)
    closed = _travel_direction(env, "heading", start)
    assert abs(open_loop) > 0.6  # the open-loop gait keeps roughly its start direction
    assert abs(closed) < 0.3  # the heading controller crawls along the target


def test_a_beam_robot_without_its_row_step_cannot_be_made():
    # the shared control step (envs._beam_robot) needs each robot's row step, heading, drawing
    from mf_envs.envs._beam_robot import BeamRobotMixin
    from mf_envs.envs.serpentine.env import SerpentineEnv

    class NoHeading(SerpentineEnv):
        _heading = BeamRobotMixin._heading

    with pytest.raises(TypeError, match="_heading"):
        NoHeading()


@pytest.mark.slow
def test_pyelastica_preset_crawls_at_pyelastica_speed_through_gym_make():
    """`gym.make("Serpentine-v0", preset="pyelastica")` under its `elastica_muscles` baseline
    against PyElastica 1.0's continuum snake itself (n = 50, dt = 1e-4, the `compare` extra),
    side by side in one run: the forward speed over periods 5-11 within 3 %. (The CPU ratio is
    the speed benchmark's row, `benchmarks.speed.snake_elastica`.)"""
    pytest.importorskip("elastica")
    from mf_envs.benchmarks.speed.snake_elastica import forward_speed, run_elastica, run_env_preset

    t, com, _ = run_elastica(50, 1e-4)
    v_ref = forward_speed(t, com)
    t, com, _ = run_env_preset()
    assert forward_speed(t, com) == pytest.approx(v_ref, rel=0.03)


def test_preset_sets_its_scene_and_refuses_a_clash():
    """The preset is the scene of `build.PYELASTICA_SCENE`; a kwarg it sets, given as well, or
    an unknown preset is a ValueError naming it."""
    from mf_envs.envs.serpentine import build

    env = gym.make("Serpentine-v0", preset="pyelastica").unwrapped
    assert env.n_ctrl == 61 and env.model.n_elements == 10 and env.physics_dt == 0.01
    assert env.scene.material_damping == 0.0 and env.effects == frozenset({"friction"})
    law = env.scene.ground
    assert law.drag_rate == build.PYELASTICA_DAMPER
    assert law.couple_damping == pytest.approx(
        build.PYELASTICA_DAMPER * env.scene.params.mass_per_length
    )
    with pytest.raises(ValueError, match="n_elements"):
        gym.make("Serpentine-v0", preset="pyelastica", n_elements=8)
    with pytest.raises(ValueError, match="preset"):
        gym.make("Serpentine-v0", preset="pyelastic")


def test_default_discretisation_converges_for_a_fast_saturated_gait():
    """At the defaults (n_elements, physics_dt) the gait PPO found (`PPO_LIKE`: 1.6 Hz, nearly in
    phase, at the action bounds a third of the time, near the body's first bending mode; open
    loop from rest, speed over 4-10 s) moves within SPEED_TOLERANCE of 2 n_elements at
    physics_dt / 4 (measured 2.3 %; the old defaults, 6 elements at 25 ms, moved it 2.4 times
    as fast: docs/serpentine.md, "What accuracy costs in time")."""
    sig = inspect.signature(SerpentineEnv.__init__)
    n, dt = sig.parameters["n_elements"].default, sig.parameters["physics_dt"].default
    coarse, _ = env_speed(n, dt, "saturated")
    fine, _ = env_speed(2 * n, dt / 4, "saturated")
    assert fine > 0.02  # it crawls
    assert coarse == pytest.approx(fine, rel=SPEED_TOLERANCE)
