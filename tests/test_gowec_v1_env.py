"""FloatingGOWEC-v0 env: contract, energy balance, matched PTO, stiff-hull limit, radiation
bound."""

import math

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import mf_envs  # noqa: F401
from mf_envs.controllers import make_baseline
from mf_envs.controllers.gowec_v1 import matched_pto
from mf_envs.envs.gowec_v1 import spec
from mf_envs.physics.gowec import analytic_max_power
from mf_envs.physics.gowec.hydro import HullCoefficients, load_hull
from mf_envs.physics.gowec.hydro.model import motion_limited_bound


def _episode(env, kind, seed, electrical=False, **ctrl):
    if kind == "ppo":
        from mf_envs.train.policy import load_policy

        c = load_policy("FloatingGOWEC-v0")
    else:
        c = make_baseline(env, kind, **ctrl)
    obs, _ = env.reset(seed=seed)
    c.reset()
    P, Pe, done, tilt = [], [], False, 0.0
    while not done:
        a, _ = c.predict(obs)
        obs, _, term, trunc, info = env.step(a)
        P.append(info["power_mechanical"])
        Pe.append(info["power"])
        tilt = max(tilt, abs(info["buoy_pitch"]), abs(info["buoy_roll"]))
        done = term or trunc
    info = dict(info, max_tilt=tilt)  # the episode's largest |theta| or |rho| (rad)
    if electrical:
        return np.array(P), info, np.array(Pe)
    return np.array(P), info


def test_api_contract():
    env = gym.make("FloatingGOWEC-v0", episode_seconds=2.0)
    check_env(env.unwrapped)
    obs, info = env.reset(seed=0, options={"buoy_pitch": 0.05, "gimbal_rate": 1.0})
    assert set(spec.INFO_KEYS) <= set(info)  # the spec's declaration (docs/api.md keys and more)
    assert info["buoy_pitch"] == 0.05 and info["buoy_rate"].shape == (2,)
    with pytest.raises(ValueError, match="wave_phase"):
        env.reset(options={"wave_phase": 1.0})
    with pytest.raises(ValueError, match="generator_efficiency"):
        gym.make("FloatingGOWEC-v0", generator_efficiency=1.5)
    with pytest.raises(ValueError, match="hull"):
        gym.make("FloatingGOWEC-v0", hull="/nonexistent/hull.npz")
    u = gym.make("FloatingGOWEC-v0", device="seed_buoy").unwrapped  # the 0.1-0.4 device's figures
    assert u.hydrostatic_stiffness() == load_hull().stiffness
    assert u.natural_period() == pytest.approx(5.427, rel=1e-3)
    box = env.unwrapped  # the default: ISWEC's 15 x 8 m box, its length along the sea
    # pitch C55 of the mesh against the exact box's rho g (B L^3 / 12 + V z_B) - m g z_G
    L, B, d, zg, rho, g = 15.0, 8.0, 3.2, -0.5, 1025.0, 9.81
    vol = L * B * d
    exact = rho * g * (B * L**3 / 12 - vol * d / 2) - rho * vol * g * zg  # 18.377e6
    assert box.hydrostatic_stiffness() == pytest.approx(exact, rel=1e-3)
    assert box.natural_period() == pytest.approx(5.164, rel=1e-3)
    iswec = gym.make("FloatingGOWEC-v0", device="iswec_class").unwrapped  # the cylinder
    # C55 of the mesh (8.0977e6) against the exact cylinder's rho g (I_wp + V z_B) - m g z_G
    r, d = 6.0, 2.5
    vol = math.pi * r * r * d
    exact = rho * g * (math.pi * r**4 / 4 - vol * d / 2) - rho * vol * g * zg  # 8.1027e6
    assert iswec.hydrostatic_stiffness() == pytest.approx(exact, rel=1e-3)
    assert iswec.natural_period() == pytest.approx(5.800, rel=1e-3)
    # two units of J = 1.2e4 kg m^2 at 250 rpm: 2 x 1/2 J w^2 = 8.22 MJ, reported, not charged
    assert iswec.spool_up_energy() == pytest.approx(2 * 0.5 * 1.2e4 * (250 * math.pi / 30) ** 2)
    # deep-water flux rho g^2 a^2 T / (8 pi) of the seed buoy's pitch-only table; at the ISWEC
    # table's 35 m, times c_g / c_g(deep) = tanh(kh) (1 + 2 kh / sinh 2kh) with k from
    # w^2 = g k tanh(kh) (brentq, independently)
    from scipy.optimize import brentq

    deep = 1025 * 9.81**2 * 6.0 / (8 * math.pi)
    assert u.wave_power_flux() == pytest.approx(deep, rel=1e-12)
    w, h = 2 * math.pi / 6.0, 35.0
    k = brentq(lambda k: 9.81 * k * math.tanh(k * h) - w * w, 1e-6, 10.0, xtol=1e-15)
    ratio = math.tanh(k * h) * (1 + 2 * k * h / math.sinh(2 * k * h))
    assert iswec.wave_power_flux() == pytest.approx(deep * ratio, rel=1e-9)
    a = [env.reset(seed=3)[0] for _ in range(2)]
    assert np.array_equal(a[0], a[1])


