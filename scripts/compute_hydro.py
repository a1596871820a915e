"""Compute the FloatingGOWEC-v0 default hull's hydrodynamic coefficients with Capytaine (BEM).

    pip install "mf-envs[hydro]"
    python scripts/compute_hydro.py                      # writes the shipped default hull
    python scripts/compute_hydro.py --out my_hull.npz --radius 3 --draft 2.5 --zg -0.8

The default hull is a vertical circular cylinder, radius 2.5 m (the buoy radius of GOWEC-v0's
irregular sea), draft 2.0 m, freely floating (mass = rho V = 40.25 t, it carries one Seakeeper 26
unit, ~1 t, and ballast), centre of gravity 0.6 m below the still water line (ballasted; the
metacentric height is then GM = C55/(m g) = 0.38 m), pitch radius of gyration 1.5 m about G.
With these numbers the rotor-off pitch natural period is ~5.9 s, in the band of the default sea
(T = 6 s), so the gyro reaction visibly changes the buoy motion (the two-way coupling the env is
about). The work is done by `mf_envs.physics.gowec.hydro.from_capytaine`; this script only
chooses the hull and writes the file.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from mf_envs.physics.gowec.hydro import DEFAULT_HULL_FILE, CylinderHull, from_capytaine
from mf_envs.physics.gowec.hydro.bem import CONVERGED_MESH


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--out", type=Path, default=DEFAULT_HULL_FILE)
    p.add_argument("--radius", type=float, default=2.5, help="m")
    p.add_argument("--draft", type=float, default=2.0, help="m")
    p.add_argument("--zg", type=float, default=-0.6, help="centre of gravity z (m, waterline 0)")
    p.add_argument("--gyration", type=float, default=1.5, help="pitch radius of gyration (m)")
    p.add_argument("--omega-max", type=float, default=5.0, help="rad/s")
    p.add_argument("--n-omega", type=int, default=70)
    p.add_argument(
        "--mesh", type=float, nargs=4, default=CONVERGED_MESH,
        help="keel-graded axisymmetric mesh (n_theta, n_side, n_bottom, ratio)",
    )  # fmt: skip
    p.add_argument(
        "--legacy-resolution", type=int, nargs=3, default=None, metavar=("NR", "NTHETA", "NZ"),
        help="use the pre-issue-29 uniform mesh instead (e.g. 8 48 16: the old default_hull.npz)",
    )  # fmt: skip
    a = p.parse_args(argv)
    hull = CylinderHull(a.radius, a.draft, a.zg, a.gyration)
    omega = np.linspace(0.05, a.omega_max, a.n_omega)
    if a.legacy_resolution is not None:
        coeffs = from_capytaine(hull, omega, resolution=tuple(a.legacy_resolution))
    else:
        nt, ns, nb, q = a.mesh
        coeffs = from_capytaine(hull, omega, mesh=(int(nt), int(ns), int(nb), q))
    coeffs.save(a.out)
    print(f"wrote {a.out}: {len(omega)} frequencies, C55 = {coeffs.stiffness:.4g} N m/rad")


if __name__ == "__main__":
    main()
