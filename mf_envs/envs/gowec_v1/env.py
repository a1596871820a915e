"""FloatingGOWEC-v0: the gyroscopic wave energy converter as it floats (Rios 2017
Sec. 3.2)."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_range
from mf_envs.envs import _groups
from mf_envs.envs.base import MFEnv
from mf_envs.envs.gowec_v1 import build, spec
from mf_envs.envs.gowec_v1.rows import observe_at, step_one
from mf_envs.physics import waves
from mf_envs.physics.gowec import GOWECParams
from mf_envs.physics.gowec.hydro import batch as hb
from mf_envs.physics.gowec.hydro.batch import (
    V_ELEVATION,
    V_EXCITATION,
    V_GIMBAL,
    V_GIMBAL_RATE,
    V_GYRO,
    V_PITCH,
    V_POWER,
    V_POWER_MECH,
    V_ROLL,
)
from mf_envs.physics.gowec.hydro.devices import DEFAULT_DEVICE, DEVICES
from mf_envs.physics.gowec.hydro.gimbal import PTO_STROKE, SURVIVAL_LATCHED, stiffest_rate
from mf_envs.physics.gowec.hydro.model import radiation_bound, wave_power_flux

AVAILABLE_EFFECTS = {
    "gyroscopic": "rotor spin coupling (off: rotor stopped)",
    "radiation": "radiation memory of the Cummins equation (off: A_inf only, no wave damping)",
    "viscous_damping": "linear viscous pitch/roll damping (viscous_damping, N m s/rad)",
    "quadratic_drag": "Morison drag of keel plate and side on the velocity relative to the water",
    "surge_heave": "surge (with the BEM surge-pitch coupling, slack mooring) and heave free",
    "irregular_waves": "irregular sea (also switched on by significant_wave_height)",
}
DEFAULT_EFFECTS = DEVICES[DEFAULT_DEVICE].effects  # a device's own: `devices.FloatingDevice`
_P = GOWECParams()


class GOWECV1Env(MFEnv):
    """
    ## Description
    The GOWEC of Rios (2017, Sec. 3.2) floating. Default `device="iswec_box"`: ISWEC's 15 x 8 m
    box of 3.2 m draft (394 t; Capytaine BEM coefficients shipped, its length along the
    default sea) in pitch theta (about e1), roll rho (about e2), surge and heave: Cummins
    equation with Morison drag and a mooring spring, two-way coupled to a mirrored pair of
    gyros (H = 3.14e5 N m s each) by the B-matrix equations (`physics.gowec.hydro.floating`);
    generator torque inside the substeps. The gimbals swing inside cushioned end stops
    (+-70 deg, 10 deg of cushion), and a supervisor takes the device into survival (PTO
    unloaded, gimbals braked, flywheels spinning) beyond its operating range
    (`physics.gowec.hydro.gimbal`).
    `"iswec_class"`: the same units on a cylinder of ISWEC's footprint (radius 6 m, draft 2.5 m,
    the default before the box); `"seed_buoy"`: the 0.1-0.4 device. docs/gowec_v1.md.

    ## Action Space
    `Box(-1, 1, (1,), float32)`: generator torque command / max_generator_torque. The drive adds
    c phi' + k phi (`set_pto`, default 0) and limits |M_g| <= max_generator_torque and
    |M_g phi'| <= max_generator_power at every substep.

    ## Observation Space
    OBSERVATION_TABLE

    ## Rewards
    Net electrical energy of the step / (P_ref control_dt): generator output eta_g P when P =
    n M_g phi' > 0 (n = gyro_units, the same torque on each unit), drawn power P / eta_m when
    motoring, minus rotor_loss. P_ref (> 0, W) is Eq. 88
    (n/2 H beta0 w^2, the locked-gimbal power) with beta0 the rotor-off pitch amplitude from the
    RAO at the wave (irregular: a = Hs / (2 sqrt 2), T = peak_period): `reference_power()`.
    Terms (`info["reward_terms"]`): `net_electrical_energy`, and `shutdown_loss` (< 0 only on a
    failure's step: `shutdown_energy`, the most the device could draw over the steps left, /
    (P_ref control_dt)).

    ## Starting State
    Buoy at rest, level; gimbal angle uniform in [-0.1, 0.1] rad, at rest; random wave phases;
    the incident wave ramps in over `wave_ramp` s.
    `reset(options=...)`: buoy_pitch, buoy_roll (rad), gimbal_angle (rad), gimbal_rate (rad/s).

    ## Episode End
    Truncation after `episode_seconds` or `max_episode_steps` (default 6000; docs/api.md,
    "Episode length"); termination only on a physical failure: |phi'| > max_gimbal_rate
    ("overspeed") or |phi| past the gimbal's stroke ("stroke_end", its cushion bottomed out),
    each charged `shutdown_energy` (ending early never pays), or a numerical failure. A tilt
    above pitch_limit (20 deg on the ISWEC-class device), the gimbal in its cushion, or a sea
    above the device's operating range (Hs or regular wave height > 2.5 m) puts the device in
    survival (`info["survival"]`; held 30 s after the trigger, the whole episode for the sea).

    ## Arguments
    `sea` (a `build.Sea`) groups the sea's arguments, `pto` (a `build.PTO`) the generators'; either
    also a dict of fields. Each field keeps its flat kwarg as an alias (both given: must agree):
    `wave_` + amplitude, period, direction; `max_generator_` + torque, power; else its name.

    | argument | default | meaning |
    |---|---|---|
    | device | "iswec_box" | or "iswec_class", "seed_buoy" (`hydro/devices.py`): fills None kwargs |
    | sea.amplitude, .period, .direction | 1 m, 6 s, pi/2 | regular wave (Eq. 89) |
    | sea.significant_wave_height, .peak_period | None, 6 s | irregular sea (Hs, Tp) if Hs is set |
    | sea.spectrum, .gamma, .n_components | "jonswap", 3.3, 64 | irregular-sea spectrum |
    | rotor_inertia, rotor_speed | device (1.2e4 kg m^2, 250 rpm) | rotor J3 (kg m^2), psi' |
    | gyro_units | device (2) | 2: the seed's mirrored pair (phi, -phi; spins +-psi'); 1: one |
    | pto.generator_efficiency, .motor_efficiency | device (0.9), = generator | eta_g, eta_m |
    | pto.max_torque, .max_power | device (150 kN m, 130 kW) | PTO limits per unit |
    | pto.rotor_loss | device (None: by speed, 3 kW at 250 rpm) | running loss, all units (W) |
    | viscous_damping | device (0; seed buoy 5 % of critical) | linear damping (N m s/rad) |
    | drag_coefficient | device (1) | Morison C_d of keel plate and side |
    | pitch_limit, wave_ramp | device (20 deg, 10 s) | survival tilt (rad), wave ramp (s) |
    | wave_preview | 0 | s of incident elevation ahead in 8 more observation slots (0: none) |
    | hull | None (the device's) | `HullCoefficients` or path of an .npz (`from_capytaine`) |
    | episode_seconds, control_dt, physics_dt | 120 s, 0.02 s, device (0.02 s) | timing |

    ## Version History
    - v1: floating buoy, BEM coefficients, two-way coupling, PTO efficiency.
    - v0 (0.5): the ISWEC-class device by default, surge and heave, Morison drag, wave ramp,
      pitch limit, shutdown charge, the wave elevation in the observation; later the gimbal's
      end stops and the survival supervisor (the pitch limit no longer ends episodes); `sea`, `pto`.
    """

    obs_layout = spec.OBS  # the named observation layout (`envs._spec.ObsLayout`)
    RESET_OPTIONS = spec.RESET_OPTIONS  # the keys reset(options=...) takes
    AVAILABLE_EFFECTS, DEFAULT_EFFECTS = AVAILABLE_EFFECTS, DEFAULT_EFFECTS

    def __init__(
        self,
        sea: build.Sea | dict | None = None,
        device: str = DEFAULT_DEVICE,
        pto: build.PTO | dict | None = None,
        rotor_inertia: float | None = None,
        rotor_speed: float | None = None,
        gyro_units: int | None = None,
        viscous_damping: float | None = None,
        drag_coefficient: float | None = None,
        pitch_limit: float | None = None,
        wave_ramp: float | None = None,
        wave_preview: float = 0.0,
        max_gimbal_rate: float = spec.MAX_GIMBAL_RATE,
        hull: Any = None,
        episode_seconds: float | None = None,
        control_dt: float = 0.02,
        physics_dt: float | None = None,
        effects: Any = None,
        max_episode_steps: int | None = None,
        render_mode: str | None = None,
        **aliases: Any,
    ) -> None:
        kw = _groups.kwargs_of(locals(), build.GROUPS, "GOWECV1Env")
        self._set_scene(build.build(kw))  # the kwargs, validated, as physics parameters
        super().__init__(effects=effects, render_mode=render_mode,
                         control_dt=check_range("control_dt", control_dt, 1e-4, 10.0),
                         physics_dt=check_range(
                             "physics_dt",
                             DEVICES[self.scene.device].physics_dt if physics_dt is None
                             else physics_dt, 1e-5, 1.0),
                         default_effects=build.default_effects(self.scene, hull))  # fmt: skip
        self.irregular = self.scene.hs_given or "irregular_waves" in self.effects
        self.hull, self.model = build.floating_model(self.scene, kw, self.effects)
        self._base_substeps = self.n_substeps
        self.set_pto(0.0, 0.0)  # the substeps for the brake and the cushions
        self.buoy_radius = self.hull.radius if math.isfinite(self.hull.radius) else 0.0
        self.max_steps, self.episode_seconds = self._seconds_episode(episode_seconds,
            max_episode_steps, build.EPISODE_SECONDS)  # fmt: skip
        self.action_space = spaces.Box(-1.0, 1.0, (1,), np.float32)
        self.preview_times, self.observation_space = build.observation(self.max_gimbal_rate,
                                                                       wave_preview)  # fmt: skip
        self.energy_scale = 1.0 / (self.reference_power() * self.control_dt)
        self.wave: waves.WaveField = waves.regular_wave(self.wave_amplitude, self.wave_period,
                                                        self.wave_direction)  # fmt: skip
        self.state = self.model.initial_state()
        self._t, self._steps, self._last_power = 0.0, 0, 0.0
        self._vals = np.zeros(hb.N_VALS)
        self._work = hb.step_work(len(self.state), self.n_components)  # any sea of this env
        self._consts_key: tuple | None = None  # `_consts`' cache key

    # ------------------------------------------------------------------ public quantities
    def hydrostatic_stiffness(self) -> float:
        """C55 (N m/rad) of the hull's pitch (= roll on a cylinder; a box's C44: model.p)."""
        return float(self.hull.stiffness)

    def natural_period(self) -> float:
        """Rotor-off pitch natural period 2 pi / w_n, w_n^2 (I + A(w_n)) = C (s)."""
        return 2.0 * math.pi / self.hull.natural_frequency(self.model.pitch_inertia())

    def power_bound(self) -> float:
        """Radiation-limited mean power of the current sea (W), `model.radiation_bound`."""
        return radiation_bound(self.hull, self.wave)

    def wave_power_flux(self) -> float:
        """Wave power per metre of crest of the current sea (W/m) at the hull table's water
        depth (35 m on the ISWEC-class device; deep water for a pitch-only table)."""
        three = self.model.three
        depth = float(three.water_depth) if three is not None else math.inf
        return wave_power_flux(self.wave, self.hull.rho, self.hull.g, depth)

    def reference_power(self) -> float:
        """P_ref = 1/2 |H| beta0 w^2 (W, Eq. 88) with beta0 = rotor-off RAO x a (Rewards)."""
        w = 2.0 * math.pi / self.wave_period
        H = abs(self.model.p.gyro[0] * (self.model.psid or _P.rotor_speed))
        beta0 = self.hull.rao(w) * self.wave_amplitude
        return max(0.5 * self.model.units * H * beta0 * w * w, 1e-3)

    def set_pto(self, damping: float, stiffness: float) -> None:
        """Linear PTO M_g += c phi' + k phi (c N m s/rad, k N m/rad), evaluated every substep."""
        c = check_range("damping", damping, 0.0, 1e9)
        k = check_range("stiffness", stiffness, -1e9, 1e9)
        self.model.set_pto(c, k)
        p = self.model.p  # explicit RK4: the stiffest gimbal load's rate x dt <= 2
        rate = stiffest_rate(p.pto, p.gyro[1] + p.gyro[3])
        self.n_substeps = max(self._base_substeps, math.ceil(self.control_dt * rate / 2.0))
        self.physics_dt = self.control_dt / self.n_substeps

    # ------------------------------------------------------------------ gym API
    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        tau = self._scalar_action(action) * self.max_generator_torque
        t0, self._steps = self._t, self._steps + 1
        self._t = self._steps * self.control_dt
        truncated = self._steps >= self.max_steps
        obs = np.empty(self.observation_space.shape[0], np.float32)
        loss, lo, hi, limits, sup = self._consts
        clock = (self.physics_dt, self.n_substeps, self.control_dt, loss)
        ok, y, finite, over, out = step_one(
            t0, self._t, self.state, tau, clock, self.model._args(), self.wave.amplitudes,
            self.wave.phases, self._vals, self._work, (lo, hi, self.preview_times), obs, limits,
        )  # fmt: skip
        if not ok:
            info = dict(power=0.0, overspeed=False, stroke_end=False, survival=False)
            info["reward_terms"] = {"net_electrical_energy": 0.0, "shutdown_loss": 0.0}
            return self._finish_step(self._get_obs(), 0.0, False, truncated, info, False)
        self.state = y
        reward = float(self._vals[hb.V_ENERGY] * self.energy_scale)  # net electrical energy
        info = self._info_from(self._vals)
        shut = -self.shutdown_energy(self._steps) * self.energy_scale if over or out else 0.0
        info["reward_terms"] = {"net_electrical_energy": reward, "shutdown_loss": shut}
        reward += shut
        info["overspeed"], info["stroke_end"], info["survival"] = over, out, bool(y[sup] > 0.0)
        if finite and math.isfinite(reward):  # _finish_step's checks, done in the kernel
            return self._step_ok(obs, reward, over or out, truncated, info)
        return self._finish_step(obs, reward, over or out, truncated, info, True)

    def gimbal_stroke(self) -> float:
        """The gimbal's stroke (rad, end stops + cushion travel; inf: none): past it, a failure."""
        return float(self.model.p.pto[PTO_STROKE])

    def survival(self) -> bool:
        """The supervisor holds the device in survival (`physics.gowec.hydro.gimbal`)."""
        return bool(self.state[self.model.survival_index()] > 0.0)

    def survival_at_reset(self) -> float:
        """Supervisor's timer (s) at reset: latched if Hs (or 2 a) is above the range, else 0."""
        height = 2.0 * self.wave_amplitude * (math.sqrt(2.0) if self.irregular else 1.0)
        return SURVIVAL_LATCHED if height > DEVICES[self.device].max_operating_height else 0.0

    def rotor_loss_power(self, speed: float | None = None) -> float:
        """Running loss (W) of all units at `speed` (rad/s; default now): `running_loss`."""
        w = self.model.psid if speed is None else float(speed)
        return DEVICES[self.device].running_loss(w, self.model.units, self.rotor_loss)

    def set_rotor_speed(self, speed: float) -> None:
        """The flywheels' speed psi' (rad/s) for the episode, set per sea as ISWEC does (like
        `set_pto`'s gains; docs/gowec_v1.md): H = J psi', the loss and the cushion follow."""
        s, p = check_range("rotor_speed", speed, -1e4, 1e4), self.model.p
        self.model.set_rotor_speed(s, DEVICES[self.device].cushion(p.gyro[1] + p.gyro[3],
                                                                    p.gyro[0] * s))  # fmt: skip
        self.set_pto(float(p.pto[0]), float(p.pto[1]))  # the substeps for the new cushion

    def spool_up_energy(self) -> float:
        """Kinetic energy (J) of the rotors at speed, n 1/2 J psi'^2: reported, not charged."""
        return 0.5 * self.model.units * self.model.p.gyro[0] * self.model.psid**2

    def shutdown_energy(self, steps: Any) -> Any:
        """Energy (J) a failure is charged for the steps left after `steps` (int or array): rotor
        loss + n P_max / eta_m, the most any continuation could draw (ending early never pays)."""
        rate = self.rotor_loss_power() + self.model.units * self.max_generator_power / self.eta_m
        return rate * self.control_dt * np.maximum(self.max_steps - steps, 0)

    @property
    def _consts(self) -> tuple:
        """(rotor loss W, obs bounds, (max gimbal rate, stroke), survival timer index), cached."""
        sp, key = self.observation_space, (self.rotor_loss, self.max_gimbal_rate, self.model.psid)
        if self._consts_key != key:
            lim = (self.max_gimbal_rate, self.gimbal_stroke())
            self._consts_val = (self.rotor_loss_power(), sp.low, sp.high, lim,
                                self.model.survival_index())  # fmt: skip
            self._consts_key = key
        return self._consts_val

    def _check_reset_options(self, opts: dict[str, Any]) -> dict[str, Any]:
        lim = {"buoy_pitch": spec.MAX_BUOY_ANGLE, "buoy_roll": spec.MAX_BUOY_ANGLE,
               "gimbal_angle": 1e3, "gimbal_rate": self.max_gimbal_rate}  # fmt: skip
        for k in opts:
            opts[k] = check_range(k, opts[k], -lim[k], lim[k])
        return opts

    def _start(self, opts: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any]]:
        rng = self.np_random
        self.wave = build.draw_wave(self.irregular, self.wave_amplitude, self.wave_period,
                                    self.wave_direction, self.spectrum, self.gamma,
                                    self.n_components, float(self.hull.omega[-1]), rng)  # fmt: skip
        self.model.set_sea(self.wave)
        phi0 = opts.get("gimbal_angle", float(rng.uniform(-0.1, 0.1)))
        self.state = self.model.initial_state(opts.get("buoy_pitch", 0.0),
            opts.get("buoy_roll", 0.0), phi0, opts.get("gimbal_rate", 0.0))  # fmt: skip
        self._t = 0.0
        info = self._info(0.0, 0.0, 0.0)
        self.state[self.model.survival_index()] = self.survival_at_reset()
        info.update(reward_terms={"net_electrical_energy": 0.0, "shutdown_loss": 0.0},
                    overspeed=False, stroke_end=False, survival=self.survival())  # fmt: skip
        return self._get_obs(), info

    def _info(self, p_el: float, p_mech: float, tau: float) -> dict[str, Any]:
        """The info of the current state (reset): the same compiled quantities as a step."""
        v, wave = self._vals, self.wave
        v[hb.V_POWER], v[hb.V_POWER_MECH] = p_el, p_mech
        hb.state_values(self._t, self.state, float(tau), self.model._args(), wave.amplitudes,
                        wave.phases, v)  # fmt: skip
        return self._info_from(v)

    def _info_from(self, v: np.ndarray) -> dict[str, Any]:
        """The info dict from `hb.step_row`'s value slots v (N_VALS,)."""
        x = v.tolist()  # the slots by name (`hb.INFO_SLOTS`), written out: the per-step path
        self._last_power = x[V_POWER]
        return {"power": x[V_POWER], "power_mechanical": x[V_POWER_MECH], "buoy_pitch": x[V_PITCH],
                "buoy_roll": x[V_ROLL], "buoy_rate": v[hb.RATES].copy(),
                "excitation_moment": x[V_EXCITATION], "gyro_moment": x[V_GYRO],
                "gimbal_angle": x[V_GIMBAL], "gimbal_rate": x[V_GIMBAL_RATE],
                "wave_elevation": x[V_ELEVATION], "time": self._t,
                "numerical_failure": False}  # fmt: skip

    def _get_obs(self) -> np.ndarray:
        obs = np.empty(self.observation_space.shape[0], np.float32)
        a, w = self.model._args(), self.wave
        observe_at(self.state, self._t, w.amplitudes, a[9], w.phases, a[13][1],
                   self.preview_times, self.observation_space.low, self.observation_space.high,
                   obs)  # fmt: skip
        return obs

    def _draw_frame(self) -> np.ndarray:
        from mf_envs.envs.gowec_v1.render import draw_frame

        return draw_frame(self)


GOWECV1Env.__doc__ = (GOWECV1Env.__doc__ or "").replace("OBSERVATION_TABLE", spec.OBS_DOC)
_groups.list_aliases(GOWECV1Env, build.GROUPS)  # the aliases of `sea`, `pto` in the signature
