"""FloatingGOWEC-v0's annual energy at a site: the power matrix (`power_matrix`, net electrical
power of the default baseline over Hs x the energy period Te, IEC TS 62600-100's binning)
weighted by the site's scatter diagram (occurrence of each (Hs, Te) bin over a year).

    python -m mf_envs.benchmarks.gowec_annual --scatter site.csv --out docs/results \
        [--matrix docs/img/gowec_power_matrix.json]

`--scatter`: a CSV file with the header `hs,te,occurrence` (m, s, hours per year or any
non-negative weights, normalised to the year), one row per bin at its centre; a file that
is not this raises ValueError naming it. Without `--matrix` the power matrix is run first
(`power_matrix.matrix`, with its progress bar; ~30 min on 2 cores). Writes
`gowec_annual.json` (mean power W, MWh per year, the share of the year in each regime, every
bin's contribution) and `gowec_annual.png` (occurrence and energy per bin) in `--out`.

Each scatter bin takes the power of the matrix cell whose bin holds it (cells' edges midway
between the matrix's Hs and Te values, the outer cells reaching half a step beyond); a Te
outside the matrix's takes its nearest column. Seas below the matrix's lowest Hs bin are
counted at `--below` W (default 0: the flywheels stopped in a calm sea, as ISWEC idles), and
seas above the device's operating range (Hs above the matrix) at minus the running loss of
the flywheels at the slowest scheduled speed (`--above`, default: the device's, in survival
the generator is unloaded; docs/gowec_v1.md).
"""

from __future__ import annotations

import argparse
import csv
import io
import json
from pathlib import Path
from typing import Any

import numpy as np

from mf_envs._files import make_dirs, read_regular, save_figure, write_atomic

HOURS_PER_YEAR = 8766.0  # h, 365.25 days
MAX_FILE_BYTES = 16 * 2**20  # a scatter CSV or a power matrix json read here


def read_scatter(path: Path) -> np.ndarray:
    """(n, 3) array of (hs m, te s, occurrence) rows of a scatter CSV (module doc)."""
    text = read_regular(path, MAX_FILE_BYTES, "scatter").decode("utf-8", "replace")
    try:
        rows = list(csv.DictReader(io.StringIO(text, newline="")))
        data = np.array([[float(r["hs"]), float(r["te"]), float(r["occurrence"])]
                         for r in rows], dtype=float)  # fmt: skip
    except (csv.Error, KeyError, ValueError, TypeError) as exc:
        raise ValueError(f"scatter: {path} is not a CSV of hs,te,occurrence ({exc})") from exc
    if data.shape[0] == 0 or not np.all(np.isfinite(data)) or np.any(data < 0.0) or \
            data[:, 2].sum() <= 0.0:  # fmt: skip
        raise ValueError(f"scatter: {path} needs finite, non-negative rows and occurrence > 0")
    return data


def _edges(values: list[float]) -> np.ndarray:
    """Bin edges midway between sorted values, the outer ones half a step beyond."""
    v = np.asarray(values, dtype=float)
    step = np.diff(v) if v.size > 1 else np.array([1.0])
    mid = 0.5 * (v[1:] + v[:-1])
    return np.concatenate([[v[0] - 0.5 * step[0]], mid, [v[-1] + 0.5 * step[-1]]])


