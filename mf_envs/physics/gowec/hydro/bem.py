"""Capytaine (linear potential-flow BEM) front end: a hull in, `HullCoefficients` out.

Needs the `hydro` extra (`pip install "mf-envs[hydro]"`); the core install only reads the
result. Capytaine solves the radiation and diffraction problems on a panel mesh of the wetted
surface (Babarit & Delhommeau 2015); the lid on the waterplane removes the irregular
frequencies of the interior problem. Conventions: `mf_envs.physics.gowec.hydro`.

`solve` is the mesh-agnostic core (any body, any subset of rigid-body dofs, any depth); it is
what the WAMIT regression test runs on a sphere and what `from_capytaine` (pitch of a cylinder)
and `hydro.three_dof_bem` (surge/heave/pitch) run on a cylinder.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from mf_envs.physics.gowec.hydro import RHO, CylinderHull, G, HullCoefficients

DOF_NAMES = {1: "Surge", 2: "Sway", 3: "Heave", 4: "Roll", 5: "Pitch", 6: "Yaw"}


def rigid_body(mesh: Any, lid: Any, centre: tuple[float, float, float], mass: float, name: str):
    """Capytaine FloatingBody with the six rigid-body dofs about `centre` (rotation centre and
    centre of mass)."""
    import capytaine as cpt

    return cpt.FloatingBody(
        mesh=mesh,
        lid_mesh=lid,
        dofs=cpt.rigid_body_dofs(rotation_center=centre),
        center_of_mass=centre,
        mass=mass,
        name=name,
    )


def solve(
    body: Any,
    omega: ArrayLike,
    modes: tuple[int, ...] = (5,),
    water_depth: float = math.inf,
    rho: float = RHO,
    g: float = G,
) -> dict[str, np.ndarray]:
    """Radiation and diffraction of `body` for the rigid-body modes (1..6 = surge..yaw) at the
    frequencies omega (rad/s), head waves along +x. Returns float64/complex128 arrays:
    A, B (n, m, m) [i, j] = force on mode i from motion of mode j; X (n, m) excitation per metre
    of wave amplitude (Capytaine's e^{-i w t} convention); k (n,) wavenumber (rad/m)."""
    import capytaine as cpt
    import xarray as xr

    om = np.asarray(omega, dtype=float)
    if om.ndim != 1 or om.size == 0 or not np.all(np.isfinite(om) & (om > 0)):
        raise ValueError(f"omega: expected a 1-D array of frequencies > 0, got {omega!r}")
    if not set(modes) <= set(DOF_NAMES) or len(set(modes)) != len(modes):
        raise ValueError(f"modes: expected distinct integers in 1..6, got {modes!r}")
    if not (water_depth > 0):
        raise ValueError(f"water_depth: must be > 0 (inf = deep), got {water_depth!r}")
    names = [DOF_NAMES[i] for i in modes]
    test = xr.Dataset(
        coords={
            "omega": om,
            "wave_direction": [0.0],
            "radiating_dof": names,
            "influenced_dof": names,
            "rho": rho,
            "g": g,
            "water_depth": water_depth,
        }
    )
    ds = cpt.BEMSolver().fill_dataset(test, body, hydrostatics=False).sel(omega=om)  # input order
    order = dict(influenced_dof=names, radiating_dof=names)
    A = ds.added_mass.sel(**order).transpose("omega", "influenced_dof", "radiating_dof")
    B = ds.radiation_damping.sel(**order).transpose("omega", "influenced_dof", "radiating_dof")
    X = ds.excitation_force.sel(influenced_dof=names, wave_direction=0.0)
    return dict(
        A=A.values.astype(np.float64),
        B=B.values.astype(np.float64),
        X=X.transpose("omega", "influenced_dof").values.astype(np.complex128),
        k=np.asarray(ds.wavenumber.values, dtype=np.float64),
    )


def limit_added_mass(body: Any, mode: int, omega: float, rho: float = RHO, g: float = G) -> float:
    """Added mass of `mode` at omega = 0 or inf (deep water), kg or kg m^2."""
    import capytaine as cpt

    pb = cpt.RadiationProblem(body=body, radiating_dof=DOF_NAMES[mode], omega=omega, rho=rho, g=g)
    return float(cpt.BEMSolver().solve(pb).added_mass[DOF_NAMES[mode]])


def _legacy_body(hull: CylinderHull, resolution: tuple[int, int, int]):
    """The pre-issue-29 mesh: Capytaine's uniform cylinder clipped at the waterline."""
    import capytaine as cpt

    mesh = cpt.mesh_vertical_cylinder(
        length=2.0 * hull.draft, radius=hull.radius, center=(0.0, 0.0, 0.0), resolution=resolution
    ).immersed_part()
    lid = mesh.generate_lid(z=-0.01 * hull.draft)
    return rigid_body(mesh, lid, (0.0, 0.0, hull.zg), hull.mass(RHO), "gowec_cylinder")


def cylinder_body(hull: CylinderHull, mesh: tuple[int, int, int, float], rho: float = RHO):
    """FloatingBody of `hull` on the keel-graded axisymmetric mesh (n_theta, n_side, n_bottom,
    ratio) of `meshes.cylinder_mesh`, rotation centre G."""
    from mf_envs.physics.gowec.hydro.meshes import cylinder_mesh

    nt, ns, nb, q = mesh
    hull_mesh, lid = cylinder_mesh(hull.radius, hull.draft, int(nt), int(ns), int(nb), float(q))
    return rigid_body(hull_mesh, lid, (0.0, 0.0, hull.zg), hull.mass(rho), "gowec_cylinder")


def from_capytaine(
    hull: CylinderHull,
    omega: ArrayLike,
    resolution: tuple[int, int, int] = (8, 48, 16),
    rho: float = RHO,
    g: float = G,
    mesh: tuple[int, int, int, float] | None = None,
) -> HullCoefficients:
    """Pitch A(w), B(w), X(w) (head wave along +x), A_0, A_inf and C55 of `hull` at the
    frequencies omega (rad/s), deep water. `mesh` = (n_theta, n_side, n_bottom, ratio) selects
    the keel-graded axisymmetric mesh (`meshes.cylinder_mesh`, the converged one of issue 29);
    without it, resolution = (radial, azimuthal, vertical) panels of Capytaine's uniform
    cylinder before clipping at the waterline (the pre-issue-29 mesh, under-resolved at the
    keel). C55 is the mesh hydrostatics (`CylinderHull.stiffness` is the independent check)."""
    body = _legacy_body(hull, resolution) if mesh is None else cylinder_body(hull, mesh, rho)
    r = solve(body, omega, (5,), math.inf, rho, g)
    limits = [limit_added_mass(body, 5, w, rho, g) for w in (0.0, np.inf)]
    hs = body.compute_hydrostatics(rho=rho, g=g)
    C = float(np.asarray(hs["hydrostatic_stiffness"])[4, 4])
    return HullCoefficients(
        omega=np.asarray(omega, dtype=float),
        added_mass=r["A"][:, 0, 0],
        damping=np.maximum(r["B"][:, 0, 0], 0.0),  # BEM round-off near w -> 0 can give -1e-10
        excitation=r["X"][:, 0],
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
