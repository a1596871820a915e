"""Roll damping from hull particulars: Ikeda's method in the simplified form of Kawahara,
Maekawa & Ikeda (2011), with Ikeda's forward-speed corrections (docs/stabilizer_physics.md).

Non-dimensional damping (Kawahara et al. 2011; ITTC 7.5-02-07-04.5):

    B44_hat = B44 / (rho nabla B^2) * sqrt(B / (2 g)),   omega_hat = omega sqrt(B / (2 g)),

nabla = L B d Cb. Components at zero speed (Kawahara, Maekawa & Ikeda 2011, "A simple
prediction formula of roll damping of conventional cargo ships on the basis of Ikeda's method
and its limitation", in *Contemporary Ideas on Ship Stability and Capsizing in Waves*,
Springer, pp. 465-486; the coefficients as in the authors' program Roll_Damping.for, 2009):

- friction B_F (Kato's formula): r_f = d [(0.887 + 0.145 Cb)(1.7 + Cb B/d) - 2 OG/d] / pi,
  S_f = L (1.75 d + Cb B), C_f = 1.328 (3.22 r_f^2 phi_a^2 / (T nu))^(-1/2),
  B_F = 4/(3 pi) rho S_f r_f^3 phi_a omega C_f;
- wave B_W: a regression in (B/d, Cb, Cm, 1 - OG/d, omega_hat) (`_wave_hat`);
- eddy B_E: 4 omega_hat phi_a C_R / (3 pi Cb (B/d)^3) with the regression C_R (`_eddy_hat`);
- bilge keel B_BK: a regression in (bBK/B, lBK/L, B/d, Cb, Cm, OG/d, phi_a in deg) x omega_hat.

OG is the distance from the still-water level O down to the roll axis G (positive downward).
Forward speed U (Ikeda, Himeno & Tanaka 1978, as summarised in Himeno 1981 and ITTC
7.5-02-07-04.5): B_F (1 + 4.1 U / (omega L)); the wave damping times
0.5 [A2 + 1 + (A2 - 1) tanh(20 (W - 0.3)) + (2 A1 - A2 - 1) exp(-150 (W - 0.25)^2)],
W = U omega / g, xi = omega^2 d / g, A1 = 1 + xi^-1.2 e^(-2 xi), A2 = 0.5 + xi^-1 e^(-2 xi);
the eddy damping times K^2 / (1 + K^2), K = 0.04 omega L / U; and the hull-lift damping

    B_L = rho/2 L d U k_N l_0 l_R [1 - 1.4 OG / l_R + 0.7 OG^2 / (l_0 l_R)],
    k_N = 2 pi d / L + kappa (4.1 B / L - 0.045), kappa = 106 (Cm - 0.91)^2 - 700 (Cm - 0.91)^3,
    l_0 = 0.3 d, l_R = 0.5 d.

Validity (Kawahara et al. 2011, and the input checks of their program): 2.5 <= B/d <= 4.5,
0.5 <= Cb <= 0.85, 0.9 <= Cm <= 0.99, -1.5 <= OG/d <= 0.2, omega_hat <= 1.0, and with bilge
keels 0.05 <= lBK/L <= 0.4, 0.01 <= bBK/B <= 0.06. Outside it `roll_damping` raises
ValueError naming the parameter (validity="raise") or warns (validity="warn"): the method is a
regression over conventional cargo-ship forms, not a planing or hard-chine hull's model.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, fields

from mf_envs._validate import check_choice, finite_scalar, nonnegative_scalar, positive_scalar
from mf_envs.physics.constants import RHO_SEAWATER, G

NU_SEAWATER = 1.14e-6  # m^2/s, kinematic viscosity (Kawahara et al.'s program, KVC)

# (name, low, high) of the validity range (module doc)
LIMITS = (
    ("B/d", 2.5, 4.5),
    ("Cb", 0.5, 0.85),
    ("Cm", 0.9, 0.99),
    ("OG/d", -1.5, 0.2),
    ("omega_hat", 0.0, 1.0),
)
BILGE_KEEL_LIMITS = (("lBK/L", 0.05, 0.4), ("bBK/B", 0.01, 0.06))


@dataclass(frozen=True)
class HullParticulars:
    """Particulars of a conventional (round-bilge) hull and its roll motion, SI units.

    length: L_pp, m; beam: B, m; draft: d, m; block_coefficient: Cb = nabla / (L B d);
    midship_coefficient: Cm = A_m / (B d); og: OG, still-water level to roll axis, positive
    downward, m; roll_period: T of the roll motion (usually the natural period), s;
    roll_amplitude: phi_a, rad; bilge_keel_length: lBK, m and bilge_keel_breadth: bBK, m
    (both 0: no bilge keels); speed: U, m/s; rho: water density, kg/m^3; nu: kinematic
    viscosity, m^2/s; g: m/s^2.
    """

    length: float
    beam: float
    draft: float
    block_coefficient: float
    midship_coefficient: float
    og: float
    roll_period: float
    roll_amplitude: float
    bilge_keel_length: float = 0.0
    bilge_keel_breadth: float = 0.0
    speed: float = 0.0
    rho: float = RHO_SEAWATER
    nu: float = NU_SEAWATER
    g: float = G

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if f.name == "og":
                object.__setattr__(self, f.name, finite_scalar(f.name, v))
            elif f.name in ("bilge_keel_length", "bilge_keel_breadth", "speed"):
                object.__setattr__(self, f.name, nonnegative_scalar(f.name, v))
            else:
                object.__setattr__(self, f.name, positive_scalar(f.name, v))
        if (self.bilge_keel_length > 0.0) != (self.bilge_keel_breadth > 0.0):
            raise ValueError(
                "bilge_keel_length: bilge keels need both a length and a breadth (or neither), "
                f"got {self.bilge_keel_length!r} and {self.bilge_keel_breadth!r}"
            )

    @property
    def omega(self) -> float:
        """Roll frequency 2 pi / T, rad/s."""
        return 2.0 * math.pi / self.roll_period

    @property
    def omega_hat(self) -> float:
        """omega sqrt(B / (2 g))."""
        return self.omega * math.sqrt(self.beam / (2.0 * self.g))

    @property
    def displacement_volume(self) -> float:
        """nabla = Cb L B d, m^3."""
        return self.block_coefficient * self.length * self.beam * self.draft

    @property
    def scale(self) -> float:
        """B44 / B44_hat = rho nabla B^2 / sqrt(B / (2 g)), N m s/rad."""
        return (
            self.rho
            * self.displacement_volume
            * self.beam**2
            / math.sqrt(self.beam / (2.0 * self.g))
        )

    def ratios(self) -> dict[str, float]:
        """The dimensionless inputs of the validity range (module doc)."""
        r = {
            "B/d": self.beam / self.draft,
            "Cb": self.block_coefficient,
            "Cm": self.midship_coefficient,
            "OG/d": self.og / self.draft,
            "omega_hat": self.omega_hat,
        }
        if self.bilge_keel_length > 0.0:
            r["lBK/L"] = self.bilge_keel_length / self.length
            r["bBK/B"] = self.bilge_keel_breadth / self.beam
        return r


_PARAM = {
    "B/d": "beam",
    "Cb": "block_coefficient",
    "Cm": "midship_coefficient",
    "OG/d": "og",
    "omega_hat": "roll_period",
    "lBK/L": "bilge_keel_length",
    "bBK/B": "bilge_keel_breadth",
}


def check_validity(h: HullParticulars, validity: str = "raise") -> list[str]:
    """The out-of-range messages of `h` (module doc); ValueError naming the parameter for
    validity="raise", a warning each for "warn", nothing for "ignore"."""
    check_choice("validity", validity, ("raise", "warn", "ignore"))
    lims = LIMITS + (BILGE_KEEL_LIMITS if h.bilge_keel_length > 0.0 else ())
    r = h.ratios()
    bad = []
    for key, lo, hi in lims:
        if not lo - 1e-9 <= r[key] <= hi + 1e-9:
            bad.append(
                f"{_PARAM[key]}: {key} = {r[key]:.4g} is outside the simplified Ikeda "
                f"method's range [{lo}, {hi}] (Kawahara, Maekawa & Ikeda 2011)"
            )
    if bad and validity == "raise":
        raise ValueError("; ".join(bad))
    if validity == "warn":
        for msg in bad:
            warnings.warn(msg, RuntimeWarning, stacklevel=3)
    return bad


def _poly(c: tuple[float, ...], x: float) -> float:
    """c[0] x^n + ... + c[n] (Horner)."""
    s = 0.0
    for a in c:
        s = s * x + a
    return s


def friction_hat(h: HullParticulars) -> float:
    """B_F_hat at zero speed: Kato's laminar skin friction (module doc)."""
    bd, ogd, cb = h.beam / h.draft, h.og / h.draft, h.block_coefficient
    rf = h.draft * ((0.887 + 0.145 * cb) * (1.7 + cb * bd) - 2.0 * ogd) / math.pi
    sf = h.length * (1.75 * h.draft + cb * h.beam)
    phi = h.roll_amplitude
    cf = 1.328 * (3.22 * rf**2 * phi**2 / (h.roll_period * h.nu)) ** -0.5
    bf = 4.0 / (3.0 * math.pi) * h.rho * sf * rf**3 * phi * h.omega * cf
    return bf / h.scale


