"""Inchworm-v0's buildable default robot (issue 31): SMA wires that heat and cool, feet that must
grip, the quasi-static check, the honest cost of transport and the published robot.

Independent truth: the maker's still-air relaxation time (Dynalloy F1140: 1.2 s for the 0.15 mm
HT wire), Joule's law I^2 R' l, the bent body's strain energy 1/2 EI int kappa^2 dS, Wang et al.
2014's stride (1/3 body) and speed (3.6 mm/s), the sizing by hand (EI kappa / (172 MPa area)),
and the issue's limits (5 % of the tuned gait's speed below the grip threshold)."""

from __future__ import annotations

import math

import gymnasium as gym
import numpy as np
import pytest

import mf_envs  # noqa: F401  (registers the ids)
from mf_envs.controllers import make_baseline
from mf_envs.controllers.inchworm import VALIDATION_COOL, VALIDATION_HEAT, _tune_wires
from mf_envs.envs.inchworm import LAG_FRICTION_SCENE
from mf_envs.envs.inchworm.spec import QUASI_STATIC_LIMIT
from mf_envs.physics.actuators.sma import RATED_STRESS, maker_times
from mf_envs.physics.beam import GAUSS_W
from mf_envs.physics.inchworm.open_loop import heat_cool_gait
from mf_envs.physics.inchworm.presets import BuildableInchworm

WANG_SPEED = 3.6e-3  # m/s, Wang et al. 2014 (abstract)
WANG_STRIDE = 1.0 / 3.0  # body lengths per stride (abstract: "nearly one third")
MAKER_COOLING_HT_015 = 1.2  # s, Dynalloy F1140, 0.15 mm HT wire in still air


def _env(**kw):
    # 10**6 control steps: the env's own length (gym.make's max_episode_steps is a TimeLimit)
    return gym.make("Inchworm-v0", episode_seconds=10**6 * kw.get("control_dt", 0.1), **kw)


def _crawl(env, ctrl, warm_cycles=2, cycles=3, seed=1000):
    """Speed [m/s] and stride [body lengths per cycle] of the feet's midpoint, electrical and
    mechanical energy [J] and the largest quasi_static_error over `cycles` periods of the
    open-loop gait after a warm-up."""
    base = env.unwrapped
    obs, info = env.reset(seed=seed)
    ctrl.reset()
    dt = base.control_dt
    n_warm = int(round(warm_cycles * ctrl.period / dt))
    n_meas = int(round(cycles * ctrl.period / dt))
    elec = mech = qse = 0.0
    for k in range(n_warm + n_meas):
        if k == n_warm:
            x0, elec, mech, qse = _mid(info), 0.0, 0.0, 0.0
        obs, _, term, _, info = env.step(ctrl.predict(obs)[0])
        assert not term and not info["numerical_failure"]
        elec += info["electrical_energy"]
        mech += info["mechanical_work"]
        qse = max(qse, info["quasi_static_error"])
    dist = _mid(info) - x0
    return dist / (n_meas * dt), dist / base.params.length / cycles, elec, mech, qse, dist


def _mid(info):
    """The feet's midpoint [m] (a body curling up over the warm-up does not count)."""
    return 0.5 * (info["x_tail"] + info["x_head"])


# ------------------------------------------------------------------ 1. the buildable robot
def test_the_default_robot_is_the_buildable_preset():
    env = _env()
    base, b = env.unwrapped, BuildableInchworm()
    p = base.params
    assert (p.length, p.width, p.height) == (b.length, b.width, b.height)
    assert p.youngs_modulus == b.youngs_modulus and base.max_curvature == b.kappa
    assert p.mass_per_length == pytest.approx(b.density * b.width * b.height, rel=1e-12)
    wires = base.scene.wires
    # sized by hand: EI kappa / e over the maker's 172 MPa x area, rounded up
    ei = b.youngs_modulus * b.width * b.height**3 / 12.0
    force = ei * b.kappa / b.lever_arm
    per_wire = RATED_STRESS * math.pi * b.wire_diameter**2 / 4.0
    assert wires.params.n_wires == math.ceil(force / per_wire)
    assert wires.params.n_wires * per_wire >= force
    strain = b.kappa * b.lever_arm  # the wires' recovery strain at full curl
    assert wires.params.strain_max == pytest.approx(strain, rel=1e-12)
    assert 0.02 <= strain <= 0.06  # Flexinol's repeatable range
    assert wires.kappa_full == base.max_curvature


