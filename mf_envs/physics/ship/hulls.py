"""Hulls: every coefficient the user's, in one documented dataclass, and two presets.

`Hull` holds every number the ship model uses (body frame e_1 forward, e_2 port, e_3 up; about
the centre of mass; SI units). Nothing is filled in behind the user's back: `Hull(...)` takes
each field as given, `Hull.yacht()` and `Hull.mss_naval_vessel()` are presets whose every field
is documented below, and `dataclasses.replace(hull, roll_stiffness=...)` keeps the GZ *shape*
(gz_bm_over_gm, gz_cubic are ratios to the linear term), so the restoring moment's slope at
zero roll is always `roll_stiffness`:

    K(phi) = -C44 [s(phi) + gz_cubic phi^3],
    s(phi) = sin(phi) (1 + (BM/GM)/2 tan^2 phi)  (wall-sided, gz_bm_over_gm = BM/GM > 0)
           = phi                                  (gz_bm_over_gm = 0)

so GZ(phi) = GM [s(phi) + gz_cubic phi^3] with C44 = rho g V GM. MSS writes the cubic as
K_phiphiphi phi^3 = -gz_cubic C44 phi^3.

Roll damping: -B44 p - B44q |p| p (MSS's K_p and K_|p|p), plus the forward-speed term MSS
calls K_|u|p: -roll_damping_speed |U| p.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs._validate import check_positive, nonnegative_scalar
from mf_envs.physics.constants import RHO_SEAWATER, G
from mf_envs.physics.ship.params import ShipParams, roll_inertia_of

RHO_SEA = RHO_SEAWATER  # kg/m^3, sea water (the yacht); MSS uses 1014
G_MSS = G  # m/s^2, navalvessel.m's const.g (= 9.81)


@dataclass(frozen=True)
class Hull:
    """Every hull coefficient (module doc). Fields and units:

    mass: displacement mass m = rho V, kg.
    inertia: (J44, J55, J66) rigid-body roll, pitch, yaw inertia about the CM, kg m^2.
    added_roll_inertia: A44 = -K_pdot, kg m^2.
    roll_stiffness: C44 = rho g V GM, N m/rad.
    gz_bm_over_gm: BM/GM of a wall-sided GZ (0: no wall-sided term), dimensionless.
    gz_cubic: cubic GZ term over GM, 1/rad^2 (MSS: -K_phiphiphi / C44).
    roll_damping: B44 = -K_p, N m s/rad; roll_damping_quadratic: B44q = -K_|p|p, N m s^2/rad^2;
    roll_damping_speed: -K_|u|p, N m s^2/(rad m) (times |U|).
    pitch_stiffness: C55 = rho g V GM_L, N m/rad; pitch_damping: B55, N m s/rad.
    yaw_damping: B66, N m s/rad.
    heave_stiffness: rho g A_wp, N/m; heave_damping: N s/m; surge_sway_damping: N s/m.
    length: waterline length L_wl, m; beam: B, m (wave excitation, `ship.seas`).
    effective_slope: r_eff of the wave roll moment, dimensionless (`ship.seas`).
    """

    mass: float
    inertia: tuple[float, float, float]
    added_roll_inertia: float
    roll_stiffness: float
    gz_bm_over_gm: float
    gz_cubic: float
    roll_damping: float
    roll_damping_quadratic: float
    roll_damping_speed: float
    pitch_stiffness: float
    pitch_damping: float
    yaw_damping: float
    heave_stiffness: float
    heave_damping: float
    surge_sway_damping: float
    length: float
    beam: float
    effective_slope: float

    def __post_init__(self) -> None:
        inertia = check_positive("inertia", self.inertia)
        if inertia.shape != (3,):
            raise ValueError(f"inertia: expected 3 principal inertias, got {self.inertia!r}")
        object.__setattr__(self, "inertia", tuple(float(v) for v in inertia))
        check_positive("mass", self.mass)
        for name, value in asdict(self).items():
            if name not in ("mass", "inertia"):
                object.__setattr__(self, name, nonnegative_scalar(name, value))

    # ------------------------------------------------------------------ presets
    @classmethod
    def yacht(
        cls,
        displacement: float = 18000.0,
        beam: float = 4.2,
        gm: float = 0.9,
        gm_longitudinal: float = 25.0,
        length_wl: float = 11.5,
        roll_damping_method: str = "rule_of_thumb",
        speed: float = 0.0,
    ) -> Hull:
        """The default 18 t, 12-13 m motor yacht (GyroStabilizer-v0). Field by field:

        mass 18 000 kg; L_wl 11.5 m; beam 4.2 m; GM 0.9 m, GM_L 25 m (assumed loading).
        J44 = m (0.38 B)^2 = 45 850 kg m^2 (roll radius of gyration 0.38 B, in the 0.35-0.45 B
        range of Fossen 2011 §4.3); J55 = m (0.25 L)^2, J66 = 1.1 J55.
        A44 = 0.2 J44 = 9 170 kg m^2 (10-30 % of J44 for small craft, rule of thumb).
        C44 = m g GM = 158 900 N m/rad; wall-sided GZ with BM = I_wp / V (C_wp = 0.75),
        BM/GM = 3.37; gz_cubic 0.
        B44 = 2 x 0.04 sqrt(C44 (J44 + A44)) (damping ratio 0.04, Himeno 1981 range),
        B44q = 2.5 B44 s/rad (Himeno ranges), no speed term.
        C55 = m g GM_L; B55 = 0.4 sqrt(C55 J55); B66 = 0.1 B44 J66 / J44.
        heave: rho g A_wp (C_wp = 0.75), damping ratio 0.2; surge/sway damping 0.05 m 1/s.
        effective_slope 0.7. These are rules of thumb (no published yacht data);
        `mss_naval_vessel` is the hull with published coefficients.

        roll_damping_method="ikeda": B44 and B44q instead from the simplified Ikeda method
        (`yacht_ikeda_damping`, at ship speed `speed` in m/s); B66 keeps the rule of thumb.
        """
        m, b, gml, lwl = displacement, beam, gm_longitudinal, length_wl
        for name, value in (("displacement", m), ("beam", b), ("gm", gm),
                            ("gm_longitudinal", gml), ("length_wl", lwl)):  # fmt: skip
            check_positive(name, value)
        j44 = m * (0.38 * b) ** 2
        j55 = m * (0.25 * lwl) ** 2
        j66 = 1.1 * j55
        a44 = 0.2 * j44
        c44, c55 = m * G * gm, m * G * gml
        b44 = 2.0 * 0.04 * math.sqrt(c44 * (j44 + a44))
        b44_lin, b44_quad = b44, 2.5 * b44
        if roll_damping_method == "ikeda":
            tn = 2.0 * math.pi * math.sqrt((j44 + a44) / c44)
            b44_lin, b44_quad = yacht_ikeda_damping(lwl, b, m, tn, speed)
        elif roll_damping_method != "rule_of_thumb":
            raise ValueError(
                f"hull_damping: must be 'ikeda' or 'rule_of_thumb', got {roll_damping_method!r}"
            )
        awp = 0.75 * lwl * b
        bm = 0.75 * lwl * b**3 / (12.0 * m / RHO_SEA)
        return cls(
            mass=m,
            inertia=(j44, j55, j66),
            added_roll_inertia=a44,
            roll_stiffness=c44,
            gz_bm_over_gm=bm / gm,
            gz_cubic=0.0,
            roll_damping=b44_lin,
            roll_damping_quadratic=b44_quad,
            roll_damping_speed=0.0,
            pitch_stiffness=c55,
            pitch_damping=2.0 * 0.2 * math.sqrt(c55 * j55),
            yaw_damping=0.1 * b44 * j66 / j44,
            heave_stiffness=RHO_SEA * G * awp,
            heave_damping=2.0 * 0.2 * math.sqrt(RHO_SEA * G * awp * m),
            surge_sway_damping=0.05 * m,
            length=lwl,
            beam=b,
            effective_slope=0.7,
        )

    @classmethod
    def mss_naval_vessel(cls) -> Hull:
        """The 51.5 m multipurpose naval vessel of Blanke & Christensen (1993), as coded in
        Fossen's Marine Systems Simulator (MSS, `VESSELS/navalvessel.m`). Field by field:

        rho 1014 kg/m^3, V 357 m^3 -> mass 361 998 kg; L_pp 51.5 m, B 8.6 m (L_wl := L_pp).
        J44 = I_xx = 2.3763e6, J66 = I_zz = 47.934e6 kg m^2; A44 = -K_pdot = 7.74e5 kg m^2.
        C44 = rho g V GM, GM = 1.1 m; restoring exactly as navalvessel.m: linear + K_bbb phi^3,
        K_bbb = -0.325 m g -> gz_cubic = 0.325 / 1.1 = 0.2955 (no wall-sided term).
        B44 = -K_p = 5.0e5 N m s; B44q = -K_pap = 4.16e5 N m s^2; -K_aup = 1.55e4 (speed term).
        Not in navalvessel.m (surge-sway-roll-yaw only), filled in and marked so:
        J55 := J66; C55 = rho g V BM_L with BM_L = C_wp L^3 B / (12 V), C_wp = 0.75;
        B55 = 0.4 sqrt(C55 J55); B66 := 0 (yaw damping is speed-dependent in MSS: N_|u|r);
        heave rho g A_wp, damping ratio 0.2; surge/sway 1.96e3 N s/m (MSS X_|u|u per m/s);
        effective_slope 1.0 (narrow-hull limit).
        """
        rho, lpp, b, vol = 1014.0, 51.5, 8.6, 357.0
        m = rho * vol
        c44 = rho * G_MSS * vol * 1.1
        bml = 0.75 * lpp**3 * b / 12.0 / vol
        c55 = rho * G_MSS * vol * bml
        awp = 0.75 * lpp * b
        return cls(
            mass=m,
            inertia=(2.3763e6, 47.934e6, 47.934e6),
            added_roll_inertia=7.74e5,
            roll_stiffness=c44,
            gz_bm_over_gm=0.0,
            gz_cubic=0.325 / 1.1,
            roll_damping=5.0e5,
            roll_damping_quadratic=4.16e5,
            roll_damping_speed=1.55e4,
            pitch_stiffness=c55,
            pitch_damping=0.4 * math.sqrt(c55 * 47.934e6),
            yaw_damping=0.0,
            heave_stiffness=rho * G_MSS * awp,
            heave_damping=0.4 * math.sqrt(rho * G_MSS * awp * m),
            surge_sway_damping=1.96e3,
            length=lpp,
            beam=b,
            effective_slope=1.0,
        )

    # ------------------------------------------------------------------ quantities
    def restoring_moment(self, phi: ArrayLike) -> NDArray[np.float64]:
        """K(phi) = -C44 [s(phi) + gz_cubic phi^3] (N m) at roll phi (rad), module doc."""
        p = np.asarray(phi, dtype=np.float64)
        if self.gz_bm_over_gm > 0.0:
            t2 = np.minimum(np.tan(np.clip(p, -1.4, 1.4)) ** 2, math.tan(1.4) ** 2)
            s = np.sin(p) * (1.0 + 0.5 * self.gz_bm_over_gm * t2)
        else:
            s = p
        return -self.roll_stiffness * (s + self.gz_cubic * p**3)

    def roll_damping_moment(self, p: ArrayLike, speed: float = 0.0) -> NDArray[np.float64]:
        """-(B44 + K_|u|p |U|) p - B44q |p| p (N m) at roll rate p (rad/s), speed U (m/s)."""
        p = np.asarray(p, dtype=np.float64)
        b = self.roll_damping + self.roll_damping_speed * abs(speed)
        return -b * p - self.roll_damping_quadratic * np.abs(p) * p

    def roll_inertia(self, added_inertia: bool = True) -> float:
        """J44 + A44 (kg m^2; `params.roll_inertia_of`)."""
        return roll_inertia_of(self, added_inertia)

    def natural_roll_period(self) -> float:
        """T_n = 2 pi sqrt((J44 + A44) / C44), s (inf without restoring)."""
        if self.roll_stiffness <= 0.0:
            return math.inf
        return 2.0 * math.pi * math.sqrt(self.roll_inertia() / self.roll_stiffness)

    def ship_params(self) -> ShipParams:
        """The `ShipParams` of the kernels (fields it has; gz_cubic, speed damping, length, beam
        and effective_slope are read from the hull by the seas and the env)."""
        return ShipParams(
            inertia=self.inertia,
            mass=self.mass,
            added_roll_inertia=self.added_roll_inertia,
            roll_stiffness=self.roll_stiffness,
            pitch_stiffness=self.pitch_stiffness,
            gz_bm_over_gm=self.gz_bm_over_gm,
            roll_damping=self.roll_damping,
            roll_damping_quadratic=self.roll_damping_quadratic,
            pitch_damping=self.pitch_damping,
            yaw_damping=self.yaw_damping,
            heave_stiffness=self.heave_stiffness,
            heave_damping=self.heave_damping,
            surge_sway_damping=self.surge_sway_damping,
        )


# the yacht's particulars for Ikeda's method (docs/stabilizer_physics.md, "Roll damping"): the
# simplified method's range is 2.5 <= B/d <= 4.5, 0.5 <= Cb <= 0.85, 0.9 <= Cm <= 0.99; an 18 t,
# 11.5 x 4.2 m hull has Cb = V / (L B d) = 0.39 at B/d = 4.5 (and less deeper), below it, where
# the wave-damping regression collapses (damping ratio 0.002). Chosen: d = B / 4.5, Cb and Cm at
# the range's edge (0.5, 0.9), OG = -0.4 m (G 0.4 m above the waterline), no bilge keels,
# roll amplitude 10 deg (the design roll of the drive sizing) at the natural roll period.
YACHT_IKEDA = {"b_over_d": 4.5, "cb": 0.5, "cm": 0.9, "og": -0.4, "amplitude_deg": 10.0}


def yacht_ikeda_damping(
    length: float, beam: float, mass: float, roll_period: float, speed: float = 0.0
) -> tuple[float, float]:
    """(B44 in N m s/rad, B44q in N m s^2/rad^2) of a yacht hull by the simplified Ikeda
    method (`ship.roll_damping`, Kawahara, Maekawa & Ikeda 2011) with the particulars
    `YACHT_IKEDA` at the roll period (s) and ship speed (m/s); split by
    `RollDamping.linear_quadratic`. The displacement `mass` only scales the result: nabla =
    mass / rho replaces Cb L B d (the method's non-dimensional damping is per rho nabla B^2)."""
    from mf_envs.physics.ship.roll_damping import HullParticulars, roll_damping

    p = YACHT_IKEDA
    h = HullParticulars(length, beam, beam / p["b_over_d"], p["cb"], p["cm"], p["og"],
                        roll_period, math.radians(p["amplitude_deg"]), speed=speed)  # fmt: skip
    r = roll_damping(h, validity="ignore")  # on the range's edge (B/d = 4.5 to round-off)
    lin, quad = r.linear_quadratic()
    f = (mass / RHO_SEA) / h.displacement_volume  # the hull's own displacement
    return lin * f, quad * f


def roll_decay(
    hull: Hull, roll0: float, t_end: float, n_out: int = 4001, speed: float = 0.0
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """(t, roll) of the free 1-DOF roll decay (J44 + A44) phi'' = K(phi) + damping (module doc)
    from rest at roll0 (rad), by scipy's DOP853 at rtol 1e-11 (the reference of the tests)."""
    from scipy.integrate import solve_ivp

    check_positive("t_end", t_end)
    j = hull.roll_inertia()

    def rhs(t: float, x: NDArray) -> list[float]:
        m = hull.restoring_moment(x[0]) + hull.roll_damping_moment(x[1], speed)
        return [x[1], float(m) / j]

    t = np.linspace(0.0, t_end, n_out)
    sol = solve_ivp(rhs, (0.0, t_end), [roll0, 0.0], "DOP853", t, rtol=1e-11, atol=1e-14)
    return sol.t, sol.y[0]


def small_yacht(
    displacement: float = 18000.0,
    beam: float = 4.2,
    gm: float = 0.9,
    gm_longitudinal: float = 25.0,
    length_wl: float = 11.5,
) -> ShipParams:
    """The kernels' `ShipParams` of `Hull.yacht` (the same arguments): an 18 t, 12-13 m motor
    yacht by rules of thumb, roll period with added inertia 3.71 s."""
    return Hull.yacht(displacement, beam, gm, gm_longitudinal, length_wl).ship_params()


def mss_naval_vessel() -> ShipParams:
    """The kernels' `ShipParams` of `Hull.mss_naval_vessel` (Blanke & Christensen 1993, Fossen's
    MSS `navalvessel.m`): roll period 5.64 s."""
    return Hull.mss_naval_vessel().ship_params()
