"""GOWEC-v0: harvest wave energy with a gyroscope by loading its gimbal (Rios 2017, Sec. 3.2)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_finite, check_int, check_nonnegative, check_positive
from mf_envs.envs.base import MFEnv
from mf_envs.physics import gowec as gw
from mf_envs.physics import waves

AVAILABLE_EFFECTS = {
    "gyroscopic": "rotor spin coupling H w1 cos(phi) (off: rotor stopped)",
    "gimbal_inertia": "gimbal inertia and a general rotor (off: Eq. 79 thin disk, light gimbal)",
    "buoy_rocking": "buoy rocks with the wave slope (Eqs. 77-78; off: still buoy)",
    "wave_2d": "both slope angles of an oblique wave (Eqs. 89-93; off: rocking about e1 only)",
    "irregular_waves": "JONSWAP irregular sea with Hs = 2 sqrt(2) a and Tp = wave_period",
}
DEFAULT_EFFECTS = ("gyroscopic", "buoy_rocking", "wave_2d")
_P = gw.GOWECParams()
MAX_GIMBAL_RATE = 60.0  # rad/s, default overspeed trip (and observation bound)
# Buoy waterplane radius (m) used by default in irregular seas: a 5 m diameter buoy for one
# Seakeeper 26 pair (the gyro itself is ~1.2 m across; Seakeeper 26 is fitted on 17-20 m hulls).
# It averages the wave slope over its waterplane (waves.disk_average_factor): F = 0.99 at
# T = 6 s (lambda = 56 m), and it stops the buoy following wavelets shorter than itself, without
# which the buoy rates of a spectrum grow without bound with the spectral cut-off. Regular waves
# default to the seed's point buoy (r = 0), so that analytic_max_power() is Eq. 95 exactly.
BUOY_RADIUS = 2.5
MAX_BUOY_RATE = 5.0  # rad/s, observation bound (breaking waves stay below ~1.6 rad/s)


class GOWECEnv(MFEnv):
    """
    ## Description
    One gyroscope of the gyroscopic ocean wave energy converter of Rios (2017, ch. 3.2): a buoy
    rocks with the slope of the passing wave (Eqs. 77-78, 89-93) averaged over its circular
    waterplane of radius `buoy_radius` (each component x 2 J1(k r)/(k r), so the buoy ignores
    wavelets shorter than itself; 0 = the seed's point buoy), a rotor spins at a fixed rate
    psi' inside a gimbal that may turn about the buoy's e2 axis, and a generator on that axis
    applies the torque M_g. The gimbal obeys (exact for the prescribed buoy rotation)

        (Jg2 + Jt)(phi'' + w2') - (Jg3 - Jg1 - Jt) O1 O3 - Ja (O3 + psi') O1 + M_g = 0,

    which is the seed's Eq. 81 for a thin disk and a light gimbal (sign of Eq. 80 corrected). The
    power harvested is P = M_g phi' (Eq. 82). Locking phi to the wave phase yields Eq. 95 on
    average; a square-wave sin(phi) can reach 4/pi of it.

    ## Action Space
    `Box(-1, 1, (1,), float32)`:

    | Num | Action                                  | Min | Max | Unit (after scaling) |
    |-----|-----------------------------------------|-----|-----|----------------------|
    | 0   | generator torque M_g / max_generator_torque | -1 | 1 | N m                 |

    ## Observation Space
    `Box(float32, (6,))`, what a device measures (encoder on the gimbal, IMU on the buoy):

    | Num | Observation                 | Min   | Max  | Unit  |
    |-----|-----------------------------|-------|------|-------|
    | 0   | sin(phi), gimbal angle      | -1    | 1    |       |
    | 1   | cos(phi)                    | -1    | 1    |       |
    | 2   | phi', gimbal rate           | -max_gimbal_rate | max_gimbal_rate | rad/s |
    | 3-5 | buoy body rates w1, w2, w3  | -5    | 5    | rad/s |

    The wave phase is not observed.

    ## Rewards
    `energy`: the energy harvested in the step, int M_g phi' dt, divided by
    `analytic_max_power() * dt`, so that the episode mean of the reward is the mean power as a
    fraction of Eq. 95. `info["reward_terms"]` holds the terms (they sum to the reward).

    ## Starting State
    phi ~ U(-0.1, 0.1) rad, phi' = 0, wave phase ~ U(0, 2 pi) (irregular seas: random phases
    for every component). `reset(options=...)` accepts `gimbal_angle`, `gimbal_rate`,
    `wave_phase`.

    ## Episode End
    Truncation after `n_periods` wave periods. Termination on a gimbal overspeed trip,
    |phi'| > `max_gimbal_rate` (`info["overspeed"]`; a real unit brakes its gimbal: nothing
    else limits a gimbal that the generator motors, which under a constant full torque spins up
    without bound), or on numerical failure (`info["numerical_failure"]`). The baselines stay
    below 18 rad/s.

    ## Arguments
    | Argument | Default | Meaning |
    |---|---|---|
    | rotor_inertia | 49.66 kg m^2 | polar J3 of the rotor (Seakeeper 26, Table 3-1) |
    | rotor_speed | 523.6 rad/s | psi' (5000 rpm) |
    | wave_amplitude | 1.0 m | a (irregular: Hs = 2 sqrt 2 a, Eq. 16) |
    | wave_period | 6.0 s | T (irregular: peak period) |
    | wave_direction | pi/2 | theta of Eq. 89 (pi/2 head-on) |
    | max_generator_torque | 10000 N m | action scale |
    | max_gimbal_rate | 60 rad/s | overspeed trip (ends the episode) and observation bound |
    | n_periods | 20 | episode length in wave periods |
    | steps_per_period | 300 | control steps per wave period |
    | physics_dt | 0.01 s | RK4 substep (rounded to divide the control step) |
    | gimbal_inertia | (5, 5, 5) kg m^2 | with the `gimbal_inertia` effect |
    | rotor_transverse_inertia | Ja/2 | with the `gimbal_inertia` effect |
    | n_components, gamma | 64, 3.3 | irregular sea (JONSWAP) |
    | buoy_radius | None | waterplane radius (m), slope x 2 J1(kr)/(kr); None: 0 (point buoy) |
    |             |      | for regular waves, 2.5 m with irregular_waves                       |
    | effects | gyroscopic, buoy_rocking, wave_2d | also gimbal_inertia, irregular_waves |

    ## Version History
    * v0: initial version.
    """

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 30}

    def __init__(
        self,
        rotor_inertia: float = _P.rotor_inertia,
        rotor_speed: float = _P.rotor_speed,
        wave_amplitude: float = 1.0,
        wave_period: float = 6.0,
        wave_direction: float = math.pi / 2,
        max_generator_torque: float = 10000.0,
        n_periods: int = 20,
        max_gimbal_rate: float = MAX_GIMBAL_RATE,
        effects: Any = None,
        steps_per_period: int = 300,
        physics_dt: float = 0.01,
        gimbal_inertia: Any = _P.gimbal_inertia,
        rotor_transverse_inertia: float | None = None,
        n_components: int = 64,
        gamma: float = 3.3,
        buoy_radius: float | None = None,
        render_mode: str | None = None,
    ) -> None:
        check_positive("wave_amplitude", wave_amplitude)
        self.wave_period = float(check_positive("wave_period", wave_period))
        self.wave_amplitude = float(wave_amplitude)
        self.wave_direction = float(check_finite("wave_direction", wave_direction))
        self.max_generator_torque = float(
            check_positive("max_generator_torque", max_generator_torque)
        )
        self.n_periods = check_int("n_periods", n_periods, low=1)
        self.max_gimbal_rate = float(check_positive("max_gimbal_rate", max_gimbal_rate))
        spp = check_int("steps_per_period", steps_per_period, low=4)
        self.n_components = check_int("n_components", n_components, low=1)
        self.gamma = float(check_positive("gamma", gamma))
        self.params = gw.GOWECParams(
            float(rotor_inertia),
            float(rotor_speed),
            rotor_transverse_inertia,
            tuple(gimbal_inertia),
        )
        super().__init__(
            effects=effects,
            available_effects=AVAILABLE_EFFECTS,
            default_effects=DEFAULT_EFFECTS,
            control_dt=self.wave_period / spp,
            physics_dt=physics_dt,
            render_mode=render_mode,
        )
        if buoy_radius is None:
            buoy_radius = BUOY_RADIUS if "irregular_waves" in self.effects else 0.0
        self.buoy_radius = float(check_nonnegative("buoy_radius", buoy_radius))
        self.max_steps = self.n_periods * spp
        self.action_space = spaces.Box(-1.0, 1.0, (1,), np.float32)
        hi = np.array(
            [1, 1, self.max_gimbal_rate, MAX_BUOY_RATE, MAX_BUOY_RATE, MAX_BUOY_RATE],
            dtype=np.float32,
        )
        self.observation_space = spaces.Box(-hi, hi, dtype=np.float32)
        self._p_ref = self.analytic_max_power()
        self._energy_scale = 1.0 / (self._p_ref * self.control_dt)
        self.state = np.zeros(2)  # (phi rad, phi' rad/s)
        self._t, self._steps, self._w, self._eta = 0.0, 0, (0.0, 0.0, 0.0), 0.0
        self.wave: waves.WaveField = waves.regular_wave(
            self.wave_amplitude, self.wave_period, self.wave_direction, buoy_radius=self.buoy_radius
        )
        self.model = gw.GimbalModel(self.params, self.wave, self.effects)
        self._model0 = self.model  # phase 0; reset() shifts the phase
        self._last_power = 0.0

    def analytic_max_power(self) -> float:
        """Eq. 95 (Eq. 86 head-on), W: the locked-gimbal mean power of this wave and rotor.

        Both use the buoy's waterplane-averaged slope, factor |2 J1(k r)/(k r)| (r = buoy_radius).
        Irregular sea: Eq. 95 of the equivalent regular wave (a = Hs / (2 sqrt 2), T = Tp), a
        fixed scale, not the sea's achievable maximum. Same eta variance (Hs^2/16 = a^2/2), but
        the JONSWAP sea has shorter components: with buoy_radius = 2.5 m, T = 6 s its RMS buoy
        rate is 2.7x the regular wave's (converged in the cut-off; a point buoy gives 4.8x at the
        4 wp cut-off and grows without bound with it), so irregular-sea ratios above 1 are
        physical. Rewards stay O(1); compare controllers within one scene.
        """
        return gw.analytic_max_power(
            self.params.rotor_inertia,
            self.params.rotor_speed,
            self.wave_amplitude,
            self.wave_period,
            self.wave_direction,
            buoy_radius=self.buoy_radius,
        )

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        Mg = self._torque(action)
        phi, phid, energy, w1, w2, w3, eta = self.model.step(
            self._t, self.state[0], self.state[1], Mg, self.physics_dt, self.n_substeps
        )
        self.state[0], self.state[1] = phi, phid
        self._steps += 1
        self._t = self._steps * self.control_dt
        self._w, self._eta = (w1, w2, w3), eta
        reward, terms = self._get_rew(energy)
        truncated = self._steps >= self.max_steps
        if not (math.isfinite(phi) and math.isfinite(phid) and math.isfinite(energy)):
            info = {"power": 0.0, "reward_terms": terms, "overspeed": False}
            return self._finish_step(self._get_obs(), reward, False, truncated, info, False)
        info = self._info(energy / self.control_dt)
        info["reward_terms"] = terms
        info["numerical_failure"] = False
        overspeed = abs(phid) > self.max_gimbal_rate
        info["overspeed"] = overspeed
        # the base class's _finish_step contract, inlined for speed: obs finite and within bounds
        obs = self._get_obs()
        self._last_obs = obs
        return obs, float(reward), overspeed, truncated, info

    def _torque(self, action: Any) -> float:
        """Generator torque (N m) from the action: NaN/inf -> ValueError, clipped to [-1, 1]."""
        return self._scalar_action(action) * self.max_generator_torque

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        opts = dict(options or {})
        bad = set(opts) - {"gimbal_angle", "gimbal_rate", "wave_phase"}
        if bad:
            raise ValueError(f"options: unknown keys {sorted(bad)}")
        rng = self.np_random
        phi = float(check_finite("gimbal_angle", opts.get("gimbal_angle", rng.uniform(-0.1, 0.1))))
        phid = float(check_finite("gimbal_rate", opts.get("gimbal_rate", 0.0)))
        phase = float(
            check_finite("wave_phase", opts.get("wave_phase", rng.uniform(0, 2 * math.pi)))
        )
        if "irregular_waves" in self.effects:
            hs = 2.0 * math.sqrt(2.0) * self.wave_amplitude
            self.wave = waves.IrregularSea(
                lambda w, h, tp: waves.jonswap_spectrum(w, h, tp, self.gamma),
                hs,
                self.wave_period,
                self.n_components,
                rng,
                self.wave_direction,
                buoy_radius=self.buoy_radius,
            )
            sea_model = gw.GimbalModel(self.params, self.wave, self.effects)
            self.model = sea_model.with_phases(self.wave.phases + phase)
            self.wave = self.model.wave
        else:  # the regular wave of __init__ with this episode's phase
            self.model = self._model0.with_phases([phase])
            self.wave = self.model.wave
        self.state = np.array([phi, phid])
        self._t, self._steps = 0.0, 0
        self._w = tuple(self.model.rates(0.0)[0])
        self._eta = float(self.wave.elevation(0.0))
        info = self._info(0.0)
        info["reward_terms"] = {"energy": 0.0}
        info["overspeed"] = False
        return self._finish_reset(self._get_obs()), info

    def _info(self, power: float) -> dict[str, Any]:
        self._last_power = power
        return {
            "power": power,
            "gimbal_angle": float(self.state[0]),
            "gimbal_rate": float(self.state[1]),
            "buoy_rate": float(self._w[0]),
            "wave_elevation": self._eta,
            "time": self._t,
        }

    def _get_obs(self) -> np.ndarray:
        """(sin phi, cos phi, phi', w1, w2, w3), rates clipped to the documented bounds."""
        phi, phid = self.state
        g, b = self.max_gimbal_rate, MAX_BUOY_RATE
        w1, w2, w3 = (min(max(x, -b), b) for x in self._w)
        return np.array(
            [math.sin(phi), math.cos(phi), min(max(phid, -g), g), w1, w2, w3], dtype=np.float32
        )

    def _get_rew(self, energy: float) -> tuple[float, dict[str, float]]:
        r = energy * self._energy_scale
        return r, {"energy": r}

    def _draw_frame(self) -> np.ndarray:
        from mf_envs.render import draw_gowec

        lam = waves.wavelength(self.wave_period)
        x = np.linspace(-lam, lam, 121)
        c, s = math.cos(self.wave_direction), math.sin(self.wave_direction)
        z = self.wave.elevation(self._t, x * c, x * s)
        R = self.wave.buoy_motion(self._t)[0] if "buoy_rocking" in self.effects else np.eye(3)
        psi = math.fmod(self.model.psid * self._t, 2 * math.pi)
        P = self._last_power
        phi_wrapped = math.remainder(float(self.state[0]), 2 * math.pi)
        return draw_gowec(
            buoy_R=R,
            gimbal_angle=float(self.state[0]),
            rotor_angle=psi,
            wave_x=x,
            wave_z=z,
            wave_direction=self.wave_direction,
            buoy_radius=self.buoy_radius if self.buoy_radius > 0 else None,
            text=f"t = {self._t:5.1f} s   phi = {phi_wrapped:+.2f} rad   P = {P / 1e3:.2f} kW",
        )
