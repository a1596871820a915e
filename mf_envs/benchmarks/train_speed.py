"""Training speed: env-steps/s of `mf-envs train` per headline id and algorithm, the shipped
config (native vector rows) beside the two-env config, measured in the same run.

    python -m mf_envs.benchmarks.train_speed --out bench_train_speed --docs docs/performance.md
    python -m mf_envs.benchmarks.train_speed --ids GyroStabilizer-JONSWAP-v0 --out b  # one id

Per cell `train.trainer.train` runs the shipped rl-zoo3 entry of the algorithm (`configs/`)
with no evaluation checks (`evaluations=0`: the learner's own speed; the checks of a default
`mf-envs train` add one episode of batched steps each) for `STEPS[algo]` env-steps, then the
two-env config (`TWO_ENV`: the settings every shipped config had before the native rows, on the
same id) for a tenth of them. The off-policy rows: SBX's SAC on its shipped rows, SB3's SAC on
the same config (the choice of SBX), and SB3's SAC on one env, one gradient step per env-step
(its shipped settings before). Both off-policy
configs start learning after one batch (`learning_starts` = batch size), so the rate is that of
training, not of filling the buffer. The speed is `meta.json`'s `steps_per_s` (env-steps / wall
seconds of `model.learn`, JAX's compilation included). Writes `<out>/train_speed.json` and,
with `--docs`, the generated table of that page.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from mf_envs._files import make_dirs, write_atomic

IDS = ("GyroStabilizer-JONSWAP-v0", "FloatingGOWEC-JONSWAP-v0", "Inchworm-v0", "Serpentine-v0",
       "Eel-v0")  # fmt: skip
MARINE = IDS[:2]
STEPS = {"ppo": 300_000, "sbx_sac": 100_000}
# the reference: the two-env settings (PPO: GyroStabilizer-v0's recipe; SAC: SB3's, one env)
TWO_ENV = {
    "ppo": ("ppo", {"n_envs": 2, "n_steps": 512, "batch_size": 128, "n_epochs": 10}),
    "sbx_sac": ("sac", {"n_envs": 1, "train_freq": 1, "gradient_steps": 1}),
}
BEGIN, END = "<!-- train-speed: begin (generated) -->", "<!-- train-speed: end -->"


def _config(env_id: str, algo: str, changes: dict[str, Any], steps: int, folder: Path) -> Path:
    import yaml

    from mf_envs.train.config import config_entry, default_config

    entry = {**config_entry(env_id, default_config(algo)), **changes, "n_timesteps": steps}
    if "buffer_size" in entry:  # off-policy: learn from the first batch on
        entry["learning_starts"] = int(entry.get("batch_size", 256))
    text = yaml.safe_dump({env_id: entry}, sort_keys=False)
    return write_atomic(make_dirs(folder, folder) / f"{env_id}-{algo}-{len(changes)}.yml", text)


# the configs of a cell: (label, algorithm run, changes to the shipped entry, share of STEPS)
CONFIGS = {
    "ppo": (("shipped", "ppo", {}, 1.0), ("two-env", *TWO_ENV["ppo"], 0.1)),
    "sbx_sac": (("shipped", "sbx_sac", {}, 1.0), ("shipped, SB3's SAC", "sac", {}, 0.1),
                ("two-env", *TWO_ENV["sbx_sac"], 0.02)),
}  # fmt: skip


def measure(env_id: str, algo: str, which: int, out: Path) -> dict[str, Any]:
    """One cell: train config `CONFIGS[algo][which]` and read its speed from meta.json."""
    from mf_envs.train.trainer import train

    label, name, changes, share = CONFIGS[algo][which]
    steps = int(STEPS[algo] * share)
    cfg = _config(env_id, name, changes, steps, out / "configs")
    res = train(env_id, config=cfg, out=out / "runs", algo=name, evaluations=0,
                final_eval_seeds=(), force=True, progress_bar=False)  # fmt: skip
    m = res.meta
    return {"env_id": env_id, "learner": algo, "algo": name, "config": label,
            "vectorization": m["vectorization"], "timesteps": m["timesteps"],
            "wall_s": m["wall_time_s"], "steps_per_s": m["steps_per_s"]}  # fmt: skip


def run(ids: Sequence[str], out: Path) -> dict[str, Any]:
    from tqdm import tqdm

    from mf_envs import __version__

    out = make_dirs(out, out)
    cells = [(i, a, k) for i in ids for a in STEPS if a == "ppo" or i in MARINE
             for k in range(len(CONFIGS[a]))]  # fmt: skip
    rows = [measure(i, a, t, out) for i, a, t in tqdm(cells, desc="train speed", unit="run")]
    load = " / ".join(f"{x:.1f}" for x in os.getloadavg())  # 1, 5, 15 min, at the end
    date = time.strftime("%Y-%m-%dT%H:%MZ", time.gmtime())
    result = {"version": __version__, "load": load, "date": date,
              "machine": f"{platform.machine()}, {platform.system()}, Python "
                         f"{platform.python_version()}", "rows": rows}  # fmt: skip
    write_atomic(out / "train_speed.json", json.dumps(result, indent=1) + "\n")
    return result


def table(result: dict[str, Any]) -> str:
    """Markdown: per id and learner each config's speed, and its ratio to the two-env one."""
    lines = [BEGIN, "| id | learner | config | algorithm | vectorisation | env-steps "
             "| env-steps/s | x two-env |", "|---|---|---|---|---|---|---|---|"]  # fmt: skip
    rows = result["rows"]
    for r in rows:
        learner = r["learner"]
        two = next(x for x in rows if x["env_id"] == r["env_id"] and x["config"] == "two-env"
                   and x["algo"] == TWO_ENV[learner][0])  # fmt: skip
        lines.append(f"| `{r['env_id']}` | {learner} | {r['config']} | {r['algo']} | "
                     f"{r['vectorization']} | {r['timesteps']:,} | {r['steps_per_s']:,.0f} | "
                     f"{r['steps_per_s'] / two['steps_per_s']:.1f} |")  # fmt: skip
    lines += ["", f"Measured {result['date']} ({result['machine']}, mf_envs {result['version']}, "
              "`python -m mf_envs.benchmarks.train_speed`; one process on a shared 2-core "
              f"machine, load average {result['load']}).", END]  # fmt: skip
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--ids", nargs="+", choices=IDS, default=list(IDS))
    p.add_argument("--out", type=Path, default=Path("bench_train_speed"))
    p.add_argument("--docs", type=Path, help="regenerate this page's table (performance.md)")
    a = p.parse_args(argv)
    result = run(a.ids, a.out)
    md = table(result)
    print(md)
    if a.docs is not None:
        from mf_envs.benchmarks.rl_results import splice

        write_atomic(a.docs, splice(a.docs.read_text(), md, BEGIN, END))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
