"""GyroStabilizer-v0: a ship with one or two active gyro roll stabilizers (Rios 2017, §3.3)."""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_range
from mf_envs.envs import _groups
from mf_envs.envs._rows import ONE_ROW, SINGLE
from mf_envs.envs.base import MFEnv
from mf_envs.envs.gyro_stabilizer import build, render, rows, spec
from mf_envs.physics.ship.coupling import SwayRollYaw
from mf_envs.physics.ship.hulls import Hull
from mf_envs.physics.ship.layout import Slot
from mf_envs.physics.ship.model import SHIP_EFFECTS

AVAILABLE_EFFECTS = SHIP_EFFECTS
DEFAULT_EFFECTS = (
    "gyroscopic",
    "gimbal_inertia",
    "added_inertia",
    "hydrostatic_restoring",
    "roll_damping",
    "quadratic_roll_damping",
    "wave_moment",
    "gimbal_limits",
)
OBS_HIGH = spec.OBS.high()
EPISODE_SECONDS = 30.0  # s, the default episode (600 steps of the default 0.05 s)


class GyroStabilizerEnv(MFEnv):
    """
    ## Description
    A ship rolling in waves, stabilized by gyros whose gimbal precession rate is the action.
    The hull (3 rotational DOF, surge/sway/heave with the `translation` effect) carries one gyro,
    or two counter-rotating ones (Rios 2017, ch. 3 Eqs. 98-113): a rotor spinning at a fixed
    rate psi' inside a gimbal that precesses about the ship's athwartships axis e_2. Precessing
    at phi' gives the roll moment -n H phi' cos(phi), H = J3 psi' (Eq. 123). The physics is the
    numba fast path of `mf_envs.physics.ship.kernels` (agrees with the multibody engine to
    round-off).

    Defaults (`preset="seakeeper_7000"`; docs/stabilizer_physics.md §4): one
    Seakeeper Model 7000 (J = 6.7 kg m^2 at 10,000 rpm, H = 7 016 N m s; +-60 deg precession;
    sold for 15.9-24.9 t boats) on the 18 t, 12-13 m motor yacht (`physics.ship.hulls.Hull.
    yacht`, roll period 3.70 s, roll damping by the simplified Ikeda method), its closed-circuit
    hydraulic brake as the gimbal drive (it only dissipates), the precession rate capped at
    max_precession_rate in the physics, cushioned stops from 50 to 60 deg; beam seas at the roll
    resonance, M0 = 8 000 N m. `preset="seed"`: the electric-drive default (the seed's Table 3-1
    Seakeeper 9 on the same yacht, a torque-limited electric drive, inelastic stops, the
    rule-of-thumb damping), bit for bit. The gimbal drive is a machine (`physics.ship.drive`);
    seas (`physics.ship.seas`) are met at `heading` and `ship_speed` (encounter frequency); the
    hull is one `physics.ship.hulls.Hull`.
    The seed's model: `effects=("gyroscopic",)` (+ "gimbal_inertia", "wave_moment": Figs. 3-10/11).

    ## Action Space
    `Box(-1, 1, (1,), float32)`: precession-rate command / max_precession_rate (rad/s scaled).
    For gyro 1 (gyro 2 mirrors it). The active drives follow it with a PI rate loop inside
    each RK stage: "brake" (the default: the hydraulic brake's valve, torque opposing phi' only,
    up to its relief torque), "electric" (four-quadrant; torque <= max_gimbal_torque, motoring
    power <= max_drive_power); "damper" (the brake at a fixed valve: tau = -c phi'),
    "pendulous" (Schlick 1906), "spring" are passive (action ignored); "kinematic" is v0's servo.
    Seakeeper preset: every drive meets the unit's rate cap (|phi'| <= max_precession_rate,
    enforced after each physics step by a torque <= the relief torque) and cushioned stops
    (spring-damper from max_gimbal_angle over 10 deg). Seed preset: speed <= 1.1
    max_precession_rate (motoring), torque 0.1 H, inelastic stops.

    ## Observation Space
    `Box(float32, (6,))`, what a real controller measures, laid out by
    `mf_envs.envs.gyro_stabilizer.spec.OBS` (read slots by name: `OBS.index("roll")`; physical
    values: `OBS.physical(obs)`). Roll and roll rate come in fixed units of 0.05 rad and 0.05
    rad/s, so that every slot is O(1) without running normalisation; pitch and yaw rate stay
    near zero in a beam sea (the headline scene: std 4e-4 and 5e-3 rad/s) and carry the hull's
    response at other headings:

    | Num | Name | Observation | Bound | Unit |
    |---|---|---|---|---|
    | 0 | roll | roll angle (z-y-x Euler angle, `physics.ship.roll_angle`) | +-62.8319 | 0.05 rad |
    | 1 | roll_rate | roll rate omega_1 (body) | +-200 | 0.05 rad/s |
    | 2 | pitch_rate | pitch rate omega_2 (body) | +-10 | rad/s |
    | 3 | yaw_rate | yaw rate omega_3 (body) | +-10 | rad/s |
    | 4 | gimbal_angle | gimbal angle phi of gyro 1, wrapped to [-pi, pi) | +-3.14159 | rad |
    | 5 | gimbal_rate | gimbal rate phi' | +-20 | rad/s |

    ## Rewards
    `reward = roll + effort`, the terms in `info["reward_terms"]`: roll = -(roll / roll_scale)^2,
    effort = -effort_weight * E, E = int n |tau phi'| dt the step's drive energy (J). Info keys:
    `spec.INFO_KEYS` (SI; `drive_torque` N m, `drive_power` W, `drive_energy` J,
    `mount_moment` N m per unit: |(H phi', drive + cushion torque)|, below `mount_moment_bound`;
    `rotor_power` W, the rotors' running power, 0 in the seed preset).

    ## Starting State
    Roll uniform in +-0.05 rad, roll rate in +-0.02 rad/s, pitch/yaw rates 0, gimbal at 0 and
    at rest, wave phase uniform in [0, 2 pi) (a new irregular sea each reset with
    `irregular_waves`). `reset(options=...)` overrides `roll` (|.| <= pi/2), `roll_rate` (<= 10),
    `gimbal_angle` (<= max_gimbal_angle), `wave_phase` (<= 4 pi); others: ValueError.

    ## Episode End
    Truncation after `episode_seconds` (`max_episode_steps` = ceil(episode_seconds / control_dt))
    or `max_episode_steps`; termination only on a numerical failure (`info["numerical_failure"]`).
    The default episode is 600 steps (30 s at 0.05 s); the env truncates itself, so
    `gym.make(..., episode_seconds=...)` alone sets the length (docs/api.md, "Episode length").

    ## Arguments
    | Argument | default | meaning |
    |---|---|---|
    | preset | "seakeeper_7000" | or "seed" (module doc); sets the None defaults below |
    | hull, coupling | None | the hull and its sway-roll-yaw coupling: `build` module doc |
    | ship_inertia | (45 850, 148 781, 163 659) | hull (J1, J2, J3), kg m^2 (overrides hull) |
    | n_gyros | None | 1 or 2 (counter-rotating pair); preset: 1 (MSS vessel 2) |
    | gyro_unit | None | "7000" or a seed Table 3-1 model ("3DC", "5", "9", "16", "26", "35") |
    | units_per_gyro | None | identical units precessing together per gyro (MSS vessel 4) |
    | rotor_inertia | None | rotor polar J3^(3) per unit, kg m^2 (7000: 6.7; seed: 9.549) |
    | gimbal_inertia | None | gimbal J2^(2) per unit, kg m^2 (assumed = rotor_inertia) |
    | rotor_speed | None | psi', rad/s (7000: 1047.2 = 10 000 rpm; seed: 942.5) |
    | design_roll_rate | None | p_d, rad/s: the unit's sizing (None: 10 deg x w_n) |
    | hull_damping | None | "ikeda" (Seakeeper preset) or "rule_of_thumb" (seed) |
    | wave_moment_amplitude | 8 000 | M0, N m |
    | wave_period | None | s; None = natural roll period (resonance), 10 s without restoring |
    | roll_stiffness | 158 922 | C44 = rho g V GM, N m/rad (the GZ shape follows it) |
    | roll_damping | 7 481 | linear B44, N m s/rad (quadratic B44q: hull field) |
    | max_precession_rate | 2.0 | rad/s |
    | max_gimbal_angle | None | rad: end stops (seed pi/3) or cushions' start (7000: 50 deg) |
    | episode_seconds | None | s; None: 30 s, or max_episode_steps steps |
    | max_episode_steps | None | control steps per episode (or episode_seconds) |
    | effects | see DEFAULT_EFFECTS | tuple of names from `SHIP_EFFECTS` |
    | control_dt | 0.05 | s |
    | physics_dt | None | s; default and RK4 limit: `spec.PHYSICS_DT_NOTE` |
    | form | "exact" | "seed": Eqs. 123-128 as printed |
    | drive | None | `spec.Drive` or a dict of its fields (kind "brake" (7000), "electric" (seed), |
    |  |  | servo_time_constant 0.05 s, ...: `build` doc); flat aliases: `spec.DRIVE` |
    | heading, ship_speed, wave_spreading | pi/2, 0, None | seas: `build` module doc |
    | significant_wave_height | 0.6 | m (irregular_waves, JONSWAP, peak period = wave_period) |
    | effective_slope | None | r_eff of the wave roll moment (hull field; yacht 0.7) |
    | roll_scale, effort_weight | 0.1745, 1e-3 | reward terms (effort per J) |

    Ranges (ValueError naming the argument): inertias, stiffness, damping >= 0; |rotor_speed|
    <= 1e4 rad/s; wave_period in [0.5, 60] s; servo_time_constant in [1e-3, 10] s;
    max_gimbal_angle in (0, pi]; control_dt <= 60 s, <= 1e4 physics substeps per step.

    ## Version History
    - v0: initial release; then the torque-limited electric drive became the default, with
      heading, speed, short-crested seas, the Hull dataclass and the energy effort term;
      later a Seakeeper Model 7000 with its hydraulic brake, rate cap and cushioned stops
      became the default (`preset="seed"` keeps the previous default) and added the info keys
      `mount_moment`, `rotor_power`.
    """

    obs_layout = spec.OBS  # the named observation layout (`envs._spec.ObsLayout`)
    RESET_OPTIONS = spec.RESET_OPTIONS  # the keys reset(options=...) takes

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 20}
    AVAILABLE_EFFECTS, DEFAULT_EFFECTS = AVAILABLE_EFFECTS, DEFAULT_EFFECTS

    def __init__(
        self,
        ship_inertia: Iterable[float] | None = None,
        n_gyros: int | None = None,
        rotor_inertia: float | None = None,
        gimbal_inertia: float | None = None,
        rotor_speed: float | None = None,
        wave_moment_amplitude: float = 8000.0,
        wave_period: float | None = None,
        roll_stiffness: float | None = None,
        roll_damping: float | None = None,
        max_precession_rate: float = 2.0,
        max_gimbal_angle: float | None = None,
        episode_seconds: float | None = None,
        effects: Iterable[str] | str | None = None,
        control_dt: float = 0.05,
        physics_dt: float | None = None,
        form: str = "exact",
        drive: spec.Drive | dict | None = None,
        hull: Hull | str | dict | None = None,
        coupling: SwayRollYaw | bool | None = None,
        heading: float = math.pi / 2,
        ship_speed: float = 0.0,
        wave_spreading: float | None = None,
        significant_wave_height: float = 0.6,
        effective_slope: float | None = None,
        roll_scale: float = 0.1745,
        effort_weight: float = 1.0e-3,
        preset: str = "seakeeper_7000",
        gyro_unit: str | None = None,
        units_per_gyro: int | None = None,
        design_roll_rate: float | None = None,
        hull_damping: str | None = None,
        sensor_noise_scale: float = 1.0,
        sensor_delay_time: float = 0.1,
        max_episode_steps: int | None = None,
        render_mode: str | None = None,
        **aliases: Any,
    ) -> None:
        kw = _groups.kwargs_of(locals(), (spec.DRIVE,), "GyroStabilizerEnv")
        scene = build.build(kw, DEFAULT_EFFECTS)  # the kwargs, validated, as physics parameters
        super().__init__(effects=scene.effects, control_dt=control_dt,
                         physics_dt=scene.physics_dt, render_mode=render_mode)  # fmt: skip
        build.check_step(self.physics_dt, scene.dt_max)
        self.max_steps, self.episode_seconds = self._seconds_episode(
            episode_seconds, max_episode_steps, EPISODE_SECONDS
        )
        self._set_scene(build.timed(scene, self.physics_dt))
        # the rotor speed the preset resolved (rad/s): domain randomisation's nominal value
        self.rotor_speed = self.gyro.rotor_speed
        self.action_space = spaces.Box(-1.0, 1.0, (1,), np.float32)
        self.observation_space = spaces.Box(-OBS_HIGH, OBS_HIGH, dtype=np.float32)
        # the env is row 0 of a batch of one: the vector env's kernels step and reset it
        self.rows = rows.alloc_rows(1, (1, 2), self.physics_dt, self.n_substeps)
        self.rows.P[SINGLE] = rows.pack(self.scene, 0.0)
        self._task = rows.Task(self.roll_scale, self.effort_weight, self.control_dt)
        self._energy = 0.0
        # what the controller sees: opt-in effects, nothing to do per step when both are off
        scale = check_range("sensor_noise_scale", sensor_noise_scale, 0.0, 1e3)
        delay = check_range("sensor_delay_time", sensor_delay_time, 0.0, 60.0)
        self._sigma = (  # in the observation's units
            spec.sensor_sigma(self.control_dt, scale) / spec.OBS.scales()
            if "sensor_noise" in self.effects
            else None
        )
        self._delay = (
            max(1, round(delay / self.control_dt)) if "sensor_delay" in self.effects else 0
        )
        self._sensed = self._sigma is not None or self._delay > 0
        self._buf = np.zeros((self._delay + 1, spec.OBS.size), dtype=np.float32)
        self._spool = 1.0  # rotor speed fraction of this episode (reset option spool_up)

    @property
    def angular_momentum(self) -> float:
        """H = J3^(3) psi' of one rotor (N m s); 0 when `gyroscopic` is off."""
        return self.gyro.angular_momentum if "gyroscopic" in self.effects else 0.0

    def capacity(self) -> float:
        """M0 / (n H w sin(max_gimbal_angle)) for the regular wave (docs/design.md bound)."""
        return build.capacity(self.scene)

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        b = self.rows
        b.u[SINGLE] = spec.precession_command(self._scalar_action(action), self.max_precession_rate)
        rows.step_rows(SINGLE, SINGLE + 1, ONE_ROW, b, self._task)
        obs = b.obs[SINGLE].copy()  # clipped to the observation bounds
        info = rows.info_of(b.cols[:, 0])
        self._energy = info["drive_energy"]
        reward, ok = float(b.reward[SINGLE]), bool(b.ok[SINGLE])
        truncated = bool(b.steps[SINGLE] >= self.max_steps)
        if self._sensed and ok:
            obs = self._sense(obs)
        if not ok:
            return self._finish_step(obs, reward, False, truncated, info, False)
        if self.render_mode is not None:  # what render() draws if the state later blows up
            self._frame_state = (b.R[SINGLE].copy(), float(b.y[SINGLE, 3]), float(b.t[SINGLE]))
        return self._step_ok(obs, reward, False, truncated, info)

    # the state of row 0 (views: tests and baselines read and perturb them)
    _y = property(lambda self: self.rows.y[SINGLE])
    _R = property(lambda self: self.rows.R[SINGLE])
    _P = property(lambda self: self.rows.P[SINGLE])
    _tab = property(lambda self: self.rows.tab[SINGLE])
    _out = property(lambda self: self.rows.out[SINGLE])
    _t = property(lambda self: float(self.rows.t[SINGLE]))

    def _sense(self, obs: np.ndarray) -> np.ndarray:
        """The observation as the controller sees it (`sensor_noise`, `sensor_delay`): noise
        from `self.np_random` (spec.sensor_sigma), then the reading of `_delay` control steps
        ago; clipped to the observation bounds. The reward keeps the true roll."""
        if self._sigma is not None:
            noisy = obs + self._sigma * self.np_random.standard_normal(obs.shape[0])
            obs = np.clip(noisy, -OBS_HIGH, OBS_HIGH).astype(np.float32)
        if self._delay > 0:
            self._buf[:-1] = self._buf[1:]
            self._buf[-1] = obs
            obs = self._buf[0].copy()
        return obs

    def _check_reset_options(self, opts: dict[str, Any]) -> dict[str, Any]:
        phi_max = self.max_gimbal_angle if "gimbal_limits" in self.effects else math.pi
        bounds = {"roll": 0.5 * math.pi, "roll_rate": 10.0, "gimbal_angle": phi_max}
        for key, value in opts.items():
            if key == "spool_up":  # rotor speed fraction, (0, 1]
                opts[key] = check_range(key, value, 0.0, 1.0)
                if opts[key] <= 0.0:
                    raise ValueError(f"spool_up: must be in (0, 1], got {value!r}")
                continue
            b = bounds.get(key, 4.0 * math.pi)
            opts[key] = check_range(key, value, -b, b)
        return opts

    def _start(self, opts: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any]]:
        rng = self.np_random  # the start distribution: rows.ROLL0, RATE0, PHASE0 (vector env's)
        roll = float(opts.get("roll", rng.uniform(*rows.ROLL0)))
        roll_rate = float(opts.get("roll_rate", rng.uniform(*rows.RATE0)))
        gimbal = float(opts.get("gimbal_angle", 0.0))
        phase = float(opts.get("wave_phase", rng.uniform(*rows.PHASE0)))
        P = rows.pack(self.scene, phase)
        self._spool = float(opts.get("spool_up", 1.0))
        if self._spool < 1.0:  # the rotor spooling up: slower, drawing its spool-up power
            P[Slot.PSID] *= self._spool
            P[Slot.PROTOR] = self.spool_up_power
        tab = (
            rows.irregular_table(self.scene, self.np_random, self.episode_seconds)
            if "irregular_waves" in self.effects
            else np.zeros((1, 2))
        )
        if self.rows.tab.shape[1:] != tab.shape:
            self.rows = self.rows._replace(tab=np.zeros((1, *tab.shape)))
        b = self.rows
        b.P[SINGLE], b.tab[SINGLE], b.dt[SINGLE], b.n_sub[SINGLE] = (
            P,
            tab,
            self.physics_dt,
            self.n_substeps,
        )
        self._task = rows.Task(self.roll_scale, self.effort_weight, self.control_dt)
        rows.reset_row(SINGLE, roll, roll_rate, gimbal, b)
        self._energy = 0.0
        info = rows.info_of(b.cols[:, 0])
        self._frame_state = (b.R[SINGLE].copy(), float(b.y[SINGLE, 3]), 0.0)
        obs = b.obs[SINGLE].copy()
        if self._sensed:
            self._buf[:] = obs  # the sensors read the initial state until the delay has passed
            obs = self._sense(obs)
        return obs, info

    def _draw_frame(self) -> np.ndarray:
        R, phi, t = self._R, float(self._y[3]), self._t
        note = ""
        if not (np.all(np.isfinite(R)) and math.isfinite(phi)):  # after a numerical failure
            R, phi, t = self._frame_state
            note = "  (last finite state)"
        return render.draw(R, phi, t, self.gyro.rotor_speed, self.n_gyros, note)


_groups.list_aliases(GyroStabilizerEnv, (spec.DRIVE,))  # `drive`'s aliases in the signature
