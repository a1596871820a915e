"""Shape-memory-alloy (SMA) wire actuator: Joule heating, convective cooling, martensite
fraction with hysteresis, recovery strain and electrical power, per wire group.

::

      I ->  ======== wire (d, R' = resistance per length) ========  -> I
            heat in: I^2 R'         heat out: h p (T - T_amb)     contraction: eps_max (1 - xi)

Thermal (lumped: a thin wire's Biot number h d / (4 k) is ~1e-3): per unit length,
rho c A dT/dt = I^2 R' - h p (T - T_amb) (+ latent heat), solved exactly over a step for a held
current (`sma_kernels`). The film coefficient h(d) is a power law in the diameter fitted to the
maker's contraction and cooling times (`convection_coefficient`; the fit: `fit_convection`).

Phase (Liang & Rogers 1990, J. Intell. Mater. Syst. Struct. 1, 207-234: cosine law of the
martensite fraction xi between the transformation temperatures, stress-free form at the
maker's rated load): heating moves xi from its value at the last reversal to 0 between As and
Af, cooling to 1 between Ms and Mf. The latent heat L of the transformation is absorbed on
heating and released on cooling; the step conserves energy exactly (sma_kernels.sma_step).

Output: recovery strain eps = eps_max (1 - xi) (the wire shortens by eps of its length) with
eps_max within the alloy's repeatable range; the force of a wire at the maker's rated stress is
`pull_force` (172 MPa x area); electrical power I^2 R' length per wire.

Sources (docs/inchworm.md, "A buildable robot", lists what was verified how):
Dynalloy, "Technical Characteristics of Flexinol Actuator Wires", F1140 Rev I.2: NiTi density
6.45 g/cm^3, specific heat 0.2 cal/(g K), latent heat 5.78 cal/g, resistivity 80 (martensite) /
100 (austenite) micro-ohm cm, the 70 degC "LT" and 90 degC "HT" austenite start temperatures at
172 MPa; the wire table (resistance, current for a 1 s contraction, pull force, cooling time in
still air) of its Rev M as quoted in public design notes (`FLEXINOL_WIRES`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from mf_envs._validate import check_positive, finite_scalar
from mf_envs.physics.actuators import sma_kernels as sk

CAL = 4.1868  # J per calorie (international table)
NITI_DENSITY = 6450.0  # rho [kg/m^3], F1140 physical properties
NITI_SPECIFIC_HEAT = 0.2 * CAL * 1e3  # c [J/(kg K)], 0.2 cal/(g degC), F1140
NITI_LATENT_HEAT = 5.78 * CAL * 1e3  # L [J/kg], 5.78 cal/g, F1140
RATED_STRESS = 172e6  # [Pa] the maker's heating pull force basis (25 ksi)
# [degC] the wires' over-temperature limit. Dynalloy's technical data, as far as we could read
# it (F1140 Rev I.2, first pages), gives no maximum temperature; a Nitinol actuator designer
# states that actuators "are very easily damaged if the stress exceeds roughly 40 ksi or if the
# temperature exceeds 150 degrees C" (nitinolactuators.com, "Nitinol actuator over-stress
# protection"). Not the maker's number: docs/inchworm.md
MAX_WIRE_TEMPERATURE = 150.0
ROOM_TEMPERATURE = 20.0  # [degC] still air of the maker's tests (our reading of "room")
GRAM_FORCE = 9.80665e-3  # [N]

# h(d) = H_REF (d / 0.1 mm)^(-H_EXPONENT) [W/(m^2 K)]: `fit_convection` on the cooling times of
# FLEXINOL_WIRES (LT and HT) without the 0.076 mm row (FIT_EXCLUDED; docs/inchworm.md: residuals)
H_REF = 189.07
H_EXPONENT = 0.28857
FIT_EXCLUDED = (76e-6,)  # its quoted HT/LT cooling ratio 0.4 is out of line with the others
D_REF = 1e-4


@dataclass(frozen=True)
class SMAAlloy:
    """Transformation temperatures [degC] (austenite start/finish on heating, martensite
    start/finish on cooling) and the repeatable recovery strain range (fractions)."""

    name: str
    austenite_start: float
    austenite_finish: float
    martensite_start: float
    martensite_finish: float
    repeatable_strain: tuple[float, float] = (0.02, 0.06)
    source: str = ""

    def __post_init__(self) -> None:
        for f in ("austenite_start", "austenite_finish", "martensite_start", "martensite_finish"):
            finite_scalar(f, getattr(self, f))
        if not self.austenite_start < self.austenite_finish:
            raise ValueError(f"austenite_finish: must exceed austenite_start, got {self}")
        if not self.martensite_finish < self.martensite_start <= self.austenite_finish:
            raise ValueError(
                f"martensite_start: needs martensite_finish < Ms <= austenite_finish, got {self}"
            )

    @property
    def temperatures(self) -> tuple[float, float, float, float]:
        """(As, Af, Ms, Mf) [degC], the kernels' order."""
        return (
            self.austenite_start,
            self.austenite_finish,
            self.martensite_start,
            self.martensite_finish,
        )


