"""Ship with one or two gyroscopic roll stabilizers (Rios 2017, ch. 3 §3.3 and appendix §3.5).

        e3 (yaw)          ship e^(1), attitude R(t) in SO(3)
         |   gimbal e^(2) = e^(1) R_2(phi)       precession axis e_2 (athwartships)
         |   rotor  e^(3) = e^(2) R_3(psi)       spin axis: the gimbal's e_3
         +----- e1 (roll)          gyro roll moment on the hull: -n H phi' cos(phi) (Eq. 123)

Public facade over the concept modules:

- `params`: `ShipParams`, `GyroParams`, presets (`small_yacht`, `seed_test_hull`,
  `seakeeper_gyro` from Table 3-1) and the capacity bound `capacity_ratio`;
- `kernels`: the numba fast paths (exact angular-momentum balance; the seed's Eqs. 123-128),
  stepped by the RKMK4 of `mf_envs.frames.kernels`; `loads`: moments and gimbal drives;
  `layout`: the packed parameter vector, generated from `layout.KernelParams`;
- `model`: effects, `GimbalDrive`, `WaveLoad`, `pack_params`, `simulate`, named quantities;
- `engine`: the same ship on the general multibody engine (`build_ship_multibody`,
  `simulate_engine`) used to check the fast paths;
- `waves`: wave roll moment / heave force tables from an irregular sea.
"""

from mf_envs.physics.ship.engine import build_ship_multibody, simulate_engine
from mf_envs.physics.ship.hulls import mss_naval_vessel, small_yacht
from mf_envs.physics.ship.model import (
    FORMS,
    SEED_EFFECTS,
    SHIP_EFFECTS,
    GimbalDrive,
    ShipRun,
    WaveLoad,
    gyro_roll_moment,
    initial_state,
    pack_params,
    pitch_angle,
    roll_angle,
    roll_inertia,
    simulate,
)
from mf_envs.physics.ship.params import (
    RPM,
    SEAKEEPER,
    GyroParams,
    ShipParams,
    capacity_ratio,
    seakeeper_gyro,
    seed_test_hull,
)
from mf_envs.physics.ship.seas import regular_heave_force, wave_table

__all__ = [
    "FORMS",
    "RPM",
    "SEAKEEPER",
    "SEED_EFFECTS",
    "SHIP_EFFECTS",
    "GimbalDrive",
    "GyroParams",
    "ShipParams",
    "ShipRun",
    "WaveLoad",
    "build_ship_multibody",
    "capacity_ratio",
    "gyro_roll_moment",
    "initial_state",
    "mss_naval_vessel",
    "pack_params",
    "pitch_angle",
    "regular_heave_force",
    "roll_angle",
    "roll_inertia",
    "seakeeper_gyro",
    "seed_test_hull",
    "simulate",
    "simulate_engine",
    "small_yacht",
    "wave_table",
]
