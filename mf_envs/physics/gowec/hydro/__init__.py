"""Hydrodynamic coefficients of a floating GOWEC hull (BEM, linear potential flow).

Not in the seed (Rios 2017 ch. 3 Sec. 3.2.6 prescribes the buoy and notes that "for larger scale
computations with a known buoy geometry, the impedance matrix must be accounted for"). Here a
hull is described by its pitch coefficients about the centre of gravity G, one rotational degree
of freedom (the hull is axisymmetric, so roll has the same coefficients; a box's roll is a second
table of this form, `axes.roll_hull`; surge-pitch coupling is not modelled here: the buoy rotates
about G, its translation is held by the mooring; `three_dof` has the coupled tables):

    A(w)  added inertia (kg m^2)            A_inf = A(w -> inf), A_0 = A(w -> 0)
    B(w)  radiation damping (N m s/rad)     B >= 0, B -> 0 at both ends
    X(w)  excitation moment per metre of wave amplitude (N m/m, complex) about the y axis for a
          regular wave travelling along +x, eta(0, t) = Re(a e^{-i w t})  (Capytaine's
          convention): M(t) = Re(X a e^{-i w t})
    C     hydrostatic pitch stiffness C55 = rho g (I_wp + V z_B) - m g z_G (N m/rad)

The shipped default hull (`cylinder_r2p5_converged.npz`, made by `scripts/compute_hydro.py` with
Capytaine on a keel-graded mesh) is a vertical cylinder: radius 2.5 m, draft 2.0 m,
z_G = -0.6 m, pitch radius of gyration 1.5 m. The earlier 768-panel table of the same hull
(B55 18-56 % low at 1-2.5 rad/s) is no longer shipped: it fails the Haskind check;
tests/data/legacy_hull_768_panels.npz keeps it as a regression fixture.
Files are `.npz` read with `allow_pickle=False` (nothing loaded executes code).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from mf_envs._files import npz_array, read_npz
from mf_envs.physics.constants import RHO_SEAWATER, G

# the converged mesh's coefficients (the seed buoy's hull, `devices`)
DEFAULT_HULL_FILE = Path(__file__).with_name("cylinder_r2p5_converged.npz")
RHO = RHO_SEAWATER  # kg/m^3, what the BEM runs use (the seed's Eq. 15 uses 1020)

_ARRAYS = ("omega", "added_mass", "damping", "excitation")
_SCALARS = (
    "added_mass_inf",
    "added_mass_zero",
    "stiffness",
    "inertia",
    "mass",
    "rho",
    "g",
    "radius",
    "draft",
    "zg",
)


def _check_geometry(hull: Any, names: tuple[str, ...]) -> None:
    """ValueError naming the field unless each of `names` is a finite number > 0 and zg is
    finite and above the keel (> -draft)."""
    for name in names:
        v = getattr(hull, name)
        if not (isinstance(v, (int, float)) and math.isfinite(v) and v > 0):
            raise ValueError(f"hull.{name}: must be > 0, got {v!r}")
    if not (math.isfinite(hull.zg) and -hull.draft < hull.zg):
        raise ValueError(f"hull.zg: must be above the keel (> {-hull.draft}), got {hull.zg}")


class _FreeFloating:
    """A wall-sided hull floating freely (m = rho V) with its centre of buoyancy at half the
    draft: what the cylinder and the box share (each gives `volume`, `draft`, `zg`)."""

    volume: float
    draft: float
    zg: float

    @property
    def zb(self) -> float:
        """Centre of buoyancy z_B = -d/2 (m)."""
        return -0.5 * self.draft

    def mass(self, rho: float = RHO) -> float:
        """m = rho V (kg), freely floating."""
        return rho * self.volume

    def _restoring(self, waterplane_inertia: float, rho: float, g: float) -> float:
        """rho g (I_wp + V z_B) - m g z_G (N m/rad): the hydrostatic restoring moment about an
        axis whose waterplane second moment is I_wp."""
        return rho * g * (waterplane_inertia + self.volume * self.zb) - self.mass(rho) * g * self.zg


@dataclass(frozen=True)
class CylinderHull(_FreeFloating):
    """A vertical circular cylinder floating upright: radius (m), draft (m), centre of gravity
    height zg (m, still water line 0, negative below), pitch radius of gyration about G (m).
    Freely floating: mass = rho V."""

    radius: float = 2.5
    draft: float = 2.0
    zg: float = -0.6
    gyration: float = 1.5

    def __post_init__(self) -> None:
        _check_geometry(self, ("radius", "draft", "gyration"))

    @property
    def volume(self) -> float:
        """Displaced volume V = pi r^2 d (m^3)."""
        return math.pi * self.radius**2 * self.draft

    @property
    def waterplane_inertia(self) -> float:
        """I_wp = pi r^4 / 4 (m^4), second moment of the waterplane about a diameter."""
        return 0.25 * math.pi * self.radius**4

    def inertia(self, rho: float = RHO) -> float:
        """Rigid-body pitch inertia about G, m k^2 (kg m^2)."""
        return self.mass(rho) * self.gyration**2

    def stiffness(self, rho: float = RHO, g: float = G) -> float:
        """C55 = rho g (I_wp + V z_B) - m g z_G (N m/rad), from the geometry alone."""
        return self._restoring(self.waterplane_inertia, rho, g)


@dataclass(frozen=True)
class BoxHull(_FreeFloating):
    """A rectangular box floating level: length along x (the head-wave direction), beam along y,
    draft (m), centre of gravity height zg (m, still water line 0), radii of gyration about G for
    pitch (y axis) and roll (x axis) (m). Freely floating: mass = rho V. The default is ISWEC's
    Pantelleria hull (15 x 8 m, 3.2 m draft; sources in docs/gowec_v1.md) with chosen mass
    properties (none published that could be read): zg = -0.5 m as the cylinder stand-in's, and the
    gyration radii of a solid box of the hull's full 4.5 m height, k^2 = (L^2 + H^2) / 12 for
    pitch and (B^2 + H^2) / 12 for roll (docs/gowec_v1.md, "ISWEC's box hull")."""

    length: float = 15.0
    beam: float = 8.0
    draft: float = 3.2
    zg: float = -0.5
    gyration: float = math.sqrt((15.0**2 + 4.5**2) / 12.0)  # 4.521 m
    roll_gyration: float = math.sqrt((8.0**2 + 4.5**2) / 12.0)  # 2.648 m

    def __post_init__(self) -> None:
        _check_geometry(self, ("length", "beam", "draft", "gyration", "roll_gyration"))

    @property
    def volume(self) -> float:
        """Displaced volume V = L B d (m^3)."""
        return self.length * self.beam * self.draft

    @property
    def waterplane_area(self) -> float:
        """A_wp = L B (m^2)."""
        return self.length * self.beam

    def waterplane_inertia(self, axis: str = "pitch") -> float:
        """Second moment of the waterplane (m^4) about the y axis (pitch, B L^3 / 12) or the
        x axis (roll, L B^3 / 12)."""
        if axis not in ("pitch", "roll"):
            raise ValueError(f"axis: expected 'pitch' or 'roll', got {axis!r}")
        a, b = (self.beam, self.length) if axis == "pitch" else (self.length, self.beam)
        return a * b**3 / 12.0

    def inertia(self, rho: float = RHO, axis: str = "pitch") -> float:
        """Rigid-body inertia about G (kg m^2), m k^2 with k the pitch or roll gyration."""
        k = self.gyration if axis == "pitch" else self.roll_gyration
        return self.mass(rho) * k**2

    def stiffness(self, rho: float = RHO, g: float = G, axis: str = "pitch") -> float:
        """C55 (pitch) or C44 (roll) = rho g (I_wp + V z_B) - m g z_G (N m/rad), z_B = -d/2:
        exact for a box."""
        return self._restoring(self.waterplane_inertia(axis), rho, g)


MAX_MEMBER_BYTES = 16 << 20  # one array of a hull file (a 1,000-frequency table is 8 KB)
MAX_COEFFICIENT = 1e20  # SI; the largest ships' pitch stiffness and inertia are ~1e11-1e12


@dataclass(frozen=True)
class HullCoefficients:
    """Pitch coefficients of a hull about G (module docstring for conventions and units).

    omega (n,) rad/s strictly increasing > 0; added_mass (n,) kg m^2; damping (n,) N m s/rad
    (>= 0); excitation (n,) complex N m/m; scalars as named (SI); radius, draft, zg (m) describe
    the geometry for drawing and checks (nan if unknown). `name` labels the source in messages.
    """

    omega: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    excitation: NDArray[np.complex128]
    added_mass_inf: float
    added_mass_zero: float
    stiffness: float
    inertia: float
    mass: float
    rho: float = RHO
    g: float = G
    radius: float = math.nan
    draft: float = math.nan
    zg: float = math.nan
    name: str = field(default="hull")

    def __post_init__(self) -> None:
        _validate(self)

    # ------------------------------------------------------------------ file io
    def save(self, path: str | Path) -> None:
        """Write an .npz of plain arrays (no pickled objects)."""
        data: dict[str, Any] = {k: np.asarray(getattr(self, k), dtype=float) for k in _SCALARS}
        for k in _ARRAYS[:3]:
            data[k] = np.asarray(getattr(self, k), dtype=float)
        data["excitation_re"] = self.excitation.real.astype(float)
        data["excitation_im"] = self.excitation.imag.astype(float)
        np.savez(path, **data)

    @classmethod
    def load(cls, path: str | Path) -> HullCoefficients:
        """Read a file written by `save`; ValueError naming the file if missing or inconsistent."""

        def read(z: Any) -> dict[str, Any]:
            kw: dict[str, Any] = {k: npz_array(z, k, 0) for k in _SCALARS}
            for k in _ARRAYS[:3]:
                kw[k] = npz_array(z, k, 1)
            kw["excitation"] = npz_array(z, "excitation_re", 1) + 1j * npz_array(
                z, "excitation_im", 1
            )
            return kw

        kw = read_npz(path, MAX_MEMBER_BYTES, read, "a hull coefficient file")
        return cls(**kw, name=str(Path(path)))

    # ------------------------------------------------------------------ interpolation
    def at(self, w: float) -> tuple[float, float, complex]:
        """(A, B, X) at w (rad/s), linear interpolation (clamped to the table; A -> A_inf,
        B, X -> 0 above it, A -> A_0, B, X -> 0 below it)."""
        om = self.omega
        if w >= om[-1]:
            return self.added_mass_inf, 0.0, 0j
        A = float(np.interp(w, om, self.added_mass, left=self.added_mass_zero))
        B = float(np.interp(w, om, self.damping, left=0.0))
        X = complex(
            np.interp(w, om, self.excitation.real, left=0.0)
            + 1j * np.interp(w, om, self.excitation.imag, left=0.0)
        )
        return A, B, X

    def impedance(self, w: float) -> complex:
        """Intrinsic pitch impedance Z_h = B + i (w (I + A) - C / w) (N m s/rad), so that the
        velocity response is Theta' = M / Z_h (e^{+i w t} convention)."""
        A, B, _ = self.at(w)
        return complex(B, w * (self.inertia + A) - self.stiffness / w)

    def rao(self, w: float) -> float:
        """|Theta| / a = |X| / |-w^2 (I + A) + i w B + C| (rad/m), rotor off."""
        A, B, X = self.at(w)
        return abs(X) / abs(complex(-(w**2) * (self.inertia + A) + self.stiffness, w * B))

    def natural_frequency(self, inertia: float | None = None) -> float:
        """w_n solving w^2 (I + A(w)) = C (rad/s), by fixed-point iteration on the table; I is
        the hull's own pitch inertia unless `inertia` (kg m^2, e.g. hull + gyros) is given."""
        inertia = self.inertia if inertia is None else inertia
        w = math.sqrt(self.stiffness / (inertia + self.added_mass_inf))
        for _ in range(200):
            w_new = math.sqrt(self.stiffness / (inertia + self.at(w)[0]))
            if abs(w_new - w) < 1e-13 * w:
                break
            w = w_new
        return w_new