@pytest.mark.parametrize("device, kind, direction", [
    ("seed_buoy", "pll", math.pi / 2), ("iswec_class", "efficient_pto", math.pi / 2),
    ("iswec_box", "efficient_pto", math.pi / 2), ("iswec_box", "efficient_pto", 1.2)])  # fmt: skip
def test_energy_balance_irregular(device, kind, direction):
    """300 s of JONSWAP Hs 1.5 m, Tp 6 s: excitation work = radiated + viscous (linear and the
    quadratic drag's work relative to the water) + PTO + stored - rotor-motor work, to 1 %;
    on the ISWEC-class default the drag dissipates a real share of it. ISWEC's box also in a
    sea 21 deg off its length, which rolls it (its own roll block, `axes`)."""
    env = gym.make(
        "FloatingGOWEC-v0",
        significant_wave_height=1.5,
        peak_period=6.0,
        episode_seconds=300,
        max_episode_steps=15_000,  # 300 s of 0.02 s (gym.make's TimeLimit)
        device=device,
        wave_direction=direction,
    )
    _, info = _episode(env, kind, seed=11)
    assert not info["overspeed"] and not info["stroke_end"]
    m = env.unwrapped.model
    e = m.energies(env.unwrapped.state)
    stored0 = 0.0  # buoy level and at rest, gimbal at rest: 1/2 C q^2 = 0 and kinetic 0
    out = e["radiated"] + e["viscous"] + e["pto_mechanical"] + e["stored"] - stored0 - e["motor"]
    assert abs(e["excitation"] - out) <= 0.01 * abs(e["excitation"])
    assert e["excitation"] > 0 and e["radiated"] > 0
    if device != "seed_buoy":
        assert m.sp[0] == 1.0 and 0.05 * e["excitation"] < e["viscous"] < e["excitation"]


