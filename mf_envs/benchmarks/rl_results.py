"""The RL benchmark's results: one record file per run, the results file, and what is generated
from it (docs/benchmark.md's tables and figures).

Record (`<out>/records/<env_id>/<name>[-<budget>][-seed<S>].json`, written atomically, one per
trained run or scored controller; the schema of a row of the results file):

| field | meaning |
|---|---|
| env_id | the registered id |
| kind | "learner" (a trained run), "baseline" (a classical controller), "zero", "random", \
"reference" (from elsewhere: "oracle", "mpc", "tuned baseline") |
| name | algorithm (`ppo`, `sbx_sac`), baseline kind (`lqr`), or the reference's name |
| seed | training seed (learners; null otherwise) |
| budget | nominal env-steps of the run (learners; null otherwise); `env_steps`: those trained |
| score_name | the task's score (`rms_roll_reduction`, `net_power_of_ceiling`, `speed_m_s`) |
| test_seeds, scores, returns | per test condition: its seed, the score and the episode return |
| wall_s, steps_per_s | training wall-clock seconds and env-steps/s (learners) |
| machine, version, date, command | where, which mf_envs, when, and the command that made it |

A reference enters by writing a record of kind "reference" with its scores on the same test
seeds into `records/<env_id>/`; `collect` puts it on the normalised scale with the rest.

The results file (`results.json`): {"schema", "budget_scale", "ids": {env_id: {score_name,
zero, best_baseline, best, oracle (the reference "oracle"'s mean: what perfect information
achieves; nan without), headroom (oracle - best)}}, "rows": [records + "score" (mean over
test conditions) and
"normalised" ((score - zero) / (best - zero): 0 = the zero action, 1 = the best classical
baseline, per id from the means over the test conditions)]}.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import inside, make_dirs, read_regular, write_atomic

SCHEMA = "mf-envs-rl-benchmark/1"
KINDS = ("baseline", "reference", "zero", "random", "learner")
ORACLE = ("reference", "oracle")  # the practical ceiling: `benchmarks.references`' oracle
MAX_RECORD_BYTES = 1 << 20
BEGIN, END = "<!-- rl-benchmark: begin (generated) -->", "<!-- rl-benchmark: end -->"


def record_path(out: Path, env_id: str, name: str, budget: int | None, seed: int | None) -> Path:
    """Where a record lives inside `out` (`out/records/<env_id>/...`)."""
    stem = (
        name
        + (f"-{budget}" if budget is not None else "")
        + (f"-seed{seed}" if seed is not None else "")
    )
    return Path(out) / "records" / env_id / f"{stem}.json"


def write_record(out: Path, rec: dict[str, Any]) -> Path:
    """Write `rec` atomically to its `record_path`, creating its folders below `out` (a link
    that leads out of `out` is refused, ValueError naming out)."""
    p = record_path(out, rec["env_id"], rec["name"], rec.get("budget"), rec.get("seed"))
    make_dirs(out, p.parent)
    inside(out, p.parent, "out")
    return write_atomic(p, json.dumps(rec, indent=1, default=float) + "\n")


def read_record(out: Path, p: Path) -> dict[str, Any] | None:
    """The record in `p` (inside `out`; a link leading out is refused), None if absent."""
    if not os.path.lexists(p):
        return None
    inside(out, p, "out")
    rec = json.loads(read_regular(p, MAX_RECORD_BYTES, "out"))
    if not isinstance(rec, dict) or rec.get("kind") not in KINDS:
        raise ValueError(f"out: {p} is not a benchmark record")
    return rec


def collect(out: Path, budget_scale: float = 1.0) -> dict[str, Any]:
    """Every record under `out/records/` as the results file's content (module docstring)."""
    root = Path(out) / "records"
    rows = []
    for p in sorted(root.glob("*/*.json")) if root.is_dir() else []:
        rec = read_record(out, p)
        if rec is not None:
            rows.append(rec)
    conditions = {tuple(r["test_seeds"]) for r in rows}
    if len(conditions) > 1:
        raise ValueError(f"out: {out}'s records were scored on different test seeds "
                         f"({sorted(len(c) for c in conditions)} of them); rerun with one "
                         "--test-seeds in its own folder")  # fmt: skip
    ids: dict[str, dict[str, Any]] = {}
    for env_id in sorted({r["env_id"] for r in rows}):
        mine = [r for r in rows if r["env_id"] == env_id]
        zero = [np.mean(r["scores"]) for r in mine if r["kind"] == "zero"]
        base = {r["name"]: float(np.mean(r["scores"])) for r in mine if r["kind"] == "baseline"}
        best = max(base, key=base.get) if base else None
        oracle = [np.mean(r["scores"]) for r in mine if (r["kind"], r["name"]) == ORACLE]
        ids[env_id] = {"score_name": mine[0]["score_name"],
                       "zero": float(zero[0]) if zero else math.nan,
                       "best_baseline": best, "best": base.get(best, math.nan),
                       "oracle": float(oracle[0]) if oracle else math.nan}  # fmt: skip
        ids[env_id]["headroom"] = ids[env_id]["oracle"] - ids[env_id]["best"]
    for r in rows:
        a = ids[r["env_id"]]
        r["score"] = float(np.mean(r["scores"]))
        r["normalised"] = normalise(r["score"], a["zero"], a["best"])
    return {"schema": SCHEMA, "budget_scale": budget_scale, "ids": ids, "rows": rows}


