"""`FloatingModel`: a hull, its radiation fit, one gyroscope and a sea, ready to step.

Wires `HullCoefficients` (BEM table), `radiation.fit_radiation` (state-space memory) and a wave
field (`mf_envs.physics.waves`) into the numba fast path `floating.rk4_steps`, and builds the
same system in the general multibody engine (`engine_model`) for the check. SI units.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
from numpy.typing import NDArray

from mf_envs.physics.end_stops import cushion_spring_energy
from mf_envs.physics.gowec import GOWECParams
from mf_envs.physics.gowec.hydro import HullCoefficients, axes, gimbal, sea
from mf_envs.physics.gowec.hydro import floating as fl
from mf_envs.physics.gowec.hydro.radiation import RadiationFit, fit_radiation
from mf_envs.physics.gowec.hydro.three_dof import ThreeDofCoefficients
from mf_envs.physics.multibody import Body, Multibody, Revolute, constant_rate
from mf_envs.physics.waves import WaveField, group_velocity

PTO_FIELDS = gimbal.PTO_NAMES  # the drive, end stops, brake and supervisor (`gimbal`)


class FloatingModel:
    """Floating buoy + gyro (`floating` module doc). `viscous_damping` (N m s/rad) is an extra
    linear damping per axis (0 = potential flow only); `pto` a dict of PTO_FIELDS (gains,
    limits, efficiencies; the end stops, brake and supervisor optional: `gimbal`). `hull` is
    the pitch block, used for roll too unless the `three_dof` table has the sway/roll data
    (a box: `axes.roll_hull`, its own roll block and wave moments by heading)."""

    def __init__(
        self,
        hull: HullCoefficients,
        gyro: GOWECParams,
        pto: dict[str, float],
        viscous_damping: float = 0.0,
        gyroscopic: bool = True,
        radiation: RadiationFit | None = None,
        units: int = 2,
        three_dof: ThreeDofCoefficients | None = None,
    ) -> None:
        self.hull = hull
        self.three = three_dof  # surge/heave/pitch table: `set_translation` can free them
        self._tr = _TRANSLATION_OFF
        self.gyro = gyro
        self.fit = radiation or fit_radiation(
            hull.omega, hull.added_mass, hull.damping, hull.added_mass_inf
        )
        self.roll = axes.roll_hull(three_dof)  # None: axisymmetric, roll = the pitch block
        r = self.roll or hull
        self.roll_fit = self.fit if self.roll is None else fit_radiation(
            r.omega, r.added_mass, r.damping, r.added_mass_inf)  # fmt: skip
        Ar, Br, Cr = axes.stack_fits(self.fit, self.roll_fit)
        Iz = axes.yaw_inertia(hull, three_dof)
        if units not in (1, 2):
            raise ValueError(f"gyro_units: 1 or 2 (the seed's dual configuration), got {units!r}")
        g = np.array(
            [gyro.rotor_inertia, gyro.transverse, *gyro.gimbal_inertia, units], dtype=float
        )
        self._packed: tuple | None = None  # `_args`' cache
        self._spin_on = bool(gyroscopic)
        self.sp = np.zeros(sea.SP_LEN)  # drag off, no ramp (`set_drag`, `set_ramp`)
        self.drag_coefficient = 0.0
        self.mooring_stiffness = 0.0  # N/m (`set_translation`)
        self.p = fl.FloatingParams(
            inertia=np.array(
                [hull.inertia + hull.added_mass_inf, Iz, r.inertia + r.added_mass_inf]
            ),
            gyro=g,
            psid=float(gyro.rotor_speed) if gyroscopic else 0.0,  # `set_rotor_speed`
            stiffness=np.array([hull.stiffness, r.stiffness], dtype=float),
            viscous=float(viscous_damping),
            Ar=Ar,
            Br=Br,
            Cr=Cr,
            pto=np.array(gimbal.pto_vector(pto), dtype=float),
        )
        self.set_sea(None)

    @property
    def inert(self) -> NDArray[np.float64]:
        """(Ja, Jt, Jg1, Jg2, Jg3) kg m^2, as `GimbalModel.inert` (controllers read it)."""
        return self.p.gyro[:5]

    @property
    def units(self) -> int:
        """Number of gyro units (1, or 2 for the dual mirrored pair)."""
        return int(self.p.gyro[5])

    @property
    def psid(self) -> float:
        """Rotor spin psi' (rad/s; 0 with the rotor off)."""
        return self.p.psid

    def pitch_inertia(self) -> float:
        """Rigid pitch inertia about G at phi = 0: hull + gimbal + rotor (kg m^2), no A_inf."""
        return self.hull.inertia + self.units * (self.p.gyro[1] + self.p.gyro[2])

    # ------------------------------------------------------------------ sea and PTO
    def set_sea(self, wave: WaveField | None) -> None:
        """Excitation from a wave field (None = calm water)."""
        self.wave, self._packed = wave, None
        if wave is None:
            self._om = np.zeros(0)
            self._cp = self._cr = np.zeros(0, dtype=complex)
            self._dk = np.zeros((0, sea.N_LOADS), dtype=complex)
            return
        X = self.wave_excitation(wave.omegas, wave.direction)
        self._om = np.asarray(wave.omegas, dtype=float)
        self._cp, self._cr = sea.excitation_coefficients(
            X, wave.amplitudes, wave.phases, wave.direction
        )
        self.sp = sea.drag_geometry(self.hull, self.drag_coefficient, float(self.sp[1]),
                                   wave.direction, axes.plan(self.three))  # fmt: skip
        self.sp[sea.SP_TRANS] = self._tr[0][fl.TP_ON]
        self._dk = sea.drag_velocity_coefficients(
            self.sp, self.hull, self._om, wave.amplitudes, wave.phases
        )
        if self.translating:
            sea.translation_loads(self._dk, self.three, self._om, wave.amplitudes, wave.phases)

    @property
    def translating(self) -> bool:
        """Surge and heave are free (`set_translation`)."""
        return bool(self._tr[0][fl.TP_ON])

    def set_translation(self, on: bool, mooring_stiffness: float = 0.0) -> None:
        """Free surge (along the wave) and heave with the 3-dof table's added mass, radiation
        (state-space fits of K11, K15 = K51 symmetrised, K33) and excitation, and a linear
        mooring spring in surge (N/m); off: the hull rotates about a fixed G (0.1-0.4)."""
        if on and self.three is None:
            raise ValueError("effects: surge_heave needs a surge/heave/pitch hull table")
        self.mooring_stiffness = float(mooring_stiffness)
        self._tr = translation_params(self.three, self.mooring_stiffness) if on else \
            _TRANSLATION_OFF  # fmt: skip
        self.set_sea(self.wave)

    @property
    def n_state(self) -> int:
        """Length of the state vector (`floating` module doc, plus the translation block)."""
        tp = self._tr[0]
        return self.p.n_state + (4 + int(tp[fl.TP_NT]) if tp[fl.TP_ON] else 0)

    def set_drag(self, drag_coefficient: float) -> None:
        """Quadratic Morison drag on the keel plate and the side (`floating.drag_loads`) with
        the drag coefficient C_d (0 = off, no cost)."""
        self.drag_coefficient = float(drag_coefficient)
        self.set_sea(self.wave)

    def set_ramp(self, seconds: float) -> None:
        """Ramp the incident wave in over `seconds` (s; 0 = none, `floating.ramp`)."""
        self.sp = self.sp.copy()
        self.sp[1] = float(seconds)
        self._packed = None

    def hull_excitation(self, omegas: NDArray) -> NDArray[np.complex128]:
        """The hull's complex pitch excitation per unit amplitude (N m/m) at each frequency
        (rad/s) of omegas (`HullCoefficients.at`)."""
        return np.array([self.hull.at(float(w))[2] for w in omegas])

    def wave_excitation(self, omegas: NDArray, direction: float) -> NDArray[np.complex128]:
        """What `sea.excitation_coefficients` takes for a sea towards `direction` (rad): the
        pitch excitation (n,) of an axisymmetric hull, or (2, n) the moments about e1 and e2
        from a box's heading table (`axes.directional_excitation`)."""
        if self.roll is None:
            return self.hull_excitation(omegas)
        return axes.directional_excitation(self.three, omegas, direction)

    def surge_coupling(
        self, omegas: NDArray
    ) -> tuple[NDArray[np.complex128], NDArray[np.complex128], NDArray[np.complex128]]:
        """(Z_s, Z_c, X_1) at each frequency (rad/s), e^{-i w t}: the surge impedance
        Z_s = B11 - i (w (m + A11) - K_mooring / w), the surge-pitch coupling Z_c = B15 - i w A15
        (the table's, symmetrised) and the surge excitation per metre of amplitude, with which a
        frequency-domain pitch model eliminates the free surge (Z55 - Z_c^2 / Z_s and
        X5 - Z_c X1 / Z_s); (1, 0, 0) with surge held."""
        om = np.asarray(omegas, dtype=float)
        if not self.translating:
            zero = np.zeros(om.size, complex)
            return np.ones(om.size, complex), zero, zero.copy()
        three = self.three
        w0, A, B = three.omega, three.added_mass, three.damping

        def at(y: NDArray) -> NDArray[np.complex128]:
            return np.interp(om, w0, y.real) + 1j * np.interp(om, w0, y.imag)

        a15, b15 = 0.5 * (A[:, 0, 2] + A[:, 2, 0]), 0.5 * (B[:, 0, 2] + B[:, 2, 0])
        m = float(three.mass_matrix[0, 0])
        z_s = at(B[:, 0, 0]) - 1j * (om * (m + at(A[:, 0, 0])) - self.mooring_stiffness / om)
        return z_s, at(b15) - 1j * om * at(a15), at(three.excitation[:, 0])

    def set_viscous(self, damping: float) -> None:
        """Extra linear viscous damping b_v per axis (N m s/rad)."""
        self.p, self._packed = dataclasses.replace(self.p, viscous=float(damping)), None

    def set_radiation(self, on: bool) -> None:
        """Radiation memory on (the fit) or off (A_inf only: no wave damping)."""
        Cr = axes.stack_fits(self.fit, self.roll_fit)[2]
        Cr = Cr if on else np.zeros_like(Cr)
        self.p, self._packed = dataclasses.replace(self.p, Cr=Cr), None

    def set_pto(self, damping: float, stiffness: float) -> None:
        """Linear PTO gains c (N m s/rad) and k (N m/rad) of the drive's inner loop."""
        self.p.pto[0], self.p.pto[1] = float(damping), float(stiffness)

    def set_rotor_speed(self, speed: float, pto: dict[str, float]) -> None:
        """The flywheels' spin psi' (rad/s; held by their motors, the gyroscopic coupling
        H = J psi' follows) and the PTO fields that depend on it (`gimbal.PTO_NAMES`: the
        cushion sized for H). With the `gyroscopic` effect off the rotor stays stopped."""
        pv = self.p.pto.copy()
        for name, value in pto.items():
            pv[gimbal.PTO_NAMES.index(name)] = float(value)
        psid = float(speed) if self._spin_on else 0.0
        self.p = dataclasses.replace(self.p, psid=psid, pto=pv)
        self._packed = None

    # ------------------------------------------------------------------ state
    def initial_state(
        self, pitch: float = 0.0, roll: float = 0.0, gimbal: float = 0.0, gimbal_rate: float = 0.0
    ) -> NDArray[np.float64]:
        y = np.zeros(self.n_state)
        y[0], y[1], y[2], y[5] = pitch, roll, gimbal, gimbal_rate
        return y

    def step(self, t: float, y: NDArray, tau: float, dt: float, n: int) -> NDArray[np.float64]:
        """y after n RK4 substeps of dt (s) with the PTO command tau (N m) held."""
        return fl.rk4_steps(t, y, float(tau), dt, n, self._args())

    def _args(self) -> tuple:
        """`floating.pack` of the params and the sea, cached until either changes."""
        if self._packed is None:
            self._packed = fl.pack(self.p, self._om, self._cp, self._cr, self._dk, self.sp,
                                   self._tr)  # fmt: skip
        return self._packed

    def excitation(self, t: float) -> tuple[float, float]:
        """(M_x, M_y) wave excitation moments (N m) about e1 (pitch) and e2 (roll), ramped."""
        a = self._args()
        return sea.sea_inputs(t, a[9], a[10], a[11], a[12], a[13])[:2]

    def generator_torque(self, y: NDArray, tau: float) -> float:
        """M_g (N m) the PTO applies at state y for the command tau."""
        return float(gimbal.pto_torque(y[2], y[5], tau, self.p.pto))

    def accelerations(self, t: float, y: NDArray, tau: float) -> NDArray[np.float64]:
        """(theta'', rho'', phi'') (rad/s^2)."""
        d = fl.deriv(t, y, float(tau), self._args())
        return d[3:6]

    def gyro_moment(self, t: float, y: NDArray, tau: float) -> NDArray[np.float64]:
        """(2,) moment of the gyro unit on the hull about the pitch and roll axes (N m)."""
        return gyro_moment(self.p, y, self.accelerations(t, y, tau))

    def energies(self, y: NDArray) -> dict[str, float]:
        """Integrated energies (J) and the stored mechanical energy (`floating` module doc)."""
        k = int(fl.energy_index(self._args()))
        names = ("excitation", "radiated", "viscous", "pto_mechanical", "pto_electrical", "motor")
        out = {n: float(y[k + i]) for i, n in enumerate(names)}
        d = self.wave.direction if self.wave is not None else 0.0
        out["stored"] = mechanical_energy(self.p, y, self._tr[0], d)
        return out

    def survival_index(self) -> int:
        """Index of the supervisor's survival timer (s) in the state (`gimbal.supervise`)."""
        return int(fl.energy_index(self._args())) + fl.N_ENERGY

    # ------------------------------------------------------------------ engine twin
    def engine_model(self) -> Multibody:
        """The same bodies in the general B-matrix engine: a massless pitch frame (revolute
        about x1), the hull (revolute about e2 = roll), the gimbal (revolute about e2) and the
        rotor (revolute about e3, prescribed psi' t); all centres of mass at G."""
        p = self.p
        if self.units != 1:
            raise ValueError("engine_model: the engine's tree holds one gyro unit (units=1)")
        Ja, Jt, Jg1, Jg2, Jg3 = p.gyro[:5]
        Ih, Iz, Ir = p.inertia
        return Multibody(
            [
                Body("pitch", 0.0, (0.0, 0.0, 0.0), Revolute((1, 0, 0))),
                Body("hull", 1.0, (Ih, Ir, Iz), Revolute((0, 1, 0)), parent="pitch"),
                Body("gimbal", 1.0, (Jg1, Jg2, Jg3), Revolute((0, 1, 0)), parent="hull"),
                Body(
                    "rotor",
                    1.0,
                    (Jt, Jt, Ja),
                    Revolute((0, 0, 1)),
                    parent="gimbal",
                    prescribed=constant_rate(p.psid),
                ),
            ]
        )