# fmt: off
# Coefficients of the wave-damping regression (Kawahara et al. 2011), highest power first:
# rows are polynomials in x1 = B/d; a row list is then a polynomial in x2 = Cb.
_A11 = ((-0.002222, 0.040871, -0.286866, 0.599424), (0.010185, -0.161176, 0.904989, -1.641389),
        (-0.015422, 0.220371, -1.084987, 1.834167))
_A12 = ((-0.0628667, 0.4989259, 0.52735, -10.7918672, 16.616327),
        (0.1140667, -0.8108963, -2.2186833, 25.1269741, -37.7729778),
        (-0.0589333, 0.2639704, 3.1949667, -21.8126569, 31.4113508),
        (0.0107667, 0.0018704, -1.2494083, 6.9427931, -10.2018992))
_A13 = ((0.192207, -2.787462, 12.507855, -14.764856), (-0.350563, 5.222348, -23.974852, 29.007851),
        (0.237096, -3.535062, 16.368376, -20.539908), (-0.067119, 0.966362, -4.407535, 5.894703))
_AA11 = ((17.945, -166.294, 489.799, -493.142), (-25.507, 236.275, -698.683, 701.494),
         (9.077, -84.332, 249.983, -250.787))
_AA12 = ((-16.872, 156.399, -460.689, 463.848), (24.015, -222.507, 658.027, -660.665),
         (-8.56, 79.549, -235.827, 236.579))
