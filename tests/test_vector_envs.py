"""Native batched vector envs (`vector_entry_point`): bit-identical to single envs with the same
seeds across autoresets (against independent `gym.make` envs and against `SyncVectorEnv`),
per-env seeding, `gym.make_vec` wiring, the SB3 adapter, input validation."""

from __future__ import annotations

import importlib.util
from typing import Any

import gymnasium as gym
import numba
import numpy as np
import pytest
from gymnasium.vector import AutoresetMode

import mf_envs  # noqa: F401  (registers the envs)
from mf_envs.envs import VECTOR_SPECS, available_env_ids

VEC_IDS = [
    i
    for i in available_env_ids()
    if i in VECTOR_SPECS and importlib.util.find_spec(VECTOR_SPECS[i].split(":")[0])
]
# short episodes so that a few dozen steps cross several autoresets
SHORT: dict[str, dict[str, Any]] = {
    "GOWEC-v0": {"n_periods": 1, "steps_per_period": 12},
    "GyroStabilizer-v0": {"episode_seconds": 0.6},
    "FloatingGOWEC-v0": {"episode_seconds": 0.2},
    "Inchworm-v0": {"max_episode_steps": 5},
    "Serpentine-v0": {"episode_seconds": 0.25},
    "Eel-v0": {"episode_seconds": 0.1},
}
# scenes with the most effects on (irregular seas draw per-env random components at reset)
FULL: dict[str, dict[str, Any]] = {
    "GOWEC-v0": {
        "effects": ("gyroscopic", "gimbal_inertia", "buoy_rocking", "wave_2d", "irregular_waves"),
        "n_components": 8,
    },
    "GyroStabilizer-v0": {
        "effects": (
            "gyroscopic",
            "gimbal_inertia",
            "added_inertia",
            "hydrostatic_restoring",
            "roll_damping",
            "irregular_waves",
            "gimbal_limits",
            "translation",
            "gimbal_damping",
        ),
        "n_gyros": 2,
        "gimbal_drive": "torque",
        "gimbal_damping": 50.0,
    },
    "FloatingGOWEC-v0": {"significant_wave_height": 2.0, "n_components": 8},
    "Inchworm-v0": {"n_control_points": 5, "n_elements": 8, "reset_noise_scale": 0.5},
    "Serpentine-v0": {"effects": ("viscous_ground",), "n_control_points": 5, "n_elements": 8},
    "Eel-v0": {
        "n_control_points": 5,
        "n_elements": 8,
        "reset_noise_scale": 0.5,
        "action_mode": "wave",
    },
}
# kwargs that blow the state up within a step (numerical-failure path)
BLOWUP: dict[str, dict[str, Any]] = {
    "GOWEC-v0": {"max_generator_torque": 1e305},
    "GyroStabilizer-v0": {
        "max_precession_rate": 1e300,
        "effects": ("gyroscopic",),
        "gimbal_drive": "kinematic",  # the torque-limited default drive cannot blow up
    },
    "FloatingGOWEC-v0": {"max_generator_torque": 1e300, "max_generator_power": 1e300},
    "Inchworm-v0": {"friction_coefficients": (0.0, 0.0, 0.0, 0.0)},  # both feet slip
    # a stiff elastic rod commanded full curvature in one large step (no actuator lag): Newton
    # fails after 2^6 halvings
    "Serpentine-v0": {
        "youngs_modulus": 1e12,
        "n_elements": 6,
        "physics_dt": 0.05,
        "max_curvature": 57.0,
        "material_damping": 0.0,
        "effects": ("friction",),
    },
    # a stiff eel commanded full curvature at once over a 50 ms step: Newton fails
    "Eel-v0": {
        "youngs_modulus": 1e12,
        "control_dt": 0.05,
        "physics_dt": 0.05,
        "max_curvature": 100.0,
        "max_curvature_rate": 1e9,
    },
}
SEEDS = [11, 3, 7]
ENV_STAB = "GyroStabilizer-v0"


def make_vec(env_id: str, n: int = 3, **kw: Any) -> gym.vector.VectorEnv:
    return gym.make_vec(env_id, num_envs=n, vectorization_mode="vector_entry_point", **kw)