# ---------------------------------------------------------------------- translation
_TRANSLATION_OFF = (np.zeros(fl.TP_LEN), np.zeros((1, 1)), np.zeros(1), np.zeros(1))


def translation_params(three: ThreeDofCoefficients, mooring_stiffness: float) -> tuple:
    """(tp, As, Bs, Cs) of `floating`'s translation block: masses, the symmetrised A15_inf,
    the mooring and heave stiffness, and the radiation fits of K11, K15 (from alpha' to the
    surge force), K51 (from s' to the moment; the same symmetrised kernel) and K33 stacked
    block-diagonally (`radiation.fit_radiation` each)."""
    om, A, B, Ai = three.omega, three.added_mass, three.damping, three.added_mass_inf
    a15 = 0.5 * (A[:, 0, 2] + A[:, 2, 0])
    b15 = 0.5 * (B[:, 0, 2] + B[:, 2, 0])
    a15_inf = 0.5 * (Ai[0, 2] + Ai[2, 0])
    fits = [fit_radiation(om, A[:, 0, 0], B[:, 0, 0], Ai[0, 0]),
            fit_radiation(om, a15, b15, a15_inf)]  # fmt: skip
    fits += [fits[1], fit_radiation(om, A[:, 1, 1], B[:, 1, 1], Ai[1, 1], max_order=6)]
    sizes = [f.A.shape[0] for f in fits]
    nt = int(sum(sizes))
    As, Bs, Cs = np.zeros((nt, nt)), np.zeros(nt), np.zeros(nt)
    o = 0
    offsets = []
    for f, n in zip(fits, sizes):
        offsets.append(o)
        As[o : o + n, o : o + n] = f.A
        Bs[o : o + n] = f.B[:, 0]
        Cs[o : o + n] = f.C[0]
        o += n
    m = float(three.mass_matrix[0, 0])
    tp = np.zeros(fl.TP_LEN)
    tp[fl.TP_ON], tp[fl.TP_M1], tp[fl.TP_A15] = 1.0, m + Ai[0, 0], a15_inf
    tp[fl.TP_K], tp[fl.TP_M3], tp[fl.TP_C33] = mooring_stiffness, m + Ai[1, 1], \
        three.hydrostatic_stiffness[1, 1]  # fmt: skip
    tp[fl.TP_O11], tp[fl.TP_O15], tp[fl.TP_O51], tp[fl.TP_O33] = offsets
    tp[fl.TP_NT] = nt
    return tp, As, Bs, Cs


