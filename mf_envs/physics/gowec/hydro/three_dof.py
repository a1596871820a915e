"""Surge-heave-pitch hydrodynamic coefficients of a floating hull (BEM, linear potential flow).

The ISWEC-class hull's data: 3 x 3 added mass and damping matrices over the modes
(surge 1, heave 3, pitch 5) with their couplings (A15, A51, B15, ...), the excitation of each
mode, the hydrostatic and rigid-body mass matrices, all about the centre of gravity G, at a
finite water depth. Conventions as `mf_envs.physics.gowec.hydro`: head wave along +x,
eta(0, t) = Re(a e^{-i w t}), force or moment F_i(t) = Re(X_i a e^{-i w t}); A[:, i, j] is the
force on mode i per unit acceleration of mode j. Units: kg, kg m, kg m^2 (translation,
coupling, rotation) for A and the mass matrix; N s/m, N s, N m s/rad for B; N/m, N/rad, N m/rad
for C; N/m and N m/m for X.

File schema (`.npz`, read with `allow_pickle=False`, all arrays float64):

    modes            (3,)      1, 3, 5 (surge, heave, pitch)
    omega            (n,)      rad/s, > 0, strictly increasing
    wavenumber       (n,)      rad/m, finite-depth: w^2 = g k tanh(k h)
    added_mass       (n, 3, 3)
    damping          (n, 3, 3)
    excitation_re    (n, 3)    Re X, per metre of wave amplitude
    excitation_im    (n, 3)    Im X
    added_mass_inf   (3, 3)    w -> inf limit (deep-water solve: the limit of a body 14 drafts
                               above the seabed; Capytaine's finite-depth w = inf is not used)
    hydrostatic_stiffness (3, 3)
    mass_matrix      (3, 3)    diag(m, m, m k^2) about G
    water_depth, rho, g, radius, draft, zg, gyration   scalars (m, kg/m^3, m/s^2, m, m, m, m)

Optional (a box hull's file has them, the cylinder's does not; absent = not computed):

    length, beam, roll_gyration   scalars (m): a box's size along x and y and its roll radius of
                               gyration about G (radius is then nan)
    transverse_modes (2,)      2, 4 (sway, roll), about G; decoupled from 1, 3, 5 by the xOz
                               mirror plane
    transverse_added_mass, transverse_damping   (n, 2, 2)
    transverse_added_mass_inf, transverse_hydrostatic_stiffness, transverse_mass_matrix (2, 2)
    headings         (nb,)     wave directions beta (rad, from +x towards +y), 0 first
    heading_excitation_re, heading_excitation_im   (n, nb, 5)  X of modes 1..5 (surge, sway,
                               heave, roll, pitch) for a wave travelling towards beta: the
                               far-field data of the general Haskind relation
                               (`checks.haskind_headings`); [:, 0, (0, 2, 4)] = excitation
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from mf_envs._files import npz_array, read_npz

MAX_MEMBER_BYTES = 16 << 20  # one array of a hull file (the shipped one: a few KB)
ISWEC_HULL_FILE = Path(__file__).with_name("iswec_cylinder_3dof.npz")
# the file's mesh, (n_theta, n_side, n_bottom, ratio) of `meshes.cylinder_mesh` (docs/gowec_v1.md,
# "ISWEC-class hull"): 192 x (24 + 48) panels graded 1.04 towards the keel edge
ISWEC_MESH = (192, 24, 48, 1.04)
# ISWEC's own hull, the 15 x 8 m box (`hydro.BoxHull`, `scripts/compute_hydro_box.py`), and its
# mesh (n_length, n_beam, n_draft, ratio) of `meshes.box_mesh`: 4 x (36 x 16 + 20 x 16 + 36 x 20)
# hull panels of ~0.2 m, ungraded (grading measured worse here; docs/gowec_v1.md, "ISWEC's box
# hull")
ISWEC_BOX_FILE = Path(__file__).with_name("iswec_box_3dof.npz")
ISWEC_BOX_MESH = (36, 20, 16, 1.0)
MODES = (1, 3, 5)
TRANSVERSE_MODES = (2, 4)
_MATRICES = ("added_mass", "damping")
_FIXED = ("added_mass_inf", "hydrostatic_stiffness", "mass_matrix")
_SCALARS = ("water_depth", "rho", "g", "radius", "draft", "zg", "gyration")
_BOX_SCALARS = ("length", "beam", "roll_gyration")
# optional arrays and their dimensions (transverse block: all or none; headings: both or none)
_TRANSVERSE = {"transverse_" + k: nd for k, nd in (*((k, 3) for k in _MATRICES),
                                                   *((k, 2) for k in _FIXED))}  # fmt: skip


@dataclass(frozen=True)
class ThreeDofCoefficients:
    """Surge/heave/pitch coefficients about G (module docstring for the fields and units)."""

    omega: NDArray[np.float64]
    wavenumber: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    excitation: NDArray[np.complex128]
    added_mass_inf: NDArray[np.float64]
    hydrostatic_stiffness: NDArray[np.float64]
    mass_matrix: NDArray[np.float64]
    water_depth: float
    rho: float
    g: float
    radius: float
    draft: float
    zg: float
    gyration: float
    name: str = field(default="hull")
    length: float = math.nan
    beam: float = math.nan
    roll_gyration: float = math.nan
    transverse_added_mass: NDArray[np.float64] | None = None
    transverse_damping: NDArray[np.float64] | None = None
    transverse_added_mass_inf: NDArray[np.float64] | None = None
    transverse_hydrostatic_stiffness: NDArray[np.float64] | None = None
    transverse_mass_matrix: NDArray[np.float64] | None = None
    headings: NDArray[np.float64] | None = None
    heading_excitation: NDArray[np.complex128] | None = None

    def __post_init__(self) -> None:
        _validate(self)

    def save(self, path: str | Path) -> None:
        """Write an .npz of plain float64 arrays (no pickled objects)."""
        data: dict[str, Any] = {k: np.asarray(getattr(self, k), float) for k in _SCALARS}
        for k in ("omega", "wavenumber", *_MATRICES, *_FIXED):
            data[k] = np.asarray(getattr(self, k), dtype=float)
        data["modes"] = np.asarray(MODES, dtype=float)
        data |= _complex_parts("excitation", self.excitation)
        data.update({k: np.asarray(getattr(self, k), float) for k in _BOX_SCALARS
                     if math.isfinite(getattr(self, k))})  # fmt: skip
        if self.transverse_added_mass is not None:
            data.update({k: np.asarray(getattr(self, k), float) for k in _TRANSVERSE})
            data["transverse_modes"] = np.asarray(TRANSVERSE_MODES, dtype=float)
        if self.headings is not None:
            data["headings"] = np.asarray(self.headings, float)
            data |= _complex_parts("heading_excitation", self.heading_excitation)
        np.savez(path, **data)

    @classmethod
    def load(cls, path: str | Path = ISWEC_HULL_FILE) -> ThreeDofCoefficients:
        """Read a file written by `save`; ValueError naming the file if missing or inconsistent."""

        def read(z: Any) -> dict[str, Any]:
            kw: dict[str, Any] = {k: npz_array(z, k, 0) for k in _SCALARS}
            for k, nd in (("omega", 1), ("wavenumber", 1), ("added_mass", 3),
                          ("damping", 3), *((k, 2) for k in _FIXED)):  # fmt: skip
                kw[k] = npz_array(z, k, nd)
            if not np.array_equal(npz_array(z, "modes", 1), MODES):
                raise ValueError(f"modes: expected {MODES}")
            kw["excitation"] = _read_complex(z, "excitation", 2)
            return kw | _read_optional(z)

        kw = read_npz(path, MAX_MEMBER_BYTES, read, "a 3-dof coefficient file")
        return cls(**kw, name=str(Path(path)))

    @property
    def group_velocity(self) -> NDArray[np.float64]:
        """c_g = (w / 2k)(1 + 2kh / sinh 2kh) (m/s), finite depth."""
        kh2 = 2.0 * self.wavenumber * self.water_depth
        shoal = np.where(kh2 < 700.0, kh2 / np.sinh(np.minimum(kh2, 700.0)), 0.0)
        return self.omega / (2.0 * self.wavenumber) * (1.0 + shoal)

    def wave_power_flux(self, amplitude: float = 1.0) -> NDArray[np.float64]:
        """J = rho g a^2 c_g / 2 (W per metre of crest) of a regular wave at each omega."""
        return 0.5 * self.rho * self.g * amplitude**2 * self.group_velocity


def _complex_parts(name: str, x: NDArray[np.complex128]) -> dict[str, NDArray[np.float64]]:
    """A complex array as the file stores it: `name`_re and `name`_im, float64."""
    return {f"{name}_re": x.real.astype(float), f"{name}_im": x.imag.astype(float)}


def _read_complex(z: Any, name: str, ndim: int) -> NDArray[np.complex128]:
    """`name`_re + 1j `name`_im of an open archive (`npz_array`'s checks on each)."""
    return npz_array(z, f"{name}_re", ndim) + 1j * npz_array(z, f"{name}_im", ndim)


def _read_optional(z: Any) -> dict[str, Any]:
    """The optional box fields of an open archive (module docstring), those present."""
    kw: dict[str, Any] = {k: npz_array(z, k, 0) for k in _BOX_SCALARS if k in z.files}
    if "transverse_modes" in z.files:
        if not np.array_equal(npz_array(z, "transverse_modes", 1), TRANSVERSE_MODES):
            raise ValueError(f"transverse_modes: expected {TRANSVERSE_MODES}")
        kw.update({k: npz_array(z, k, nd) for k, nd in _TRANSVERSE.items()})
    if "headings" in z.files:
        kw["headings"] = npz_array(z, "headings", 1)
        kw["heading_excitation"] = _read_complex(z, "heading_excitation", 3)
    return kw


def _validate_optional(h: ThreeDofCoefficients) -> None:
    """Shapes and values of the optional box fields (all or none of each group)."""
    n, nw = h.name, np.asarray(h.omega).size
    present = [getattr(h, k) is not None for k in _TRANSVERSE]
    if any(present) and not all(present):
        raise ValueError(f"hull {n!r}: the transverse_* fields go together (all or none)")
    if (h.headings is None) != (h.heading_excitation is None):
        raise ValueError(f"hull {n!r}: headings and heading_excitation go together")
    shapes: dict[str, tuple[int, ...]] = {}
    if all(present):
        m = len(TRANSVERSE_MODES)
        shapes |= {k: (nw, m, m) if nd == 3 else (m, m) for k, nd in _TRANSVERSE.items()}
    if h.headings is not None:
        b = np.asarray(h.headings, dtype=float)
        if b.ndim != 1 or b.size < 2 or b[0] != 0.0 or not np.all(np.diff(b) > 0):
            raise ValueError(f"hull {n!r}: headings must start at 0 and increase (rad)")
        shapes["heading_excitation"] = (nw, b.size, 5)
    _check_shapes(h, shapes)


def _check_shapes(h: ThreeDofCoefficients, shapes: dict[str, tuple[int, ...]]) -> None:
    """ValueError naming the field unless each has its shape and finite values <= 1e20 (SI)."""
    for k, shape in shapes.items():
        v = np.asarray(getattr(h, k))
        if v.shape != shape:
            raise ValueError(f"hull {h.name!r}: {k} must have shape {shape}, got {v.shape}")
        if not np.all(np.isfinite(v)) or np.max(np.abs(v)) > 1e20:
            raise ValueError(f"hull {h.name!r}: {k} must be finite and |value| <= 1e20 (SI)")


def _validate(h: ThreeDofCoefficients) -> None:
    n, om = h.name, np.asarray(h.omega, dtype=float)
    if om.ndim != 1 or om.size < 4:
        raise ValueError(f"hull {n!r}: omega must be a 1-D table of >= 4 frequencies")
    if not (np.all(np.isfinite(om)) and om[0] > 0 and np.all(np.diff(om) > 0)):
        raise ValueError(f"hull {n!r}: omega must be > 0 and strictly increasing")
    m = len(MODES)
    shapes = dict(wavenumber=om.shape, added_mass=(om.size, m, m), damping=(om.size, m, m),
                  excitation=(om.size, m), added_mass_inf=(m, m), hydrostatic_stiffness=(m, m),
                  mass_matrix=(m, m))  # fmt: skip
    _check_shapes(h, shapes)
    box = math.isfinite(h.length) or math.isfinite(h.beam)  # a box's radius is nan
    positive = ("water_depth", "rho", "g", "draft", "gyration",
                *(_BOX_SCALARS if box else ("radius",)))  # fmt: skip
    for k in positive:
        v = getattr(h, k)
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"hull {n!r}: {k} must be > 0, got {v!r}")
    if not (math.isfinite(h.zg) and h.zg > -h.draft):
        raise ValueError(f"hull {n!r}: zg must be above the keel (> {-h.draft}), got {h.zg!r}")
    k = np.asarray(h.wavenumber)
    if not np.allclose(om**2, h.g * k * np.tanh(k * h.water_depth), rtol=1e-6):
        raise ValueError(f"hull {n!r}: wavenumber must solve w^2 = g k tanh(k h) at water_depth")
    _validate_optional(h)
    for pre in ("", "transverse_") if h.transverse_damping is not None else ("",):
        B, M = getattr(h, pre + "damping"), getattr(h, pre + "mass_matrix")
        if np.any(np.diagonal(B, axis1=1, axis2=2) < -1e-9 * np.max(np.abs(B))):
            raise ValueError(f"hull {n!r}: {pre}damping diagonal must be >= 0 (negative "
                             "radiation damping)")  # fmt: skip
        if np.any(np.diag(M) <= 0):
            raise ValueError(f"hull {n!r}: {pre}mass_matrix diagonal must be > 0")
