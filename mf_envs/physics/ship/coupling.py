"""Sway-roll-yaw coupling of a ship at forward speed (on when the hull has its coefficients).

The MSS naval vessel (Blanke & Christensen 1993, as coded in Fossen's Marine Systems Simulator,
`VESSELS/navalvessel.m`) couples sway velocity v, roll rate p and yaw rate r at surge speed u
through added mass and speed-dependent hydrodynamic forces (body frame: x forward, y to port in
this package; MSS's y is to starboard and z down, so v, p, r, phi keep their sign only after
the flip below). In MSS's own axes (x fwd, y stbd, z down):

    [m - Y_vdot,        -(m z_G + Y_pdot),  m x_G - Y_rdot] [v']   [Y_h + Y_c]
    [-(m z_G + K_vdot),  I_xx - K_pdot,     -K_rdot       ] [p'] = [K_h + K_c]
    [m x_G - N_vdot,    -N_pdot,            I_zz - N_rdot ] [r']   [N_h + N_c]

    Y_h = Y_|u|v |u| v + Y_ur u r + Y_v|v| v|v| + Y_v|r| v|r| + Y_r|v| r|v|
          + Y_phi|uv| phi |u v| + Y_phi|ur| phi |u r| + Y_phiuu phi u^2
    K_h = (the same pattern with K) + K_|u|p |u| p + K_p|p| p|p| + K_p p + K_phiphiphi phi^3
          - rho g GM V phi
    N_h = N_|u|v |u| v + N_|u|r |u| r + N_r|r| r|r| + N_r|v| r|v|
          + N_phi|uv| phi |u phi| + N_phiu|r| phi u |r| + N_phiu|u| phi u |u|
    Y_c = -m u r,  K_c = m z_G u r,  N_c = -m x_G u r        (rigid-body centripetal terms)

(the N_phi|uv| term multiplies |u phi| in navalvessel.m, kept as coded). The roll terms the hull
already has (K_p, K_p|p|, K_|u|p, K_phiphiphi, GM: `hulls.Hull`) are not repeated here:
`extra_forces` returns Y_h + Y_c and the *remaining* K and N terms, and `mass_coupling` the
off-diagonal added-mass terms; `kernels.ship_accel` solves them with the gyro-ship balance.
Axes: this package's e_2 points to port and e_3 up, MSS's y to starboard and z down, so
v_MSS = -v, p_MSS = p, r_MSS = -r, phi_MSS = phi, and Y, N change sign (K does not); z_G > 0
down in MSS. Hand-written (numba): it runs inside the kernel's Runge-Kutta stages.
"""

from __future__ import annotations

import math
from dataclasses import astuple, dataclass

import numba
import numpy as np
from numpy.typing import NDArray

RHO_MSS = 1014.0
N_COUPLING = 34


@dataclass(frozen=True)
class SwayRollYaw:
    """Coefficients of the coupling (MSS names, SI units as in navalvessel.m: N, N m, kg, m).

    mass m (kg), x_g, z_g (m, MSS axes: x fwd, z down), the added-mass derivatives and the
    hydrodynamic derivatives of the module doc, in navalvessel.m's order.
    """

    mass: float
    x_g: float
    z_g: float
    y_vdot: float
    y_pdot: float
    y_rdot: float
    k_vdot: float
    k_rdot: float
    n_vdot: float
    n_pdot: float
    n_rdot: float
    y_auv: float
    y_ur: float
    y_vav: float
    y_var: float
    y_rav: float
    y_bauv: float
    y_baur: float
    y_buu: float
    k_auv: float
    k_ur: float
    k_vav: float
    k_var: float
    k_rav: float
    k_bauv: float
    k_baur: float
    k_buu: float
    n_auv: float
    n_aur: float
    n_rar: float
    n_rav: float
    n_bauv: float = 0.0
    n_buar: float = 0.0
    n_buau: float = 0.0

    @classmethod
    def mss_naval_vessel(cls) -> SwayRollYaw:
        """navalvessel.m (MSS): Y_vdot = -3.93e5 etc.; z_G = -(VCG - D) = -1.06 m, x_G = -3.38 m."""
        return cls(
            mass=357.0 * RHO_MSS, x_g=-3.38, z_g=-(3.36 - 2.3),
            y_vdot=-393000.0, y_pdot=-296000.0, y_rdot=-1400000.0,
            k_vdot=296000.0, k_rdot=0.0, n_vdot=538000.0, n_pdot=0.0, n_rdot=-38.7e6,
            y_auv=-11800.0, y_ur=131000.0, y_vav=-3700.0, y_var=-794000.0, y_rav=-182000.0,
            y_bauv=10800.0, y_baur=251000.0, y_buu=-74.0,
            k_auv=9260.0, k_ur=-102000.0, k_vav=29300.0, k_var=621000.0, k_rav=142000.0,
            k_bauv=-8400.0, k_baur=-196000.0, k_buu=-1180.0,
            n_auv=-92000.0, n_aur=-4710000.0, n_rar=-202000000.0, n_rav=-15600000.0,
            n_bauv=-214000.0, n_buar=-4980000.0, n_buau=-8000.0,
        )  # fmt: skip

    def pack(self) -> NDArray[np.float64]:
        """The coefficients as a float64 vector in field order (read by `extra_forces`)."""
        return np.array(astuple(self), dtype=np.float64)