_TT_SOURCE = (
    "As: Dynalloy F1140 Rev I.2 (70 / 90 degC austenite start at 172 MPa); the widths Af - As "
    "= 10 K, As - Ms = 16 K, Ms - Mf = 10 K: the LT/HT values 68/78/52/42 and 88/98/72/62 degC "
    "of a public Flexinol model (NicholasBaraghini/Modeling-and-Simulation-of-Mechatronic-"
    "Systems, Model_Parameters.m), not verified against the maker's figure"
)
FLEXINOL_LT = SMAAlloy("Flexinol LT (70 degC)", 70.0, 80.0, 54.0, 44.0, source=_TT_SOURCE)
FLEXINOL_HT = SMAAlloy("Flexinol HT (90 degC)", 90.0, 100.0, 74.0, 64.0, source=_TT_SOURCE)


@dataclass(frozen=True)
class FlexinolWire:
    """One row of the maker's wire table: diameter [m], resistance per length [ohm/m], current
    for a 1 s contraction [A], pull force at 172 MPa [N], cooling times in still air [s] of the
    LT and HT alloys (None where no value was found), and where the numbers come from."""

    diameter: float
    resistance: float | None
    current: float | None
    pull_force: float
    cooling_lt: float | None
    cooling_ht: float | None
    source: str

    def cooling_time(self, alloy: SMAAlloy) -> float | None:
        return self.cooling_ht if alloy.austenite_start >= 85.0 else self.cooling_lt


_REV_M = "Dynalloy F1140 Rev M wire table (2025), as quoted in "
_Q_AMF = "a public design review's source record AMF-77"
_Q_D5 = "a public design note, section D5 (RobotShop-hosted Dynalloy table)"
_Q_MECH = "a public Mechanism Lab actuator config (0.008 in / 0.20 mm, 70 degC table row)"
INCH = 0.0254
FLEXINOL_WIRES = (
    FlexinolWire(25e-6, 1425.0, 0.045, 8.9 * GRAM_FORCE, 0.18, 0.15, _REV_M + _Q_AMF),
    FlexinolWire(76e-6, 5.0 / INCH, 0.100, 80 * GRAM_FORCE, 0.5, 0.2, _REV_M + _Q_D5),
    FlexinolWire(100e-6, None, None, 143 * GRAM_FORCE, 1.1, 0.9, _REV_M + _Q_AMF),
    FlexinolWire(150e-6, 1.3 / INCH, 0.400, 330 * GRAM_FORCE, 2.0, 1.2, _REV_M + _Q_D5),
    FlexinolWire(200e-6, 29.0, 0.660, 570 * GRAM_FORCE, 3.2, None, _REV_M + _Q_MECH),
)


