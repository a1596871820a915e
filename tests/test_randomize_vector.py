"""Domain randomisation on the native vector env (issue 32): `train.randomize.randomized_vector_env`
is bit-identical to `SyncVectorEnv` over `DomainRandomization`-wrapped single envs with the same
seeds and so the same randomisation draws (observations, rewards, flags, infos with
`info["randomized"]`), through seeded resets, autoresets of every mode and masked resets;
kwargs the rows cannot hold apart are refused (ValueError naming `ranges`), and training uses
the native env with the wrapper when it can."""

from __future__ import annotations

import functools
from typing import Any

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode, SyncVectorEnv
from test_vector_envs import actions, assert_infos_equal  # (tests/ is on sys.path)

import mf_envs  # noqa: F401  (registers the ids)
from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS
from mf_envs.envs.inchworm import LAG_FRICTION_SCENE
from mf_envs.envs.inchworm.build import FRICTION_KEYS
from mf_envs.train.randomize import (
    DomainRandomization,
    Randomizer,
    default_choices,
    default_ranges,
    native_randomization_supported,
    randomized_vector_env,
    shift_scenes,
)

SEEDS = [11, 3, 7]
IRREGULAR = (*DEFAULT_EFFECTS, "irregular_waves")
FRICTION = {"friction_coefficients": (0.5, 1.5)}  # Inchworm-v0's feet, every coefficient
GOWEC_IRREGULAR = ("gyroscopic", "buoy_rocking", "irregular_waves")
# (env id, env kwargs: short episodes, ranges (None: the declared), choices (None: declared))
CASES = {
    # the declared ranges: wave period, moment, Hs and rotor speed (whose x1.1 needs 3 physics
    # substeps instead of 2: rows of different physics steps)
    "stabilizer": ("GyroStabilizer-v0", {"episode_seconds": 0.3}, None, None),
    "stabilizer_irregular": (
        "GyroStabilizer-v0",
        {"episode_seconds": 0.3, "effects": IRREGULAR},
        {"wave_period": (0.8, 1.2), "significant_wave_height": (0.5, 1.5)},
        None,
    ),
    # the declared ranges: wave period (each row's control and physics steps), amplitude and
    # rotor speed
    "gowec": ("GOWEC-v0", {"n_periods": 1, "steps_per_period": 8}, None, None),
    "gowec_irregular": (
        "GOWEC-v0",
        {"n_periods": 1, "steps_per_period": 8, "effects": GOWEC_IRREGULAR},
        None,
        None,
    ),
    # an episode in seconds: the rows' episodes of 2 or 3 control steps of their own period
    "gowec_seconds": (
        "GOWEC-v0",
        {"episode_seconds": 1.5, "steps_per_period": 8},
        {"wave_period": (0.8, 1.2)},
        None,
    ),
    # the declared seas: regular (one component, padded) and JONSWAP (64) rows stepped together
    "floating": ("FloatingGOWEC-v0", {"episode_seconds": 0.2}, None, None),
    # the beam robots' declared material, ground and water (each row its compiled config)
    "serpentine": ("Serpentine-v0", {"episode_seconds": 0.3}, None, None),
    "eel": ("Eel-v0", {"episode_seconds": 0.3}, None, None),
    # the inchworm's declared body and feet's friction (one factor on every coefficient of
    # `friction_coefficients`): the default robot (SMA wires, gripping feet: the grip law) and
    # issue 16's (Coulomb friction feet); then the friction alone (a row stepped with the
    # template's feet would leave Sync's trajectory)
    **{
        f"inchworm{scene}{only}": ("Inchworm-v0", {"episode_seconds": 0.5, **kw}, ranges, None)
        for scene, kw in (("", {}), ("_friction", LAG_FRICTION_SCENE))
        for only, ranges in (("", None), ("_feet_only", FRICTION))
    },
}


def drawn_values(d: dict, name: str) -> set[float]:
    """The values of kwarg `name` in a batched `info["randomized"]` at the rows that drew it (a
    dict-valued kwarg: its first number)."""
    values = d[name]
    if isinstance(values, dict):
        values = values[next(k for k in values if not k.startswith("_"))]
    return {float(v) for v in np.asarray(values)[d[f"_{name}"]]}


def sync_randomized(env_id, kw, ranges, choices, mode) -> SyncVectorEnv:
    def make() -> gym.Env:
        return DomainRandomization(gym.make(env_id, **kw), ranges=ranges, choices=choices)

    return SyncVectorEnv([make] * 3, autoreset_mode=mode)