@pytest.mark.parametrize(
    "kwargs, name",
    [
        ({"max_curvature": 120.0}, "max_curvature"),  # 120 x 0.6 mm = 7.2 % > 6 %
        ({"wire_lever_arm": 2e-3}, "wire_lever_arm"),  # outside the 3 mm section
        ({"wire_diameter": 3e-4}, "wire_diameter"),  # no such Flexinol row
        ({"wire_alloy": "XT"}, "wire_alloy"),
        ({"ambient_temperature": 70.0}, "ambient_temperature"),
        ({"grip_threshold": 0.95}, "grip_threshold"),
    ],
)
def test_an_unbuildable_robot_names_the_parameter(kwargs, name):
    with pytest.raises(ValueError, match=name):
        _env(**kwargs)


def test_the_sma_scene_refuses_an_outward_curl_at_reset():
    env = _env()
    with pytest.raises(ValueError, match="kappa"):
        env.reset(seed=0, options={"kappa": np.array([0.0, 5.0, 0.0])})


# ------------------------------------------------------------------ 2. wires that heat and cool
def test_the_wires_step_response_against_the_maker():
    """Duty 1 from rest until every group has contracted (95 % of its stroke), then the current
    off: the contraction time is the wire model's at the rated current (`sma.maker_times`, to one
    control step), the relaxation time is the maker's still-air cooling time of the 0.15 mm HT
    wire, 1.2 s, within 20 %. (The maker's ~1 s contraction at 0.4 A is not reproduced: the
    model's 2.9 s, docs/inchworm.md.)"""
    env = _env()
    base = env.unwrapped
    env.reset(seed=0, options={"kappa": np.zeros(3)})
    k_full, dt = base.max_curvature, base.control_dt
    n = base.action_space.shape[0]
    t, t_contracted = 0.0, None
    while t_contracted is None:
        _, _, _, _, info = env.step(np.ones(n, np.float32))
        t += dt
        if np.all(info["kappa_sharp"] <= -0.95 * k_full):
            t_contracted = t
        assert t < 10.0
    t_model, _ = maker_times(base.scene.wires.params)
    assert abs(t_contracted - t_model) <= 2 * dt  # 0.1 s steps: the latent heat per substep
    t, t_relaxed = 0.0, None
    while t_relaxed is None:
        _, _, _, _, info = env.step(-np.ones(n, np.float32))
        t += dt
        if np.all(info["kappa_sharp"] >= -0.05 * k_full):
            t_relaxed = t
        assert t < 10.0
    assert t_relaxed == pytest.approx(MAKER_COOLING_HT_015, rel=0.2)


def test_the_effort_is_the_electrical_energy():
    """Per step: sum over groups of duty I_rated^2 R' (L / n) n_wires dt (Joule heating of the
    maker's resistance per length at its rated current), and effort = -w E."""
    env = _env(effort_weight=3.0)
    base = env.unwrapped
    env.reset(seed=0)
    w = base.scene.wires.params
    rng = np.random.default_rng(3)
    for _ in range(5):
        a = rng.uniform(-1, 1, base.action_space.shape).astype(np.float32)
        _, _, _, _, info = env.step(a)
        duty = 0.5 * (a[:3].astype(float) + 1.0)
        joule = float(np.sum(duty)) * w.current**2 * w.resistance_per_length * w.length
        assert info["electrical_energy"] == pytest.approx(joule * w.n_wires * 0.1, rel=1e-12)
        assert info["reward_terms"]["effort"] == pytest.approx(-3.0 * info["electrical_energy"])
        assert np.array_equal(info["duty"], duty)


# ------------------------------------------------------------------ 3. feet that must grip
def _hold_grips_speed(g_hold, t_heat, t_cool, duty_off, cycles=3, warm=5):
    """The default robot driven by the heat/cool gait with both feet's engagement held at g_hold
    (their command equals their state, so they stay): speed of the feet's midpoint [m/s]."""
    env = _env()
    base = env.unwrapped
    env.reset(seed=0, options={"kappa": np.zeros(3)})
    driven, dt = base.driven, base.control_dt
    driven.g = np.array([g_hold, g_hold])
    fn = heat_cool_gait(t_heat, t_cool, base.n_ctrl, duty_off)
    period = t_heat + t_cool
    n_warm, n_meas = int(round(warm * period / dt)), int(round(cycles * period / dt))
    sim = driven.sim
    for k in range(n_warm + n_meas):
        if k == n_warm:
            x0 = 0.5 * (sim.x_tail + sim.x_head)
        u = fn((k + 1) * dt)
        driven.step(u, None, dt, grip=np.array([g_hold, g_hold]))
        assert np.all(driven.g == g_hold)
    return (0.5 * (sim.x_tail + sim.x_head) - x0) / (n_meas * dt)


