"""FloatingGOWEC-v0 across its operating range and beyond: does the default baseline net
power in every sea it is built for, and survive the others?

Seas: regular waves of height H = 2 a and JONSWAP seas of significant height Hs, each of
1, 1.5, 2 and 2.5 m, at (peak) periods 5, 6, 7 and 8 s (the ISWEC-class operating range), and
beyond it Hs 3, 3.5 and 4 m (Tp 6, 7, 8 s) and a 60 deg oblique sea; seeds 3000.. (no
controller is tuned on seeds: `efficient_pto` and `passive_damper` set their gains from the
sea drawn at reset). Per sea and controller: the net electrical power realised (W, mean over
the episode after the ramp, `power_matrix.episode`) and predicted by the controller's linear
model, the share of time in survival, the largest gimbal angle against the stroke and the
episodes ended early.

    python -m mf_envs.benchmarks.gowec_operating --seeds 5 --seconds 300 > table.md
    python -m mf_envs.benchmarks.gowec_operating --seeds 10 --kinds efficient_pto \
        --json docs/results/gowec_operating.json > table.md     # the default baseline alone
    python -m mf_envs.benchmarks.gowec_operating --device iswec_box ...   # another device
"""

from __future__ import annotations

import argparse
import json
import math
from typing import Any

import numpy as np

from mf_envs._files import write_atomic
from mf_envs.benchmarks.power_matrix import episode
from mf_envs.physics.gowec.hydro.devices import DEFAULT_DEVICE

HEIGHTS = (1.0, 1.5, 2.0, 2.5)  # m
PERIODS = (5.0, 6.0, 7.0, 8.0)  # s
KINDS = ("efficient_pto", "passive_damper")


def seas() -> list[tuple[str, dict[str, Any]]]:
    """(label, env kwargs) of the operating range's seas and those beyond it."""
    out = []
    for h in HEIGHTS:
        for t in PERIODS:
            out.append((f"regular H {h:g} m T {t:g} s", dict(wave_amplitude=h / 2, wave_period=t)))
            out.append((f"JONSWAP Hs {h:g} m Tp {t:g} s",
                        dict(significant_wave_height=h, peak_period=t)))  # fmt: skip
    for h, t in ((3.0, 6.0), (3.5, 7.0), (4.0, 8.0)):
        out.append((f"beyond: JONSWAP Hs {h:g} m Tp {t:g} s",
                    dict(significant_wave_height=h, peak_period=t)))  # fmt: skip
    out.append(("beyond: JONSWAP Hs 2 m Tp 6 s, 60 deg oblique",
                dict(significant_wave_height=2.0, peak_period=6.0,
                     wave_direction=math.pi / 2 - math.radians(60.0))))  # fmt: skip
    return out


def rows(seeds: tuple[int, ...], seconds: float, kinds: tuple[str, ...] = KINDS,
         progress: bool = False, **env_kw: Any) -> list[dict[str, Any]]:  # fmt: skip
    """One row per sea and controller: means over the seeds, the lowest seed's net power;
    env_kw go to every env (e.g. device)."""
    from tqdm import tqdm

    out = []
    for label, kw in tqdm(seas(), desc="seas", disable=not progress):
        for kind in kinds:
            runs = [episode(kind, s, seconds, **kw, **env_kw) for s in seeds]
            out.append(dict(
                sea=label, kind=kind, seeds=list(seeds), seconds=seconds, **env_kw,
                net_W=float(np.mean([r["Pe"] for r in runs])),
                net_min_W=float(min(r["Pe"] for r in runs)),
                predicted_W=float(np.mean([r["predicted"] for r in runs])),
                per_seed_W=[r["Pe"] for r in runs],
                survival=float(np.mean([r["survival"] for r in runs])),
                max_gimbal_deg=math.degrees(max(r["max_gimbal"] for r in runs)),
                stroke_deg=math.degrees(runs[0]["stroke"]),
                ended_early=int(sum(r["terminated"] for r in runs)),
                speed_rpm=[r["speed_rpm"] for r in runs],
            ))  # fmt: skip
    return out


def table(rs: list[dict[str, Any]]) -> str:
    """Markdown: per sea, efficient_pto and passive_damper side by side (kW), or the default
    baseline alone (`speed_table`) when the damper was not run."""
    by = {(r["sea"], r["kind"]): r for r in rs}
    if not any(k == KINDS[1] for _, k in by):
        return speed_table(rs)
    lines = ["| sea | efficient: realised (min) / predicted kW | damper: realised (min) / "
             "predicted kW | survival | max gimbal (deg) | ended early |",
             "|---|---|---|---|---|---|"]  # fmt: skip
    for label in dict.fromkeys(r["sea"] for r in rs):
        e, d = by[(label, KINDS[0])], by[(label, KINDS[1])]
        lines.append(
            f"| {label} | {e['net_W'] / 1e3:.1f} ({e['net_min_W'] / 1e3:.1f}) / "
            f"{e['predicted_W'] / 1e3:.1f} | {d['net_W'] / 1e3:.1f} ({d['net_min_W'] / 1e3:.1f})"
            f" / {d['predicted_W'] / 1e3:.1f} | {e['survival']:.2f} | "
            f"{max(e['max_gimbal_deg'], d['max_gimbal_deg']):.0f} of {e['stroke_deg']:.0f} | "
            f"{e['ended_early'] + d['ended_early']} |"
        )
    return "\n".join(lines)


def speed_table(rs: list[dict[str, Any]]) -> str:
    """Markdown: per sea, the default baseline's realised net power (mean, lowest seed), its
    prediction, the flywheel speeds it chose, survival, the largest gimbal swing, early ends."""
    lines = ["| sea | realised kW (lowest seed) | predicted kW | flywheel rpm (min-max) | "
             "survival | max gimbal (deg) | ended early |",
             "|---|---|---|---|---|---|---|"]  # fmt: skip
    for e in rs:
        if e["kind"] != KINDS[0]:
            continue
        lines.append(
            f"| {e['sea']} | {e['net_W'] / 1e3:.2f} ({e['net_min_W'] / 1e3:.2f}) | "
            f"{e['predicted_W'] / 1e3:.2f} | {min(e['speed_rpm']):.0f}-{max(e['speed_rpm']):.0f} |"
            f" {e['survival']:.2f} | {e['max_gimbal_deg']:.0f} of {e['stroke_deg']:.0f} | "
            f"{e['ended_early']} |"
        )
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--seeds", type=int, default=5, help="seeds per sea (3000..)")
    ap.add_argument("--seconds", type=float, default=300.0, help="scored time per seed (s)")
    ap.add_argument("--first-seed", type=int, default=3000, help="seeds first..first+seeds-1")
    ap.add_argument("--kinds", default=",".join(KINDS), help="controllers, comma-separated")
    ap.add_argument("--json", default=None, help="also write the rows here")
    ap.add_argument("--device", default=DEFAULT_DEVICE, help="FloatingGOWEC-v0's device")
    a = ap.parse_args(argv)
    seeds = tuple(range(a.first_seed, a.first_seed + a.seeds))
    rs = rows(seeds, a.seconds, tuple(a.kinds.split(",")), progress=True, device=a.device)
    if a.json:  # a link or a non-regular file there is refused, not followed
        write_atomic(a.json, json.dumps(rs, indent=1), "json")
    print(table(rs))


if __name__ == "__main__":
    main()