def flexinol_wire(diameter: float) -> FlexinolWire:
    """The table row of `diameter` [m] (ValueError naming it when the table has none)."""
    for w in FLEXINOL_WIRES:
        if abs(w.diameter - diameter) < 1e-9:
            return w
    have = ", ".join(f"{w.diameter * 1e3:g} mm" for w in FLEXINOL_WIRES)
    raise ValueError(f"diameter: no Flexinol row for {diameter!r} m (rows: {have})")


def convection_coefficient(diameter: float) -> float:
    """Film coefficient h [W/(m^2 K)] of a wire of `diameter` [m] in still air, the fitted power
    law H_REF (d / 0.1 mm)^(-H_EXPONENT) (thinner wires shed heat faster per area)."""
    check_positive("diameter", diameter)
    return H_REF * (diameter / D_REF) ** (-H_EXPONENT)


def pull_force(diameter: float, stress: float = RATED_STRESS) -> float:
    """Force [N] of one wire at the recovery `stress` [Pa] (the maker rates 172 MPa)."""
    check_positive("diameter", diameter)
    return stress * math.pi * diameter**2 / 4.0


@dataclass(frozen=True)
class SMAWireParams:
    """A group of `n_wires` identical wires driven alike: diameter [m], resistance per length
    [ohm/m] (None: the table row's), active length [m], rated current [A] (the duty cycle's
    100 %; None: the table row's), alloy, maximum recovery strain eps_max (fraction, at most the
    alloy's repeatable limit), film coefficient h [W/(m^2 K)] (None: `convection_coefficient`),
    ambient temperature [degC], latent heat of the transformation on/off."""

    diameter: float = 150e-6
    length: float = 0.1
    n_wires: int = 1
    alloy: SMAAlloy = FLEXINOL_LT
    strain_max: float = 0.04
    resistance: float | None = None
    rated_current: float | None = None
    film_coefficient: float | None = None
    ambient: float = ROOM_TEMPERATURE
    latent_heat: bool = True
    name: str = field(default="Flexinol wire group", compare=False)

    def __post_init__(self) -> None:
        check_positive("diameter", self.diameter)
        check_positive("length", self.length)
        if int(self.n_wires) != self.n_wires or self.n_wires < 1:
            raise ValueError(f"n_wires: must be a positive integer, got {self.n_wires!r}")
        check_positive("strain_max", self.strain_max)
        top = self.alloy.repeatable_strain[1]
        if self.strain_max > top:
            raise ValueError(
                f"strain_max: {self.strain_max} exceeds the repeatable strain {top} of "
                f"{self.alloy.name}"
            )
        finite_scalar("ambient", self.ambient)
        if self.ambient >= self.alloy.martensite_finish:
            raise ValueError(f"ambient: {self.ambient} degC is not below Mf of {self.alloy.name}")
        for name in ("resistance", "rated_current", "film_coefficient"):
            if getattr(self, name) is not None:
                check_positive(name, getattr(self, name))
        if self.resistance is None or self.rated_current is None:
            row = flexinol_wire(self.diameter)  # ValueError naming diameter if none
            if (self.resistance or row.resistance) is None:
                raise ValueError(f"resistance: the table has none for {self.diameter} m")

    @property
    def resistance_per_length(self) -> float:
        return float(self.resistance or flexinol_wire(self.diameter).resistance)

    @property
    def current(self) -> float | None:
        """Rated current [A] (the duty cycle's 100 %), None when neither given nor tabled."""
        return self.rated_current or flexinol_wire(self.diameter).current

    @property
    def h(self) -> float:
        return float(self.film_coefficient or convection_coefficient(self.diameter))

    @property
    def heat_capacity(self) -> float:
        """rho c A [J/(m K)] per length of one wire."""
        return NITI_DENSITY * NITI_SPECIFIC_HEAT * math.pi * self.diameter**2 / 4.0

    @property
    def film_conductance(self) -> float:
        """h p [W/(m K)] per length of one wire."""
        return self.h * math.pi * self.diameter

    @property
    def time_constant(self) -> float:
        """tau = rho c d / (4 h) [s] of the sensible heat (S1)."""
        return self.heat_capacity / self.film_conductance

    @property
    def latent_kelvin(self) -> float:
        """L / c [K] (0 with latent_heat off): the latent heat as a temperature."""
        return NITI_LATENT_HEAT / NITI_SPECIFIC_HEAT if self.latent_heat else 0.0

    def steady_temperature(self, duty: float = 1.0) -> float:
        """T_amb + duty I^2 R' / (h p) [degC]: the fixed point of the lumped heat balance under a
        constant duty of the rated current. The exact solution approaches it monotonically and
        the latent heat is absorbed on heating (released on cooling, below Ms), so no sequence
        of duties in [0, duty] takes a wire from at most this temperature above it."""
        return self.ambient + duty * self.current**2 * self.resistance_per_length / (
            self.film_conductance
        )

    def kernel_args(self) -> tuple:
        """(hp, cap, T_amb) and (As, Af, Ms, Mf, L/c), the kernels' order."""
        return (self.film_conductance, self.heat_capacity, self.ambient), (
            *self.alloy.temperatures,
            self.latent_kelvin,
        )