def test_gyro_moment_is_the_hull_pitch_balance():
    """info["gyro_moment"] (the compiled row-0 form) = what the hull alone needs besides its
    external loads: (M_hull u' + v_hull)_theta - (M_x - C theta - mu_theta - b_v theta'), with
    u' from the coupled solve (`model.accelerations`) and the hull-only mass terms; a second
    formulation of the moment, at states reached under random torque in an oblique sea."""
    from mf_envs.physics.gowec.hydro import floating as fl

    env = gym.make(
        "FloatingGOWEC-v0", wave_direction=0.7, wave_amplitude=1.0, device="seed_buoy"
    ).unwrapped
    env.reset(seed=4)
    rng = np.random.default_rng(0)
    m, nr, checked = env.model, env.model.p.Ar.shape[1], 0
    for _ in range(200):
        a = float(rng.uniform(-1, 1))
        _, _, term, _, info = env.step(np.array([a], dtype=np.float32))
        if term:
            env.reset()
            continue
        y, t, tau = env.state, env._t, a * env.max_generator_torque
        ud = m.accelerations(t, y, tau)
        Mh, vh, _, _ = fl.mass_and_rhs(y[0:3], y[3:6], m.p.inertia, np.zeros(6), 0.0)
        mu = float(m.p.Cr[0] @ y[6 : 6 + nr])
        ext = m.excitation(t)[0] - m.p.stiffness[0] * y[0] - mu - m.p.viscous * y[3]
        expected = (Mh @ ud + vh)[0] - ext
        assert info["gyro_moment"] == pytest.approx(expected, rel=1e-9, abs=1e-9 * abs(ext))
        checked += 1
    assert checked > 100 and abs(info["gyro_moment"]) > 0.0


def test_matched_linear_pto_absorbs_the_optimum():
    """c*, k* (issue 14) on a small regular wave: mean PTO power = |M_ex|^2 / (8 R), R = B + b_v."""
    T, a = 6.5, 0.02
    env = gym.make(
        "FloatingGOWEC-v0",
        wave_amplitude=a,
        wave_period=T,
        episode_seconds=240.0,
        max_episode_steps=12_000,
        rotor_loss=0.0,
        max_generator_torque=1e6,
        max_generator_power=1e9,
        device="seed_buoy",
    )
    P, _ = _episode(env, "linear_pto", seed=0)
    u = env.unwrapped
    w = 2 * math.pi / T
    A, B, X = u.hull.at(w)
    R = B + u.model.p.viscous
    target = (abs(X) * a) ** 2 / (8 * R)
    n = int(2 * T / u.control_dt) * 10  # the last 20 periods
    assert np.mean(P[-n:]) == pytest.approx(target, rel=0.03)
    c, k = matched_pto(env)
    assert c > 0 and u.model.p.pto[0] == c and u.model.p.pto[1] == k


def _stiff_hull(C=1e10):
    h = load_hull()
    w = h.omega
    k = w**2 / h.g
    B = 1e-6 * w**7  # negligible radiation
    return HullCoefficients(
        omega=w,
        added_mass=np.full_like(w, 1e5),
        damping=B,
        excitation=-1j * k * C,
        added_mass_inf=1e5,
        added_mass_zero=1e5,
        stiffness=C,
        inertia=1e7,
        mass=1e7,
        name="stiff",
    )


def test_stiff_heavy_hull_returns_gowec_v0():
    """X = -i k C (the wave slope times C), C >> w^2 (I + A): the buoy follows the wave slope
    (Eqs. 77-78) and the PLL's locked gimbal returns Eq. 95 (GOWEC-v0's number) per unit."""
    T, a, theta = 6.0, 1.0, 1.2
    env = gym.make(
        "FloatingGOWEC-v0",
        hull=_stiff_hull(),
        wave_amplitude=a,
        wave_period=T,
        wave_direction=theta,
        episode_seconds=90.0,
        effects=("gyroscopic", "viscous_damping"),
        rotor_loss=0.0,
        device="seed_buoy",
    )
    P, _ = _episode(env, "pll", seed=0)
    u = env.unwrapped
    # Eq. 95 is per gyroscope; the default is the seed's pair (twice the power, Sec. 3.2.3)
    eq95 = u.model.units * analytic_max_power(u.model.p.gyro[0], u.model.psid, a, T, theta)
    n = int(10 * T / u.control_dt)
    assert np.mean(P[-n:]) == pytest.approx(eq95, rel=0.02)


