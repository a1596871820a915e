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

# (n_theta, n_side, n_bottom, ratio) of `meshes.cylinder_mesh` for the GOWEC default cylinder
# (r 2.5 m, d 2 m): 13 824 hull panels, Haskind within 5 % at 0.3-3 rad/s (docs/gowec_v1.md,
# "Convergence"; scripts/hydro_convergence.py)
CONVERGED_MESH = (192, 36, 36, 1.12)
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
    green_function: Any = None,
) -> dict[str, np.ndarray]:
    """Radiation and diffraction of `body` for the rigid-body modes (1..6 = surge..yaw) at the
    frequencies omega (rad/s), head waves along +x. Returns float64/complex128 arrays:
    A, B (n, m, m) [i, j] = force on mode i from motion of mode j; X (n, m) excitation per metre
    of wave amplitude (Capytaine's e^{-i w t} convention); k (n,) wavenumber (rad/m).
    green_function: a Capytaine Green function object (default: Capytaine's Delhommeau)."""
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
    gf = {} if green_function is None else dict(green_function=green_function)
    solver = cpt.BEMSolver(**gf)
    ds = solver.fill_dataset(test, body, hydrostatics=False).sel(omega=om)  # input order
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


def deep_green_function():
    """Liang-Wu-Noblesse deep-water Green function (Capytaine's `LiangWuNoblesseGF`, as in
    HAMS): evaluated from its series and asymptotic expansions, not interpolated from a table.
    Capytaine's default (Delhommeau's tabulated wave term) leaves an interpolation error in the
    influence matrices, which B55 about G of the GOWEC cylinder, a 0.1-3 % difference of large
    terms, turns into +-8 % frequency-to-frequency noise at 2.3-3.3 rad/s."""
    import capytaine as cpt

    return cpt.LiangWuNoblesseGF()


def _legacy_body(hull: CylinderHull, resolution: tuple[int, int, int]):
    """The older uniform mesh: Capytaine's uniform cylinder clipped at the waterline."""
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
    the keel-graded axisymmetric mesh (`meshes.cylinder_mesh`, the converged one);
    without it, resolution = (radial, azimuthal, vertical) panels of Capytaine's uniform
    cylinder before clipping at the waterline (the older uniform mesh, under-resolved at the
    keel). C55 is the mesh hydrostatics (`CylinderHull.stiffness` is the independent check).
    The graded mesh is solved with the exact deep-water Green function (`deep_green_function`);
    the legacy mesh with Capytaine's default, as the old file was."""
    if mesh is None:
        body, gf = _legacy_body(hull, resolution), None
    else:
        body, gf = cylinder_body(hull, mesh, rho), deep_green_function()
    r = solve(body, omega, (5,), math.inf, rho, g, gf)
    limits = [float(solve_limit(body, (5,), w, rho, g)[0, 0]) for w in (0.0, np.inf)]
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
        **_provenance(hull, rho, g),
    )


def three_dof_from_capytaine(
    hull: CylinderHull,
    omega: ArrayLike,
    water_depth: float,
    mesh: tuple[int, int, int, float],
    rho: float = RHO,
    g: float = G,
):
    """Surge/heave/pitch `ThreeDofCoefficients` of `hull` about G at finite `water_depth` (m)
    on the keel-graded axisymmetric mesh (n_theta, n_side, n_bottom, ratio). The hydrostatic
    matrix is the mesh hydrostatics (rows/columns 1, 3, 5 of Capytaine's 6 x 6); the mass
    matrix is diag(m, m, m k^2) with m = rho V (freely floating) and k the pitch gyration."""
    from mf_envs.physics.gowec.hydro.three_dof import MODES, ThreeDofCoefficients

    body = cylinder_body(hull, mesh, rho)
    r = solve_depth(body, omega, MODES, water_depth, rho, g)
    deep = solve_limit(body, MODES, np.inf, rho, g)
    idx = np.ix_([m - 1 for m in MODES], [m - 1 for m in MODES])
    C = np.asarray(body.compute_hydrostatics(rho=rho, g=g)["hydrostatic_stiffness"])[idx]
    m = hull.mass(rho)
    return ThreeDofCoefficients(
        omega=np.asarray(omega, dtype=float),
        wavenumber=r["k"],
        added_mass=r["A"],
        damping=r["B"],
        excitation=r["X"],
        added_mass_inf=deep,
        hydrostatic_stiffness=np.asarray(C, dtype=float),
        mass_matrix=np.diag([m, m, hull.inertia(rho)]),
        water_depth=float(water_depth),
        gyration=hull.gyration,
        **_provenance(hull, rho, g, f" h={water_depth}"),
    )


def _provenance(hull: CylinderHull, rho: float, g: float, depth: str = "") -> dict[str, Any]:
    """The fields a coefficient set records of what it was solved for: water, hull, a name."""
    return {
        "rho": rho,
        "g": g,
        "radius": hull.radius,
        "draft": hull.draft,
        "zg": hull.zg,
        "name": f"capytaine cylinder r={hull.radius} d={hull.draft}{depth}",
    }


def solve_depth(
    body: Any,
    omega: ArrayLike,
    modes: tuple[int, ...],
    water_depth: float,
    rho: float = RHO,
    g: float = G,
    deep_kh: float = 6.0,
    deep_green: Any = None,
) -> dict[str, np.ndarray]:
    """`solve` at a finite depth h: Capytaine's finite-depth Green function where k h <= deep_kh,
    a deep-water one where the seabed is deeper than deep_kh / k (its effect on the potential
    there is ~exp(-2 k h) = 6e-6 at k h = 6, less than the finite-depth function's tabulation
    error). k is the finite-depth wavenumber throughout. deep_green: a Capytaine Green function
    object for the deep part; default Capytaine's Delhommeau (tabulated), the same family as
    the finite-depth part. (`deep_green_function`, Liang-Wu-Noblesse, is not used here: on the
    ISWEC-class hull it puts heave damping 16-25 % above the Haskind value at 2.8-3.0 rad/s on
    every mesh tried, where Delhommeau's agrees to 1-3 %; docs/gowec_v1.md, "Convergence".)"""
    from mf_envs.physics.waves import wavenumber

    om = np.asarray(omega, dtype=float)
    if om.ndim != 1 or om.size == 0 or not np.all(np.diff(om) > 0):
        raise ValueError(f"omega: expected strictly increasing frequencies, got {omega!r}")
    k = wavenumber(om, water_depth, g)
    deep = k * water_depth > deep_kh
    parts = []
    if np.any(~deep):
        parts.append(solve(body, om[~deep], modes, water_depth, rho, g))
    if np.any(deep):
        parts.append(solve(body, om[deep], modes, math.inf, rho, g, deep_green))
    out = {key: np.concatenate([p[key] for p in parts]) for key in ("A", "B", "X")}
    out["k"] = k
    return out


def solve_limit(body: Any, modes: tuple[int, ...], omega: float, rho: float = RHO, g: float = G):
    """Added-mass matrix (m, m) of `modes` at omega = 0 or inf, deep water; [i, j] = force on
    mode i from mode j."""
    import capytaine as cpt

    out = np.zeros((len(modes), len(modes)))
    for j, mj in enumerate(modes):
        pb = cpt.RadiationProblem(body=body, radiating_dof=DOF_NAMES[mj], omega=omega, rho=rho, g=g)
        res = cpt.BEMSolver().solve(pb)
        out[:, j] = [float(res.added_mass[DOF_NAMES[mi]]) for mi in modes]
    return out
