"""GyroStabilizer-v0 on irregular seas: the grid bench.

The default device (a Seakeeper Model 7000 on the 18 t yacht, hydraulic brake; docs/
stabilizer_physics.md §4) in long-crested JONSWAP seas over a grid

    Hs (0.3, 0.8, 1.5 m) x Tp (T_n = 3.70 s, the roll resonance; 1.6 T_n = 5.92 s, off it)
    x heading (beam 90 deg, stern-quartering 45 deg) x speed (0, cruising 5 m/s),

24 cells; per cell and controller, over seeds 100-104 (never used in any tuning: the baselines
were tuned on seeds 0-2 of the regular resonance scene), 120 s episodes, the RMS roll after the
10 s settling time (`task.SETTLE`):
- `rr`: RMS roll reduction 1 - RMS_on / RMS_rotor_off per seed (same seed = same sea), mean and
  sample std over the seeds;
- `peak_mount`: largest mount moment per unit (N m, `info["mount_moment"]`) over all seeds;
- `drive_power`: mean drive power int n |tau phi'| dt / t (W; the brake's: heat in its oil);
- `demand` (per cell): 1 / capacity of the sea met (`demand`).
Controllers: `pid`, `lqr` (`mf_envs.controllers.stabilizer`, rate commands to the brake's
valve loop) and `passive`: the brake at a fixed valve (`gimbal_drive="damper"`, tau = -c phi',
c = n H^2 / sqrt(C44 J); action ignored), with the same rate cap and cushions.
Encounter: a stern-quartering sea met at 5 m/s is met at w_e = w - w^2 U cos(beta) / g, at most
g / (4 U cos beta) = 0.69 rad/s, far below the roll resonance 1.70 rad/s (`physics.ship.seas`).

    python -m mf_envs.benchmarks.stabilizer_grid [--seeds 5] [--seconds 120] [--out DIR]
        [--quick] [--policy PPO_FOLDER ...]

writes `stabilizer_grid.csv` and `stabilizer_grid.md` (the table of docs/stabilizer_physics.md
§5) into DIR (default `bench_out/`), with a progress bar per episode batch.
"""

from __future__ import annotations

import argparse
import csv
import math
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs.envs.gyro_stabilizer.task import DECLARATION, SETTLE

ENV_ID = DECLARATION.env_id
HS = (0.3, 0.8, 1.5)  # m
TP_FACTORS = (1.0, 1.6)  # x T_n
HEADINGS = {"beam": 0.5 * math.pi, "quartering": 0.25 * math.pi}
SPEEDS = (0.0, 5.0)  # m/s
SEEDS = (100, 101, 102, 103, 104)
CONTROLLERS = ("pid", "lqr", "passive")


def cells(quick: bool = False) -> list[dict[str, Any]]:
    """The grid's cells as env kwargs (plus a `name`)."""
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS
    from mf_envs.physics.ship.hulls import Hull

    tn = Hull.yacht().natural_roll_period()
    irr = tuple(e for e in DEFAULT_EFFECTS if e != "wave_moment") + ("irregular_waves",)
    out = []
    hs_list = (0.8,) if quick else HS
    for hs in hs_list:
        for f in TP_FACTORS:
            for hname, beta in HEADINGS.items():
                for u in SPEEDS:
                    kw = {"effects": irr, "significant_wave_height": hs, "wave_period": f * tn,
                          "heading": beta, "ship_speed": u}  # fmt: skip
                    out.append({"name": f"Hs{hs:g}_Tp{f * tn:.2f}_{hname}_U{u:g}", **kw})
    return out


POLICIES: dict[str, Any] = {}  # controller name -> a loaded PPO policy (`--policy`)


def _episode(kw: dict[str, Any], kind: str | None, seed: int, seconds: float) -> dict[str, float]:
    """One episode: RMS roll after SETTLE (rad), peak mount moment (N m), mean drive power (W);
    kind: None (rotor off), a baseline, "passive" or a name in `POLICIES`."""
    import gymnasium as gym

    import mf_envs  # noqa: F401
    from mf_envs.controllers import make_baseline

    kw = {k: v for k, v in kw.items() if k != "name"}
    if kind is None:
        kw["effects"] = tuple(e for e in kw["effects"] if e != "gyroscopic")
    elif kind == "passive":
        kw["gimbal_drive"] = "damper"
    env = gym.make(ENV_ID, episode_seconds=seconds, max_episode_steps=-1, **kw)  # no TimeLimit
    obs, _ = env.reset(seed=seed)
    ctrl = make_baseline(env, kind) if kind in ("pid", "lqr") else POLICIES.get(kind)
    sq, n, mount, energy = 0.0, 0, 0.0, 0.0
    done = False
    zero = np.zeros(1, np.float32)
    while not done:
        a = ctrl.predict(obs)[0] if ctrl is not None else zero
        obs, _, term, trunc, info = env.step(a)
        done = term or trunc
        if info["time"] > SETTLE:
            sq += info["roll"] ** 2
            n += 1
            mount = max(mount, info["mount_moment"])
            energy += info["drive_energy"]
    return {"rms_roll": math.sqrt(sq / max(n, 1)), "peak_mount": mount,
            "drive_power": energy / max(n * env.unwrapped.control_dt, 1e-12)}  # fmt: skip