def actions(env: gym.vector.VectorEnv, steps: int, seed: int = 0) -> np.ndarray:
    """Pre-sampled actions (T, N, *act) in [-1.2, 1.2] (clipping is exercised too)."""
    shape = (steps, env.num_envs, *env.single_action_space.shape)
    return np.random.default_rng(seed).uniform(-1.2, 1.2, shape).astype(np.float32)


def assert_infos_equal(
    a: dict[str, Any], b: dict[str, Any], where: str = "", strict: bool = False
) -> None:
    """Batched infos equal: same keys and masks, equal values where the mask is set (`strict`:
    everywhere, also the rows whose mask is False, which SyncVectorEnv leaves at zero)."""
    assert set(a) == set(b), (where, set(a) ^ set(b))
    for key in a:
        if key.startswith("_"):
            continue
        if isinstance(a[key], dict):
            assert_infos_equal(a[key], b[key], f"{where}{key}.", strict)
            continue
        m = a[f"_{key}"]
        np.testing.assert_array_equal(m, b[f"_{key}"], err_msg=where + key)
        assert np.asarray(a[key]).dtype == np.asarray(b[key]).dtype, where + key
        if strict and a[key].dtype != object:
            np.testing.assert_array_equal(a[key], b[key], err_msg=f"{where}{key} (all rows)")
        for i in np.flatnonzero(m):
            np.testing.assert_array_equal(a[key][i], b[key][i], err_msg=f"{where}{key}[{i}]")


@pytest.mark.parametrize("kind", ["short", "full"])
@pytest.mark.parametrize("env_id", VEC_IDS)
def test_vector_equals_independent_single_envs(env_id: str, kind: str) -> None:
    """One vector env reset with seed=[s_i] == N gym.make envs reset with s_i, step by step,
    through NEXT_STEP autoresets (the env after a done step is reset with its own generator)."""
    kw = {**SHORT[env_id], **(FULL[env_id] if kind == "full" else {})}
    vec = make_vec(env_id, **kw)
    singles = [gym.make(env_id, **kw) for _ in SEEDS]
    obs_v, info_v = vec.reset(seed=SEEDS)
    for i, (env, s) in enumerate(zip(singles, SEEDS)):
        obs, info = env.reset(seed=s)
        np.testing.assert_array_equal(obs_v[i], obs)
        for key, value in info.items():
            if not isinstance(value, dict):
                assert np.array_equal(info_v[key][i], value), key
    done = [False] * len(SEEDS)
    acts = actions(vec, 40)
    n_resets = 0
    for t in range(len(acts)):
        obs_v, rew_v, term_v, trunc_v, info_v = vec.step(acts[t])
        for i, env in enumerate(singles):
            if done[i]:
                obs, info = env.reset()
                rew, term, trunc = 0.0, False, False
                n_resets += 1
            else:
                obs, rew, term, trunc, info = env.step(acts[t, i])
            done[i] = term or trunc
            np.testing.assert_array_equal(obs_v[i], obs, err_msg=f"step {t} env {i}")
            assert (rew_v[i], term_v[i], trunc_v[i]) == (rew, term, trunc), (t, i)
            for key, value in info.items():
                if isinstance(value, dict):
                    for k, v in value.items():
                        assert info_v[key][k][i] == v, (t, i, key, k)
                else:
                    assert info_v[f"_{key}"][i], (t, i, key)
                    assert np.array_equal(info_v[key][i], value), (t, i, key)
    assert n_resets >= 2 * len(SEEDS)


