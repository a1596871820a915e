"""`GimbalModel`: the GOWEC fast path (scalar gimbal equation, numba RK4) over a wave field."""

from __future__ import annotations

import copy
import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from mf_envs.physics.gowec.kernels import Waves, buoy_rates, fast_step, gimbal_accel
from mf_envs.physics.gowec.params import GOWECParams
from mf_envs.physics.waves import WaveField


class GimbalModel:
    """The fast path: the scalar gimbal equation driven by a wave field (numba RK4).

    effects: `gyroscopic` (psi' != 0), `gimbal_inertia` (general inertias; off = Eq. 79: thin
    disk, massless gimbal), `buoy_rocking` (off = still buoy), `wave_2d` (both slope angles; off
    = rocking about e1 only, Eq. 94).
    """

    def __init__(self, params: GOWECParams, wave: WaveField, effects: frozenset[str]) -> None:
        self.params, self.wave, self.effects = params, wave, frozenset(effects)
        Ja = params.rotor_inertia
        if "gimbal_inertia" in self.effects:
            self.inert = np.array([Ja, params.transverse, *params.gimbal_inertia], dtype=float)
        else:
            self.inert = np.array([Ja, 0.5 * Ja, 0.0, 0.0, 0.0])
        self.psid = params.rotor_speed if "gyroscopic" in self.effects else 0.0
        rock = "buoy_rocking" in self.effects
        self._amp, self._om = wave.amplitudes, wave.omegas
        self._eps, self._k = wave.phases, wave.slope_wavenumbers  # k F(k r), waterplane mean
        # a still buoy: zero slope projections (the elevation is still computed)
        self._cth = math.cos(wave.direction) if rock else 0.0
        self._sth = math.sin(wave.direction) if rock else 0.0
        self._two_d = "wave_2d" in self.effects

    def with_phases(self, phases: ArrayLike) -> GimbalModel:
        """This model on the same wave components with other phases (rad): what a reset needs,
        without rebuilding the response factors (a shallow copy; arrays are not written)."""
        w = self.wave
        phases = np.asarray(phases, dtype=np.float64)
        wave = WaveField(w.amplitudes, w.omegas, phases, w.wavenumbers, w.direction, w.buoy_radius)
        model = copy.copy(self)
        model.wave, model._eps = wave, wave.phases
        return model

    def step(
        self, t: float, phi: float, phid: float, Mg: float, dt: float, n: int = 1
    ) -> tuple[float, ...]:
        """(phi, phi', energy J, w1, w2, w3, eta) after n substeps of dt (s) with the generator
        torque Mg (N m); w (rad/s) buoy rates and eta (m) the elevation (0 without rocking)."""
        waves = Waves(self._amp, self._om, self._eps, self._k, self._cth, self._sth, self._two_d)
        return fast_step(t, phi, phid, Mg, dt, n, self.inert, self.psid, waves)

    def rates(self, t: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Buoy body rates w (3,) rad/s and w' (3,) rad/s^2 at time t."""
        return buoy_rates(
            t, self._amp, self._om, self._eps, self._k, self._cth, self._sth, self._two_d
        )

    def accel(self, t: float, phi: float, phid: float, Mg: float) -> float:
        w, wd = self.rates(t)
        i = self.inert
        return gimbal_accel(phi, phid, w, wd, Mg, i[0], i[1], i[2], i[3], i[4], self.psid)