@pytest.mark.parametrize("sea", [{}, {"significant_wave_height": 2.0}])
@pytest.mark.parametrize(
    "kind", ["pll", "bang_bang", "linear_pto", "passive_damper", "efficient_pto", "ppo"]
)
def test_no_controller_beats_the_bounds(sea, kind):
    """Mean absorbed (mechanical PTO) power below the radiation-limited bound and below the
    motion-limited bound at the episode's largest tilt (`model.motion_limited_bound`) on five
    unseen seeds of a regular and a JONSWAP sea, for every baseline and the shipped PPO
    policy, on the default (ISWEC-class) device."""
    if kind == "ppo":
        pytest.importorskip("stable_baselines3", reason="the PPO policy needs the train extra")
        from mf_envs.train.policy import policy_dir

        if not (policy_dir("FloatingGOWEC-v0") / "policy.json").is_file():
            pytest.skip("no PPO policy shipped for FloatingGOWEC-v0 (its last one was removed "
                        "when the device changed; the RL benchmark retrains it)")  # fmt: skip
    for seed in range(100, 105):
        env = gym.make("FloatingGOWEC-v0", episode_seconds=60.0, **sea)
        P, info = _episode(env, kind, seed)
        u = env.unwrapped
        assert np.mean(P) < u.power_bound()
        assert np.mean(P) < motion_limited_bound(u.hull, u.wave, info["max_tilt"])


@pytest.mark.parametrize("sea", [dict(wave_amplitude=0.5, wave_period=8.0),
                                 dict(significant_wave_height=2.0, peak_period=8.0),
                                 dict(significant_wave_height=2.5, peak_period=6.0)])  # fmt: skip
