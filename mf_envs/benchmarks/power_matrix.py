"""FloatingGOWEC-v0's power matrix: mean net electrical power over significant wave height x
energy period, binned as IEC TS 62600-100 bins a power matrix (on Te, not Tp).

Each cell is a JONSWAP sea (gamma 3.3) of the cell's Hs and Te (peak period Tp = Te / r, r =
Te / Tp of the spectrum from MHKiT's `energy_period`, 0.90 at gamma 3.3) drawn with
N_COMPONENTS components, scored over `--seconds` (default 1200 s, 20 min) of simulated time
per seed after the start-up ramp, on unseen seeds 2000.., with a controller from
`mf_envs.controllers.gowec_v1` (default: `efficient_pto`; `passive_damper` beside it).
Reported per cell: net electrical power (W, mean and spread over seeds), the controller's
predicted net power (its linear model, `pto_search`), mechanical PTO power, capture width
P_mech / J (m) with J the sea's energy flux at the hull table's water depth (35 m) by MHKiT
(`mhkit.wave.resource.energy_flux` of the IEC JONSWAP spectrum, finite depth), capture-width
ratio over the hull's width across the sea (`hull_width`: the box's 8 m beam), the share of
time in survival and of episodes ended by a failure.

    python -m mf_envs.benchmarks.power_matrix --out docs/img   # ~10 min on 2 cores
    python -m mf_envs.benchmarks.power_matrix --device iswec_box --out DIR   # another device

writes `gowec_power_matrix.json` and `.png` there and prints a Markdown table.
The spectrum and energy flux are the package's own (`physics.waves`: the sea is drawn inside
the compiled step, with no pandas/xarray on that path); they equal MHKiT's (IEC TS 62600-2
JONSWAP, `mhkit.wave.resource.energy_flux`) to 1e-10 in shape and 1e-6 in flux, up to IEC's
approximate A_gamma normalisation (0.24 % at gamma 3.3): `tests/test_waves_mhkit.py`, compare
extra.
"""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import Any

import gymnasium as gym
import numpy as np

import mf_envs  # noqa: F401
from mf_envs._files import save_figure
from mf_envs.controllers import make_baseline

ENV_ID = "FloatingGOWEC-v0"
HS = (1.0, 1.5, 2.0, 2.5)  # m
TE = (4.0, 5.0, 6.0, 7.0, 8.0)  # s, energy period bins
SEEDS = (2000, 2001, 2002)
GAMMA = 3.3
N_COMPONENTS = 256  # the sea's components (the env's default 64 puts ~10 in the resonance band)
WATER_DEPTH = 35.0  # m, the hull table's (Pantelleria site)


def _spectrum(hs: float, tp: float) -> Any:
    """MHKiT's IEC JONSWAP spectrum (m^2/Hz) of (hs, tp, GAMMA) on 0.01-1 Hz."""
    from mhkit.wave import resource

    f = np.linspace(0.01, 1.0, 2000)
    return resource.jonswap_spectrum(f, tp, hs, gamma=GAMMA)


def te_over_tp() -> float:
    """r = Te / Tp of the JONSWAP spectrum (GAMMA), by MHKiT's `energy_period`."""
    from mhkit.wave import resource

    return float(np.squeeze(resource.energy_period(_spectrum(1.0, 1.0 / 0.1)))) / 10.0


def energy_flux(hs: float, tp: float, depth: float = WATER_DEPTH) -> float:
    """J (W/m) of the JONSWAP sea (hs, tp) at the water depth (m), MHKiT's finite-depth flux."""
    from mhkit.wave import resource

    return float(np.squeeze(resource.energy_flux(_spectrum(hs, tp), depth)))


def hull_width(device: str | None = None) -> float:
    """The hull's width across the default (head) sea (m), the capture-width ratio's: a box's
    beam (its length lies along the sea), a cylinder's diameter."""
    from mf_envs.physics.gowec.hydro import axes
    from mf_envs.physics.gowec.hydro.devices import DEFAULT_DEVICE, DEVICES

    dev = DEVICES[device or DEFAULT_DEVICE]
    plan = axes.plan(dev.three_dof_table())
    return plan[1] if plan is not None else 2.0 * float(dev.hull().radius)