# ---------------------------------------------------------------------- ceilings
def radiation_bound(hull: HullCoefficients, wave: WaveField) -> float:
    """Radiation-limited mean absorbed power (W): sum_i |X(w_i)|^2 a_i^2 / (8 B(w_i)) over the
    sea's components (pitch and roll together: |X|^2 (sin^2 + cos^2) of the direction), the
    optimum of a linear oscillating body (Falnes 2002, Eq. 6.48). Components where the table
    gives B = 0 (X = 0 there by Haskind) contribute nothing."""
    total = 0.0
    for a, w in zip(wave.amplitudes, wave.omegas):
        _, B, X = hull.at(float(w))
        if B > 0:
            total += abs(X) ** 2 * a * a / (8.0 * B)
    return total


def motion_limited_bound(hull: HullCoefficients, wave: WaveField, theta_max: float) -> float:
    """Mean absorbed power (W) when the hull's tilt is limited to theta_max (rad): the power a
    linear body absorbs is P = 1/2 Re(X a conj(u)) - 1/2 B |u|^2 <= 1/2 |X| a |u| with the tilt
    rate u = w Theta (Falnes 2002 ch. 6; the constrained optimum is below this), so for a
    regular wave P <= 1/2 |X| a w theta_max. For several components the time average of the
    squared tilt, 1/2 sum |Theta_i|^2, cannot exceed theta_max^2, and Cauchy-Schwarz gives
    P <= theta_max sqrt(sum (|X_i| a_i w_i)^2 / 2). Returns the smaller of this and
    `radiation_bound`. ValueError if theta_max is not > 0."""
    if not (isinstance(theta_max, (int, float)) and math.isfinite(theta_max) and theta_max > 0):
        raise ValueError(f"theta_max: must be a finite angle > 0 (rad), got {theta_max!r}")
    drive = np.array([abs(hull.at(float(w))[2]) * a * w for a, w in zip(wave.amplitudes,
                                                                         wave.omegas)])  # fmt: skip
    if drive.size == 1:
        motion = 0.5 * float(drive[0]) * theta_max
    else:
        motion = theta_max * math.sqrt(0.5 * float(np.sum(drive**2)))
    return min(motion, radiation_bound(hull, wave))