# indices into the packed vector (field order of SwayRollYaw)
(CM, CXG, CZG, YVD, YPD, YRD, KVD, KRD, NVD, NPD, NRD, YAUV, YUR, YVAV, YVAR, YRAV, YBAUV, YBAUR,
 YBUU, KAUV, KUR, KVAV, KVAR, KRAV, KBAUV, KBAUR, KBUU, NAUV, NAUR, NRAR, NRAV, NBAUV, NBUAR,
 NBUAU) = range(34)  # fmt: skip


@numba.njit(cache=True)
def extra_forces(u, v, p, r, phi, C):
    """(Y, K, N) in MSS axes: Y_h + Y_c, the K_h terms not in the hull (module doc) + K_c, and
    N_h + N_c (N, N m) at surge u, sway v (m/s), roll/yaw rates p, r (rad/s), roll phi (rad)."""
    au, av, ar = abs(u), abs(v), abs(r)
    y = (C[YAUV] * au * v + C[YUR] * u * r + C[YVAV] * v * av + C[YVAR] * v * ar
         + C[YRAV] * r * av + C[YBAUV] * phi * abs(u * v) + C[YBAUR] * phi * abs(u * r)
         + C[YBUU] * phi * u * u - C[CM] * u * r)  # fmt: skip
    k = (C[KAUV] * au * v + C[KUR] * u * r + C[KVAV] * v * av + C[KVAR] * v * ar
         + C[KRAV] * r * av + C[KBAUV] * phi * abs(u * v) + C[KBAUR] * phi * abs(u * r)
         + C[KBUU] * phi * u * u + C[CM] * C[CZG] * u * r)  # fmt: skip
    n = (C[NAUV] * au * v + C[NAUR] * au * r + C[NRAR] * r * ar + C[NRAV] * r * av
         + C[NBAUV] * phi * abs(u * phi) + C[NBUAR] * phi * u * ar + C[NBUAU] * phi * u * au
         - C[CM] * C[CXG] * u * r)  # fmt: skip
    return y, k, n


@numba.njit(cache=True)
def solve_sway_roll_yaw(jxx, jzz, jxz, r1, r3, u, v, p, r, phi, C):
    """(v', w1', w3') in this package's axes (m/s^2, rad/s^2) of the coupled system: the hull
    + gyro roll-yaw balance jxx w1' + jxz w3' = r1, jxz w1' + jzz w3' = r3 (kernel) with the
    MSS sway equation, the off-diagonal added masses and the yaw added inertia -N_rdot.

    Axis flip (module doc): v_M = -v, r_M = -r, Y = -Y_M, N = -N_M; the MSS rows in our axes
    keep the same matrix entries with the signs of the v and r columns and rows flipped.
    """
    y_m, k_m, n_m = extra_forces(u, -v, p, -r, phi, C)
    m = C[CM]
    # MSS mass matrix in (v_M, p, r_M); rows (Y_M, K, N_M)
    a00, a01, a02 = m - C[YVD], -(m * C[CZG] + C[YPD]), m * C[CXG] - C[YRD]
    a10, a12 = -(m * C[CZG] + C[KVD]), -C[KRD]
    a20, a21 = m * C[CXG] - C[NVD], -C[NPD]
    # our unknowns x = (v', w1', w3') = (-v_M', p', -r_M'); rows: Y (= -Y_M), roll, yaw (= -N_M)
    b00, b01, b02, c0 = a00, -a01, a02, -y_m
    b10, b11, b12, c1 = -a10, jxx, jxz - a12, r1 + k_m
    b20, b21, b22, c2 = a20, jxz - a21, jzz - C[NRD], r3 - n_m
    det = (
        b00 * (b11 * b22 - b12 * b21)
        - b01 * (b10 * b22 - b12 * b20)
        + b02 * (b10 * b21 - b11 * b20)
    )
    x0 = (
        c0 * (b11 * b22 - b12 * b21) - b01 * (c1 * b22 - b12 * c2) + b02 * (c1 * b21 - b11 * c2)
    ) / det
    x1 = (
        b00 * (c1 * b22 - b12 * c2) - c0 * (b10 * b22 - b12 * b20) + b02 * (b10 * c2 - c1 * b20)
    ) / det
    x2 = (
        b00 * (b11 * c2 - c1 * b21) - b01 * (b10 * c2 - c1 * b20) + c0 * (b10 * b21 - b11 * b20)
    ) / det
    return x0, x1, x2


def coupling_ok(C: NDArray) -> bool:
    """True if the packed vector holds a mass (the effect is configured)."""
    return bool(C.shape[0] >= N_COUPLING and math.isfinite(C[CM]) and C[CM] > 0.0)