@pytest.mark.parametrize("mode", list(AutoresetMode))
@pytest.mark.parametrize("env_id", VEC_IDS)
def test_vector_equals_sync_vector_env(env_id: str, mode: AutoresetMode) -> None:
    """Same batched output as SyncVectorEnv (info masks, final_obs/final_info included), with a
    partial reset through options["reset_mask"] that staggers the episodes."""
    kw = SHORT[env_id]
    sync = gym.make_vec(env_id, 3, "sync", vector_kwargs={"autoreset_mode": mode}, **kw)
    vec = make_vec(env_id, autoreset_mode=mode, **kw)
    out_s, out_v = sync.reset(seed=SEEDS), vec.reset(seed=SEEDS)
    np.testing.assert_array_equal(out_s[0], out_v[0])
    assert_infos_equal(out_s[1], out_v[1])
    acts = actions(vec, 30, seed=1)
    done = np.zeros(3, dtype=bool)
    for t in range(len(acts)):
        # DISABLED: the caller resets finished rows itself (terminations included, e.g. GOWEC's
        # gimbal overspeed trip under random torque), plus a periodic full reset
        periodic = mode == AutoresetMode.DISABLED and t % 12 == 0 and t > 0
        finished = mode == AutoresetMode.DISABLED and done.any()
        if t == 5 or periodic or finished:
            mask = np.array([True, False, True]) if t == 5 else np.ones(3, dtype=bool)
            if finished and not periodic:
                mask = done | (mask if t == 5 else False)
            out_s = sync.reset(options={"reset_mask": mask})
            out_v = vec.reset(options={"reset_mask": mask.copy()})
            np.testing.assert_array_equal(out_s[0], out_v[0])
            assert_infos_equal(out_s[1], out_v[1])
        out_s, out_v = sync.step(acts[t]), vec.step(acts[t])
        for a, b in zip(out_s[:4], out_v[:4]):
            np.testing.assert_array_equal(a, b, err_msg=f"step {t}")
        assert_infos_equal(out_s[4], out_v[4], f"step {t}: ")
        done = out_v[2] | out_v[3]


@pytest.mark.parametrize("env_id", VEC_IDS)
def test_numerical_failure_matches_single_env(env_id: str) -> None:
    """A blown-up state ends the episode exactly as MFEnv's contract does in the single env."""
    kw = {**SHORT[env_id], **BLOWUP[env_id]}
    for mode in (AutoresetMode.NEXT_STEP, AutoresetMode.SAME_STEP):
        sync = gym.make_vec(env_id, 3, "sync", vector_kwargs={"autoreset_mode": mode}, **kw)
        vec = make_vec(env_id, autoreset_mode=mode, **kw)
        sync.reset(seed=SEEDS)
        vec.reset(seed=SEEDS)
        acts = np.ones((4, 3, *vec.single_action_space.shape), dtype=np.float32)
        acts[:, 2] = 0.0  # a calmer row: failures come on different steps in different rows
        failures = 0
        for t in range(len(acts)):
            out_s, out_v = sync.step(acts[t]), vec.step(acts[t])
            for a, b in zip(out_s[:4], out_v[:4]):
                np.testing.assert_array_equal(a, b)
            # strict: a row whose reset info has no numerical_failure holds False there, not
            # the failed step's stale True (SAME_STEP)
            assert_infos_equal(out_s[4], out_v[4], f"{mode} step {t}: ", strict=True)
            info = out_v[4].get("final_info", out_v[4])
            failures += int(np.sum(info.get("numerical_failure", [])))
            assert np.isfinite(out_v[0]).all()
        assert failures >= 3


@pytest.mark.parametrize("env_id", VEC_IDS)
def test_per_env_seeding(env_id: str) -> None:
    """Seeded resets repeat; an int seed s means seeds s, s+1, ...; rows differ."""
    vec = make_vec(env_id, **SHORT[env_id])
    acts = actions(vec, 15)

    def rollout(seed: Any) -> np.ndarray:
        obs = [vec.reset(seed=seed)[0]]
        obs += [vec.step(a)[0] for a in acts]
        return np.array(obs)

    a, b, c = rollout(SEEDS), rollout(SEEDS), rollout([5, 6, 7])
    np.testing.assert_array_equal(a, b)
    np.testing.assert_array_equal(rollout(5), c)
    assert not np.array_equal(a[:, 0], a[:, 1])
    # a sub-env's trajectory depends only on its own seed
    d = rollout([11, 99, 7])
    np.testing.assert_array_equal(a[:, [0, 2]], d[:, [0, 2]])
    assert not np.array_equal(a[:, 1], d[:, 1])