def normalise(score: float, zero: float, best: float) -> float:
    """(score - zero) / (best - zero): 0 = the zero action, 1 = the best classical baseline."""
    span = best - zero
    return float((score - zero) / span) if span and math.isfinite(span) else math.nan


def interval(scores: np.ndarray, reps: int = 2000, seed: int = 0) -> dict[str, float]:
    """IQM and stratified-bootstrap 95 % percentile interval of `scores` (runs,) or (runs, tasks),
    as in Agarwal et al. (NeurIPS 2021): each bootstrap sample redraws the runs of every task
    (column) with replacement, and its IQM is the 25 % trimmed mean of all the drawn scores. The
    mean and its sample std beside them. Written with numpy and scipy (rliable's
    `get_interval_estimates` with `aggregate_iqm` computes the same statistic)."""
    from scipy.stats import trim_mean

    m = np.atleast_2d(np.asarray(scores, dtype=float))
    if m.shape[0] == 1:
        m = m.T
    runs, tasks = m.shape
    rng = np.random.default_rng(seed)
    rows = rng.integers(0, runs, size=(reps, runs, tasks))  # per task, its own draw of runs
    drawn = m[rows, np.arange(tasks)]
    boot = trim_mean(drawn.reshape(reps, -1), 0.25, axis=1)
    lo, hi = np.percentile(boot, [2.5, 97.5])
    flat = m.ravel()
    return {"iqm": float(trim_mean(flat, 0.25)), "lo": float(lo), "hi": float(hi),
            "mean": float(flat.mean()), "std": float(flat.std(ddof=1)) if flat.size > 1 else 0.0,
            "n": int(runs)}  # fmt: skip


def groups(result: dict[str, Any], env_id: str) -> dict[tuple[str, str, Any], list[dict]]:
    """The rows of `env_id` grouped by (kind, name, budget), in `KINDS` order."""
    out: dict[tuple[str, str, Any], list[dict]] = {}
    order = sorted(result["rows"], key=lambda r: (KINDS.index(r["kind"]), r["name"],
                                                  r.get("budget") or 0))  # fmt: skip
    for r in order:
        if r["env_id"] == env_id:
            out.setdefault((r["kind"], r["name"], r.get("budget")), []).append(r)
    return out


