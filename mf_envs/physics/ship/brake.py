"""A closed-circuit hydraulic precession brake with a controllable valve (physics only).

The machine (docs/stabilizer_physics.md): Seakeeper's Model 7000 regulates precession with "an
active hydraulic brake mechanism" of two cylinders and a manifold, a "'closed' circuit with no
pump or reservoir" (Operation Manual 90021 rev 4, §1.1, §4.2): the gimbal pumps oil through a
valve, so the brake can only take power out of the gimbal. Here, at gimbal rate a' (rad/s) and
valve command u in [0, 1] (clipped; 1 = valve closed, the most resistance):

    tau_b = -sign(a') min(T_r, (c(u) + q(u) |a'|) |a'| + k_cap max(|a'| - r_cap, 0)),
    c(u) = c_min + u (c_max - c_min),  q(u) = q_min + u (q_max - q_min)  (orifice law),

with T_r the relief-valve torque. Every term opposes a', so tau_b a' <= 0 for every u and a'
(it cannot motor). The rate cap is a flow-limiting valve: above r_cap the resistance rises
steeply (k_cap), whatever u is: the precession-rate cap that bounds the gyro's roll moment
H a' cos(a) on the structure (the purpose of precession braking that limits the precession
rate "so that the gyro torque created is effectively capped"; docs/stabilizer_physics.md §3).

End stops: a cushion (spring-damper) engaging at +-a_s (60 deg, the Model 7000's precession
range), pushing only (never pulling the gimbal back into the stop):

    tau_s = -sign(a) max(0, k_s d + c_s d'),  d = |a| - a_s > 0 (the penetration).

`BrakeParams.design` sizes it all from the rotor H, gimbal inertia J_g, the design roll rate
p_max and the cap r_cap, so that three documented bounds hold whenever |p| <= p_max:
1. cushion: k_s d_max^2 / 2 = J_g (1.1 r_cap)^2 / 2 + H p_max d_max: the gimbal's kinetic
   energy at the capped rate plus the gyroscopic work over the penetration fit in the spring,
   so the penetration stays below d_max (damping only helps); c_s = 2 zeta_s sqrt(k_s J_g);
2. rate cap: above r_cap, J_g a'' <= T_d - k_cap (a' - r_cap) with the largest driving torque
   T_d = H p_max + M_s (gyroscopic torque plus the largest cushion torque
   M_s = k_s d_max + c_s 1.1 r_cap), so k_cap = T_d / (eps r_cap) keeps a' <= (1 + eps) r_cap
   (eps = 0.05; the brake's other terms only add resistance);
3. relief: T_r = 1.5 T_d, above every driving torque, so a saturated brake still decelerates.
Hence the mount moments: roll |H a' cos a| <= 1.05 H r_cap; gimbal axis |tau_b + tau_s| <=
T_r + M_s. Scalar numba kernels (`mf_envs._jit.kernel`), not wired into an env.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from mf_envs._jit import kernel
from mf_envs._validate import nonnegative_scalar, positive_scalar
from mf_envs.physics.end_stops import cushion_torque, size_cushion

# packed brake vector B
BCMIN, BCMAX, BQMIN, BQMAX, BRCAP, BKCAP, BTREL, BASTOP, BKS, BCS = range(10)
N_BRAKE = 10
CAP_OVERSHOOT = 0.05  # eps of the rate cap's design (module doc)


@dataclass(frozen=True)
class BrakeParams:
    """A hydraulic precession brake and its cushioned stops (module doc), SI units.

    c_min, c_max: linear valve resistance at u = 0 and u = 1, N m s/rad;
    q_min, q_max: orifice (quadratic) resistance at u = 0 and 1, N m s^2/rad^2;
    rate_cap: r_cap, rad/s; cap_resistance: k_cap above it, N m s/rad;
    relief_torque: T_r, N m; stop_angle: a_s, rad; stop_stiffness: k_s, N m/rad;
    stop_damping: c_s, N m s/rad; max_penetration: d_max the cushion is sized for, rad.
    """

    c_min: float
    c_max: float
    rate_cap: float
    cap_resistance: float
    relief_torque: float
    stop_stiffness: float
    stop_damping: float
    max_penetration: float
    stop_angle: float = math.pi / 3
    q_min: float = 0.0
    q_max: float = 0.0

    def __post_init__(self) -> None:
        for f in ("c_min", "c_max", "q_min", "q_max", "stop_damping"):
            nonnegative_scalar(f, getattr(self, f))
        for f in ("rate_cap", "cap_resistance", "relief_torque", "stop_stiffness"):
            positive_scalar(f, getattr(self, f))
        positive_scalar("max_penetration", self.max_penetration)
        positive_scalar("stop_angle", self.stop_angle)
        if self.c_max < self.c_min:
            raise ValueError(f"c_max: must be >= c_min = {self.c_min!r}, got {self.c_max!r}")
        if self.q_max < self.q_min:
            raise ValueError(f"q_max: must be >= q_min = {self.q_min!r}, got {self.q_max!r}")
        if self.stop_angle + self.max_penetration >= math.pi / 2:
            raise ValueError(
                "max_penetration: stop_angle + max_penetration must stay below 90 deg, got "
                f"{math.degrees(self.stop_angle + self.max_penetration):.1f} deg"
            )

    @classmethod
    def design(
        cls,
        angular_momentum: float,
        gimbal_inertia: float,
        design_roll_rate: float,
        rate_cap: float = 2.0,
        max_penetration: float = math.radians(5.0),
        stop_angle: float = math.pi / 3,
        stop_damping_ratio: float = 0.5,
        c_range: tuple[float, float] = (0.05, 10.0),
        q_range: tuple[float, float] = (0.0, 0.0),
    ) -> BrakeParams:
        """Sized for rotor H (N m s), gimbal inertia J_g (kg m^2), design roll rate p_max
        (rad/s) and cap r_cap (rad/s), module doc bounds 1-3. c_range: (c_min, c_max) in units
        of H (s: c = H is the brake that lets the gimbal precess at the roll rate);
        q_range likewise in units of H (s^2)."""
        h = positive_scalar("angular_momentum", angular_momentum)
        jg = positive_scalar("gimbal_inertia", gimbal_inertia)
        p = positive_scalar("design_roll_rate", design_roll_rate)
        r = positive_scalar("rate_cap", rate_cap)
        d = positive_scalar("max_penetration", max_penetration)
        zeta = nonnegative_scalar("stop_damping_ratio", stop_damping_ratio)
        v = (1.0 + 2.0 * CAP_OVERSHOOT) * r  # margin over the capped rate at contact
        ks, cs = size_cushion(jg, v, h, p, d, zeta)
        td = h * p + ks * d + cs * v
        return cls(
            c_min=c_range[0] * h,
            c_max=c_range[1] * h,
            q_min=q_range[0] * h,
            q_max=q_range[1] * h,
            rate_cap=r,
            cap_resistance=td / (CAP_OVERSHOOT * r),
            relief_torque=1.5 * td,
            stop_angle=stop_angle,
            stop_stiffness=ks,
            stop_damping=cs,
            max_penetration=d,
        )

    @property
    def stop_moment_bound(self) -> float:
        """M_s = k_s d_max + c_s 1.1 r_cap, N m: the largest cushion torque (module doc)."""
        return (
            self.stop_stiffness * self.max_penetration
            + self.stop_damping * (1.0 + 2.0 * CAP_OVERSHOOT) * self.rate_cap
        )

    def pack(self) -> NDArray[np.float64]:
        """The packed float64 vector B (N_BRAKE,) the kernels read."""
        B = np.zeros(N_BRAKE)
        B[BCMIN], B[BCMAX], B[BQMIN], B[BQMAX] = self.c_min, self.c_max, self.q_min, self.q_max
        B[BRCAP], B[BKCAP], B[BTREL] = self.rate_cap, self.cap_resistance, self.relief_torque
        B[BASTOP], B[BKS], B[BCS] = self.stop_angle, self.stop_stiffness, self.stop_damping
        return B

    def stable_dt(self, gimbal_inertia: float) -> float:
        """A classical-RK4 step (s) inside the stability region for the brake's stiffest
        linear modes: the cap's decay k_cap / J_g (real, |z| <= 2.78) and the cushion's
        oscillation sqrt(k_s / J_g) (|z| <= 2.8 near the imaginary axis), with a factor 2."""
        jg = positive_scalar("gimbal_inertia", gimbal_inertia)
        rmax = (1.0 + 2.0 * CAP_OVERSHOOT) * self.rate_cap
        lam = max(
            (self.cap_resistance + self.c_max + 2.0 * self.q_max * rmax + self.stop_damping) / jg,
            math.sqrt(self.stop_stiffness / jg),
        )
        return 1.39 / lam


@kernel(forceinline=True)
def brake_torque(u: float, ad: float, B: np.ndarray) -> float:
    """tau_b (N m) at valve command u (clipped to [0, 1]) and gimbal rate ad (rad/s)."""
    uc = min(max(u, 0.0), 1.0)
    c = B[BCMIN] + uc * (B[BCMAX] - B[BCMIN])
    q = B[BQMIN] + uc * (B[BQMAX] - B[BQMIN])
    a = abs(ad)
    mag = (c + q * a) * a + B[BKCAP] * max(a - B[BRCAP], 0.0)
    mag = min(mag, B[BTREL])
    return -mag if ad > 0.0 else (mag if ad < 0.0 else 0.0)


@kernel(forceinline=True)
def stop_torque(a: float, ad: float, B: np.ndarray) -> float:
    """tau_s (N m) of the cushioned stops at gimbal angle a (rad) and rate ad (rad/s)
    (`end_stops.cushion_torque`)."""
    return cushion_torque(a, ad, B[BASTOP], B[BKS], B[BCS])


@kernel(forceinline=True)
def gimbal_accel(a: float, ad: float, u: float, p: float, h: float, jg: float, B: np.ndarray):
    """(a'' in rad/s^2, tau_b, tau_s in N m) of a gimbal of inertia jg (kg m^2) carrying a
    rotor of angular momentum h (N m s) on a hull rolling at p (rad/s): the gyroscopic torque
    h p cos(a) plus the brake and the cushion."""
    tb = brake_torque(u, ad, B)
    ts = stop_torque(a, ad, B)
    return (h * p * math.cos(a) + tb + ts) / jg, tb, ts