@pytest.mark.parametrize("env_id", VEC_IDS)
def test_make_vec_vector_entry_point(env_id: str) -> None:
    spec = gym.spec(env_id)
    assert spec.vector_entry_point == VECTOR_SPECS[env_id]
    vec = make_vec(env_id, 4, **SHORT[env_id])
    cls = type(vec.unwrapped)
    assert f"{cls.__module__}:{cls.__name__}" == VECTOR_SPECS[env_id]
    single = gym.make(env_id, **SHORT[env_id])
    assert vec.single_observation_space == single.observation_space
    assert vec.single_action_space == single.action_space
    assert vec.metadata["autoreset_mode"] == AutoresetMode.NEXT_STEP
    obs, _ = vec.reset(seed=0)
    assert obs.shape == (4, *single.observation_space.shape) and obs.dtype == np.float32
    assert vec.observation_space.contains(obs)
    out = vec.step(vec.action_space.sample())
    assert out[1].shape == (4,) and out[2].dtype == np.bool_
    assert vec.unwrapped.state_nbytes() > 0


@pytest.mark.parametrize("env_id", VEC_IDS)
def test_invalid_arguments(env_id: str) -> None:
    for bad in (0, -3, 2.5, True, "4", None):
        with pytest.raises(ValueError, match="num_envs"):
            make_vec(env_id, bad)
    with pytest.raises(ValueError, match="autoreset_mode"):
        make_vec(env_id, 2, autoreset_mode="sometimes")
    with pytest.raises(ValueError, match="render_mode"):
        make_vec(env_id, 2, render_mode="rgb_array")
    vec = make_vec(env_id, 2)
    with pytest.raises(ValueError, match="seed"):
        vec.reset(seed=[1, 2, 3])
    vec.reset(seed=0)
    act = np.zeros((2, *vec.single_action_space.shape), dtype=np.float32)
    act[1] = np.nan
    with pytest.raises(ValueError, match="actions"):
        vec.step(act)
    with pytest.raises(ValueError, match="actions"):
        vec.step(np.zeros((3, 5)))


@pytest.mark.parametrize("env_id", VEC_IDS)
def test_sb3_adapter_round_trip(env_id: str) -> None:
    """mf_envs.train.vec.GymVectorToSB3 over the native env == SB3's DummyVecEnv of single envs."""
    pytest.importorskip(
        "stable_baselines3", reason="needs the train extra: pip install -e '.[train]'"
    )
    from stable_baselines3.common.vec_env import DummyVecEnv

    from mf_envs.train.vec import GymVectorToSB3

    kw = SHORT[env_id]
    ours = GymVectorToSB3(make_vec(env_id, autoreset_mode=AutoresetMode.SAME_STEP, **kw))
    ref = DummyVecEnv([lambda: gym.make(env_id, **kw) for _ in SEEDS])
    ours.seed(4)
    ref.seed(4)
    np.testing.assert_array_equal(ours.reset(), ref.reset())
    acts = actions(ours.venv, 30)
    ends = 0
    for a in acts:
        o1, r1, d1, i1 = ours.step(a)
        o2, r2, d2, i2 = ref.step(a)
        np.testing.assert_array_equal(o1, o2)
        np.testing.assert_array_equal(d1, d2)
        np.testing.assert_allclose(r1, r2, rtol=1e-6)  # SB3 keeps rewards as float32
        for x, y in zip(i1, i2):
            if "terminal_observation" in y:
                ends += 1
                np.testing.assert_array_equal(x["terminal_observation"], y["terminal_observation"])
                assert x["TimeLimit.truncated"] == y["TimeLimit.truncated"]
    assert ends >= 3


def _assert_final_info_like_sync(a: dict[str, Any], b: dict[str, Any], where: str) -> None:
    """Every value equal, also where the mask is False (Sync puts the dtype's zero there)."""
    assert set(a) == set(b), (where, set(a) ^ set(b))
    for key in a:
        if isinstance(a[key], dict):
            _assert_final_info_like_sync(a[key], b[key], f"{where}{key}.")
        else:
            np.testing.assert_array_equal(a[key], b[key], err_msg=where + key)
            assert np.asarray(a[key]).dtype == np.asarray(b[key]).dtype, where + key