@pytest.mark.parametrize("mode", list(AutoresetMode))
@pytest.mark.parametrize("case", sorted(CASES))
def test_native_randomization_equals_sync_over_wrappers(case: str, mode: AutoresetMode) -> None:
    env_id, kw, ranges, choices = CASES[case]
    sync = sync_randomized(env_id, kw, ranges, choices, mode)
    vec = randomized_vector_env(env_id, 3, kw, ranges, choices, autoreset_mode=mode)
    out_s, out_v = sync.reset(seed=SEEDS), vec.reset(seed=SEEDS)
    np.testing.assert_array_equal(out_s[0], out_v[0])
    assert_infos_equal(out_s[1], out_v[1])
    drawn, substeps, padded, lengths = [out_v[1]["randomized"]], set(), False, set()
    hs = np.full(3, None, dtype=object)  # each row's current significant_wave_height draw
    acts = actions(vec, 24, seed=2)
    done = np.zeros(3, dtype=bool)
    for t in range(len(acts)):
        if mode == AutoresetMode.DISABLED and (done.any() or t == 9):
            mask = done | (t == 9)
            out_s = sync.reset(options={"reset_mask": mask})
            out_v = vec.reset(options={"reset_mask": mask.copy()})
            np.testing.assert_array_equal(out_s[0], out_v[0], err_msg=f"reset at {t}")
            assert_infos_equal(out_s[1], out_v[1], f"reset at {t}: ")
            drawn.append(out_v[1]["randomized"])
        out_s, out_v = sync.step(acts[t]), vec.step(acts[t])
        for a, b in zip(out_s[:4], out_v[:4]):
            np.testing.assert_array_equal(a, b, err_msg=f"step {t}")
        assert_infos_equal(out_s[4], out_v[4], f"step {t}: ")
        done = out_v[2] | out_v[3]
        drawn.append(out_v[4].get("randomized"))
        rows = getattr(vec.unwrapped, "b", None)  # the native rows' batch (its physics substeps)
        substeps.update(getattr(rows, "n_sub", np.zeros(1)).tolist())
        for d in drawn[-2:]:
            if d and "significant_wave_height" in d:
                m = d["_significant_wave_height"]
                hs[m] = d["significant_wave_height"][m]
        lengths.update(getattr(vec.unwrapped, "_max_steps", np.zeros(1)).tolist())
        sea = getattr(vec.unwrapped, "sea", None)
        padded |= sea is not None and sea["om"].shape[1] > 1 and any(h is None for h in hs)
    for name in Randomizer(env_id, kw, ranges, choices).ranges:
        values = set().union(*(drawn_values(d, name) for d in drawn if d))
        assert len(values) >= 4, name  # new draws at the autoresets, not only the first reset
    if case == "stabilizer":
        assert substeps == {2, 3}  # rows with different physics steps were stepped together
    if case == "gowec":
        assert len(substeps) >= 2  # rows of different physics steps (their own periods)
    if case == "gowec_seconds":
        assert lengths == {2, 3}  # rows of different episode lengths were stepped together
    if case == "floating":
        assert padded  # a regular row, padded, stepped with JONSWAP rows
    sync.close()
    vec.close()


@pytest.mark.parametrize(
    ("env_id", "kw"),
    [
        ("GyroStabilizer-v0", {}),
        ("GyroStabilizer-v0", {"effects": IRREGULAR, "physics_dt": 0.01}),
        ("GOWEC-v0", {}),
        ("GOWEC-v0", {"effects": GOWEC_IRREGULAR}),
        ("FloatingGOWEC-v0", {}),
        ("FloatingGOWEC-v0", {"significant_wave_height": 2.0}),
        ("Inchworm-v0", {}),
        ("Inchworm-v0", LAG_FRICTION_SCENE),
        ("Serpentine-v0", {}),
        ("Serpentine-v0", {"effects": ("viscous_ground",)}),
        ("Eel-v0", {}),
    ],
)
def test_every_declared_randomisation_runs_natively(env_id: str, kw: dict) -> None:
    """Every env's declared ranges and choices (all of them: `Randomizer.names`) are held per
    row by its native vector env, in these scenes too; the one scene left on the fallback is
    GyroStabilizer-v0's irregular sea with the default physics_dt (rotor_speed, below)."""
    draws = Randomizer(env_id, kw)
    assert set(draws.choices) == set(default_choices(env_id))
    assert set(draws.ranges) <= set(default_ranges(env_id)) and draws.ranges
    assert native_randomization_supported(env_id, draws.names, kw)


