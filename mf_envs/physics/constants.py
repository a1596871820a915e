"""Physical constants used by every model, defined once (SI units).

G: 9.81 m/s^2, the value the source uses throughout (Rios 2017: ch. 2 tennis-racket flight, ch. 3
   wave relations). Standard gravity (CGPM 1901) is 9.80665 m/s^2, 3.5e-4 lower; we keep the
   seed's value so that the dissertation's models (GOWEC-v0, Eq. 95, the ship) reproduce its numbers
   exactly. Pass your own g where a model takes one.
RHO_SEAWATER: sea-water density 1025 kg/m^3 (ITTC 2011 at 15 C, 35 g/kg salinity: 1025.9; the
naval-architecture value of Fossen 2011 and Faltinsen 1990).
RHO_FRESHWATER: fresh-water density 1000 kg/m^3 (999.1 at 15 C; the round value of the swimming
literature, e.g. Tytell & Lauder 2004's flow tank).
RPM: rad/s per revolution per minute, 2 pi / 60.
"""

import math

G = 9.81  # m/s^2
RHO_SEAWATER = 1025.0  # kg/m^3
RHO_FRESHWATER = 1000.0  # kg/m^3
RPM = 2.0 * math.pi / 60.0  # (rad/s) / rpm
