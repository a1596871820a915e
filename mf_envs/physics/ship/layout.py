"""The packed float64 parameter vector P that the ship's numba kernels read, generated here once.

`KernelParams` declares every slot (field order = slot order, SI units); `Slot` (an IntEnum the
kernels index with, `P[Slot.J1]`; numba folds it to a constant), `N_PARAMS` and `pack` are all
derived from it, so adding a hull parameter is one field here plus its use in the kernels and in
`mf_envs.physics.ship.model.pack_params`. A tuple field is a block (`BLOCKS`: the torque drive's
`ship.drive.DriveParams.pack`, the `ship.coupling` coefficients) filling slots NAME_0 ..
NAME_{len-1}; the kernels slice it at the generated offset (`DRV0 = Slot.DRIVE_0`, `CPL0`), so
the sub-indices are the block's own (`ship.drive.DPHIMAX` ...). Also the layouts of the
kernels' state y (`N_STATE`) and outputs (`N_OUT`). The kernels' numba caches are stamped by
this file too (`mf_envs._cache`: it is among their imports).
"""

from __future__ import annotations

import dataclasses
import enum

import numpy as np
from numpy.typing import NDArray

from mf_envs._validate import check_finite
from mf_envs.physics.ship.coupling import N_COUPLING
from mf_envs.physics.ship.drive import N_DRIVE

BLOCKS: dict[str, int] = {"drive": N_DRIVE, "coupling": N_COUPLING}  # tuple fields, lengths


@dataclasses.dataclass(frozen=True)
class KernelParams:
    """One ship + gyro scene as the kernels see it (effects already applied: an effect that is
    off is a zero coefficient). Modes are integer codes stored as floats."""

    j1: float = 0.0  # hull roll inertia (+ A44 with added_inertia), kg m^2
    j2: float = 0.0  # hull pitch inertia, kg m^2
    j3: float = 0.0  # hull yaw inertia, kg m^2
    d1: float = 0.0  # gimbal + rotor inertia about gimbal e1, kg m^2
    d2: float = 0.0  # ... about gimbal e2 (the precession axis), kg m^2
    d3: float = 0.0  # ... about gimbal e3 (the spin axis), kg m^2
    jr3: float = 0.0  # rotor polar inertia J3^(3), kg m^2
    psid: float = 0.0  # rotor spin rate psi', rad/s (0: gyroscopic off)
    ngyro: float = 1.0  # number of gyros, 1 or 2
    form: float = 0.0  # FORM_EXACT or FORM_SEED
    k44: float = 0.0  # roll stiffness C44, N m/rad
    gzr: float = 0.0  # BM/GM of the wall-sided GZ (0: linear)
    k55: float = 0.0  # pitch stiffness C55, N m/rad
    b44: float = 0.0  # linear roll damping, N m s/rad
    b44q: float = 0.0  # quadratic roll damping, N m s^2/rad^2
    b55: float = 0.0  # pitch damping, N m s/rad
    b66: float = 0.0  # yaw damping, N m s/rad
    gmode: float = 0.0  # gimbal drive code (GIMBAL_*)
    gamp: float = 0.0  # Eq. 118/119 amplitude, rad
    gfreq: float = 0.0  # Eq. 118/119 frequency, Hz
    gphase: float = 0.0  # Eq. 119 phase, rad
    tau: float = 0.0  # servo time constant, s
    ratemax: float = 0.0  # precession-rate limit, rad/s
    phimax: float = 0.0  # end stops, rad
    limits: float = 0.0  # 1: gimbal_limits on
    tstop: float = 0.0  # end-stop envelope time, s
    wmode: float = 0.0  # wave code (WAVE_*)
    wm0: float = 0.0  # regular wave roll moment amplitude, N m
    womega: float = 0.0  # wave frequency, rad/s
    wphase: float = 0.0  # wave phase, rad
    wf0: float = 0.0  # regular wave heave force amplitude, N
    tabdt: float = 0.0  # wave table step, s
    jg2: float = 0.0  # gimbal frame inertia J2^(2), kg m^2 (seed form's Eqs. 126/128)
    trans: float = 0.0  # 1: translation on
    mass: float = 0.0  # hull mass, kg
    kh: float = 0.0  # heave stiffness, N/m
    ch: float = 0.0  # heave damping, N s/m
    css: float = 0.0  # surge/sway damping, N s/m
    gz3: float = 0.0  # cubic GZ term over GM, 1/rad^2 (`ship.hulls.Hull.gz_cubic`)
    speed: float = 0.0  # ship speed U, m/s (sway-roll-yaw coupling)
    cplon: float = 0.0  # 1: sway-roll-yaw coupling on (`ship.coupling`)
    units: float = 1.0  # identical units lumped in each gyro (mount moment per unit)
    protor: float = 0.0  # rotor running (or spool-up) power of all units, W (reported)
    # blocks (a tuple field fills len slots NAME_0 .. NAME_{len-1}; BLOCKS gives the lengths)
    drive: tuple[float, ...] = (0.0,) * N_DRIVE  # `ship.drive.DriveParams.pack` (may hold inf)
    coupling: tuple[float, ...] = (0.0,) * N_COUPLING  # `ship.coupling.SwayRollYaw.pack`

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            if f.name in BLOCKS:
                if len(v) != BLOCKS[f.name] or np.isnan(np.asarray(v, dtype=float)).any():
                    raise ValueError(f"{f.name}: needs {BLOCKS[f.name]} numbers, none NaN")
            else:
                check_finite(f.name, v)

    def pack(self) -> NDArray[np.float64]:
        """P (N_PARAMS,) float64 in slot order (blocks flattened in place)."""
        vals: list[float] = []
        for f in dataclasses.fields(self):
            v = getattr(self, f.name)
            vals.extend(v) if f.name in BLOCKS else vals.append(v)
        return np.array(vals, dtype=np.float64)


FORM_EXACT, FORM_SEED = 0, 1  # `form` codes
GIMBAL_SERVO, GIMBAL_SINUSOIDAL, GIMBAL_CONTINUOUS, GIMBAL_TORQUE = 0, 1, 2, 3  # `gmode` codes
WAVE_NONE, WAVE_REGULAR, WAVE_TABLE = 0, 1, 2  # `wmode` codes


def _slot_names() -> list[str]:
    """Slot names in order: a scalar field NAME, a block field NAME_0 .. NAME_{len-1}."""
    names: list[str] = []
    for f in dataclasses.fields(KernelParams):
        n = f.name.upper()
        names += [f"{n}_{i}" for i in range(BLOCKS[f.name])] if f.name in BLOCKS else [n]
    return names


Slot = enum.IntEnum("Slot", _slot_names(), start=0)
N_PARAMS = len(Slot)
DRV0 = int(Slot.DRIVE_0)  # first slot of the drive block: P[DRV0 : DRV0 + N_DRIVE]
CPL0 = int(Slot.COUPLING_0)  # first slot of the coupling block: P[CPL0 : CPL0 + N_COUPLING]

# the kernels' state y (N_STATE,): body rates w1, w2, w3 (rad/s), gimbal angle phi (rad) and
# rate phi' (rad/s), hull translation (3 positions, 3 velocities) and these three
N_STATE = 14  # + drive loop integral z (rad), drive energy int n |tau phi'| dt (J), sway v (m/s)
Z_STATE, E_STATE, V_STATE = 11, 12, 13
# a step's outputs out (N_OUT,): gyro roll moment, wave moment, drive torque (N m), drive power
# (W), mount moment per unit (N m; |(H phi', drive + cushion torque)| of one unit), rotor running
# power (W, all)
N_OUT = 6