def test_same_step_final_info_holds_no_other_rows() -> None:
    """SAME_STEP with staggered episodes (row 0 reset 3 steps later): final_info equals
    SyncVectorEnv's value for value, i.e. zeros (not the running rows' values) where the mask
    is False."""
    for env_id in VEC_IDS:
        mode = AutoresetMode.SAME_STEP
        kw = SHORT[env_id]
        sync = gym.make_vec(env_id, 3, "sync", vector_kwargs={"autoreset_mode": mode}, **kw)
        vec = make_vec(env_id, autoreset_mode=mode, **kw)
        acts = actions(vec, 30)
        for env in (sync, vec):
            env.reset(seed=SEEDS)
            for t in range(3):
                env.step(acts[t])
            env.reset(options={"reset_mask": np.array([True, False, False])})
        seen = 0
        for t in range(3, 30):
            out_s, out_v = sync.step(acts[t]), vec.step(acts[t])
            if "final_info" in out_s[4]:
                done = out_s[4]["_final_info"]
                fs, fv = out_s[4]["final_info"], out_v[4]["final_info"]
                _assert_final_info_like_sync(fs, fv, f"{env_id} {t}: ")
                assert np.all(fv["time"][~done] == 0) and np.all(fv["time"][done] > 0)
                seen += int(done.sum() < 3)  # rows that run on: their values must not leak
        assert seen >= 2


def _compiled_resets_match_sync(env_id, kw, mode, option, buffer) -> None:
    """4 envs through compiled resets past the end of the draw buffer (`buffer` resets per row),
    mixed with template resets with `option` (one draw less) that rewind the pre-draw: bit for
    bit SyncVectorEnv (steps, resets, infos)."""
    n = 4
    sync = gym.make_vec(env_id, n, "sync", vector_kwargs={"autoreset_mode": mode}, **kw)
    vec = make_vec(env_id, n, autoreset_mode=mode, **kw)
    out_s, out_v = sync.reset(seed=5), vec.reset(seed=5)
    acts = actions(vec, 6 * buffer, seed=2)
    resets, done = 0, np.zeros(n, dtype=bool)
    for t in range(len(acts)):
        disabled = mode == AutoresetMode.DISABLED
        if disabled and (done.any() or t % 8 == 0) or t in (13, 40):
            mask = done | (np.array([True, False, True, False]) if t % 3 else True)
            opts: dict[str, Any] = {"reset_mask": mask}
            if t in (13, 40):  # a template reset with an option draws one double less
                opts.update(option)
            out_s = sync.reset(options={**opts, "reset_mask": mask.copy()})
            out_v = vec.reset(options=opts)
            np.testing.assert_array_equal(out_s[0], out_v[0])
            assert_infos_equal(out_s[1], out_v[1], f"reset {t}: ")
        out_s, out_v = sync.step(acts[t]), vec.step(acts[t])
        for a, b in zip(out_s[:4], out_v[:4]):
            np.testing.assert_array_equal(a, b, err_msg=f"step {t}")
        assert_infos_equal(out_s[4], out_v[4], f"step {t}: ")
        done = out_v[2] | out_v[3]
        resets += int(np.sum(done))
    assert resets > 2 * buffer  # the buffer of a row runs out and is refilled


@pytest.mark.parametrize("mode", list(AutoresetMode))
def test_gowec_compiled_resets_equal_sync(mode: AutoresetMode) -> None:
    """GOWEC-v0's compiled resets (pre-drawn from each row's generator) past the end of the
    draw buffer, mixed with template resets (options, seeds) that rewind the pre-draw: bit for
    bit SyncVectorEnv, in every autoreset mode."""
    from mf_envs.envs.gowec.vector import GOWECVectorEnv

    kw = {"n_periods": 1, "steps_per_period": 4}  # an episode every 4 steps
    buffer = GOWECVectorEnv.DRAW_BUFFER
    _compiled_resets_match_sync("GOWEC-v0", kw, mode, {"gimbal_angle": 0.05}, buffer)


GOWEC_V1_SCENES = [{}, {"wave_direction": 0.4, "gyro_units": 1, "wave_amplitude": 0.3},
                   {"device": "iswec_box", "wave_direction": 1.2}]  # fmt: skip