def test_feet_held_just_below_the_threshold_do_not_crawl():
    """The issue's test: both grips held at the threshold - 1 % crawl at <= 5 % of the tuned
    gait's speed (with the tuned gait's own timing and the validation timing)."""
    env = _env()
    base = env.unwrapped
    t_heat, t_cool, off, speed = _tune_wires(base.drive_config())
    tuned = speed * base.params.length
    g = base.scene.grip_feet.law.threshold - 0.01
    assert tuned > 0.0
    assert abs(_hold_grips_speed(g, t_heat, t_cool, off)) <= 0.05 * tuned
    assert abs(_hold_grips_speed(g, VALIDATION_HEAT, VALIDATION_COOL, 0.0)) <= 0.05 * tuned


def _two_step_speed(dt, cycles=4, warm=2):
    """The fastest possible command: wires heated for one control step (head gripping) and off
    for the next (tail gripping), period 2 dt; tail speed [m/s]."""
    env = _env(control_dt=dt, physics_dt=dt)
    env.reset(seed=0, options={"kappa": np.zeros(3)})
    for k in range(2 * (warm + cycles)):
        sign = 1.0 if k % 2 == 0 else -1.0
        _, _, _, _, info = env.step(np.full(4, sign, np.float32))
        assert not info["numerical_failure"]
        if k == 2 * warm - 1:
            x0 = info["x_tail"]
    return (info["x_tail"] - x0) / (2 * cycles * dt)


def test_gait_speed_falls_when_the_control_step_is_shorter_than_the_cooling():
    """Frequency is not free: the one-step-heat, one-step-cool gait slows as the control step
    (half its period) drops below the wires' 1.3 s relaxation, and stops at 0.1 s (issue 31:
    on issue 16's robot it crawled fastest at the shortest step)."""
    speeds = [_two_step_speed(dt) for dt in (2.4, 1.8, 1.2, 0.6, 0.1)]
    assert speeds[0] > 0.0
    assert all(a > b for a, b in zip(speeds[:3], speeds[1:3]))
    assert max(abs(s) for s in speeds[3:]) <= 0.02 * speeds[0]


# ------------------------------------------------------------------ 4. the quasi-static check
def test_the_quasi_static_flag_fires_on_the_old_5_hz_gait_only():
    """Issue 16's tuned gait (T = 0.2 s, a = 7.30, b = 5.45 1/m on the seed's body): its feet
    jerk by 20 mm per 0.1 s step: inertia above QUASI_STATIC_LIMIT of the friction. The SMA
    robot's validation gait stays below it."""
    old = _env(**LAG_FRICTION_SCENE)
    gait = make_baseline(old, "tuned", period=0.2, amplitude=7.30, bias=5.45)
    speed, *_, qse_old, _ = _crawl(old, gait, warm_cycles=8, cycles=5)
    assert speed > 0.05  # it crawls (m/s)
    assert qse_old > QUASI_STATIC_LIMIT
    new = _env()
    *_, qse_new, _ = _crawl(new, make_baseline(new, "heat_cool"))
    assert qse_new < QUASI_STATIC_LIMIT < qse_old


# ------------------------------------------------------------------ 5. cost of transport
def test_wire_work_is_the_bent_bodys_strain_energy_and_the_electrical_cost_dwarfs_it():
    """Curling the body from straight with the head gripping: the wires' mechanical work (info
    `mechanical_work`, the work of EI kappa# on the body) equals the rise of 1/2 EI int kappa^2
    dS of the realised curvature and at most 15 % more (gravity and the feet take the rest);
    the electrical energy is > 100 x that (SMA efficiency of order 1 %)."""
    env = _env()
    base = env.unwrapped
    env.reset(seed=0, options={"kappa": np.zeros(3)})
    model, ei = base.sim.model, base.params.EI

    def bending_energy():
        kappa = model.gauss_fields(base.sim.state.d)["kappa"]
        return 0.5 * ei * float(np.sum(model.le[:, None] * GAUSS_W[None, :] * kappa**2))

    u0, work, elec = bending_energy(), 0.0, 0.0
    for _ in range(40):  # 4 s at duty 1: fully contracted
        _, _, _, _, info = env.step(np.ones(4, np.float32))
        work += info["mechanical_work"]
        elec += info["electrical_energy"]
    bent = bending_energy() - u0
    assert bent <= work <= 1.15 * bent  # measured: +10 %, lifting the hump and the feet
    assert elec > 100.0 * work


# ------------------------------------------------------------------ 6. the published robot
def test_wang_2014_stride_and_speed_within_30_percent():
    """Wang et al. 2014 (SMA in PDMS, the seed's robot): 3.6 mm/s, stride about a third of the
    body. Ours: the validation gait (heated at the rated current for the model's 2.9 s
    contraction, cooled for the maker's 1.2 s), Eq. 102 grips; 2 warm-up cycles, 3 measured."""
    env = _env()
    speed, stride, elec, mech, _, dist = _crawl(env, make_baseline(env, "heat_cool"))
    assert speed == pytest.approx(WANG_SPEED, rel=0.3)
    assert stride == pytest.approx(WANG_STRIDE, rel=0.3)
    p = env.unwrapped.params
    weight = p.mass_per_length * p.gravity * p.length
    assert elec / (weight * dist) > 100.0 * mech / (weight * dist)  # CoT: electrical >> mech