NOMINAL_FEET = dict(zip(FRICTION_KEYS, (0.6, 1.0, 0.1, 0.15)))  # `FrictionParams`' defaults


def test_inchworm_draws_its_feet_friction():
    """Inchworm-v0's declared friction range is drawn (not dropped): one factor in [0.5, 1.5] on
    every coefficient of its resolved `friction_coefficients`, natively held per row in both
    feet's scenes; a given friction (4 numbers or a partial dict) is the nominal; bad input is
    refused naming the parameter."""
    for kw in ({}, LAG_FRICTION_SCENE):
        draws = Randomizer("Inchworm-v0", kw)
        assert set(draws.ranges) == set(default_ranges("Inchworm-v0"))
        assert draws.ranges["friction_coefficients"] == (0.5, 1.5)
        assert draws.nominal["friction_coefficients"] == NOMINAL_FEET
        assert native_randomization_supported("Inchworm-v0", draws.names, kw)
    factors = []
    for seed in range(6):
        _, drawn, _ = draws.draw(None, seed)
        mu = drawn["friction_coefficients"]
        f = [mu[k] / NOMINAL_FEET[k] for k in FRICTION_KEYS]
        assert max(f) - min(f) < 1e-12 and 0.5 <= f[0] <= 1.5
        factors.append(f[0])
    assert len(set(factors)) == 6
    four = (0.8, 1.2, 0.2, 0.3)
    given = Randomizer("Inchworm-v0", {"friction_coefficients": list(four)}, FRICTION)
    assert given.nominal == {"friction_coefficients": dict(zip(FRICTION_KEYS, four))}
    partial = Randomizer("Inchworm-v0", {"friction_coefficients": {"grip_forward": 0.8}}, FRICTION)
    assert partial.nominal["friction_coefficients"] == {**NOMINAL_FEET, "grip_forward": 0.8}
    half = {k: 0.5 * v for k, v in NOMINAL_FEET.items()}
    assert shift_scenes("Inchworm-v0")["friction x0.5"] == {"friction_coefficients": half}
    with pytest.raises(ValueError, match="friction_coefficients"):
        Randomizer("Inchworm-v0", {"friction_coefficients": [1.0, 2.0]}, FRICTION)
    with pytest.raises(ValueError, match="ranges"):
        Randomizer("Inchworm-v0", ranges={"friction_coefficients": (0.0, 1.0)})


class FeetByRow:
    """`randomize_rows`'s draws contract: the row reset with seed s gets the feet's friction x
    factors[s] (and reset seed s)."""

    names = frozenset({"friction_coefficients"})

    def __init__(self, factors: tuple[float, ...]) -> None:
        self.factors = factors

    def draw(self, rng: Any, seed: Any) -> tuple[Any, dict[str, Any], int]:
        mu = {k: self.factors[seed] * v for k, v in NOMINAL_FEET.items()}
        return np.random.default_rng(seed), {"friction_coefficients": mu}, seed


@pytest.mark.parametrize("scene", ["gripping", "friction"])
def test_a_drawn_friction_changes_the_inchworm(scene: str) -> None:
    """Two rows drawn with the feet's friction x0.5 and x1.5 run the same gait (the wires heated
    2.9 s with the head gripping, cooled 1.2 s with the tail gripping; on issue 16's robot the
    same square wave of kappa#): each row is, bit for bit, a single env made with its friction,
    and the rows differ: the feet's holding margin (info["quasi_static_error"] ~ 1 / factor)
    and, on the gripping feet, the crawl. (Quasi-static: the feet's forces balance each other,
    so one factor on every coefficient moves the crawl only through the body's axial load.)"""
    kw = {"episode_seconds": 6.0, **(LAG_FRICTION_SCENE if scene == "friction" else {})}
    vec = gym.make_vec("Inchworm-v0", 2, vectorization_mode="vector_entry_point", **kw)
    vec.unwrapped.randomize_rows(FeetByRow((0.5, 1.5)))
    _, info = vec.reset(seed=[0, 1])
    singles = []
    for seed, f in ((0, 0.5), (1, 1.5)):
        mu = {k: f * v for k, v in NOMINAL_FEET.items()}
        env = gym.make("Inchworm-v0", **kw, friction_coefficients=mu)
        env.reset(seed=seed)
        singles.append(env)
    x0 = info["x_tail"].copy()
    qse = np.zeros(2)
    for t in range(60):
        a = np.full(4, 1.0 if t % 41 < 29 else -1.0, np.float32)
        *_, info = vec.step(np.stack([a, a]))
        for i, env in enumerate(singles):
            *_, single = env.step(a)
            assert single["x_tail"] == info["x_tail"][i], (t, i)
            assert single["quasi_static_error"] == info["quasi_static_error"][i], (t, i)
        qse = np.maximum(qse, info["quasi_static_error"])
    advance = info["x_tail"] - x0
    assert advance.min() > 0.01  # both crawl forward (> 1 cm in 6 s)
    assert advance[0] != advance[1]
    if scene == "gripping":
        assert abs(advance[0] - advance[1]) > 1e-5  # tens of micrometres
    assert 2.5 < qse[0] / qse[1] < 3.5  # the holding margin scales with the friction
    vec.close()
    for env in singles:
        env.close()


