"""Mesh convergence of the GOWEC default cylinder's pitch coefficients about G (issue 29).

    pip install "mf-envs[hydro]"
    nice -n 10 python scripts/hydro_convergence.py            # ~10 min on 2 shared cores
    nice -n 10 python scripts/hydro_convergence.py --quick    # without the finest mesh (~5 min)

Prints Markdown tables (rows: meshes; columns: frequencies) of A55, B55 and |X5| about G and of
the Haskind ratio B_Haskind / B55, where B_Haskind = k |X5|^2 / (8 rho g c_g) is the damping the
far field carries away (`checks.haskind_damping`). Pitch about G of this hull is nearly
non-radiating (B55(G) = B55(O) + 2 dz B15 + dz^2 B11, O on the waterline, is 0.35 % of the sum
of its terms' magnitudes at 2 rad/s), so near-field panel errors are amplified in B55 while
|X5| converges fast: the ratio measures the B55 error. The last mesh is `bem.CONVERGED_MESH`'s
finer neighbour (a check that the shipped data have converged, not only that Haskind holds).
"""

from __future__ import annotations

import argparse
import math

import numpy as np

from mf_envs.physics.gowec.hydro import RHO, CylinderHull, G
from mf_envs.physics.gowec.hydro.bem import (
    _legacy_body,
    cylinder_body,
    deep_green_function,
    solve,
)

OMEGA = (0.5, 1.0, 1.5, 2.0, 2.5, 3.0)
# (label, legacy resolution or graded mesh (n_theta, n_side, n_bottom, ratio))
LADDER = (
    ("uniform 8x48x16 (old default)", (8, 48, 16)),
    ("graded 48x(16+16) q1.2", (48, 16, 16, 1.2)),
    ("graded 96x(24+24) q1.2", (96, 24, 24, 1.2)),
    ("graded 144x(36+36) q1.12", (144, 36, 36, 1.12)),
    ("graded 192x(36+36) q1.12 (shipped)", (192, 36, 36, 1.12)),
    ("graded 192x(48+48) q1.1", (192, 48, 48, 1.1)),
)


def run(hull: CylinderHull, mesh: tuple, omega: np.ndarray) -> dict[str, np.ndarray]:
    """A55, B55, |X5| and the Haskind ratio at omega on one mesh (deep water; the Green function
    `from_capytaine` uses with that kind of mesh)."""
    if len(mesh) == 3:
        body, gf = _legacy_body(hull, mesh), None
    else:
        body, gf = cylinder_body(hull, mesh), deep_green_function()
    r = solve(body, omega, (5,), math.inf, RHO, G, gf)
    B, X = r["B"][:, 0, 0], np.abs(r["X"][:, 0])
    k, cg = omega**2 / G, G / (2.0 * omega)
    return dict(
        panels=np.array(body.mesh.nb_faces),
        A55=r["A"][:, 0, 0],
        B55=B,
        X5=X,
        haskind=k * X**2 / (8.0 * RHO * G * cg) / B,
    )


def table(rows: list[tuple[str, dict]], key: str, title: str, fmt: str) -> str:
    """One Markdown table of `key` (rows: meshes, columns: OMEGA)."""
    head = "| mesh | panels | " + " | ".join(f"w = {w:g}" for w in OMEGA) + " |"
    lines = [f"**{title}**", "", head, "|---|---|" + "---|" * len(OMEGA)]
    for label, r in rows:
        vals = " | ".join(format(v, fmt) for v in r[key])
        lines.append(f"| {label} | {int(r['panels'])} | {vals} |")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--quick", action="store_true", help="skip the finest mesh")
    a = p.parse_args(argv)
    hull, omega = CylinderHull(), np.array(OMEGA)
    ladder = LADDER[:-1] if a.quick else LADDER
    rows = [(label, run(hull, mesh, omega)) for label, mesh in ladder]
    print(f"cylinder r = {hull.radius} m, d = {hull.draft} m, z_G = {hull.zg} m, deep water, "
          f"w in rad/s\n")  # fmt: skip
    print(table(rows, "A55", "A55 about G (kg m^2)", ".0f"), end="\n\n")
    print(table(rows, "B55", "B55 about G (N m s/rad)", ".1f"), end="\n\n")
    print(table(rows, "X5", "abs(X5) about G (N m/m)", ".0f"), end="\n\n")
    print(table(rows, "haskind", "Haskind ratio k abs(X5)^2 / (8 rho g c_g B55)", ".3f"))


if __name__ == "__main__":
    main()