def demand(cell: dict[str, Any], seed: int) -> float:
    """1 / capacity of the cell's sea for the default unit (`physics.ship.seakeeper.capacity`'s
    bound on the sea met): M0 / min(n H w_e sin(phi_max), n H r_cap), with M0 = sqrt(2) x the
    RMS roll moment met by the ship (seed `seed`'s sea) and w_e the encounter frequency of the
    spectral peak. Above 1 the unit cannot cancel a sinusoid of that amplitude: RR saturates."""
    import gymnasium as gym

    import mf_envs  # noqa: F401
    from mf_envs.physics.ship.seas import G

    kw = {k: v for k, v in cell.items() if k != "name"}
    env = gym.make(ENV_ID, **kw).unwrapped
    env.reset(seed=seed)
    m0 = math.sqrt(2.0) * float(np.std(env._tab[:, 0]))
    w = 2.0 * math.pi / env.wave_period
    we = abs(w - w * w * env.ship_speed * math.cos(env.heading) / G)
    nh = env.n_gyros * env.angular_momentum
    return m0 / min(nh * we * math.sin(env.max_gimbal_angle), nh * env.max_precession_rate)


def run(seeds: tuple[int, ...], seconds: float, quick: bool = False) -> list[dict[str, Any]]:
    """Rows (cell, controller, metric, mean, std, n_seeds) of the grid, with a progress bar."""
    from tqdm import tqdm

    controllers = CONTROLLERS + tuple(POLICIES)
    grid = cells(quick)
    rows: list[dict[str, Any]] = []
    bar = tqdm(total=len(grid) * (1 + len(controllers)) * len(seeds), desc="stabilizer grid",
               unit="episode")  # fmt: skip
    for cell in grid:
        off = []
        for s in seeds:
            off.append(_episode(cell, None, s, seconds)["rms_roll"])
            bar.update()
        base = {"cell": cell["name"], "hs": cell["significant_wave_height"],
                "demand": demand(cell, seeds[0]),
                "tp": cell["wave_period"], "heading_deg": math.degrees(cell["heading"]),
                "speed": cell["ship_speed"], "n_seeds": len(seeds)}  # fmt: skip
        rows.append({**base, "controller": "rotor_off", "metric": "rms_roll",
                     "mean": float(np.mean(off)), "std": float(np.std(off, ddof=1))})  # fmt: skip
        for kind in controllers:
            res = []
            for s in seeds:
                res.append(_episode(cell, kind, s, seconds))
                bar.update()
            rr = [1.0 - r["rms_roll"] / o for r, o in zip(res, off)]
            for metric, vals in (("rr", rr), ("peak_mount", [r["peak_mount"] for r in res]),
                                 ("drive_power", [r["drive_power"] for r in res])):  # fmt: skip
                v = np.asarray(vals, dtype=float)
                stat = float(v.max()) if metric == "peak_mount" else float(v.mean())
                rows.append({**base, "controller": kind, "metric": metric, "mean": stat,
                             "std": float(v.std(ddof=1)) if len(v) > 1 else 0.0})  # fmt: skip
    bar.close()
    return rows


def table(rows: list[dict[str, Any]]) -> str:
    """The markdown table: one line per cell, RR mean +- std per controller, rotor-off RMS roll,
    the largest peak mount moment and the mean drive power of the best controller."""
    by: dict[tuple[str, str, str], dict] = {(r["cell"], r["controller"], r["metric"]): r
                                            for r in rows}  # fmt: skip
    names = list(dict.fromkeys(r["cell"] for r in rows))
    ctrls = tuple(dict.fromkeys(r["controller"] for r in rows if r["metric"] == "rr"))
    cs = "/".join(ctrls)
    head = (
        "| Hs m | Tp s | heading | U m/s | demand | roll off (deg RMS) | "
        + "".join(f"RR {c} | " for c in ctrls)
        + f"peak mount kN m ({cs}) | drive W ({cs}) |"
    )
    lines = [head, "|" + "---|" * (8 + len(ctrls))]
    for c in names:
        off = by[(c, "rotor_off", "rms_roll")]
        rr = [by[(c, k, "rr")] for k in ctrls]
        pm = "/".join(f"{by[(c, k, 'peak_mount')]['mean'] / 1e3:.1f}" for k in ctrls)
        dp = "/".join(f"{by[(c, k, 'drive_power')]['mean']:.0f}" for k in ctrls)
        hd = "beam" if abs(off["heading_deg"] - 90) < 1 else "quartering"
        rrs = " | ".join(f"{100 * r['mean']:.0f} ± {100 * r['std']:.0f} %" for r in rr)
        lines.append(f"| {off['hs']:g} | {off['tp']:.2f} | {hd} | {off['speed']:g} | "
                     f"{off['demand']:.2f} | "
                     f"{math.degrees(off['mean']):.2f} | {rrs} | {pm} | {dp} |")  # fmt: skip
    return "\n".join(lines) + "\n"


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--seeds", type=int, default=len(SEEDS), help="seeds per cell (from 100)")
    p.add_argument("--seconds", type=float, default=120.0, help="episode length, s")
    p.add_argument("--out", type=Path, default=Path("bench_out"))
    p.add_argument("--quick", action="store_true", help="only Hs 0.8 m (8 cells)")
    p.add_argument(
        "--policy",
        type=Path,
        action="append",
        default=[],
        help="a PPO policy folder (mf-envs train's output) benched as ppo, ppo2, ...",
    )
    a = p.parse_args(argv)
    if a.policy:
        from mf_envs.train.policy import load_policy

        POLICIES.clear()
        for i, path in enumerate(a.policy):
            POLICIES["ppo" if i == 0 else f"ppo{i + 1}"] = load_policy(ENV_ID, path)
    if not 1 <= a.seeds <= 1000 or not SETTLE < a.seconds <= 3600:
        p.error("--seeds in [1, 1000], --seconds in (10, 3600]")
    rows = run(tuple(range(100, 100 + a.seeds)), a.seconds, a.quick)
    a.out.mkdir(parents=True, exist_ok=True)
    with open(a.out / "stabilizer_grid.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    md = table(rows)
    (a.out / "stabilizer_grid.md").write_text(md)
    print(md)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