def test_a_kwarg_the_rows_share_is_refused():
    """GOWEC-v0's rows share the generator's torque limit (a template scalar of the step): the
    native env refuses to draw it, naming ranges; training falls back."""
    shared = {"max_generator_torque": (0.5, 1.5)}
    names = Randomizer("GOWEC-v0", ranges=shared).names
    assert not native_randomization_supported("GOWEC-v0", names)
    with pytest.raises(ValueError, match=r"ranges: \['max_generator_torque'\]"):
        randomized_vector_env("GOWEC-v0", 2, ranges=shared)
    # irregular seas: the rotor speed sets the physics step and so the sea table's length
    kw = {"effects": IRREGULAR}
    assert not native_randomization_supported("GyroStabilizer-v0", {"rotor_speed"}, kw)
    assert native_randomization_supported(
        "GyroStabilizer-v0", {"rotor_speed"}, kw | {"physics_dt": 0.01}
    )
    with pytest.raises(ValueError, match=r"ranges: \['rotor_speed'\]"):
        randomized_vector_env("GyroStabilizer-v0", 2, kw)


def test_a_draw_that_changes_the_shared_step_is_refused():
    """The guard behind ROW_KWARGS: a draw that changes what the batch step reads from the
    template (here the reward's effort weight) raises ValueError naming ranges."""

    class Draws:
        names = frozenset({"rotor_speed"})

        def draw(self, rng: Any, seed: Any) -> tuple[Any, dict[str, Any], int]:
            return np.random.default_rng(0), {"effort_weight": 0.5}, 1

    vec = gym.make_vec("GyroStabilizer-v0", 2, vectorization_mode="vector_entry_point")
    vec.unwrapped.randomize_rows(Draws())
    with pytest.raises(ValueError, match="ranges: the draw"):
        vec.reset(seed=0)
    vec.unwrapped.randomize_rows(None)  # off again: the plain rows
    vec.reset(seed=0)
    vec.close()


def test_training_uses_the_native_env_with_domain_randomization():
    pytest.importorskip("stable_baselines3")
    from mf_envs.train.vec import make_train_env, randomization_only

    assert randomization_only([DomainRandomization]) == {}
    part = functools.partial(DomainRandomization, ranges={"wave_amplitude": (0.5, 1.5)})
    assert randomization_only([part]) == {"ranges": {"wave_amplitude": (0.5, 1.5)}}
    assert randomization_only([DomainRandomization, gym.wrappers.ClipAction]) is None
    kw = {"episode_seconds": 0.3}
    venv, kind = make_train_env("GyroStabilizer-v0", 2, 0, kw, wrappers=[DomainRandomization])
    assert kind == "native"
    venv.reset()
    ends = 0
    for _ in range(8):  # through an episode end (SAME_STEP: SB3's terminal_observation)
        *_, infos = venv.step(np.zeros((2, 1), np.float32))
        ends += sum("terminal_observation" in i for i in infos)
    assert ends == 2  # both rows ended their 6-step episode once
    venv.close()
    short = {"n_periods": 1, "steps_per_period": 8}
    venv, kind = make_train_env("GOWEC-v0", 2, 0, short, wrappers=[DomainRandomization])
    assert kind == "native"  # its declared ranges, the wave period's control step included
    venv.close()
    shared = functools.partial(DomainRandomization, ranges={"max_generator_torque": (0.5, 1.5)})
    venv, kind = make_train_env("GOWEC-v0", 2, 0, short, wrappers=[shared])
    assert kind == "dummy"  # the rows share the torque limit
    venv.close()