def id_table(result: dict[str, Any], env_id: str) -> str:
    """Markdown table of one id: per controller (learners per budget) the IQM over runs of
    the mean score over the test conditions, with its 95 % interval, and the normalised IQM."""
    a = result["ids"][env_id]
    lines = [f"| controller | kind | budget (env-steps) | runs | {a['score_name']}: IQM [95 % CI] "
             "| normalised IQM [95 % CI] | wall per run (s) |",
             "|---|---|---|---|---|---|---|"]  # fmt: skip
    for (kind, name, budget), rows in groups(result, env_id).items():
        if kind == "learner":
            s = interval(np.array([r["score"] for r in rows]))
            z = interval(np.array([r["normalised"] for r in rows]))
            wall = f"{np.median([r['wall_s'] for r in rows]):.0f}"
        else:  # one controller: the interval is the bootstrap over its test conditions
            (r,) = rows
            s = interval(np.asarray(r["scores"]))
            z = {k: normalise(v, a["zero"], a["best"]) if k in ("iqm", "lo", "hi") else v
                 for k, v in s.items()}  # fmt: skip
            wall = "-"
        lines.append(f"| {name} | {kind} | {_steps(budget)} | {s['n']} | {_ci(s)} | {_ci(z)} | "
                     f"{wall} |")  # fmt: skip
    return "\n".join(lines)


def aggregate_table(result: dict[str, Any]) -> str:
    """Markdown table across ids: per (algorithm, budget) the IQM of the normalised scores of
    every run on every id that has it, stratified by id (runs matched by training seed)."""
    lines = ["| learner | budget (env-steps) | ids | runs per id | normalised IQM [95 % CI] |",
             "|---|---|---|---|---|"]  # fmt: skip
    for (name, budget), by_id in _learner_matrix(result).items():
        n = min(len(v) for v in by_id.values())
        m = np.column_stack([v[:n] for v in by_id.values()])
        lines.append(f"| {name} | {_steps(budget)} | {len(by_id)} | {n} | "
                     f"{_ci(interval(m))} |")  # fmt: skip
    return "\n".join(lines)


def _learner_matrix(result: dict[str, Any]) -> dict[tuple[str, int], dict[str, list[float]]]:
    out: dict[tuple[str, int], dict[str, list[float]]] = {}
    for r in sorted(result["rows"], key=lambda r: (r["env_id"], r.get("seed") or 0)):
        if r["kind"] == "learner" and math.isfinite(r["normalised"]):
            out.setdefault((r["name"], r["budget"]), {}).setdefault(r["env_id"], []).append(
                r["normalised"]
            )
    return out


def _ci(d: dict[str, float]) -> str:
    return f"{d['iqm']:.3g} [{d['lo']:.3g}, {d['hi']:.3g}]"


def _steps(budget: Any) -> str:
    return "-" if budget is None else f"{budget:.0e}".replace("e+0", "e")


