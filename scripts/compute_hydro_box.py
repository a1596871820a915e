"""Compute ISWEC's box hull coefficients with Capytaine (BEM): surge/heave/pitch, sway/roll and
the excitation at 10 headings, about G, in 35 m of water.

    pip install "mf-envs[hydro]"
    OMP_NUM_THREADS=1 nice -n 5 python scripts/compute_hydro_box.py        # the shipped file
    python scripts/compute_hydro_box.py --mesh 24 12 12 1.1 --out box_medium.npz   # a coarser level

The hull is ISWEC's Pantelleria prototype, 15 x 8 m, 3.2 m draft (`hydro.BoxHull`: mass rho V
= 393.6 t; z_G and the radii of gyration chosen, not published; docs/gowec_v1.md, "ISWEC's box
hull"). The mesh (`meshes.box_mesh`: n_length, n_beam, n_draft panels per quarter, graded by
`ratio` towards the keel edges, the vertical corners and the waterline) is stored as one quarter
with the xOz and yOz mirror planes, so each frequency is four quarter-size solves. Green
functions as the cylinder's (`bem.solve_depth`: Delhommeau, finite depth where k h <= 6).
A progress bar counts the frequencies. Output: the `three_dof` schema with the
optional box fields.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from rich.progress import Progress

from mf_envs.physics.gowec.hydro import BoxHull
from mf_envs.physics.gowec.hydro.bem import box_coefficients, box_solve
from mf_envs.physics.gowec.hydro.three_dof import ISWEC_BOX_FILE, ISWEC_BOX_MESH

# the convergence table's quantities: (label, mode index in `bem.BOX_MODES`, kind)
COMPARED = tuple((f"abs(X{i})" if k == "X" else f"{k}{i}{i}", "12345".index(i), k)
                 for i in "513" for k in ("A", "B", "X"))  # fmt: skip


def compare(paths: list[Path], lo: float = 0.3, hi: float = 3.0) -> str:
    """Markdown table of the convergence between `--raw` files of successive mesh levels:
    panels, CPU time, and per level after the first the largest relative change from the
    previous level of A, B, abs(X) for pitch, surge, heave over lo..hi rad/s (B and abs(X)
    relative to 10 % of their peak where they are below it: a change near a zero of the
    excitation or in the damping's tail is not one that matters)."""
    runs = [dict(np.load(p, allow_pickle=False)) for p in paths]
    head = "| mesh (n_length, n_beam, n_draft, q) | panels + lid | CPU (s) | "
    lines = [head + " | ".join(c[0] for c in COMPARED) + " |",
             "|---|---|---|" + "---|" * len(COMPARED)]  # fmt: skip
    for prev, r in zip([None, *runs], runs):
        band = (r["omega"] >= lo - 1e-9) & (r["omega"] <= hi + 1e-9)
        cells = []
        for _, i, kind in COMPARED:
            if prev is None:
                cells.append("")
                continue
            a, b = (np.abs(x[kind][band, i] if kind == "X" else x[kind][band, i, i])
                    for x in (r, prev))  # fmt: skip
            scale = np.abs(a) if kind == "A" else np.maximum(np.abs(a), 0.1 * np.abs(a).max())
            cells.append(f"{100 * np.max(np.abs(a - b) / scale):.1f} %")
        m = r["mesh"]
        label = f"{int(m[0])}, {int(m[1])}, {int(m[2])}, {m[3]:g}"
        lines.append(f"| {label} | {int(r['panels'])} | {float(r['cpu']):.0f} | "
                     + " | ".join(cells) + " |")  # fmt: skip
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    d = BoxHull()
    p.add_argument("--out", type=Path, default=ISWEC_BOX_FILE)
    p.add_argument("--length", type=float, default=d.length, help="m, along x (head waves)")
    p.add_argument("--beam", type=float, default=d.beam, help="m, along y")
    p.add_argument("--draft", type=float, default=d.draft, help="m")
    p.add_argument("--zg", type=float, default=d.zg, help="centre of gravity z (m, waterline 0)")
    p.add_argument("--gyration", type=float, default=d.gyration, help="pitch gyration (m)")
    p.add_argument("--roll-gyration", type=float, default=d.roll_gyration, help="m")
    p.add_argument("--depth", type=float, default=35.0, help="water depth (m)")
    p.add_argument("--omega", type=float, nargs=3, default=(0.2, 3.4, 33), help="w0 w1 n (rad/s)")
    p.add_argument("--raw", type=Path, help="also write box_solve's arrays here (convergence)")
    p.add_argument("--headings", type=int, default=10, help="wave directions over 0..pi/2")
    p.add_argument("--mesh", type=float, nargs=4, default=ISWEC_BOX_MESH,
                   help="n_length n_beam n_draft ratio (panels per quarter)")  # fmt: skip
    p.add_argument("--from-raw", type=Path, help="write --out from a --raw file, no solve")
    p.add_argument("--compare", type=Path, nargs="+", help="--raw files, coarse to fine: "
                   "print the convergence table and exit")  # fmt: skip
    a = p.parse_args(argv)
    if a.compare:
        print(compare(a.compare))
        return
    hull = BoxHull(a.length, a.beam, a.draft, a.zg, a.gyration, a.roll_gyration)
    if a.from_raw:  # the file from a --raw run's arrays, without solving again
        raw = dict(np.load(a.from_raw, allow_pickle=False))
        box_coefficients(hull, raw["omega"], a.depth, raw).save(a.out)
        print(f"wrote {a.out} from {a.from_raw}")
        return
    omega = np.linspace(a.omega[0], a.omega[1], int(a.omega[2]))
    nl, nb, nd, q = a.mesh
    t0 = time.process_time()
    with Progress() as bar:  # rich: Capytaine's own dependency
        task = bar.add_task("BEM, one frequency at a time", total=omega.size)
        raw = box_solve(hull, omega, a.depth, (int(nl), int(nb), int(nd), q), a.headings,
                        progress=lambda done, _: bar.update(task, completed=done))  # fmt: skip
    cpu = time.process_time() - t0
    if a.raw is not None:  # every array as solved, before the schema's checks
        np.savez(a.raw, **raw, omega=omega, cpu=cpu, mesh=np.array(a.mesh))
    h = box_coefficients(hull, omega, a.depth, raw)
    h.save(a.out)
    print(f"wrote {a.out}: {omega.size} frequencies, {cpu:.0f} s CPU, "
          f"C55 = {h.hydrostatic_stiffness[2, 2]:.4g}")  # fmt: skip


if __name__ == "__main__":
    main()