def _validate(h: HullCoefficients) -> None:
    n = h.name
    om = np.asarray(h.omega, dtype=float)
    if om.ndim != 1 or om.size < 4:
        raise ValueError(f"hull {n!r}: omega must be a 1-D table of >= 4 frequencies")
    for k in ("added_mass", "damping", "excitation"):
        if np.shape(getattr(h, k)) != om.shape:
            raise ValueError(f"hull {n!r}: {k} must have the shape of omega {om.shape}")
        if not np.all(np.isfinite(getattr(h, k))):
            raise ValueError(f"hull {n!r}: {k} must be finite")
    if not (np.all(np.isfinite(om)) and om[0] > 0 and np.all(np.diff(om) > 0)):
        raise ValueError(f"hull {n!r}: omega must be > 0 and strictly increasing")
    if np.any(np.asarray(h.damping) < 0):
        raise ValueError(f"hull {n!r}: damping must be >= 0 (negative radiation damping)")
    for k in ("stiffness", "inertia", "mass", "rho", "g"):
        v = getattr(h, k)
        if not (math.isfinite(v) and v > 0):
            raise ValueError(f"hull {n!r}: {k} must be > 0, got {v!r}")
    for k in ("added_mass_inf", "added_mass_zero"):
        if not math.isfinite(getattr(h, k)):
            raise ValueError(f"hull {n!r}: {k} must be finite")
    if h.inertia + h.added_mass_inf <= 0:
        raise ValueError(f"hull {n!r}: inertia + added_mass_inf must be > 0")
    for k in (*_ARRAYS[:3], "excitation", "stiffness", "inertia", "mass", "added_mass_inf",
              "added_mass_zero"):  # fmt: skip
        big = float(np.max(np.abs(getattr(h, k))))
        if big > MAX_COEFFICIENT:  # 1e308 passes isfinite, then overflows in C (I + A)
            raise ValueError(
                f"hull {n!r}: {k} reaches {big:.3g}, beyond any floating body "
                f"(|value| <= {MAX_COEFFICIENT:g} in SI units)"
            )


def load_hull(hull: HullCoefficients | str | Path | None = None) -> HullCoefficients:
    """The hull to simulate: None = the shipped default, a path = an .npz written by
    `HullCoefficients.save` (e.g. by `from_capytaine`), or coefficients as they are."""
    if hull is None:
        return HullCoefficients.load(DEFAULT_HULL_FILE)
    if isinstance(hull, HullCoefficients):
        return hull
    if isinstance(hull, (str, Path)):
        return HullCoefficients.load(hull)
    raise ValueError(f"hull: expected None, a path or HullCoefficients, got {type(hull).__name__}")


def from_capytaine(*args: Any, **kwargs: Any) -> HullCoefficients:
    """Run Capytaine on a hull (needs the `hydro` extra); see `hydro.bem.from_capytaine`."""
    from mf_envs.physics.gowec.hydro.bem import from_capytaine as _f

    return _f(*args, **kwargs)


__all__ = [
    "DEFAULT_HULL_FILE",
    "CylinderHull",
    "HullCoefficients",
    "from_capytaine",
    "load_hull",
]
