"""Soil contact for a planar beam or chain lying on deformable ground (Rios 2017, ch. 4 §4.5).

::

      body (width b, bottom surface at points (x, z))
    ~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~~  ground z = ground_z (z up)
          | sinkage Delta = ground_z - z > 0
          v  pressure p (Bekker, Eq. 56), shear tau (Janosi, Eq. 57) act on the body

Per unit length of the body (the contact patch is b wide), a point of the bottom surface in
contact carries the line loads (N/m, inertial frame, acting ON the body)

    f_z = b p(Delta),         p = (k_c / b + k_phi) Delta^n                          (Eq. 56)
    f_x = -b tau_max S(j),    tau_max = c + p tan(phi),  S(j) = sign(j)(1 - exp(-|j|/K))
                                                         (Eq. 57 with beta = 1/K)

where j is the slip (shear) displacement of the point along the ground accumulated since it
touched down. f_x opposes the slip; |f_x| -> b (c + p tan phi) for |j| >> K and d f_x / d j =
-b tau_max / K at j = 0 (S is C1 there, so zero slip needs no regularisation).

Regularisation (for Newton): for n < 1, dp/dDelta is infinite at Delta = 0, and the cohesion c
would switch on with a jump. Below a regularisation depth delta (`reg_depth`, default 10 um)
the pressure is the cubic Hermite blend p = k delta^n ((3 - n) t^2 + (n - 2) t^3), t = Delta/delta,
which matches p and dp/dDelta at delta, vanishes with zero slope at Delta = 0 and is increasing for
0 < n < 3; the cohesion is multiplied by the smoothstep s(t) = 3 t^2 - 2 t^3. Both loads are
therefore C1 in z across contact onset and exactly zero out of contact; above delta they are
Eqs. 56-57 unchanged. An optional normal damping c_n (Pa s/m) adds b c_n (-v_z) s(t) to f_z for
dynamic runs (it does not enter tau_max).

Slip history (what a Newton/FE user keeps): `SlipState(j, x_ref)` holds, per contact point, the
slip j and the x of the point at the last converged step. For a trial configuration x,
j_trial = j + (x - x_ref) where the point is in contact and 0 where it is not (a point that lifts
off forgets its slip). `TerrainContact.loads` returns the line loads, their derivatives with
respect to the point's z, x (and v_z), and the trial `SlipState(j_trial, x)`; keep the one from the
converged iterate as the state for the next step. The soil is nonlinear-elastic in the normal
direction (no rut memory) and the ground is flat.

Example (a 4-point patch, one Newton iteration's worth)::

    import numpy as np
    from mf_envs.physics.terrain import TerrainContact, SlipState, soil
    contact = TerrainContact(soil("dry_sand"), width=0.02)
    x = np.linspace(0.0, 0.1, 4); z = np.full(4, -0.002)          # 2 mm into the sand
    state = SlipState.at_rest(x)                                     # no slip yet
    out = contact.loads(x + 1e-3, z, state)                          # trial: slid 1 mm forward
    out.fz, out.fx                 # (4,) N/m on the body: up, and backwards (opposing the slip)
    out.dfz_dz, out.dfx_dx, out.dfx_dz  # (4,) N/m^2 for the tangent (dfz_dx = 0 on flat ground)
    state = out.slip                                                 # commit after convergence

Soil data: Wong, J. Y., *Theory of Ground Vehicles*, 4th ed., Wiley 2008, Table 2.3 (Bekker
terrain values: n, k_c, k_phi, c, phi; the same data are in the 3rd ed., 2001, the seed's
ref. [17]); shear deformation modulus K from Wong's §2.4 text values (about 1 cm for firm sand,
2.5 cm for loose sand, 0.6 cm for clay at maximum compaction) and, for LETE sand, Wong's
measured 1.2 cm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import (
    check_fields,
    check_finite,
    check_nonnegative,
    check_positive,
    finite_scalar,
    nonnegative_scalar,
    positive_scalar,
)
from mf_envs.physics.constants import G as STANDARD_GRAVITY


@dataclass(frozen=True)
class SoilParams:
    """Bekker-Janosi soil (SI units).

    k_c: cohesive modulus, N/m^(n+1); k_phi: frictional modulus, N/m^(n+2); n: sinkage exponent;
    cohesion: c, Pa; friction_angle: phi, rad; shear_deformation_modulus: K, m (Janosi).
    """

    k_c: float
    k_phi: float
    n: float
    cohesion: float
    friction_angle: float
    shear_deformation_modulus: float
    name: str = ""

    def __post_init__(self) -> None:
        check_nonnegative("k_c", self.k_c)
        check_nonnegative("k_phi", self.k_phi)
        if not 0.0 < positive_scalar("n", self.n) < 3.0:
            raise ValueError(f"n: must be in (0, 3), got {self.n!r}")
        check_nonnegative("cohesion", self.cohesion)
        if not 0.0 <= finite_scalar("friction_angle", self.friction_angle) < math.pi / 2:
            raise ValueError(
                f"friction_angle: must be in [0, pi/2) rad, got {self.friction_angle!r}"
            )
        check_positive("shear_deformation_modulus", self.shear_deformation_modulus)

    def modulus(self, width: float) -> float:
        """k_c / b + k_phi, N/m^(n+2), for contact width b (m) (Eq. 56)."""
        return self.k_c / width + self.k_phi


def _soil(
    name: str, n: float, kc: float, kphi: float, c: float, phi: float, K: float
) -> SoilParams:
    """Table units: k_c kN/m^(n+1), k_phi kN/m^(n+2), c kPa, phi deg; K m."""
    return SoilParams(kc * 1e3, kphi * 1e3, n, c * 1e3, math.radians(phi), K, name)


SOILS: dict[str, SoilParams] = {
    # Wong (2008) Table 2.3, dry sand (Land Locomotion Lab.), moisture 0 %; K: loose sand
    "dry_sand": _soil("dry_sand", 1.1, 0.99, 1528.43, 1.04, 28.0, 0.025),
    # Wong (2008) Table 2.3, sandy loam (LLL), moisture 15 %; K: firm sandy terrain
    "sandy_loam": _soil("sandy_loam", 0.7, 5.27, 1515.04, 1.72, 29.0, 0.01),
    # Wong (2008) Table 2.3, clayey soil (Thailand), moisture 38 %; K: clay
    "clay": _soil("clay", 0.5, 13.19, 692.15, 4.14, 13.0, 0.006),
    # Wong (2008) Table 2.3, LETE sand (Wong); K measured 1.2 cm
    "lete_sand": _soil("lete_sand", 0.79, 102.0, 5301.0, 1.3, 31.1, 0.012),
}


def soil(name: str) -> SoilParams:
    """A named soil preset from `SOILS` (ValueError naming `name` if unknown)."""
    if name not in SOILS:
        raise ValueError(f"name: unknown soil {name!r}; available: {', '.join(SOILS)}")
    return SOILS[name]


def bekker_pressure(soil: SoilParams, width: float, sinkage: ArrayLike) -> NDArray[np.float64]:
    """p = (k_c/b + k_phi) Delta^n, Pa, Eq. 56 without regularisation (0 for Delta <= 0)."""
    d = np.maximum(check_finite("sinkage", sinkage), 0.0)
    return soil.modulus(positive_scalar("width", width)) * d**soil.n


def plate_sinkage(soil: SoilParams, weight: float, width: float, length: float) -> float:
    """Static sinkage (m) of a rigid plate b x l (m) under weight W (N), Eq. 56 inverted:
    z = (W / (b l (k_c/b + k_phi)))^(1/n)."""
    b, l = positive_scalar("width", width), positive_scalar("length", length)
    W = nonnegative_scalar("weight", weight)
    return (W / (b * l * soil.modulus(b))) ** (1.0 / soil.n)


def gravity_line_load(mass_per_length: float, g: float = STANDARD_GRAVITY) -> NDArray[np.float64]:
    """(f_x, f_z) = (0, -m_A g), N/m: the seed's Eq. 99a with z up."""
    m = nonnegative_scalar("mass_per_length", mass_per_length)
    return np.array([0.0, -m * nonnegative_scalar("g", g)])


