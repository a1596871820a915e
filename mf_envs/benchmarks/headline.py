"""The README's env table, measured: each id's default baseline on the first test seeds, scored
by its headline quantity against its ceiling, written to a results file that the README's table
is generated from (`python -m mf_envs.benchmarks.headline --readme README.md`).

    python -m mf_envs.benchmarks.headline --out docs/results/headline.json   # measure (minutes)
    python -m mf_envs.benchmarks.headline --readme README.md                 # regenerate table
    python -m mf_envs.benchmarks.headline --readme README.md --check         # table up to date?

Per id (`ROWS`): the declared default baseline (`controllers.make_baseline(env)`) runs the id's
default episode (its spec's length) from `reset(seed=s)` for s in `SEEDS`, the benchmark's first
test seeds (never used by training). The score per episode:
- `rms_roll_reduction`: 1 - RMS roll / RMS roll of the same seed with the rotor off (ceiling 1);
- `net_power_of_ceiling`: mean net electrical power over the episode's second half / the sea's
  `net_power_ceiling` (loss-inclusive, loose);
- `power_ratio`: mean power over the last 3/4 / Eq. 95 (ceiling 4/pi, tight);
- `speed`: the env's declared speed in m/s (no ceiling derived).
The file records each episode's score, the seeds, the package version and the machine.
"""

from __future__ import annotations

import argparse
import json
import math
import platform
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

SEEDS = tuple(range(20_000, 20_005))
RESULTS = Path("docs/results/headline.json")
REFERENCES = Path("docs/results/references.json")  # `benchmarks.references` (the oracle)
BEGIN, END = "<!-- headline-table: begin (generated) -->", "<!-- headline-table: end -->"


@dataclass(frozen=True)
class Row:
    """One row of the README's table: the id, what it is in words, and how it is scored."""

    env_id: str
    system: str
    observation: str
    action: str
    score: str  # rms_roll_reduction | net_power_of_ceiling | power_ratio | speed


ROWS = (
    Row("GyroStabilizer-v0", "18 t motor yacht with a Seakeeper 7000 gyro, regular beam sea at "
        "roll resonance (§3.3)", "roll, body rates, gimbal angle and rate",
        "gimbal precession-rate command (hydraulic brake)", "rms_roll_reduction"),
    Row("GyroStabilizer-JONSWAP-v0", "the same, JONSWAP beam sea Hs 0.8 m, Tp 5.92 s, 120 s "
        "(headline)", "as above", "as above", "rms_roll_reduction"),
    Row("GOWEC-v0", "one gyroscope of a gyroscopic wave energy converter on a buoy rocked by a "
        "regular wave (§3.2)", "gimbal angle and rate, buoy rates",
        "generator torque on the gimbal", "power_ratio"),
    Row("FloatingGOWEC-v0", "the GOWEC afloat: ISWEC's 15 x 8 m, 394 t box hull (BEM, "
        "Cummins equation) with two gyro units, regular sea",
        "gimbal angle and rate, hull rates, pitch, roll, wave elevation",
        "generator torque (power-limited)", "net_power_of_ceiling"),
    Row("FloatingGOWEC-JONSWAP-v0", "the same, JONSWAP Hs 1.5 m, Tp 6 s, a new sea per seed "
        "(headline)", "as above", "as above", "net_power_of_ceiling"),
    Row("Inchworm-v0", "50 mm PDMS inchworm robot: planar active C¹ beam, SMA wires, gripping "
        "feet (§4.7-4.10)", "curvatures, wire temperatures, feet", "SMA wire duty cycles",
        "speed"),
    Row("Serpentine-v0", "PyElastica's continuum snake (0.35 m) as a planar active beam on "
        "anisotropic friction (§4.5)", "curvatures, heading to target, velocity",
        "curvature at 7 control points", "speed"),
    Row("Eel-v0", "planar anguilliform swimmer (0.2 m eel) with resistive and reactive fluid "
        "forces (§4.5)", "curvatures, heading to target, velocity, tail",
        "curvature at 7 control points", "speed"),
)  # fmt: skip