@pytest.mark.parametrize("scene", GOWEC_V1_SCENES)
@pytest.mark.parametrize("mode", list(AutoresetMode))
def test_gowec_v1_compiled_resets_equal_sync(mode: AutoresetMode, scene: dict) -> None:
    """FloatingGOWEC-v0's compiled resets (regular seas: the phase and gimbal angle pre-drawn, the
    excitation coefficients from the single env's function) as GOWEC-v0's above, with template
    resets carrying an option (`buoy_pitch`) in between; also a wave off the pitch axis and
    one gyro unit. Irregular seas keep the template path."""
    from mf_envs.envs.gowec_v1.vector import GOWECV1VectorEnv as V

    kw = {"episode_seconds": 0.08, **scene}  # an episode every 4 steps
    assert make_vec("FloatingGOWEC-v0", 2, **kw).unwrapped._fast  # the compiled path is taken
    assert not make_vec("FloatingGOWEC-v0", 2, **FULL["FloatingGOWEC-v0"]).unwrapped._fast
    _compiled_resets_match_sync("FloatingGOWEC-v0", kw, mode, {"buoy_pitch": 0.05}, V.DRAW_BUFFER)


STAB_SCENES = [
    {},
    {"heading": 0.3, "ship_speed": 10.0},
    {"effects": ("gyroscopic", "hydrostatic_restoring", "translation")},
    {"hull": "mss_naval_vessel", "ship_speed": 6.0, "n_gyros": 2, "gimbal_drive": "kinematic"},
]


@pytest.mark.parametrize("scene", STAB_SCENES)
@pytest.mark.parametrize("mode", list(AutoresetMode))
def test_stabilizer_compiled_resets_equal_sync(mode: AutoresetMode, scene: dict) -> None:
    """GyroStabilizer-v0's compiled resets (`reset_rows`, three pre-drawn doubles per reset)
    as GOWEC-v0's above (an option draws one double less), also in a following sea met at a
    negative encounter frequency (the wave phase's sign flips), without a wave (the phase
    unused), and on the MSS vessel with its sway-roll-yaw coupling and a kinematic pair."""
    from mf_envs.envs.gyro_stabilizer.vector import GyroStabilizerVectorEnv as V

    kw = {"episode_seconds": 0.2, **scene}  # an episode every 4 steps
    assert make_vec(ENV_STAB, 2, **kw).unwrapped._fast  # the compiled path is taken
    _compiled_resets_match_sync(ENV_STAB, kw, mode, {"roll_rate": 0.01}, V.DRAW_BUFFER)


@pytest.mark.parametrize("env_id", VEC_IDS)
def test_threads_do_not_change_results(env_id: str) -> None:
    """Rows stepped in blocks on worker threads (num_threads > 1) == one thread, bit for bit,
    through autoresets; num_threads is checked and its automatic choice follows the row cost."""
    from mf_envs.envs._vector import MIN_ROWS_PER_THREAD

    heavy = env_id in ("Inchworm-v0", "Serpentine-v0", "Eel-v0")  # millisecond rows
    n = 5 if heavy else 300
    kw = SHORT[env_id]
    one = make_vec(env_id, n, num_threads=1, **kw)
    many = make_vec(env_id, n, num_threads=3, **kw)  # 3 row blocks at once
    assert (one.unwrapped.num_threads, many.unwrapped.num_threads) == (1, 3)
    auto = make_vec(env_id, 2 if heavy else 2 * MIN_ROWS_PER_THREAD["light"], **kw).unwrapped
    assert auto.row_cost == ("heavy" if heavy else "light")
    assert auto.num_threads == min(2, numba.get_num_threads())
    assert make_vec(env_id, 1, **kw).unwrapped.num_threads == 1
    out_a, out_b = one.reset(seed=1), many.reset(seed=1)
    for t, a in enumerate(actions(one, 12 if heavy else 20)):
        out_a, out_b = one.step(a), many.step(a)
        for x, y in zip(out_a[:4], out_b[:4]):
            np.testing.assert_array_equal(x, y, err_msg=f"step {t}")
        assert_infos_equal(out_a[4], out_b[4], f"step {t}: ")
    for bad in (0, 1.5, "2", True):
        with pytest.raises(ValueError, match="num_threads"):
            make_vec(env_id, 2, num_threads=bad)