@dataclass(frozen=True)
class SlipState:
    """Per contact point: j (N,) m, slip since touch-down; x_ref (N,) m, x at the last step."""

    j: NDArray[np.float64]
    x_ref: NDArray[np.float64]

    @classmethod
    def at_rest(cls, x: ArrayLike) -> SlipState:
        """No slip yet, reference at the current x."""
        x = np.array(check_finite("x", x), dtype=np.float64)
        return cls(np.zeros_like(x), x)


@dataclass(frozen=True)
class ContactLoads:
    """Line loads on the body (N/m) and their derivatives (N/m^2; dfz_dvz in N s/m^2), all (N,).

    dfz_dx = 0 and dfx_dvz = 0 on flat ground. `slip` is the trial SlipState for this x.
    """

    fx: NDArray[np.float64]
    fz: NDArray[np.float64]
    dfx_dx: NDArray[np.float64]
    dfx_dz: NDArray[np.float64]
    dfz_dz: NDArray[np.float64]
    dfz_dvz: NDArray[np.float64]
    sinkage: NDArray[np.float64]
    pressure: NDArray[np.float64]
    in_contact: NDArray[np.bool_]
    slip: SlipState


@dataclass(frozen=True)
class TerrainContact:
    """Bekker/Janosi contact of a body of width b (m) with a flat ground at z = ground_z (m).

    reg_depth: delta, m (regularisation depth, module docstring); normal_damping: c_n, Pa s/m.
    """

    soil: SoilParams
    width: float
    ground_z: float = 0.0
    reg_depth: float = 1e-5
    normal_damping: float = 0.0

    def __post_init__(self) -> None:
        check_fields(self, positive=("width", "reg_depth"), finite=("ground_z",))
        check_nonnegative("normal_damping", self.normal_damping)

    def pressure(self, sinkage: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Regularised Bekker pressure p (Pa) and dp/dDelta (Pa/m) at sinkage Delta (m)."""
        d = np.asarray(sinkage, dtype=np.float64)
        k, n, dl = self.soil.modulus(self.width), self.soil.n, self.reg_depth
        deep = d >= dl
        dd = np.where(deep, d, dl)  # keeps the power finite where it is not used
        t = np.clip(d / dl, 0.0, 1.0)
        cap = k * dl**n
        p = np.where(deep, k * dd**n, cap * ((3 - n) * t**2 + (n - 2) * t**3))
        dp = np.where(
            deep, n * k * dd ** (n - 1), cap / dl * (2 * (3 - n) * t + 3 * (n - 2) * t**2)
        )
        return p, dp

    def _ramp(self, sinkage: NDArray[np.float64]) -> tuple[NDArray, NDArray]:
        """Smoothstep s(Delta/delta) and ds/dDelta."""
        t = np.clip(sinkage / self.reg_depth, 0.0, 1.0)
        return t * t * (3 - 2 * t), 6 * t * (1 - t) / self.reg_depth

    def loads(
        self, x: ArrayLike, z: ArrayLike, slip: SlipState, vz: ArrayLike | None = None
    ) -> ContactLoads:
        """Line loads at bottom-surface points (x, z) (N,) m, with vertical velocities vz (N,) m/s
        (only for normal damping), given the slip state of the last converged step."""
        x, z = check_finite("x", x), check_finite("z", z)
        if x.shape != z.shape or slip.j.shape != x.shape or slip.x_ref.shape != x.shape:
            raise ValueError(f"x, z, slip: shapes differ: {x.shape}, {z.shape}, {slip.j.shape}")
        vz = np.zeros_like(z) if vz is None else check_finite("vz", vz)
        b, so = self.width, self.soil
        sink = self.ground_z - z
        touch = sink > 0.0
        p, dp = self.pressure(sink)
        s, ds = self._ramp(sink)
        damp = self.normal_damping * np.where(touch, -vz, 0.0)
        fz = b * (p + damp * s)
        dfz_dz = -b * (dp + damp * ds)
        j = np.where(touch, slip.j + (x - slip.x_ref), 0.0)
        e = np.exp(-np.abs(j) / so.shear_deformation_modulus)
        S, dS = np.sign(j) * (1.0 - e), e / so.shear_deformation_modulus
        tan_phi = math.tan(so.friction_angle)
        tau_max = so.cohesion * s + tan_phi * p
        fx = -b * tau_max * S
        dfx_dx = np.where(touch, -b * tau_max * dS, 0.0)
        dfx_dz = b * (so.cohesion * ds + tan_phi * dp) * S
        dfz_dvz = np.where(touch, -b * self.normal_damping * s, 0.0)
        return ContactLoads(
            fx,
            fz,
            dfx_dx,
            dfx_dz,
            dfz_dz,
            dfz_dvz,
            np.maximum(sink, 0.0),
            p,
            touch,
            SlipState(j, x.copy()),
        )
