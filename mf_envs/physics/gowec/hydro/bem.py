"""Capytaine (linear potential-flow BEM) front end: a hull in, `HullCoefficients` out.

Needs the `hydro` extra (`pip install "mf-envs[hydro]"`); the core install only reads the
result. Capytaine solves the radiation and diffraction problems on a panel mesh of the wetted
surface (Babarit & Delhommeau 2015); the lid on the waterplane removes the irregular
frequencies of the interior problem. Conventions: `mf_envs.physics.gowec.hydro`.

`solve` is the mesh-agnostic core (any body, any subset of rigid-body dofs, any depth); it is
what the WAMIT regression test runs on a sphere and what `from_capytaine` (pitch of a cylinder)
and `hydro.three_dof_bem` (surge/heave/pitch) run on a cylinder; `box_solve` runs it on ISWEC's
box (five modes, ten headings, one frequency at a time).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from mf_envs.physics.gowec.hydro import RHO, BoxHull, CylinderHull, G, HullCoefficients

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
    headings: tuple[float, ...] = (0.0,),
    progress_bar: bool | None = None,
) -> dict[str, np.ndarray]:
    """Radiation and diffraction of `body` for the rigid-body modes (1..6 = surge..yaw) at the
    frequencies omega (rad/s), head waves along +x. Returns float64/complex128 arrays:
    A, B (n, m, m) [i, j] = force on mode i from motion of mode j; X (n, m) excitation per metre
    of wave amplitude (Capytaine's e^{-i w t} convention); k (n,) wavenumber (rad/m).
    green_function: a Capytaine Green function object (default: Capytaine's Delhommeau).
    headings: wave directions beta (rad from +x towards +y); with more than the head wave the
    result also has X_headings (n, len(headings), m) (the diffraction problems share each
    frequency's factorised matrix, so a heading costs a right-hand side, not a solve).
    progress_bar: Capytaine's (None: its default, on unless CAPYTAINE_PROGRESS_BAR says off)."""
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
    beta = [float(b) for b in headings]
    if not (beta and beta[0] == 0.0 and np.all(np.isfinite(beta))):
        raise ValueError(f"headings: expected finite angles starting with 0, got {headings!r}")
    test = xr.Dataset(
        coords={
            "omega": om,
            "wave_direction": beta,
            "radiating_dof": names,
            "influenced_dof": names,
            "rho": rho,
            "g": g,
            "water_depth": water_depth,
        }
    )
    gf = {} if green_function is None else dict(green_function=green_function)
    solver = cpt.BEMSolver(**gf)
    ds = solver.fill_dataset(test, body, hydrostatics=False, progress_bar=progress_bar)
    ds = ds.sel(omega=om)  # input order
    order = dict(influenced_dof=names, radiating_dof=names)
    A = ds.added_mass.sel(**order).transpose("omega", "influenced_dof", "radiating_dof")
    B = ds.radiation_damping.sel(**order).transpose("omega", "influenced_dof", "radiating_dof")
    X = ds.excitation_force.sel(influenced_dof=names, wave_direction=beta)
    X = X.transpose("omega", "wave_direction", "influenced_dof").values.astype(np.complex128)
    out = dict(
        A=A.values.astype(np.float64),
        B=B.values.astype(np.float64),
        X=X[:, 0],
        k=np.asarray(ds.wavenumber.values, dtype=np.float64),
    )
    if len(beta) > 1:
        out["X_headings"] = X
    return out


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


def box_body(hull: BoxHull, mesh: tuple[int, int, int, float], rho: float = RHO):
    """FloatingBody of `hull` on the twice mirror-symmetric mesh (n_length, n_beam, n_draft,
    ratio) of `meshes.box_mesh` (with its waterplane lid), rotation centre G."""
    from mf_envs.physics.gowec.hydro.meshes import box_mesh

    nl, nb, nd, q = mesh
    hull_mesh, lid = box_mesh(hull.length, hull.beam, hull.draft, int(nl), int(nb), int(nd), q)
    return rigid_body(hull_mesh, lid, (0.0, 0.0, hull.zg), hull.mass(rho), "iswec_box")


def _release_matrices() -> None:
    """Free the influence matrices Capytaine 3.0 keeps: `NestedBlockCirculantMatrix.
    to_BlockCirculantMatrix` (the twice mirror-symmetric mesh's S @ sigma) is memoised by a
    method-level `functools.lru_cache` of 128 entries, which holds every solved frequency's S
    and its dense macro-blocks alive (measured: +240 MB per frequency at 3 168 panels; the
    7 184-panel box was killed out of memory after about a dozen frequencies). A no-op where
    the method has no cache (`tests/test_hydro_box.py` pins the hook)."""
    from capytaine.tools.block_circulant_matrices import NestedBlockCirculantMatrix

    clear = getattr(NestedBlockCirculantMatrix.to_BlockCirculantMatrix, "cache_clear", None)
    if clear is not None:
        clear()


BOX_MODES = (1, 2, 3, 4, 5)  # surge, sway, heave, roll, pitch: what `box_solve` computes


def box_solve(
    hull: BoxHull,
    omega: ArrayLike,
    water_depth: float,
    mesh: tuple[int, int, int, float],
    n_headings: int = 10,
    rho: float = RHO,
    g: float = G,
    progress: Callable[[int, int], None] | None = None,
) -> dict[str, np.ndarray]:
    """The raw BEM arrays of a box about G at finite `water_depth` (m), modes `BOX_MODES`:
    `solve_depth`'s A, B (n, 5, 5), X (n, 5), k (n,) and X_headings (n, n_headings, 5) at
    wave directions evenly spaced over 0..pi/2 (the rest of the circle follows from the two
    mirror planes), plus A_inf (5, 5) (deep water), C (6, 6) (the mesh hydrostatics), headings
    (rad) and panels (hull + lid). One run: the headings and the modes are right-hand sides of
    each frequency's factorised matrix. Solved one frequency at a time (`_release_matrices`
    between them); progress(done, total) is called after each."""
    if not (isinstance(n_headings, int) and n_headings >= 3):
        raise ValueError(f"n_headings: must be an integer >= 3, got {n_headings!r}")
    om = np.asarray(omega, dtype=float)
    body = box_body(hull, mesh, rho)
    beta = tuple(np.linspace(0.0, 0.5 * np.pi, n_headings))
    parts = []
    for i in range(om.size):
        parts.append(solve_depth(body, om[i : i + 1], BOX_MODES, water_depth, rho, g,
                                 headings=beta, progress_bar=progress is None))  # fmt: skip
        _release_matrices()
        if progress is not None:
            progress(i + 1, om.size)
    out = {k: np.concatenate([p[k] for p in parts]) for k in parts[0]}
    out["A_inf"] = solve_limit(body, BOX_MODES, np.inf, rho, g)
    out["C"] = np.asarray(body.compute_hydrostatics(rho=rho, g=g)["hydrostatic_stiffness"], float)
    out["headings"] = np.asarray(beta)
    out["panels"] = np.array(body.mesh_including_lid.nb_faces)  # hull + lid
    return out


def _clip_tail(B: np.ndarray, tol: float = 0.01) -> np.ndarray:
    """B (n, m, m) with negative diagonal values set to 0 where they are within `tol` of the
    mode's peak (the mesh's noise where a mode radiates almost nothing, e.g. heave of the box
    at 3.3 rad/s, B33 ~ 1e-3 of its peak); ValueError naming the mode if one is more negative
    (a failed solve, not noise)."""
    B = np.array(B, dtype=float)
    for i in range(B.shape[1]):
        d = B[:, i, i]
        if np.any(d < -tol * d.max()):
            raise ValueError(f"damping: mode index {i} has B_ii < -{tol} x its peak")
        B[d < 0, i, i] = 0.0
    return B


def box_coefficients(
    hull: BoxHull, omega: ArrayLike, water_depth: float, raw: dict[str, np.ndarray],
    rho: float = RHO, g: float = G,
):  # fmt: skip
    """`ThreeDofCoefficients` of a box from `box_solve`'s arrays: surge/heave/pitch as the
    cylinder's (`three_dof_from_capytaine`) plus the optional sway/roll block and the heading
    table. Mass matrices diag(m, m, I55) and diag(m, I44) about G, m = rho V. Negative
    B_ii of the table's tail are set to 0 (`_clip_tail`)."""
    from mf_envs.physics.gowec.hydro.three_dof import MODES, TRANSVERSE_MODES, ThreeDofCoefficients

    m = hull.mass(rho)
    lon = [BOX_MODES.index(i) for i in MODES]
    tra = [BOX_MODES.index(i) for i in TRANSVERSE_MODES]

    def block(M: np.ndarray, idx: list[int]) -> np.ndarray:
        return M[..., idx, :][..., idx]

    def c6(idx: list[int]) -> np.ndarray:  # Capytaine's 6 x 6 is indexed by mode - 1
        return block(raw["C"], [BOX_MODES[i] - 1 for i in idx])

    A, B = raw["A"], _clip_tail(raw["B"])
    return ThreeDofCoefficients(
        omega=np.asarray(omega, dtype=float), wavenumber=raw["k"],
        added_mass=block(A, lon), damping=block(B, lon), excitation=raw["X"][:, lon],
        added_mass_inf=block(raw["A_inf"], lon), hydrostatic_stiffness=c6(lon),
        mass_matrix=np.diag([m, m, hull.inertia(rho)]),
        water_depth=float(water_depth), rho=rho, g=g, radius=math.nan, draft=hull.draft,
        zg=hull.zg, gyration=hull.gyration,
        name=f"capytaine box {hull.length}x{hull.beam} d={hull.draft} h={water_depth}",
        length=hull.length, beam=hull.beam, roll_gyration=hull.roll_gyration,
        transverse_added_mass=block(A, tra), transverse_damping=block(B, tra),
        transverse_added_mass_inf=block(raw["A_inf"], tra),
        transverse_hydrostatic_stiffness=c6(tra),
        transverse_mass_matrix=np.diag([m, hull.inertia(rho, "roll")]),
        headings=raw["headings"], heading_excitation=raw["X_headings"],
    )  # fmt: skip


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
    headings: tuple[float, ...] = (0.0,),
    progress_bar: bool | None = None,
) -> dict[str, np.ndarray]:
    """`solve` at a finite depth h: Capytaine's finite-depth Green function where k h <= deep_kh,
    a deep-water one where the seabed is deeper than deep_kh / k (its effect on the potential
    there is ~exp(-2 k h) = 6e-6 at k h = 6, less than the finite-depth function's tabulation
    error). k is the finite-depth wavenumber throughout. deep_green: a Capytaine Green function
    object for the deep part; default Capytaine's Delhommeau (tabulated), the same family as
    the finite-depth part. (`deep_green_function`, Liang-Wu-Noblesse, is not used here: on the
    ISWEC-class hull it puts heave damping 16-25 % above the Haskind value at 2.8-3.0 rad/s on
    every mesh tried, where Delhommeau's agrees to 1-3 %; docs/gowec_v1.md, "Convergence".)
    headings, progress_bar: passed to `solve`."""
    from mf_envs.physics.waves import wavenumber

    om = np.asarray(omega, dtype=float)
    if om.ndim != 1 or om.size == 0 or not np.all(np.diff(om) > 0):
        raise ValueError(f"omega: expected strictly increasing frequencies, got {omega!r}")
    k = wavenumber(om, water_depth, g)
    deep = k * water_depth > deep_kh
    parts = []
    for sel, h, gf in ((~deep, water_depth, None), (deep, math.inf, deep_green)):
        if np.any(sel):
            parts.append(solve(body, om[sel], modes, h, rho, g, gf, headings, progress_bar))
    out = {key: np.concatenate([p[key] for p in parts]) for key in parts[0] if key != "k"}
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