def cell(hs: float, tp: float, seed: int, seconds: float, kind: str, **kw: Any) -> dict:
    """One episode: JONSWAP (hs, tp) of N_COMPONENTS components (`episode`)."""
    kw.setdefault("n_components", N_COMPONENTS)
    return episode(kind, seed, seconds, significant_wave_height=hs, peak_period=tp, **kw)


def episode(kind: str, seed: int, seconds: float, **kw: Any) -> dict:
    """One episode of the env made with kw, the `kind` controller set at reset: mean net and
    mechanical power after the ramp (W), the controller's prediction (W), the share of steps
    in survival, the largest gimbal angle (rad) against the stroke, terminated (a failure:
    overspeed or the stroke's end)."""
    env = gym.make(ENV_ID, episode_seconds=seconds + 20.0, max_episode_steps=-1, **kw)
    ctrl = make_baseline(env, kind)
    obs, _ = env.reset(seed=seed)
    ctrl.reset()
    u = env.unwrapped
    skip = int(math.ceil(max(u.wave_ramp, 1.0) * 2.0 / u.control_dt))  # ramp + as long again
    pe, pm, done, n, term, surv, phi = 0.0, 0.0, False, 0, False, 0, 0.0
    steps = 0
    while not done:
        a, _ = ctrl.predict(obs)
        obs, _, term, trunc, info = env.step(a)
        steps += 1
        phi = max(phi, abs(info["gimbal_angle"]))
        if steps > skip:
            pe += info["power"]
            pm += info["power_mechanical"]
            surv += info["survival"]
            n += 1
        done = term or trunc
    out = dict(Pe=pe / max(n, 1), Pm=pm / max(n, 1), terminated=bool(term),
               survival=surv / max(n, 1), c=float(getattr(ctrl, "c", 0.0)),
               k=float(getattr(ctrl, "k", 0.0)), speed_rpm=abs(u.model.psid) * 30.0 / math.pi,
               loss_W=u.rotor_loss_power(),
               max_gimbal=phi, stroke=u.gimbal_stroke(),
               steps=steps, max_steps=u.max_steps,
               predicted=float(getattr(ctrl, "prediction", {}).get("net_W", math.nan)))  # fmt: skip
    env.close()
    return out


def matrix(hs=HS, te=TE, seeds=SEEDS, seconds: float = 1200.0, kind: str = "efficient_pto",
           progress: bool = True, **kw: Any) -> list[dict]:  # fmt: skip
    """Rows (one per cell, binned on Te) of mean and std over seeds of `cell`'s figures; kw
    go to the env (e.g. n_components)."""
    from tqdm import tqdm

    rows, r = [], te_over_tp()
    width = hull_width(kw.get("device"))
    jobs = [(h, e) for h in hs for e in te]
    for h, e in tqdm(jobs, desc=f"power matrix ({kind})", disable=not progress):
        tp = e / r
        runs = [cell(h, tp, s, seconds, kind, **kw) for s in seeds]
        pe = np.array([x["Pe"] for x in runs])
        pm = np.array([x["Pm"] for x in runs])
        J = energy_flux(h, tp)
        pred = float(np.mean([x["predicted"] for x in runs]))
        rows.append(dict(hs=h, te=e, tp=tp, kind=kind, net_W=float(pe.mean()),
                         net_std_W=float(pe.std()), predicted_W=pred,
                         mech_W=float(pm.mean()), J_W_per_m=J, capture_width_m=float(pm.mean()) / J,
                         cwr=float(pm.mean()) / J / width, hull_width_m=width,
                         survival=float(np.mean([x["survival"] for x in runs])),
                         terminated=float(np.mean([x["terminated"] for x in runs])),
                         speed_rpm=[x["speed_rpm"] for x in runs],
                         loss_W=float(np.mean([x["loss_W"] for x in runs])),
                         seeds=list(seeds), seconds=seconds, **kw))  # fmt: skip
    return rows