# A31..A37: sixth-order polynomials in Cb, the coefficients of a sixth-order polynomial in x4
_A3_CB = (
    (-7686.0287, 30131.5678, -49048.9664, 42480.7709, -20665.147, 5355.2035, -577.8827),
    (61639.9103, -241201.0598, 392579.5937, -340629.4699, 166348.6917, -43358.7938, 4714.7918),
    (-130677.4903, 507996.2604, -826728.7127, 722677.104, -358360.7392, 95501.4948, -10682.8619),
    (-110034.6584, 446051.22, -724186.4643, 599411.9264, -264294.7189, 58039.7328, -4774.6414),
    (709672.0656, -2803850.2395, 4553780.5017, -3888378.9905, 1839829.259, -457313.6939,
     46600.823),
    (-822735.9289, 3238899.7308, -5256636.5472, 4500543.147, -2143487.3508, 538548.1194,
     -55751.1528),
    (299122.8727, -1175773.1606, 1907356.1357, -1634256.8172, 780020.9393, -196679.7143,
     20467.0904),
)
_AA3_X = (-1.05584, 12.688, -63.70534, 172.84571, -274.05701, 257.68705, -141.40915, 44.13177,
          -7.1654, 0.0)
# fmt: on


def _nested(rows: tuple[tuple[float, ...], ...], x1: float, x2: float) -> float:
    """A polynomial in x2 whose coefficients are the polynomials `rows` in x1."""
    return _poly(tuple(_poly(r, x1) for r in rows), x2)


def _wave_amplitude(x1: float, x2: float, x3: float, x4: float) -> float:
    """A1 of the wave-damping regression (x1 = B/d, x2 = Cb, x3 = Cm, x4 = 1 - OG/d)."""
    a11, a12, a13 = (_nested(c, x1, x2) for c in (_A11, _A12, _A13))
    aa1 = (_nested(_AA11, x1, x2) * x3 + _nested(_AA12, x1, x2)) * (1.0 - x4) + 1.0
    return _poly((a11, a12, a13), x4) * aa1


