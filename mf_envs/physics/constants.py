"""Physical constants used by every model, defined once (SI units).

G: standard gravity 9.80665 m/s^2 (CGPM 1901; the seed's 9.81 rounds it).
RHO_SEAWATER: sea-water density 1025 kg/m^3 (ITTC 2011 at 15 C, 35 g/kg salinity: 1025.9; the
naval-architecture value of Fossen 2011 and Faltinsen 1990).
RPM: rad/s per revolution per minute, 2 pi / 60.
"""

import math

G = 9.80665  # m/s^2
RHO_SEAWATER = 1025.0  # kg/m^3
RPM = 2.0 * math.pi / 60.0  # (rad/s) / rpm