def table(rows: list[dict]) -> str:
    """Markdown: net electrical power (kW, mean +- std over seeds) by Hs (rows) x Te (cols)."""
    hs = sorted({r["hs"] for r in rows})
    tp = sorted({r["te"] for r in rows})
    at = {(r["hs"], r["te"]): r for r in rows}
    lines = ["| Hs (m) \\ Te (s) | " + " | ".join(f"{t:g}" for t in tp) + " |",
             "|---" * (len(tp) + 1) + "|"]  # fmt: skip
    for h in hs:
        cells = []
        for t in tp:
            r = at[(h, t)]
            mark = " (fails)" if r["terminated"] > 0 else ""
            cells.append(f"{r['net_W'] / 1e3:.1f} ± {r['net_std_W'] / 1e3:.1f}{mark}")
        lines.append(f"| {h:g} | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def plot(rows: list[dict], path: Path) -> Path:
    """The matrix as a coloured grid with the values written in (kW)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from mf_envs.physics.gowec.hydro.devices import DEFAULT_DEVICE

    hs = sorted({r["hs"] for r in rows})
    tp = sorted({r["te"] for r in rows})
    at = {(r["hs"], r["te"]): r for r in rows}
    z = np.array([[at[(h, t)]["net_W"] / 1e3 for t in tp] for h in hs])
    fig, ax = plt.subplots(figsize=(7, 4))
    lim = float(np.max(np.abs(z))) or 1.0
    im = ax.imshow(z, origin="lower", cmap="RdYlGn", vmin=-lim, vmax=lim, aspect="auto")
    for i, h in enumerate(hs):
        for j, t in enumerate(tp):
            end = "*" if at[(h, t)]["terminated"] > 0 else ""
            ax.text(j, i, f"{z[i, j]:.1f}{end}", ha="center", va="center", fontsize=9)
    ax.set_xticks(range(len(tp)), [f"{t:g}" for t in tp])
    ax.set_yticks(range(len(hs)), [f"{h:g}" for h in hs])
    ax.set_xlabel("energy period Te (s)")
    ax.set_ylabel("significant wave height Hs (m)")
    r0 = rows[0]
    ax.set_title(f"FloatingGOWEC-v0 ({r0.get('device', DEFAULT_DEVICE)}): net electrical "
                 f"power, {r0['kind']}\n"
                 f"JONSWAP, {len(r0['seeds'])} seeds x {r0['seconds']:.0f} s each "
                 f"(* = a failure ended an episode)", fontsize=9)  # fmt: skip
    fig.colorbar(im, ax=ax, label="net electrical power (kW)")
    fig.tight_layout()
    return save_figure(fig, path, dpi=110)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=Path("."), help="folder for the json and png")
    ap.add_argument("--seconds", type=float, default=1200.0, help="scored time per seed (s)")
    ap.add_argument("--seeds", type=int, default=len(SEEDS), help="seeds per cell (2000..)")
    ap.add_argument("--kind", default="efficient_pto", help="baseline of controllers.gowec_v1")
    ap.add_argument("--device", default=None, help="FloatingGOWEC-v0's device (its default)")
    a = ap.parse_args(argv)
    a.out.mkdir(parents=True, exist_ok=True)
    from mf_envs.physics.gowec.hydro.devices import DEFAULT_DEVICE

    kw = {"device": a.device or DEFAULT_DEVICE}  # recorded in every row
    rows = matrix(seeds=tuple(range(2000, 2000 + a.seeds)), seconds=a.seconds, kind=a.kind, **kw)
    (a.out / "gowec_power_matrix.json").write_text(json.dumps(rows, indent=1))
    plot(rows, a.out / "gowec_power_matrix.png")
    print(table(rows))


if __name__ == "__main__":
    main()
