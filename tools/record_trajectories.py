"""Record env trajectories (default baseline + fixed random actions) to an npz; compare two records.

Used to prove a refactor bit-identical: `python tools/record_trajectories.py before.npz` on the old
commit, again on the new one, then
`python tools/record_trajectories.py --compare before.npz after.npz`.
"""

import sys

import gymnasium as gym
import numpy as np

import mf_envs  # noqa

try:
    from mf_envs.controllers import make_baseline
except ImportError:  # before the namespace move
    from controllers import make_baseline

STEPS = {"GOWEC-v0": 300, "GyroStabilizer-v0": 300, "Inchworm-v0": 40}
VARIANTS = {
    "GOWEC-v0": [
        {},
        {"effects": ("gyroscopic", "gimbal_inertia", "buoy_rocking", "wave_2d", "irregular_waves")},
    ],
    "GyroStabilizer-v0": [{}, {"n_gyros": 1}, {"gimbal_drive": "torque"}],
    "Inchworm-v0": [{}, {"effects": ("gravity", "inertia", "anchor_switching")}],
}


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
    env = gym.make(env_id, **kw)
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


def compare(a_path, b_path):
    a, b = np.load(a_path), np.load(b_path)
    worst = {}
    for k in a.files:
        case = k.rsplit("|", 1)[0]
        if k not in b.files or a[k].shape != b[k].shape:
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
    for env_id, vs in VARIANTS.items():
        for vi, kw in enumerate(vs):
            for mode in ("baseline", "random"):
                r = run(env_id, kw, mode)
                for k, v in r.items():
                    res[f"{env_id}|{vi}|{mode}|{k}"] = v
                print(env_id, vi, mode, r["rew"].sum(), flush=True)
    np.savez(sys.argv[1], **res)