def _wave_peak(x1: float, x2: float, x4: float) -> float:
    """A3 (the log-frequency of the peak) of the wave-damping regression."""
    a3 = _poly(tuple(_poly(c, x2) for c in _A3_CB), x4)
    aa311 = _poly((-17.102, 41.495, -33.234, 8.8007), x2) * x4 + _poly(
        (36.566, -89.203, 71.8, -18.108), x2
    )
    aa31 = _poly((-0.3767, 3.39, -10.356, 11.588), x1) * aa311
    xx4 = x4 - _poly((-0.0727, 0.7, -1.2818), x1)
    aa3 = aa31 * (_poly(_AA3_X, xx4) + _poly((-0.0495, 0.4518, -0.61655), x1))
    return a3 + aa3


def wave_hat(h: HullParticulars) -> float:
    """B_W_hat at zero speed (Kawahara et al. 2011's regression of Ikeda's wave damping):
    A1 / w exp(-A2 (ln w - A3)^2 / 1.44), w = omega_hat."""
    x1, x2, x3 = h.beam / h.draft, h.block_coefficient, h.midship_coefficient
    x4, x5 = 1.0 - h.og / h.draft, h.omega_hat
    a1 = _wave_amplitude(x1, x2, x3, x4)
    a2 = _poly((-1.402, 7.189, -10.993, 9.45), x4)
    a3 = _wave_peak(x1, x2, x4)
    return a1 / x5 * math.exp(-a2 * (math.log(x5) - a3) ** 2 / 1.44)


def eddy_hat(h: HullParticulars) -> float:
    """B_E_hat at zero speed: 4 omega_hat phi_a C_R / (3 pi Cb (B/d)^3) (module doc)."""
    cb, cm, bd, ogd = h.block_coefficient, h.midship_coefficient, h.beam / h.draft, h.og / h.draft
    ae = (-0.0182 * cb + 0.0155) * (bd - 1.8) ** 3 + _poly(
        (-79.414, 215.695, -215.883, 93.894, -14.848), cb
    )
    be1 = (
        (3.98 * cb - 5.1525)
        * (-0.2 * bd + 1.6)
        * ogd
        * ((0.9717 * cb**2 - 1.55 * cb + 0.723) * ogd + 0.04567 * cb + 0.9408)
    )
    be2 = (0.25 * ogd + 0.95) * ogd + _poly((-219.2, 443.7, -283.3, 59.6), cb)
    be3 = -15.0 * cb * bd + 46.5 * cb + 11.2 * bd - 28.6
    cr = ae * math.exp(be1 + be2 * cm**be3)
    return 4.0 * h.omega_hat * h.roll_amplitude / (3.0 * math.pi * cb * bd**3) * cr


def bilge_keel_hat(h: HullParticulars) -> float:
    """B_BK_hat (Kawahara et al. 2011's regression; 0 without bilge keels). Its roll
    amplitude enters in degrees, as in the paper."""
    if h.bilge_keel_length <= 0.0:
        return 0.0
    cb, cm, bd, ogd = h.block_coefficient, h.midship_coefficient, h.beam / h.draft, h.og / h.draft
    lk, bk = h.bilge_keel_length / h.length, h.bilge_keel_breadth / h.beam
    ph = math.degrees(h.roll_amplitude)
    f1 = (-0.3651 * cb + 0.3907) * (bd - 2.83) ** 2 - 2.21 * cb + 2.632
    f2 = 0.00255 * ph**2 + 0.122 * ph + 0.4794
    f3 = (-0.8913 * bk**2 - 0.0733 * bk) * lk**2 + (5.2857 * bk**2 - 0.01185 * bk + 0.00189) * lk
    b1 = (5.0 * bk + 0.3 * bd - 0.2 * lk + 0.00125 * ph**2 - 0.0425 * ph - 1.86) * ogd
    b2 = -15.0 * bk + 1.2 * cb - 0.1 * bd - 0.0657 * ogd**2 + 0.0586 * ogd + 1.6164
    b3 = 2.5 * ogd + 15.75
    return f1 * f2 * f3 * math.exp(b1 + b2 * cm**b3) * h.omega_hat


