"""Record env trajectories to an npz; compare two records.

Every env's default baseline and a fixed random action sequence on the single env, and the native
vector env under fixed random actions, each on a few scenes (regular and irregular seas, drives,
the inchworm's seed scene).

Used to prove a refactor bit-identical: `python tools/record_trajectories.py before.npz` on the old
commit, again on the new one, then
`python tools/record_trajectories.py --compare before.npz after.npz`. `--only ENV_ID` (after the
output path) records one env.
"""

import sys

import gymnasium as gym
import numpy as np

import mf_envs  # noqa

try:
    from mf_envs.controllers import make_baseline
except ImportError:  # before the namespace move
    from controllers import make_baseline
from mf_envs.envs.gyro_stabilizer.env import GyroStabilizerEnv

SHIP_IRREGULAR = (*GyroStabilizerEnv.DEFAULT_EFFECTS, "irregular_waves")

# the floating GOWEC under its id (FloatingGOWEC-v0; GOWEC-v1 before it had its own id)
FLOATING = "FloatingGOWEC-v0" if "FloatingGOWEC-v0" in gym.registry else "GOWEC-v1"
INCHWORM_SEED_BODY = {
    "length": 0.3,
    "width": 0.02,
    "height": 0.01,
    "youngs_modulus": 2.4e9,
    "shear_modulus": 0.96e9,
    "mass_per_length": 0.278,
    "max_curvature": 13.0,
}
STEPS = {
    "GOWEC-v0": 300,
    "GyroStabilizer-v0": 300,
    "Inchworm-v0": 40,
    "FloatingGOWEC-v0": 300,
    "Serpentine-v0": 60,
    "Eel-v0": 120,
}
VARIANTS = {
    "GOWEC-v0": [
        {},
        {"effects": ("gyroscopic", "gimbal_inertia", "buoy_rocking", "wave_2d", "irregular_waves")},
    ],
    "GyroStabilizer-v0": [
        {},
        {"n_gyros": 1},
        {"gimbal_drive": "torque"},
        {"effects": SHIP_IRREGULAR},
        {"episode_seconds": 4.0},  # episodes of 80 steps: the env's own truncation and resets
    ],
    # the seed's body spelled out (the default robot changed in issue 31); the cases run the
    # same physics on a commit before it
    "Inchworm-v0": [
        {},
        {**INCHWORM_SEED_BODY, "effects": ("gravity", "inertia", "anchor_switching")},
        {**INCHWORM_SEED_BODY, "effects": ("gravity", "shear_deformation", "anchor_switching")},
        {
            **INCHWORM_SEED_BODY,
            "grip_time_constant": 0.2,
            "effects": (
                "gravity",
                "shear_deformation",
                "anchor_switching",
                "actuator_dynamics",
                "friction",
            ),
        },
    ],
    "FloatingGOWEC-v0": [{}, {"significant_wave_height": 1.5}],
    # the beam robots; a short episode (40 and 100 steps) crosses its end within the run
    # the serpentine's discretisation before 12 elements at 3.125 ms spelled out (bit-identical
    # to a record of that commit's defaults); the default changes by design
    "Serpentine-v0": [{}, {"episode_seconds": 2.0}, {"n_elements": 6, "physics_dt": 0.025}],
    # the eel without the form drag and the muscles' power limit: the physics before they were
    # added (bit-identical to a record of that commit); the default changes by design
    "Eel-v0": [{}, {"episode_seconds": 2.0}, {"effects": ("resistive", "reactive")}],
}
VECTOR_STEPS = 120  # native vector env, 3 rows, fixed random actions, NEXT_STEP autoreset


def numeric_info(info):
    out = {}
    for k, v in info.items():
        if k in ("reward_terms",) and isinstance(v, dict):
            for kk, vv in v.items():
                out[f"rt_{kk}"] = float(vv)
        elif isinstance(v, (bool, int, float, np.floating, np.integer)):
            out[k] = float(v)
        elif isinstance(v, np.ndarray) and v.dtype.kind in "fiub":
            out[k] = v.astype(float).ravel()
    return out