def maker_times(
    params: SMAWireParams, current: float | None = None, dt: float = 1e-3, done: float = 0.95
) -> tuple[float, float]:
    """The maker's two tests in still air on `params`: the contraction time [s] under `current`
    [A] (default: rated) from rest (`sma_kernels.contraction_time`; inf if not within 60 s),
    and the cooling time [s] with the current off from the contracted state a full heating
    reaches, whatever current got it there (`relaxation_time`). A wire counts as contracted /
    relaxed at `done` of its stroke."""
    (hp, cap, t_amb), tt = params.kernel_args()
    i = params.current if current is None else current
    t_c, _temp = sk.contraction_time(
        i * i * params.resistance_per_length, hp, cap, t_amb, dt, *tt, done, 60.0
    )
    # contracted state: heated fast (1000 x the power that holds Af) to xi = 1 - done
    _t, temp = sk.contraction_time(1e3 * hp * (tt[1] - t_amb), hp, cap, t_amb, 1e-6, *tt, done, 1.0)
    return t_c, sk.relaxation_time(temp, 1.0 - done, hp, cap, t_amb, dt, *tt, done, 60.0)


def cooling_cases(wires=FLEXINOL_WIRES) -> list[tuple[FlexinolWire, SMAAlloy, float]]:
    """(row, alloy, the maker's cooling time [s]) of every table entry with a cooling time."""
    out = []
    for w in wires:
        for alloy in (FLEXINOL_LT, FLEXINOL_HT):
            t = w.cooling_time(alloy)
            if t is not None:
                out.append((w, alloy, t))
    return out


def model_cooling_time(w: FlexinolWire, alloy: SMAAlloy, h: float) -> float:
    """The model's cooling time [s] of the row's wire with film coefficient h (`maker_times`)."""
    p = SMAWireParams(
        diameter=w.diameter, alloy=alloy, film_coefficient=h, resistance=w.resistance or 1.0,
        rated_current=w.current or 1.0,
    )  # fmt: skip
    return maker_times(p, current=0.0)[1]


def fit_convection(cases=None) -> tuple[float, float, list[float]]:
    """Least-squares fit of h(d) = h_ref (d / 0.1 mm)^(-p) to the maker's cooling times (log
    residuals): returns (h_ref [W/(m^2 K)], p, relative errors of the cases)."""
    from scipy.optimize import least_squares

    if cases is None:
        cases = [
            c for c in cooling_cases() if min(abs(c[0].diameter - d) for d in FIT_EXCLUDED) > 1e-9
        ]

    def resid(x):
        h_ref, p = math.exp(x[0]), x[1]
        return [
            math.log(model_cooling_time(w, a, h_ref * (w.diameter / D_REF) ** (-p)) / t)
            for w, a, t in cases
        ]

    sol = least_squares(resid, [math.log(200.0), 0.3], x_scale=[1.0, 0.3])
    errors = [math.expm1(r) for r in resid(sol.x)]
    return math.exp(sol.x[0]), float(sol.x[1]), errors