def wave_speed_factor(h: HullParticulars) -> float:
    """B_W(U) / B_W(0) of Ikeda's forward-speed correction (module doc); 1 at U = 0."""
    if h.speed == 0.0:
        return 1.0
    w = h.speed * h.omega / h.g
    xi = h.omega**2 * h.draft / h.g
    a1 = 1.0 + xi**-1.2 * math.exp(-2.0 * xi)
    a2 = 0.5 + math.exp(-2.0 * xi) / xi
    return 0.5 * (
        a2
        + 1.0
        + (a2 - 1.0) * math.tanh(20.0 * (w - 0.3))
        + (2.0 * a1 - a2 - 1.0) * math.exp(-150.0 * (w - 0.25) ** 2)
    )


def eddy_speed_factor(h: HullParticulars) -> float:
    """B_E(U) / B_E(0) = K^2 / (1 + K^2), K = 0.04 omega L / U (module doc); 1 at U = 0."""
    if h.speed == 0.0:
        return 1.0
    u = h.speed / (0.04 * h.omega * h.length)  # 1 / K: no overflow at a subnormal speed
    return 1.0 / (1.0 + u * u)


def lift_hat(h: HullParticulars) -> float:
    """B_L_hat: Ikeda's hull-lift damping (module doc), proportional to U."""
    d, og = h.draft, h.og
    c = h.midship_coefficient - 0.91
    kappa = 106.0 * c**2 - 700.0 * c**3
    kn = 2.0 * math.pi * d / h.length + kappa * (4.1 * h.beam / h.length - 0.045)
    l0, lr = 0.3 * d, 0.5 * d
    bl = (
        0.5
        * h.rho
        * h.length
        * d
        * h.speed
        * kn
        * l0
        * lr
        * (1.0 - 1.4 * og / lr + 0.7 * og**2 / (l0 * lr))
    )
    return bl / h.scale


@dataclass(frozen=True)
class RollDamping:
    """The equivalent linear roll damping of `roll_damping`: non-dimensional components
    (B_hat = B / (rho nabla B^2) sqrt(B / (2 g))) and the dimensional total.

    friction, wave, eddy, lift, bilge_keel: component B_hat (speed-corrected);
    scale: B44 / B44_hat, N m s/rad; omega: rad/s; amplitude: phi_a, rad.
    """

    friction: float
    wave: float
    eddy: float
    lift: float
    bilge_keel: float
    scale: float
    omega: float
    amplitude: float

    @property
    def b44_hat(self) -> float:
        """Total B44_hat."""
        return self.friction + self.wave + self.eddy + self.lift + self.bilge_keel

    @property
    def b44(self) -> float:
        """Total equivalent linear roll damping B44, N m s/rad."""
        return self.b44_hat * self.scale

    def linear_quadratic(self) -> tuple[float, float]:
        """(B_lin in N m s/rad, B_quad in N m s^2/rad^2) for a moment -B_lin p - B_quad |p| p:
        friction, wave and lift linear; eddy and bilge keel quadratic, from the equivalent
        linearisation B_eq = 8/(3 pi) omega phi_a B_quad (equal energy per cycle, Himeno 1981;
        ITTC 7.5-02-07-04.5 §3.2), at this amplitude and frequency."""
        lin = (self.friction + self.wave + self.lift) * self.scale
        quad = (self.eddy + self.bilge_keel) * self.scale
        return lin, quad * 3.0 * math.pi / (8.0 * self.omega * self.amplitude)


def roll_damping(h: HullParticulars, validity: str = "raise") -> RollDamping:
    """The simplified Ikeda roll damping of hull `h` (module doc) after `check_validity`."""
    check_validity(h, validity)
    return RollDamping(
        friction=friction_hat(h) * (1.0 + 4.1 * h.speed / (h.omega * h.length)),
        wave=wave_hat(h) * wave_speed_factor(h),
        eddy=eddy_hat(h) * eddy_speed_factor(h),
        lift=lift_hat(h),
        bilge_keel=bilge_keel_hat(h),
        scale=h.scale,
        omega=h.omega,
        amplitude=h.roll_amplitude,
    )
