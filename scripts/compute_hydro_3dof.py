"""Compute the ISWEC-class hull's surge/heave/pitch coefficients with Capytaine (BEM, issue 29).

    pip install "mf-envs[hydro]"
    nice -n 10 python scripts/compute_hydro_3dof.py      # writes the shipped file (~30 min)
    nice -n 10 python scripts/compute_hydro_3dof.py --out h.npz --radius 5 --draft 3 --depth 50

The hull is a vertical circular cylinder standing in for the ISWEC Pantelleria prototype
(15 x 8 m hull, 3.2 m draft, 35 m depth): radius 6 m (footprint 113 m^2 vs 120 m^2), draft
2.5 m (m = rho V = 290 t), pitch radius of gyration 4.2 m, centre of gravity z_G = -0.5 m
(an assumption: ballasted slightly below the waterline, GM = 2.85 m), water depth 35 m. A
cylinder and not the box: its surface of revolution lets Capytaine solve one wedge of the mesh
(a block-circulant system), so a keel-graded mesh converged to the Haskind relation costs
minutes, where a box of the same panel size (four keel edges and four vertical corners, only
two mirror symmetries) would cost hours on 2 cores; and pitch about G depends mainly on the
waterplane (footprint) and draft, which the cylinder matches. Output: `three_dof` module doc.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from mf_envs.physics.gowec.hydro import CylinderHull
from mf_envs.physics.gowec.hydro.bem import three_dof_from_capytaine
from mf_envs.physics.gowec.hydro.three_dof import ISWEC_HULL_FILE, ISWEC_MESH


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--out", type=Path, default=ISWEC_HULL_FILE)
    p.add_argument("--radius", type=float, default=6.0, help="m")
    p.add_argument("--draft", type=float, default=2.5, help="m")
    p.add_argument("--zg", type=float, default=-0.5, help="centre of gravity z (m, waterline 0)")
    p.add_argument("--gyration", type=float, default=4.2, help="pitch radius of gyration (m)")
    p.add_argument("--depth", type=float, default=35.0, help="water depth (m)")
    p.add_argument("--omega", type=float, nargs=3, default=(0.2, 3.4, 33), help="w0 w1 n (rad/s)")
    p.add_argument("--mesh", type=float, nargs=4, default=ISWEC_MESH, help="nt n_side n_bottom q")
    a = p.parse_args(argv)
    hull = CylinderHull(a.radius, a.draft, a.zg, a.gyration)
    omega = np.linspace(a.omega[0], a.omega[1], int(a.omega[2]))
    nt, ns, nb, q = a.mesh
    h = three_dof_from_capytaine(hull, omega, a.depth, (int(nt), int(ns), int(nb), q))
    h.save(a.out)
    print(f"wrote {a.out}: {omega.size} frequencies, C55 = {h.hydrostatic_stiffness[2, 2]:.4g}")


if __name__ == "__main__":
    main()