def test_row_blocks_share_rows_so_that_blocks_end_together() -> None:
    """RowBlocks' split: a worker that starts its block 0.1 s late at 1 ms per row gets
    (T - start) / cost rows with T the common end, here 550 / 450 of 1000 rows (T = 0.55 s),
    approached geometrically (smoothing 0.3 per run); edges keep every block >= 1 row."""
    from mf_envs.envs._rows import RowBlocks

    rb = RowBlocks(1000, 2)
    assert rb.bounds() == [0, 500, 1000]
    for _ in range(60):
        b = rb.bounds()
        n0, n1 = b[1] - b[0], b[2] - b[1]
        rb._rebalance([(0.0, n0 * 1e-3), (0.1, 0.1 + n1 * 1e-3)])
    assert rb.bounds() == [0, 550, 1000]
    np.testing.assert_allclose(rb.shares, [550.0, 450.0], atol=1.0)
    rb.shares = [0.2, 999.8]
    assert rb.bounds() == [0, 1, 1000]
    rb3 = RowBlocks(2, 3)  # fewer rows than blocks: one row each
    assert rb3.k == 2 and rb3.bounds() == [0, 1, 2]
    # a worker 1.5x slower per row (a shared core), starting with the caller: T = 0.6 s when
    # rows split 600 / 400 (600 x 1 ms = 400 x 1.5 ms)
    rb = RowBlocks(1000, 2)
    for _ in range(80):
        b = rb.bounds()
        n0, n1 = b[1] - b[0], b[2] - b[1]
        rb._rebalance([(0.0, n0 * 1e-3), (0.0, n1 * 1.5e-3)])
    assert rb.bounds() == [0, 600, 1000]


_FORK_SCRIPT = """
import os, signal, sys, time
import gymnasium as gym, numpy as np
import mf_envs  # noqa: F401
kw = {"episode_seconds": 0.3, "num_threads": 2}
def make():
    return gym.make_vec("GyroStabilizer-v0", num_envs=300, vectorization_mode="vector_entry_point",
                        **kw)
parent = make()
parent.reset(seed=4)
acts = np.random.default_rng(0).uniform(-1.2, 1.2, (10, 300, 1)).astype(np.float32)
ref = [parent.step(a)[0] for a in acts]
pid = os.fork()
if pid == 0:  # the child: exit code 0 only if it ran and matched
    ok = False
    try:
        child = make()
        child.reset(seed=4)
        ok = all(np.array_equal(child.step(a)[0], r) for a, r in zip(acts, ref))
    finally:
        os._exit(0 if ok else 3)
for _ in range(600):  # a child stuck on its parent's (absent) worker threads: fail, not hang
    done, status = os.waitpid(pid, os.WNOHANG)
    if done:
        sys.exit(os.waitstatus_to_exitcode(status))
    time.sleep(0.1)
os.kill(pid, signal.SIGKILL)
sys.exit(4)
"""


def test_stabilizer_threaded_env_survives_fork() -> None:
    """A process forked after the worker threads started (it has none of them) steps its
    threaded vector env on its own workers, with the parent's results. Run in a fresh
    interpreter: a test worker that has imported JAX (the sbx extra) must not fork."""
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-c", _FORK_SCRIPT], capture_output=True, text=True,
                         timeout=600)  # fmt: skip
    assert out.returncode == 0, (out.returncode, out.stderr[-2000:])


def test_inchworm_native_vector_env_runs_the_friction_scene() -> None:
    """The inchworm's native vector env compiles the friction scene (the default); other scenes
    are refused with a ValueError naming `effects`, and the trainers fall back to single envs."""
    from mf_envs.envs import native_vector_supported
    from mf_envs.envs.inchworm.env import SEED_SCENE_EFFECTS

    assert native_vector_supported("Inchworm-v0")
    assert native_vector_supported("Inchworm-v0", {"effects": ("gravity", "friction")})
    assert not native_vector_supported("Inchworm-v0", {"effects": SEED_SCENE_EFFECTS})
    assert native_vector_supported("GOWEC-v0") and native_vector_supported("CartPole-v1")
    with pytest.raises(ValueError, match="effects"):
        make_vec("Inchworm-v0", 2, effects=SEED_SCENE_EFFECTS)
    pytest.importorskip("stable_baselines3", reason="needs the train extra")
    from mf_envs.train.vec import make_train_env

    kw = {"effects": SEED_SCENE_EFFECTS, "max_episode_steps": 3}
    venv, kind = make_train_env("Inchworm-v0", 2, seed=0, env_kwargs=kw)
    assert kind == "dummy"
    venv.close()
    venv, kind = make_train_env("Inchworm-v0", 2, seed=0, env_kwargs={"max_episode_steps": 3})
    assert kind == "native"
    venv.close()