def run(env_id, kw, mode):
    env = gym.make(FLOATING if env_id == "FloatingGOWEC-v0" else env_id, **kw)
    obs, info = env.reset(seed=123)
    rng = np.random.default_rng(7)
    ctrl = make_baseline(env) if mode == "baseline" else None
    if ctrl:
        ctrl.reset()
    rec = {"obs": [obs.copy()], "rew": []}
    infos = [numeric_info(info)]
    for _ in range(STEPS[env_id]):
        if ctrl:
            a, _ = ctrl.predict(obs)
        else:
            a = rng.uniform(-1, 1, env.action_space.shape).astype(np.float32)
        obs, r, te, tr, info = env.step(a)
        rec["obs"].append(obs.copy())
        rec["rew"].append(r)
        infos.append(numeric_info(info))
        if te or tr:
            obs, info = env.reset()
            infos.append(numeric_info(info))
            rec["obs"].append(obs.copy())
            if ctrl:
                ctrl.reset()
    out = {"obs": np.array(rec["obs"]), "rew": np.array(rec["rew"])}
    keys = sorted(set().union(*[i.keys() for i in infos]))
    for k in keys:
        vals = [np.atleast_1d(i.get(k, np.nan)).astype(float) for i in infos]
        try:
            out["info_" + k] = np.array(vals)
        except ValueError:
            pass
    return out


def run_vector(env_id, kw):
    """The native vector env (3 rows, seeds 11, 3, 7) under fixed random actions: obs, rewards,
    terminations and every numeric info column (masked-out rows as NaN)."""
    real = FLOATING if env_id == "FloatingGOWEC-v0" else env_id
    env = gym.make_vec(real, num_envs=3, vectorization_mode="vector_entry_point", **kw)
    obs, info = env.reset(seed=[11, 3, 7])
    rng = np.random.default_rng(5)
    out = {"obs": [obs.copy()], "rew": [], "term": []}
    cols = {}
    for _ in range(VECTOR_STEPS):
        a = rng.uniform(-1.2, 1.2, env.action_space.shape).astype(np.float32)
        obs, r, te, tr, info = env.step(a)
        out["obs"].append(obs.copy())
        out["rew"].append(r.copy())
        out["term"].append((te | tr).astype(float))
        for k, v in info.items():
            if k.startswith("_") or not isinstance(v, np.ndarray) or v.dtype.kind not in "fiub":
                continue
            col = v.astype(float).reshape(3, -1).copy()
            col[~info[f"_{k}"]] = np.nan
            cols.setdefault(k, []).append(col)
    env.close()
    rec = {k: np.array(v) for k, v in out.items()}
    rec.update({f"info_{k}": np.array(v) for k, v in cols.items() if len(v) == VECTOR_STEPS})
    return rec


def _renamed(z):
    """The record's arrays with the floating GOWEC's old id (GOWEC-v1) under its new one."""
    return {k.replace("GOWEC-v1|", "FloatingGOWEC-v0|", 1): z[k] for k in z.files}


def compare(a_path, b_path):
    a, b = _renamed(np.load(a_path)), _renamed(np.load(b_path))
    worst = {}
    for k in a:
        case = k.rsplit("|", 1)[0]
        if k not in b or a[k].shape != b[k].shape:
            worst[case] = np.inf
            continue
        d = np.nanmax(np.abs(a[k] - b[k]), initial=0.0) if a[k].size else 0.0
        same = np.array_equal(a[k], b[k], equal_nan=True)
        worst[case] = max(worst.get(case, 0.0), 0.0 if same else max(float(d), 1e-300))
    for case, d in sorted(worst.items()):
        print(f"{case:45s} {'bit-identical' if d == 0 else f'max abs diff {d:.3e}'}")
    return all(d == 0 for d in worst.values())


if __name__ == "__main__":
    if sys.argv[1] == "--compare":
        sys.exit(0 if compare(sys.argv[2], sys.argv[3]) else 1)
    res = {}
    only = sys.argv[3] if len(sys.argv) > 3 and sys.argv[2] == "--only" else None
    for env_id, vs in VARIANTS.items():
        if only is not None and env_id != only:
            continue
        for vi, kw in enumerate(vs):
            for mode in ("baseline", "random"):
                r = run(env_id, kw, mode)
                for k, v in r.items():
                    res[f"{env_id}|{vi}|{mode}|{k}"] = v
                print(env_id, vi, mode, r["rew"].sum(), flush=True)
            real = FLOATING if env_id == "FloatingGOWEC-v0" else env_id
            friction = "friction" in kw.get("effects", ())
            if gym.spec(real).vector_entry_point and (
                env_id != "Inchworm-v0" or not kw or friction
            ):
                r = run_vector(env_id, kw)
                for k, v in r.items():
                    res[f"{env_id}|{vi}|vector|{k}"] = v
                print(env_id, vi, "vector", r["rew"].sum(), flush=True)
    np.savez(sys.argv[1], **res)