@dataclass
class SMAStepReport:
    """One step of a wire group: temperature [degC], martensite fraction xi, recovery strain
    (fraction), electrical power [W] and, over the step [J]: electrical energy in, heat
    convected, sensible and latent heat stored (energy in = the three others, exactly)."""

    temperature: float
    xi: float
    strain: float
    power: float
    energy_in: float
    convected: float
    sensible: float
    latent: float


class SMAWireGroup:
    """State (T, xi and the hysteresis branch) of a group of wires driven alike, stepped by the
    compiled `sma_kernels.sma_step` under a held current or duty cycle of the rated current."""

    def __init__(self, params: SMAWireParams) -> None:
        self.params = params
        self.reset()

    def reset(self, temperature: float | None = None) -> None:
        """At rest in martensite (xi = 1) at `temperature` [degC] (default ambient), which must
        lie below As."""
        p = self.params
        t = p.ambient if temperature is None else finite_scalar("temperature", temperature)
        if t >= p.alloy.austenite_start:
            raise ValueError(f"temperature: {t} degC is not below As of {p.alloy.name}")
        self.temperature, self.xi = float(t), 1.0
        self.direction, self.t_rev, self.xi_rev = sk.COOLING, float(t), 1.0

    @property
    def strain(self) -> float:
        """Recovery strain eps_max (1 - xi): the contraction as a fraction of the length."""
        return self.params.strain_max * (1.0 - self.xi)

    @property
    def force(self) -> float:
        """Pull force [N] of the group at the maker's rated stress (fully austenitic)."""
        return self.params.n_wires * pull_force(self.params.diameter)

    def power_of(self, current: float | None = None, duty: float | None = None) -> float:
        """Joule power [W] of the group at `current` [A] per wire, or at `duty` in [0, 1] of
        the rated current (pulse-width modulation faster than the wire's time constant: the
        mean power duty I_r^2 R)."""
        p = self.params
        if (current is None) == (duty is None):
            raise ValueError("current: give exactly one of current and duty")
        if duty is not None:
            duty = finite_scalar("duty", duty)
            if not 0.0 <= duty <= 1.0:
                raise ValueError(f"duty: must lie in [0, 1], got {duty}")
            if p.current is None:
                raise ValueError("rated_current: unknown for this wire; pass current instead")
            i2 = duty * p.current**2
        else:
            i2 = finite_scalar("current", current) ** 2
        return i2 * p.resistance_per_length * p.length * p.n_wires

    def step(self, dt: float, current: float | None = None, duty: float | None = None):
        """Hold `current` [A] per wire (or `duty` of the rated current) for dt [s]."""
        dt = float(check_positive("dt", dt))
        p = self.params
        power = self.power_of(current, duty)
        scale = p.length * p.n_wires
        (hp, cap, t_amb), (a_s, a_f, m_s, m_f, lat) = p.kernel_args()
        t0, xi0 = self.temperature, self.xi
        t1, xi1, self.direction, self.t_rev, self.xi_rev, q = sk.sma_step(
            t0, xi0, self.direction, self.t_rev, self.xi_rev, power / scale, hp, cap, t_amb,
            dt, (a_s, a_f, m_s, m_f), lat,
        )  # fmt: skip
        self.temperature, self.xi = t1, xi1
        return SMAStepReport(
            t1, xi1, self.strain, power, power * dt, q * scale, cap * (t1 - t0) * scale,
            cap * lat * (xi0 - xi1) * scale,
        )  # fmt: skip
