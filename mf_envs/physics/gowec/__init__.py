"""Gyroscopic ocean wave energy converter (GOWEC): gimbal equation fast path and power.

Rios 2017, ch. 3 Sec. 3.2 (Eqs. 76-97). One gyroscope of the dual unit (the power of the device is
twice the numbers here, Sec. 3.2.3):

         wave -> buoy (1) rocks, omega^(1) prescribed by the wave slope (Eqs. 77-78, 90-93)
        +--------------------------------+
        |   gimbal (2): free about e2^(1), angle phi, generator torque M_g opposes phi'
        |     +-----------+
        |     |  rotor (3) spins about e3^(2) at the prescribed rate psi' (motor)
        |     +-----------+
        +--------------------------------+

With the buoy rotation prescribed, Lagrange's equation for phi is exact (the gimbal/rotor centre
of mass on the gimbal axis). Gimbal-frame buoy rates O1 = cos(phi) w1 - sin(phi) w3,
O3 = sin(phi) w1 + cos(phi) w3; rotor inertias Jt (transverse), Ja (axial); gimbal (Jg1, Jg2, Jg3):

    (Jg2 + Jt)(phi'' + w2') - (Jg3 - Jg1 - Jt) O1 O3 - Ja (O3 + psi') O1 + M_g = 0

For a thin disk (Jt = Ja/2), no gimbal inertia and w2 = w3 = 0 (Eq. 79) this is

    Ja { 1/2 phi'' - 1/4 w1^2 sin(2 phi) - w1 psi' cos(phi) } + M_g = 0        (Eq. 81)

(the seed's Eq. 80 has + w1^2/4 sin(2 phi); Eq. 81 and Lagrange have the minus sign). With the
rotor off (psi' = 0) phi = 0 is unstable: the gimbal turns toward +-90 deg. `gowec_engine` checks
this fast path against the general multibody engine. Power P = M_g phi' (Eq. 82, positive =
harvested); with phi = w t locked to the wave the mean is Eq. 86/95; the ceiling over all gimbal
motions is 4/pi times that (a square-wave sin(phi)).
"""

from mf_envs.physics.constants import RPM
from mf_envs.physics.gowec.kernels import (
    Waves,
    buoy_rates,
    buoy_rates_into,
    fast_step,
    gimbal_accel,
)
from mf_envs.physics.gowec.model import GimbalModel
from mf_envs.physics.gowec.params import GOWECParams
from mf_envs.physics.gowec.power import (
    SQUARE_WAVE_GAIN,
    analytic_max_power,
    analytic_max_power_from_angle,
    detuned_mean_power,
    generator_power,
    gyroscopic_power,
    power_map,
    seakeeper_net_power,
)
from mf_envs.physics.gyros import SEAKEEPER

__all__ = [
    "GOWECParams",
    "GimbalModel",
    "RPM",
    "SEAKEEPER",
    "SQUARE_WAVE_GAIN",
    "Waves",
    "analytic_max_power",
    "analytic_max_power_from_angle",
    "buoy_rates",
    "buoy_rates_into",
    "detuned_mean_power",
    "fast_step",
    "generator_power",
    "gimbal_accel",
    "gyroscopic_power",
    "power_map",
    "seakeeper_net_power",
]