def measure(row: Row, seeds: tuple[int, ...] = SEEDS) -> dict[str, Any]:
    """The default baseline's per-episode scores of `row` on `seeds`, with its name and the
    ceiling's value per episode (nan without one)."""
    import gymnasium as gym

    from mf_envs.controllers import baseline_kinds, make_baseline
    from mf_envs.envs import declaration
    from mf_envs.train.evaluate import run_episode

    decl = declaration(row.env_id)
    env = gym.make(row.env_id)
    kind = baseline_kinds(row.env_id)[0]
    ctrl = make_baseline(env, kind)
    scores, ceilings = [], []
    for s in seeds:
        m = run_episode(row.env_id, env, ctrl, s)
        if row.score == "rms_roll_reduction":
            scores.append(1.0 - m["rms_roll"] / _rotor_off_rms(row.env_id, s))
            ceilings.append(1.0)
        elif row.score == "net_power_of_ceiling":
            c = float(decl.ceiling.of(env))
            scores.append(m["net_power"] / c)
            ceilings.append(c)
        elif row.score == "power_ratio":
            scores.append(m["power_ratio"])
            ceilings.append(float(decl.ceiling.value))
        else:
            scores.append(m["speed"] if "speed" in m else inchworm_speed(env, m))
            ceilings.append(math.nan)
    env.close()
    return {"env_id": row.env_id, "baseline": kind, "score": row.score, "seeds": list(seeds),
            "scores": scores, "ceilings": ceilings}  # fmt: skip


def _rotor_off_rms(env_id: str, seed: int) -> float:
    """RMS roll of the same seed's sea with the rotor off (the stabilizer's reference)."""
    import gymnasium as gym

    from mf_envs.benchmarks.rl_benchmark import ZeroAction, rotor_off
    from mf_envs.envs import declaration
    from mf_envs.envs.gyro_stabilizer import DEFAULT_EFFECTS
    from mf_envs.train.evaluate import run_episode

    effects = declaration(env_id).kwargs.get("effects", DEFAULT_EFFECTS)
    env = gym.make(env_id, **rotor_off({"effects": effects}))
    rms = run_episode(env_id, env, ZeroAction(env.action_space, seed), seed)["rms_roll"]
    env.close()
    return float(rms)


def inchworm_speed(env: Any, m: dict[str, float]) -> float:
    """The inchworm's speed (m/s): its declared tail advance per control step / the step."""
    return m["tail_advance_per_step"] / float(env.unwrapped.control_dt)


def run(out: Path = RESULTS, seeds: tuple[int, ...] = SEEDS) -> dict[str, Any]:
    """Measure every row and write the results file (atomically)."""
    from tqdm import tqdm

    from mf_envs import __version__

    rows = []
    for row in tqdm(ROWS, desc="headline", unit="id"):
        rows.append(measure(row, seeds))
    result = {
        "command": f"python -m mf_envs.benchmarks.headline --out {out}",
        "version": __version__,
        "machine": f"{platform.machine()}, {platform.system()}, Python {platform.python_version()}",
        "date": time.strftime("%Y-%m-%d", time.gmtime()),
        "rows": rows,
    }
    out.parent.mkdir(parents=True, exist_ok=True)
    tmp = out.with_name(out.name + ".tmp")
    tmp.write_text(json.dumps(result, indent=1) + "\n")
    tmp.replace(out)
    return result


def oracle_scores(refs: dict[str, Any] | None, env_id: str, seeds: list[int]) -> Any:
    """The oracle reference's scores of `env_id` on `seeds` from a references file's content
    (`benchmarks.references`), None if it has none on every one of them."""
    rows = [r for r in (refs or {}).get("rows", []) if r["env_id"] == env_id
            and (r["kind"], r["name"]) == ("reference", "oracle")]  # fmt: skip
    if not rows:
        return None
    by_seed = dict(zip(rows[0]["test_seeds"], rows[0]["scores"]))
    return np.array([by_seed[s] for s in seeds]) if set(seeds) <= set(by_seed) else None