def figures(result: dict[str, Any], folder: Path, stem: str = "rl_benchmark") -> list[Path]:
    """Two PNGs: per id, each learner's normalised score (IQM over runs, 95 % interval) against
    env-steps trained and against its median wall-clock seconds; 0 and 1 drawn as the zero
    action and the best baseline."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullFormatter

    from mf_envs._files import save_figure

    ids = list(result["ids"])
    written = []
    for axis, label in (("env_steps", "env-steps trained"), ("wall_s", "wall-clock seconds")):
        fig, axes = plt.subplots(1, len(ids), figsize=(3.2 * len(ids), 3.0), squeeze=False)
        for ax, env_id in zip(axes[0], ids):
            by_name: dict[str, list[tuple[float, dict[str, float]]]] = {}
            for (kind, name, _), rows in groups(result, env_id).items():
                if kind == "learner":
                    x = float(np.median([r[axis] for r in rows]))
                    by_name.setdefault(name, []).append(
                        (x, interval(np.array([r["normalised"] for r in rows])))
                    )
            for name, pts in by_name.items():
                pts.sort(key=lambda p: p[0])
                y = np.array([[p[1]["iqm"], p[1]["lo"], p[1]["hi"]] for p in pts])
                err = [y[:, 0] - y[:, 1], y[:, 2] - y[:, 0]]
                ax.errorbar([p[0] for p in pts], y[:, 0], err, fmt="o-", capsize=3,
                            color=colour(name), label=name)  # fmt: skip
            ax.axhline(1.0, ls="--", color="k", lw=0.8, label="best baseline")
            ax.axhline(0.0, ls=":", color="k", lw=0.8, label="zero action")
            ax.set_xscale("log")
            ax.xaxis.set_minor_formatter(NullFormatter())
            ax.set_title(env_id, fontsize=8)
            ax.set_xlabel(label, fontsize=8)
        axes[0][0].set_ylabel("normalised score (IQM, 95 % CI)")
        handles = {h.get_label(): h for ax in axes[0] for h in ax.get_legend_handles_labels()[0]}
        fig.legend(handles.values(), handles.keys(), fontsize=7, loc="upper right")
        fig.tight_layout()
        path = folder / f"{stem}_{'steps' if axis == 'env_steps' else 'wallclock'}.png"
        make_dirs(folder, folder)
        written.append(save_figure(fig, path, dpi=100))
    return written


def colour(name: str) -> str:
    """A learner's colour in every figure (PPO blue, SBX's SAC orange, others after them)."""
    order = ("ppo", "sbx_sac", "sac", "td3")
    return f"C{order.index(name) if name in order else len(order)}"


def markdown(result: dict[str, Any], source: str, images: list[str]) -> str:
    """docs/benchmark.md's generated block: the aggregate table, one table per id, figures."""
    budgets = {r["budget"] for r in result["rows"] if r["kind"] == "learner"}
    reduced = budgets - {1_000_000, 10_000_000}  # the grid's (rl_tasks)
    note = (f" **Reduced budgets** ({', '.join(_steps(b) for b in sorted(reduced))} env-steps), "
            "not the full grid." if reduced else "")  # fmt: skip
    parts = [BEGIN, f"Generated from [{source}]({source}) (schema {SCHEMA}; "
             f"`{result.get('command', '')}`).{note}", "",
             "Across ids (normalised: 0 = zero action, 1 = best classical baseline):", "",
             aggregate_table(result)]  # fmt: skip
    for env_id, a in result["ids"].items():
        oracle = a.get("oracle", math.nan)
        ref = (f"; oracle {oracle:.4g} beside the analytic ceiling {_ceiling(env_id):.4g}: "
               f"headroom = oracle - best baseline = {oracle - a['best']:.3g} (normalised "
               f"{normalise(oracle, a['zero'], a['best']) - 1.0:.3g})"
               if math.isfinite(oracle) else "")  # fmt: skip
        parts += [
            "",
            f"**{env_id}** ({a['score_name']}; best baseline `{a['best_baseline']}` "
            f"{a['best']:.4g}, zero action {a['zero']:.4g}{ref}):",
            "",
            id_table(result, env_id),
        ]
    parts += [""] + [f"![{Path(i).stem}]({i})" for i in images] + [END]
    return "\n".join(parts)


def _ceiling(env_id: str) -> float:
    """The analytic ceiling of `env_id`'s task on its score's scale (nan: none derived)."""
    from mf_envs.benchmarks.rl_tasks import TASKS

    for make in TASKS.values():
        task = make()
        if task.env_id == env_id:
            return float(task.ceiling)
    return math.nan


def splice(text: str, block: str, begin: str = BEGIN, end: str = END) -> str:
    """`text` with the generated block between `begin` and `end` (the first and last lines of
    `block`) replaced; appended if `text` has none."""
    if begin not in text or end not in text:
        return text.rstrip("\n") + "\n\n" + block + "\n"
    head, rest = text.split(begin, 1)
    return head + block + rest.split(end, 1)[1]