def test_dynamic_feet_agree_with_the_quasi_static_step_to_a_few_percent():
    """The tuned gait run both ways from the same warmed-up state (3 cycles): the energy-momentum
    beam with the feet's friction as a velocity-dependent load (`dynamic_feet.run_dynamic`)
    crawls within 8 % of the quasi-static step (measured -4.9 %: 4.79 vs 5.04 mm/s), and with
    the inertia scaled to 0.1 the gap shrinks (measured -1.7 %): what is left is the time
    discretisation of the regularised friction, the rest is inertia."""
    import pickle

    from mf_envs.physics.inchworm.drive import make_driven
    from mf_envs.physics.inchworm.dynamic_feet import run_dynamic

    env = _env()
    cfg = dict(env.unwrapped.drive_config())
    dt = cfg.pop("control_dt")
    cfg.pop("max_curvature")
    t_heat, t_cool, off, _speed = _tune_wires(env.unwrapped.drive_config())
    fn = heat_cool_gait(t_heat, t_cool, 3, off)
    per_cycle = int(round((t_heat + t_cool) / dt))
    driven = make_driven(**cfg)
    driven.reset(np.zeros(3))
    n_warm = 4 * per_cycle
    for k in range(n_warm):
        u = fn((k + 1) * dt)
        driven.step(u, "head" if u[0] == 1.0 else "tail", dt)
    start = pickle.dumps(driven)
    n = 3 * per_cycle
    quasi = pickle.loads(start)
    mid0 = 0.5 * (quasi.sim.x_tail + quasi.sim.x_head)
    for k in range(n_warm, n_warm + n):
        u = fn((k + 1) * dt)
        quasi.step(u, "head" if u[0] == 1.0 else "tail", dt)
    v_qs = (0.5 * (quasi.sim.x_tail + quasi.sim.x_head) - mid0) / (n * dt)

    def dynamic(mass_scale):
        feet = run_dynamic(pickle.loads(start), fn, dt, n, 10, n_warm * dt, mass_scale)
        return (feet[-1].mean() - feet[0].mean()) / (n * dt)

    v_full, v_light = dynamic(1.0), dynamic(0.1)
    assert v_full == pytest.approx(v_qs, rel=0.08)
    assert abs(v_light - v_qs) < abs(v_full - v_qs)


@pytest.mark.slow
def test_stored_tuned_gait_is_the_brute_force_optimum():
    """The default baseline (`tuned`) uses the stored optimum on the default robot; the brute
    force over heating, cooling and keep-warm duty finds the same point."""
    from mf_envs.controllers import inchworm as ctrl

    t_heat, t_cool, off, speed = ctrl._tune_wires(ctrl._default_config())
    assert (t_heat, t_cool, off) == pytest.approx(ctrl.TUNED_SMA, abs=1e-9)
    assert speed > 0.08  # L/s (docs/inchworm.md: 0.0829 L/s)


def test_wires_stay_under_their_over_temperature_limit():
    """The default wires at full duty for 30 s (25 time constants) reach the lumped balance's
    fixed point ambient + I^2 R' / (h p) = 123.3 degC (to 1e-6 K) and never exceed it, under the
    150 degC limit; a robot whose wires would pass the limit (50 degC still air: 153 degC) is
    refused naming ambient_temperature, a limit at or below Af naming max_wire_temperature."""
    env = gym.make("Inchworm-v0", episode_seconds=60.0)
    env.reset(seed=0)
    base = env.unwrapped
    bound = base.scene.wires.params.steady_temperature(1.0)
    assert bound == pytest.approx(123.319, abs=1e-3)
    hottest = []
    for _ in range(round(30.0 / base.control_dt)):
        _, _, term, _, info = env.step(np.ones(base.action_space.shape, np.float32))
        assert not term
        hottest.append(float(np.max(info["wire_temperature"])))
    assert max(hottest) <= bound + 1e-9
    assert hottest[-1] == pytest.approx(bound, abs=1e-6)
    with pytest.raises(ValueError, match="^ambient_temperature"):
        gym.make("Inchworm-v0", ambient_temperature=50.0)
    with pytest.raises(ValueError, match="^max_wire_temperature"):
        gym.make("Inchworm-v0", max_wire_temperature=100.0)  # HT's Af
    assert gym.make("Inchworm-v0", ambient_temperature=40.0) is not None  # 143 degC
