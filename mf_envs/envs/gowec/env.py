"""GOWEC-v0: harvest wave energy with a gyroscope by loading its gimbal (Rios 2017, Sec. 3.2)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import (
    check_range,
)
from mf_envs.envs import _groups
from mf_envs.envs._rows import ONE_ROW, SINGLE
from mf_envs.envs.base import MFEnv
from mf_envs.envs.gowec import build, rows, spec
from mf_envs.envs.gowec.render import wave_frame
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
MAX_GIMBAL_RATE, MAX_BUOY_RATE = spec.MAX_GIMBAL_RATE, spec.MAX_BUOY_RATE
# Buoy waterplane radius (m) used by default in irregular seas: a 5 m diameter buoy for one
# Seakeeper 26 pair (the gyro itself is ~1.2 m across; Seakeeper 26 is fitted on 17-20 m hulls).
# It averages the wave slope over its waterplane (waves.disk_average_factor): F = 0.99 at
# T = 6 s (lambda = 56 m), and it stops the buoy following wavelets shorter than itself, without
# which the buoy rates of a spectrum grow without bound with the spectral cut-off. Regular waves
# default to the seed's point buoy (r = 0), so that analytic_max_power() is Eq. 95 exactly.
BUOY_RADIUS = 2.5


class GOWECEnv(MFEnv):
    """
    ## Description
    One gyroscope of the gyroscopic ocean wave energy converter of Rios (2017, ch. 3.2): a buoy
    rocks with the slope of the passing wave (Eqs. 77-78, 89-93) averaged over its circular
    waterplane of radius `buoy_radius` (each component x 2 J1(k r)/(k r); 0 = the seed's point
    buoy), a rotor spins at psi' inside a gimbal free to turn about the buoy's e2 axis, and a
    generator on that axis applies the torque M_g. The gimbal obeys (exact for the prescribed
    buoy rotation; the seed's Eq. 81 for a thin disk and a light gimbal, sign of Eq. 80 fixed)

        (Jg2 + Jt)(phi'' + w2') - (Jg3 - Jg1 - Jt) O1 O3 - Ja (O3 + psi') O1 + M_g = 0.

    The power harvested is P = M_g phi' (Eq. 82). Locking phi to the wave phase yields Eq. 95 on
    average; a square-wave sin(phi) can reach 4/pi of it.

    ## Action Space
    `Box(-1, 1, (1,), float32)`: generator torque M_g / max_generator_torque (N m after scaling).

    ## Observation Space
    `Box(float32, (6,))`, what a device measures (encoder on the gimbal, IMU on the buoy), laid
    out by `mf_envs.envs.gowec.spec.OBS` (read slots by name: `OBS.index("gimbal_rate")`):

    | Num | Name | Observation | Bound | Unit |
    |---|---|---|---|---|
    | 0 | sin_gimbal_angle | sin(phi), gimbal angle phi (encoder) | +-1 |  |
    | 1 | cos_gimbal_angle | cos(phi) | +-1 |  |
    | 2 | gimbal_rate | phi', gimbal rate | +-max_gimbal_rate | rad/s |
    | 3..5 | buoy_rates | buoy body rates w1, w2, w3 (IMU) | +-5 | rad/s |

    The wave phase is not observed.

    ## Rewards
    `energy`: the energy harvested in the step, int M_g phi' dt, divided by P_ref dt, so that the
    episode mean of the reward is the mean power as a fraction of P_ref (`reference_power`):
    |Eq. 95| of this wave, rotor and buoy, floored at 10 % of the head-on Eq. 86 (with the spin
    floored at 10 wave frequencies), so it is positive and finite for every wave direction and
    for a rotor at rest (`spec.reference_power`; the defaults give Eq. 95 exactly).
    `info["reward_terms"]` holds the terms (they sum to the reward). Info keys: `spec.INFO_KEYS`.

    ## Starting State
    phi ~ U(-0.1, 0.1) rad, phi' = 0, wave phase ~ U(0, 2 pi) (irregular seas: random phases
    for every component). `reset(options=...)` accepts `gimbal_angle` (|.| <= 4 pi rad),
    `gimbal_rate` (|.| <= max_gimbal_rate), `wave_phase` (|.| <= 4 pi rad); any other key or
    value raises ValueError naming it (and draws nothing from the generator).

    ## Episode End
    Truncation after `episode_seconds` (default `n_periods` = 20 wave periods) or
    `max_episode_steps` (default 6000 = 20 periods of 300 steps; docs/api.md, "Episode
    length").
    Termination on a gimbal overspeed trip, |phi'| > `max_gimbal_rate` (`info["overspeed"]`: a
    real unit brakes its gimbal; nothing else limits a gimbal that the generator motors), or on
    numerical failure (`info["numerical_failure"]`). The baselines stay below 18 rad/s.

    ## Arguments
    `sea` (a `build.Sea` or a dict of its fields) groups the wave's arguments, `gyro` (a
    `physics.gowec.GOWECParams` or a dict of its fields) the gyroscope's; each field keeps its
    flat kwarg as an alias (`wave_period=7.0`; a field given both ways must agree).

    | Argument | Default | Meaning |
    |---|---|---|
    | sea.amplitude, wave_amplitude | 1.0 m | a in (0, 30] (irregular: Hs = 2 sqrt 2 a, Eq. 16) |
    | sea.period, wave_period | 6.0 s | T in [0.5, 60] (irregular: peak period) |
    | sea.direction, wave_direction | pi/2 | theta of Eq. 89 in [-2 pi, 2 pi] (pi/2 head-on) |
    | sea.n_components, sea.gamma | 64, 3.3 | irregular sea (JONSWAP), <= 4096, gamma in [1, 20] |
    | (aliases n_components, gamma) | | |
    | gyro.rotor_inertia | 49.66 kg m^2 | polar J3 of the rotor (Seakeeper 26, Table 3-1), <= 1e6 |
    | gyro.rotor_speed | 523.6 rad/s | psi' (5000 rpm), abs <= 1e4; 0 = rotor off |
    | gyro.gimbal_inertia | (5, 5, 5) kg m^2 | with the `gimbal_inertia` effect |
    | gyro.rotor_transverse_inertia | Ja/2 | with the `gimbal_inertia` effect |
    | (aliases: the field names) | | |
    | max_generator_torque | 10000 N m | action scale |
    | max_gimbal_rate | 60 rad/s | overspeed trip (ends the episode) and observation bound |
    | episode_seconds | None | episode length (s); None: n_periods wave periods |
    | n_periods | 20 | episode length in wave periods (when episode_seconds is None) |
    | max_episode_steps | None | or the episode length in control steps |
    | steps_per_period | 300 | control steps per wave period (control_dt = T / this) |
    | physics_dt | 0.01 s | RK4 substep (rounded to divide the control step; <= 1e4 per step) |
    | buoy_radius | None | waterplane radius (m), None: 0 (point buoy) for regular waves, |
    |             |      | 2.5 m with irregular_waves |
    | effects | gyroscopic, buoy_rocking, wave_2d | also gimbal_inertia, irregular_waves |

    ## Version History
    * v0: initial version; reward reference floored (positive for every direction, rotor off),
      `episode_seconds`, strict reset options; the grouped `sea` and `gyro` (flat kwargs kept as
      aliases; same physics).
    """

    obs_layout = spec.OBS  # the named observation layout (`envs._spec.ObsLayout`)
    RESET_OPTIONS = spec.RESET_OPTIONS  # the keys reset(options=...) takes
    AVAILABLE_EFFECTS, DEFAULT_EFFECTS = AVAILABLE_EFFECTS, DEFAULT_EFFECTS

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 30}

    def __init__(
        self,
        sea: build.Sea | dict | None = None,
        gyro: gw.GOWECParams | dict | None = None,
        max_generator_torque: float = 10000.0,
        n_periods: int | None = None,
        max_gimbal_rate: float = MAX_GIMBAL_RATE,
        effects: Any = None,
        steps_per_period: int = 300,
        physics_dt: float = 0.01,
        buoy_radius: float | None = None,
        episode_seconds: float | None = None,
        max_episode_steps: int | None = None,
        render_mode: str | None = None,
        **aliases: Any,
    ) -> None:
        kw = _groups.kwargs_of(locals(), build.GROUPS, "GOWECEnv")
        self._set_scene(build.build(kw))  # the kwargs, validated, as physics parameters
        super().__init__(effects=effects, control_dt=self.wave_period / self.steps_per_period,
                         physics_dt=physics_dt, render_mode=render_mode)  # fmt: skip
        if buoy_radius is None:
            buoy_radius = BUOY_RADIUS if "irregular_waves" in self.effects else 0.0
        self.buoy_radius = check_range("buoy_radius", buoy_radius, 0.0, 100.0)
        spp = self.steps_per_period
        own = build.own_length(n_periods, episode_seconds, spp, self._episode_steps)
        default = build.DEFAULT_N_PERIODS * spp
        self.max_steps = self._episode_length(max_episode_steps, own, default)
        whole = self.max_steps % spp == 0 and episode_seconds is None
        self.n_periods = self.max_steps // spp if whole else self.max_steps / spp
        self.episode_seconds = self.max_steps * self.control_dt
        self.action_space = spaces.Box(-1.0, 1.0, (1,), np.float32)
        hi = spec.OBS.high({"max_gimbal_rate": self.max_gimbal_rate})
        self.observation_space = spaces.Box(-hi, hi, dtype=np.float32)
        self.reference_power = spec.reference_power(
            self.params.rotor_inertia,
            self.params.rotor_speed,
            self.wave_amplitude,
            self.wave_period,
            self.wave_direction,
            self.buoy_radius,
        )
        self.reward_scale = 1.0 / (self.reference_power * self.control_dt)  # 1 / (J per step)
        self.wave: waves.WaveField = waves.regular_wave(
            self.wave_amplitude, self.wave_period, self.wave_direction, buoy_radius=self.buoy_radius
        )
        self.model = gw.GimbalModel(self.params, self.wave, self.effects)
        self._model0 = self.model  # phase 0; reset() shifts the phase
        # the env is row 0 of a batch of one: the vector env's kernels step and reset it
        m = self.n_components if "irregular_waves" in self.effects else 1
        self.rows = rows.alloc_rows(1, m)
        self.site = rows.Site(self.model.inert, self.model._cth, self.model._sth,
                              self.model._two_d, self.max_gimbal_rate)  # fmt: skip
        self._last_power = 0.0

    def analytic_max_power(self) -> float:
        """Eq. 95 (Eq. 86 head-on), W: the locked-gimbal mean power of this wave and rotor
        (signed: negative for sin(theta) < 0; the reward uses `reference_power`, > 0).

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
        b = self.rows
        b.Mg[SINGLE] = self._scalar_action(action) * self.max_generator_torque
        rows.step_rows(SINGLE, SINGLE + 1, ONE_ROW, b, self.site)
        reward, obs = float(b.reward[SINGLE]), b.obs[SINGLE].copy()
        truncated = bool(b.steps[SINGLE] >= self.max_steps)
        if not b.ok[SINGLE]:
            info = {"power": 0.0, "reward_terms": {"energy": reward}, "overspeed": False}
            return self._finish_step(obs, reward, False, truncated, info, False)
        self._last_power = power = float(b.energy[SINGLE]) / self.control_dt
        info = spec.step_info(power, *self._info_state(), self._t, reward)
        info["overspeed"] = overspeed = bool(b.overspeed[SINGLE])
        return self._step_ok(obs, reward, overspeed, truncated, info)

    # the state of row 0 (views: tests perturb them)
    state = property(lambda self: self.rows.x[SINGLE], doc="(phi rad, phi' rad/s), row 0's view")
    _t = property(lambda self: float(self.rows.t[SINGLE]))

    def _info_state(self) -> tuple[float, float, float, float]:
        """(phi, phi', w1, eta) of row 0 as floats (`spec.step_info`)."""
        b = self.rows
        return (
            float(b.x[SINGLE, 0]),
            float(b.x[SINGLE, 1]),
            float(b.w[SINGLE, 0]),
            float(b.eta[SINGLE]),
        )

    def _check_reset_options(self, opts: dict[str, Any]) -> dict[str, Any]:
        angle = 4.0 * math.pi
        for key, bound in (("gimbal_angle", angle), ("wave_phase", angle)):
            if key in opts:
                opts[key] = check_range(key, opts[key], -bound, bound)
        if "gimbal_rate" in opts:
            g = self.max_gimbal_rate
            opts["gimbal_rate"] = check_range("gimbal_rate", opts["gimbal_rate"], -g, g)
        return opts

    def _start(self, opts: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any]]:
        rng = self.np_random  # the start distribution is rows.PHI0, rows.PHASE0 (vector env's)
        phi = float(opts.get("gimbal_angle", rng.uniform(*rows.PHI0)))
        phid = float(opts.get("gimbal_rate", 0.0))
        phase = float(opts.get("wave_phase", rng.uniform(*rows.PHASE0)))
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
        else:  # the regular wave of __init__ with this episode's phase
            self.model = self._model0.with_phases([phase])
        self.wave = self.model.wave
        b, m = self.rows, self.model
        b.amp[SINGLE], b.om[SINGLE], b.eps[SINGLE], b.k[SINGLE] = (
            self.wave.amplitudes,
            self.wave.omegas,
            m._eps,
            m._k,
        )
        b.psid[SINGLE], b.dt[SINGLE], b.n_sub[SINGLE] = m.psid, self.physics_dt, self.n_substeps
        b.cdt[SINGLE], b.scale[SINGLE] = self.control_dt, self.reward_scale
        rows.reset_row(SINGLE, phi, phid, float(self.wave.elevation(0.0)), b, self.site)
        self._last_power = 0.0
        info = spec.step_info(0.0, *self._info_state(), 0.0, 0.0)
        info["overspeed"] = False
        return b.obs[SINGLE].copy(), info

    def _draw_frame(self) -> np.ndarray:
        R = self.wave.buoy_motion(self._t)[0] if "buoy_rocking" in self.effects else np.eye(3)
        phi, P = float(self.rows.x[SINGLE, 0]), self._last_power
        text = f"t = {self._t:5.1f} s   phi = {math.remainder(phi, 2 * math.pi):+.2f} rad"
        text += f"   P = {P / 1e3:.2f} kW"
        return wave_frame(
            self.wave, self._t, self.wave_period, self.wave_direction, R, phi,
            self.model.psid, self.buoy_radius, text,
        )  # fmt: skip


# the flat aliases of `sea` and `gyro` as keyword-only parameters of the signature
_groups.list_aliases(GOWECEnv, build.GROUPS)
