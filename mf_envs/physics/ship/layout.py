"""The packed float64 parameter vector P that the ship's numba kernels read, generated here once.

`KernelParams` declares every slot (field order = slot order, SI units); `Slot` (an IntEnum the
kernels index with, `P[Slot.J1]`; numba folds it to a constant), `N_PARAMS` and `pack` are all
derived from it, so adding a hull parameter is one field here plus its use in the kernels and in
`mf_envs.physics.ship.model.pack_params`. (numba's cache watches only a kernel's own file: after
editing this one, touch `kernels.py`.)
"""

from __future__ import annotations

import dataclasses
import enum

import numpy as np
from numpy.typing import NDArray

from mf_envs._validate import check_finite


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
    kv: float = 0.0  # torque drive loop gain, N m s/rad
    taumax: float = 0.0  # torque limit, N m (0: none)
    cg: float = 0.0  # gimbal damping / brake, N m s/rad
    kstop: float = 0.0  # end-stop stiffness, N m/rad

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            check_finite(f.name, getattr(self, f.name))

    def pack(self) -> NDArray[np.float64]:
        """P (N_PARAMS,) float64 in slot order."""
        return np.array(dataclasses.astuple(self), dtype=np.float64)


FORM_EXACT, FORM_SEED = 0, 1  # `form` codes
GIMBAL_SERVO, GIMBAL_SINUSOIDAL, GIMBAL_CONTINUOUS, GIMBAL_TORQUE = 0, 1, 2, 3  # `gmode` codes
WAVE_NONE, WAVE_REGULAR, WAVE_TABLE = 0, 1, 2  # `wmode` codes

Slot = enum.IntEnum("Slot", [f.name.upper() for f in dataclasses.fields(KernelParams)], start=0)
N_PARAMS = len(Slot)