def test_efficient_pto_is_never_below_the_damper(sea):
    """`efficient_pto` against `passive_damper` on unseen seeds (3000, 3001): its predicted net
    power is the damper's or more, never a negative prediction where the damper's is positive,
    and it nets at least the damper's electrical power in the time domain (last half of
    200 s) to within 0.5 % of it, with the gimbal inside its stroke; on the long regular wave
    (8 s) it is a reactive setting (k above the damper's centring spring), a different
    controller. (The 0.5 %: in JONSWAP Hs 2.5 m, Tp 6 s the schedule may slow the flywheels a
    little where the model predicts a gain of a few tenths of a per cent, and in a 100 s window
    the two then differ by less than the model's error: 14.897 against 14.906 kW on seed 3000;
    over 300 s and five seeds it is at least the damper's, docs/gowec_v1.md.)"""
    for seed in (3000, 3001):
        e, pred = {}, {}
        for kind in ("efficient_pto", "passive_damper"):
            env = gym.make("FloatingGOWEC-v0", episode_seconds=200.0, max_episode_steps=10_000,
                           **sea)  # fmt: skip
            c = make_baseline(env, kind)
            obs, _ = env.reset(seed=seed)
            c.reset()
            pred[kind] = c.prediction
            Pe, done = [], False
            while not done:
                obs, _, term, trunc, info = env.step(c.predict(obs)[0])
                assert abs(info["gimbal_angle"]) < env.unwrapped.gimbal_stroke()
                Pe.append(info["power"])
                done = term or trunc
            assert not term
            e[kind] = float(np.mean(Pe[len(Pe) // 2 :]))
        p, d = pred["efficient_pto"], pred["passive_damper"]
        assert p["net_W"] >= d["net_W"] and (p["net_W"] > 0.0 or p["k"] == d["k"])
        assert e["efficient_pto"] >= e["passive_damper"] - 0.005 * abs(e["passive_damper"])
        if sea.get("wave_period") == 8.0:
            assert p["k"] > d["k"]


def test_passive_damper_keeps_the_rated_speed_and_the_schedule_pays_in_a_small_sea():
    """In a small sea (JONSWAP Hs 1 m, Tp 6 s, unseen seed 3002) `passive_damper` runs the
    flywheels at the rated speed the env was built with and `efficient_pto` slower, where their
    running loss is lower (`DEVICES[...].running_loss`): it nets more than the damper over the
    last half of 200 s, and both stay in operation (no early end)."""
    net, speed = {}, {}
    for kind in ("efficient_pto", "passive_damper"):
        env = gym.make("FloatingGOWEC-v0", episode_seconds=200.0, max_episode_steps=10_000,
                       significant_wave_height=1.0, peak_period=6.0)  # fmt: skip
        c = make_baseline(env, kind)
        obs, _ = env.reset(seed=3002)
        c.reset()
        raw = env.unwrapped
        speed[kind], rated = float(raw.model.psid), float(raw.model.gyro.rotor_speed)
        P, done = [], False
        while not done:
            obs, _, term, trunc, info = env.step(c.predict(obs)[0])
            P.append(info["power"])
            done = term or trunc
        assert not term
        net[kind] = float(np.mean(P[len(P) // 2 :]))
    assert speed["passive_damper"] == rated
    assert speed["efficient_pto"] < 0.8 * rated
    assert net["efficient_pto"] > net["passive_damper"]


def test_render_rgb_array():
    env = gym.make("FloatingGOWEC-v0", render_mode="rgb_array", episode_seconds=1.0)
    env.reset(seed=0)
    env.step(np.zeros(1, np.float32))
    img = env.render()
    assert img.shape == (360, 480, 3) and img.dtype == np.uint8 and img.std() > 5


@pytest.mark.parametrize("device", ["iswec_class", "seed_buoy"])
def test_ending_early_never_pays(device):
    """A failure's charge (`shutdown_energy`: the rotor loss plus every drive motoring at its
    power limit over the steps left) is never less than what continuing could cost: against
    an adversary that motors the gimbal as hard as it can (torque along -phi') and against
    full torque, no run of steps from any step to the end nets less than the charge from
    there; and a forced failure (overspeed at a tiny max_gimbal_rate) is charged exactly it."""
    for policy in ("motor", 1.0):
        env = gym.make("FloatingGOWEC-v0", device=device, episode_seconds=60.0)
        u = env.unwrapped
        obs, _ = env.reset(seed=2000)
        r, done = [], False
        while not done:
            if policy == "motor":
                a = np.array([-np.sign(obs[spec.I_RATE])], np.float32)
            else:
                a = np.full(1, policy, np.float32)
            obs, rew, term, trunc, info = env.step(a)
            r.append(rew)
            done = term or trunc
        # the ISWEC-class supervisor and end stops keep the device whole (the seed buoy has none)
        assert not term or device == "seed_buoy"
        tail = np.cumsum(np.asarray(r)[::-1])[::-1]  # return from step k to the end
        charge = u.shutdown_energy(np.arange(len(r))) * u.energy_scale
        assert np.all(tail >= -charge - 1e-9 * (1.0 + charge))
    env = gym.make("FloatingGOWEC-v0", device=device, episode_seconds=60.0, max_gimbal_rate=0.05)
    u = env.unwrapped
    env.reset(seed=2000)
    steps, done = 0, False
    while not done:
        _, rew, term, trunc, info = env.step(np.zeros(1, np.float32))
        steps += 1
        done = term or trunc
    assert term and info["overspeed"] and steps < u.max_steps
    assert info["reward_terms"]["shutdown_loss"] == pytest.approx(
        -u.shutdown_energy(steps) * u.energy_scale, rel=1e-12
    )


@pytest.mark.parametrize("action", [1.0, -1.0])
def test_full_torque_meets_the_cushioned_stops_inside_the_stroke(action):
    """Full generator torque one way drives the ISWEC-class gimbal into its end stop: it stays
    inside its stroke (stop angle + cushion travel) on every step, the supervisor takes over
    (survival), the episode runs to its end, and the energy balance closes with the cushion's
    spring energy stored and its damping and the survival brake dissipated (as above, to 1 %
    of the excitation work)."""
    env = gym.make("FloatingGOWEC-v0", wave_amplitude=1.0, wave_period=6.0, episode_seconds=120)
    u = env.unwrapped
    env.reset(seed=3001)
    phi, surv, done = [], [], False
    while not done:
        _, _, term, trunc, info = env.step(np.full(1, action, np.float32))
        phi.append(info["gimbal_angle"])
        surv.append(info["survival"])
        done = term or trunc
    stop = u.model.p.pto[6]  # `gimbal.PTO_STOP`
    assert not term and max(np.abs(phi)) > stop  # it reached the cushion ...
    assert max(np.abs(phi)) < u.gimbal_stroke()  # ... and never passed it
    assert any(surv)
    e = u.model.energies(u.state)
    out = e["radiated"] + e["viscous"] + e["pto_mechanical"] + e["stored"] - e["motor"]
    assert abs(e["excitation"] - out) <= 0.01 * abs(e["excitation"])


@pytest.mark.parametrize("sea", [dict(significant_wave_height=3.5, peak_period=7.0),
                                 dict(wave_amplitude=2.0, wave_period=8.0)])  # fmt: skip
@pytest.mark.parametrize("device", ["iswec_class", "iswec_box"])
def test_seas_beyond_the_range_are_met_in_survival(sea, device):
    """A sea higher than the ISWEC-class operating range (Hs, or the regular wave's height,
    above 2.5 m): the device is in survival from the reset to the end, the episode runs to its
    end with the gimbal inside its stroke, the PTO harvests nothing and the net power is the
    flywheels' running loss. On the cylinder and on ISWEC's box."""
    env = gym.make("FloatingGOWEC-v0", episode_seconds=120, device=device, **sea)
    u = env.unwrapped
    _, info = env.reset(seed=3002)
    assert info["survival"]
    steps, done = 0, False
    while not done:
        _, _, term, trunc, info = env.step(np.ones(1, np.float32))
        assert info["survival"] and abs(info["gimbal_angle"]) < u.gimbal_stroke()
        assert info["power_mechanical"] == 0.0
        assert info["power"] == pytest.approx(-u.rotor_loss_power(), rel=1e-12)
        steps += 1
        done = term or trunc
    assert not term and steps == u.max_steps


def test_grouped_sea_and_pto_are_the_flat_kwargs(sine_rollout):
    from mf_envs.envs.gowec.build import Sea as GOWECSea
    from mf_envs.envs.gowec_v1.build import PTO, Sea

    def rollout(**kwargs):
        return sine_rollout("FloatingGOWEC-v0", 1, 30, 0.2, **kwargs)

    flat = rollout(significant_wave_height=1.5, peak_period=7.0, gamma=2.0,
                   max_generator_torque=1e5, motor_efficiency=0.8)  # fmt: skip
    grouped = rollout(sea=Sea(significant_wave_height=1.5, peak_period=7.0, gamma=2.0),
                      pto=PTO(max_torque=1e5, motor_efficiency=0.8))  # fmt: skip
    mixed = rollout(sea={"peak_period": 7.0, "gamma": 2.0}, significant_wave_height=1.5,
                    peak_period=7.0, pto={"max_torque": 1e5}, motor_efficiency=0.8)  # fmt: skip
    assert np.array_equal(flat, grouped) and np.array_equal(flat, mixed)
    assert not np.array_equal(flat, rollout(significant_wave_height=1.5, peak_period=7.0))
    with pytest.raises(ValueError, match=r"^sea: expected a mf_envs\.envs\.gowec_v1\.build\.Sea"):
        gym.make("FloatingGOWEC-v0", sea=GOWECSea())  # GOWEC-v0's: no Hs, Tp, spectrum
    with pytest.raises(ValueError, match="^peak_period: "):
        gym.make("FloatingGOWEC-v0", sea={"peak_period": -1.0})
    # the JONSWAP variant's flat Hs and a user's sea with another: refused, naming it
    with pytest.raises(ValueError, match="^significant_wave_height: given twice"):
        gym.make("FloatingGOWEC-JONSWAP-v0", sea={"significant_wave_height": 2.0})