def _cell(r: dict[str, Any], oracle: Any = None) -> str:
    """The score column: mean over the seeds (min-max), against the ceiling; with the oracle's
    scores on the same seeds, the headroom (oracle - this baseline) in place of the ceiling's
    percentage."""
    x = np.asarray(r["scores"], float)
    spread = f"{x.min():.3f}-{x.max():.3f}" if len(x) > 1 else ""
    if r["score"] == "rms_roll_reduction":
        if oracle is not None:
            return (f"RMS roll reduction {x.mean():.3f} ({spread}); oracle {oracle.mean():.3f}: "
                    f"headroom {oracle.mean() - x.mean():.3f} (ceiling 1)")  # fmt: skip
        return f"RMS roll reduction {x.mean():.3f} ({spread}) of 1 (loose)"
    if r["score"] == "net_power_of_ceiling":
        kw = np.asarray(r["ceilings"]) * x / 1e3
        if oracle is not None:
            ko = np.asarray(r["ceilings"]) * oracle / 1e3
            return (f"net power {kw.mean():.1f} kW ({kw.min():.1f} to {kw.max():.1f}); oracle "
                    f"{ko.mean():.1f} kW: headroom {ko.mean() - kw.mean():.1f} kW")  # fmt: skip
        return (f"net power {kw.mean():.1f} kW ({kw.min():.1f} to {kw.max():.1f}): "
                f"{100 * x.mean():.1f} % of a loose ceiling")  # fmt: skip
    if r["score"] == "power_ratio":
        c = r["ceilings"][0]
        return f"{x.mean():.4f} x Eq. 95, {100 * x.mean() / c:.1f} % of 4/π (tight)"
    mm = 1e3 * x
    return f"{mm.mean():.3g} mm/s ({mm.min():.3g}-{mm.max():.3g}); no ceiling derived"


def table(result: dict[str, Any], refs: dict[str, Any] | None = None) -> str:
    """The README's env table (markdown) from a results file's content, with the oracle's
    headroom where the references file's content `refs` has it."""
    by_id = {r["env_id"]: r for r in result["rows"]}
    n = len(result["rows"][0]["seeds"])
    lines = [
        BEGIN,
        "| id | system | observation | action | default baseline | its score, mean over "
        f"{n} test seeds (range) |",
        "|---|---|---|---|---|---|",
    ]
    for row in ROWS:
        r = by_id[row.env_id]
        cell = _cell(r, oracle_scores(refs, row.env_id, r["seeds"]))
        lines.append(f"| `{row.env_id}` | {row.system} | {row.observation} | {row.action} | "
                     f"`{r['baseline']}` | {cell} |")  # fmt: skip
    lines.append(f"\nGenerated from [{RESULTS}]({RESULTS}) (`{result['command']}`, "
                 f"mf_envs {result['version']}, {result['date']})"
                 + (f" and [{REFERENCES}]({REFERENCES}) (the oracle: a planner that knows "
                    "the episode's sea; headroom = oracle - the default baseline)"
                    if refs else "") + ".")  # fmt: skip
    lines.append(END)
    return "\n".join(lines)


def splice(readme: str, block: str) -> str:
    """`readme` with the text between the markers replaced by `block` (ValueError without them)."""
    if BEGIN not in readme or END not in readme:
        raise ValueError(f"readme: no {BEGIN} ... {END} block")
    head, rest = readme.split(BEGIN, 1)
    return head + block + rest.split(END, 1)[1]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--out", type=Path, help="measure every row and write this results file")
    p.add_argument("--results", type=Path, default=RESULTS, help="results file for --readme")
    p.add_argument("--readme", type=Path, help="regenerate this README's table from the results")
    p.add_argument("--references", type=Path, default=REFERENCES,
                   help="the references file (the oracle's headroom) for --readme")  # fmt: skip
    p.add_argument("--check", action="store_true", help="with --readme: only check it is current")
    a = p.parse_args(argv)
    if a.out is not None:
        run(a.out)
    if a.readme is not None:
        text = a.readme.read_text()
        refs = json.loads(a.references.read_text()) if a.references.is_file() else None
        new = splice(text, table(json.loads(a.results.read_text()), refs))
        if a.check:
            if new != text:
                print(f"{a.readme}: its table differs from {a.results}; regenerate with --readme")
                return 1
            return 0
        a.readme.write_text(new)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