def wave_power_flux(wave: WaveField, rho: float, g: float, depth: float = math.inf) -> float:
    """J = sum_i rho g a_i^2 / 2 c_g(w_i) (W per metre of crest) at the water depth (m; inf:
    deep water, c_g = g / 2 w) (Eqs. 14, 15, 18)."""
    cg = group_velocity(np.asarray(wave.omegas, dtype=float), depth, g)
    return float(np.sum(0.5 * rho * g * wave.amplitudes**2 * cg))


def mechanical_energy(p: fl.FloatingParams, y: NDArray[np.float64], tp: NDArray | None = None,
                      direction: float = 0.0) -> float:  # fmt: skip
    """Kinetic + hydrostatic energy (J) of the mechanical state, with the rotor spin's constant
    1/2 Ja psi'^2 removed (the motor holds psi'; its work is E_motor), plus the end-stop
    cushions' springs (`gimbal`); with the translation
    parameters tp (surge and heave free) also 1/2 M1 s'^2 + A15 s' alpha' + 1/2 M3 z'^2 and
    the mooring's and heave's springs."""
    M, _, spin, _ = fl.mass_and_rhs(y[0:3], y[3:6], p.inertia, p.gyro, p.psid)
    u = y[3:6]
    kin = 0.5 * float(u @ M @ u) + p.gyro[0] * p.psid * spin
    e = kin + 0.5 * float(p.stiffness[0] * y[0] ** 2 + p.stiffness[1] * y[1] ** 2)
    e += p.gyro[5] * cushion_spring_energy(y[2], p.pto[gimbal.PTO_STOP], p.pto[gimbal.PTO_KS])
    if tp is not None and tp[fl.TP_ON] != 0.0:
        b = fl.N_MECH + 2 * p.Ar.shape[1]
        s, z, sd, zd = y[b : b + 4]
        al_d = -(math.sin(direction) * y[3] - math.cos(direction) * y[4])
        e += 0.5 * tp[fl.TP_M1] * sd * sd + tp[fl.TP_A15] * sd * al_d + 0.5 * tp[fl.TP_M3] * zd * zd
        e += 0.5 * tp[fl.TP_K] * s * s + 0.5 * tp[fl.TP_C33] * z * z
    return e


def gyro_moment(p: fl.FloatingParams, y: NDArray[np.float64], accel: NDArray) -> NDArray:
    """Moment of the gyro unit on the hull along the (theta, rho) coordinates (N m, (2,)):
    minus the gimbal+rotor's B^T (J B u' + J B' u + w x h) rows of theta and rho, with the
    generator torque's reaction included through the rho row (the gimbal axis is e2)."""
    q, u = y[0:3], y[3:6]
    Mfull, v, _, gy = fl.mass_and_rhs(q, u, p.inertia, p.gyro, p.psid)
    Mh, vh, _, _ = fl.mass_and_rhs(q, u, p.inertia, np.zeros(6), 0.0)
    Mg_part = (Mfull - Mh) @ accel + gy
    return -Mg_part[:2]
