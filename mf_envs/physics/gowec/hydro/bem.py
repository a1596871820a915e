"""Capytaine (linear potential-flow BEM) front end: a hull in, `HullCoefficients` out.

Needs the `hydro` extra (`pip install "mf-envs[hydro]"`); the core install only reads the
result. Capytaine solves the radiation and diffraction problems on a panel mesh of the wetted
surface (Babarit & Delhommeau 2015); the lid on the waterplane removes the irregular
frequencies of the interior problem. Conventions: `mf_envs.physics.gowec.hydro`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from mf_envs.physics.gowec.hydro import RHO, CylinderHull, G, HullCoefficients


def _body(hull: CylinderHull, resolution: tuple[int, int, int]):
    import capytaine as cpt

    mesh = cpt.mesh_vertical_cylinder(
        length=2.0 * hull.draft, radius=hull.radius, center=(0.0, 0.0, 0.0), resolution=resolution
    ).immersed_part()
    lid = mesh.generate_lid(z=-0.01 * hull.draft)
    centre = (0.0, 0.0, hull.zg)
    return cpt.FloatingBody(
        mesh=mesh,
        lid_mesh=lid,
        dofs=cpt.rigid_body_dofs(rotation_center=centre),
        center_of_mass=centre,
        mass=hull.mass(RHO),
        name="gowec_cylinder",
    )


def from_capytaine(
    hull: CylinderHull,
    omega: ArrayLike,
    resolution: tuple[int, int, int] = (8, 48, 16),
    rho: float = RHO,
    g: float = G,
) -> HullCoefficients:
    """Pitch A(w), B(w), X(w) (head wave along +x), A_0, A_inf and C55 of `hull` at the
    frequencies omega (rad/s), deep water. resolution = (radial, azimuthal, vertical) panels of
    the cylinder mesh before clipping at the waterline. C55 is Capytaine's mesh hydrostatics
    (the geometry formula `CylinderHull.stiffness` is the independent check)."""
    import capytaine as cpt
    import xarray as xr

    body = _body(hull, resolution)
    om = np.asarray(omega, dtype=float)
    test = xr.Dataset(
        coords={
            "omega": om,
            "wave_direction": [0.0],
            "radiating_dof": ["Pitch"],
            "influenced_dof": ["Pitch"],
            "rho": rho,
            "g": g,
            "water_depth": np.inf,
        }
    )
    solver = cpt.BEMSolver()
    ds = solver.fill_dataset(test, body)
    sel = dict(radiating_dof="Pitch", influenced_dof="Pitch")
    A = ds.added_mass.sel(**sel).values.astype(float)
    B = ds.radiation_damping.sel(**sel).values.astype(float)
    X = ds.excitation_force.sel(influenced_dof="Pitch", wave_direction=0.0).values
    limits = []
    for w in (0.0, np.inf):
        pb = cpt.RadiationProblem(body=body, radiating_dof="Pitch", omega=w, rho=rho, g=g)
        limits.append(float(solver.solve(pb).added_mass["Pitch"]))
    hs = body.compute_hydrostatics(rho=rho, g=g)
    C = float(np.asarray(hs["hydrostatic_stiffness"])[4, 4])
    return HullCoefficients(
        omega=om,
        added_mass=A,
        damping=np.maximum(B, 0.0),  # BEM round-off near w -> 0 can give -1e-10
        excitation=np.asarray(X, dtype=complex),
        added_mass_inf=limits[1],
        added_mass_zero=limits[0],
        stiffness=C,
        inertia=hull.inertia(rho),
        mass=hull.mass(rho),
        rho=rho,
        g=g,
        radius=hull.radius,
        draft=hull.draft,
        zg=hull.zg,
        name=f"capytaine cylinder r={hull.radius} d={hull.draft}",
    )