def annual(rows: list[dict[str, Any]], scatter: np.ndarray, below: float = 0.0,
           above: float = 0.0) -> dict[str, Any]:  # fmt: skip
    """Mean net power (W) and energy (MWh per year) of the power matrix `rows` (each with hs,
    te, net_W) over `scatter` ((n, 3): hs, te, occurrence), the regimes' shares of the year and
    each bin's power and energy (module doc: which cell a bin takes; `below`, `above` W)."""
    hs = sorted({float(r["hs"]) for r in rows})
    te = sorted({float(r["te"]) for r in rows})
    at = {(float(r["hs"]), float(r["te"])): float(r["net_W"]) for r in rows}
    eh, et = _edges(hs), _edges(te)
    w = scatter[:, 2] / scatter[:, 2].sum()
    bins, regime = [], {"below": 0.0, "matrix": 0.0, "above": 0.0}
    for (h, t, _), wi in zip(scatter, w):
        if h < eh[0]:
            p, kind = below, "below"
        elif h >= eh[-1]:
            p, kind = above, "above"
        else:
            i = int(np.searchsorted(eh, h, side="right")) - 1
            j = int(np.clip(np.searchsorted(et, t, side="right") - 1, 0, len(te) - 1))
            p, kind = at[(hs[i], te[j])], "matrix"
        regime[kind] += float(wi)
        bins.append(dict(hs=float(h), te=float(t), share=float(wi), net_W=p, regime=kind,
                         MWh=p * wi * HOURS_PER_YEAR / 1e6))  # fmt: skip
    mean = float(sum(b["net_W"] * b["share"] for b in bins))
    return dict(mean_W=mean, MWh_per_year=mean * HOURS_PER_YEAR / 1e6, shares=regime,
                bins=bins)  # fmt: skip


def plot(result: dict[str, Any], path: Path) -> Path:
    """Occurrence (share of the year) and energy (MWh/yr) of each scatter bin."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    b = result["bins"]
    x, y = [r["te"] for r in b], [r["hs"] for r in b]
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key, label, cmap in ((axes[0], "share", "share of the year", "Blues"),
                                 (axes[1], "MWh", "net energy (MWh/yr)", "RdYlGn")):  # fmt: skip
        v = np.array([r[key] for r in b])
        lim = float(np.max(np.abs(v))) or 1.0
        sc = ax.scatter(x, y, c=v, s=120, marker="s", cmap=cmap,
                        vmin=-lim if key == "MWh" else 0.0, vmax=lim)  # fmt: skip
        fig.colorbar(sc, ax=ax, label=label)
        ax.set_xlabel("energy period Te (s)")
        ax.set_ylabel("significant wave height Hs (m)")
    fig.suptitle(f"FloatingGOWEC-v0 at the site: mean net {result['mean_W'] / 1e3:.2f} kW, "
                 f"{result['MWh_per_year']:.1f} MWh/yr", fontsize=10)  # fmt: skip
    fig.tight_layout()
    return save_figure(fig, path, dpi=110)


def main(argv: list[str] | None = None) -> None:
    from mf_envs.benchmarks import power_matrix
    from mf_envs.physics.gowec.hydro.devices import DEFAULT_DEVICE, DEVICES

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--device", default=DEFAULT_DEVICE, choices=sorted(DEVICES),
                    help="FloatingGOWEC-v0's device (the matrix run here)")  # fmt: skip
    dev = DEVICES[ap.parse_known_args(argv)[0].device]
    idle = -dev.running_loss(dev.rotor_speed_range[0], dev.gyro_units)
    ap.add_argument("--scatter", type=Path, required=True, help="CSV hs,te,occurrence")
    ap.add_argument("--matrix", type=Path, default=None, help="power matrix json (else run it)")
    ap.add_argument("--out", type=Path, default=Path("."), help="folder for the json and png")
    ap.add_argument("--below", type=float, default=0.0, help="W below the matrix's Hs")
    ap.add_argument("--above", type=float, default=idle, help="W above the matrix's Hs")
    a = ap.parse_args(argv)
    scatter = read_scatter(a.scatter)
    if a.matrix is None:
        rows = power_matrix.matrix(device=dev.name)
    else:
        rows = json.loads(read_regular(a.matrix, MAX_FILE_BYTES, "matrix"))
    result = annual(rows, scatter, a.below, a.above)
    result.update(scatter_file=str(a.scatter), below_W=a.below, above_W=a.above)
    make_dirs(a.out, a.out)
    write_atomic(a.out / "gowec_annual.json", json.dumps(result, indent=1))
    plot(result, a.out / "gowec_annual.png")
    print(f"mean net power {result['mean_W'] / 1e3:.2f} kW, {result['MWh_per_year']:.1f} MWh/yr;"
          f" shares {result['shares']}")  # fmt: skip


if __name__ == "__main__":
    main()
