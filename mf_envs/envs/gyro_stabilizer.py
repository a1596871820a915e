"""GyroStabilizer-v0: a ship with one or two active gyro roll stabilizers (Rios 2017, §3.3)."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Iterable
from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_choice, check_finite, check_int, check_positive
from mf_envs.envs.base import MFEnv
from mf_envs.physics.ship import kernels as K
from mf_envs.physics.ship.model import (
    SHIP_EFFECTS,
    GimbalDrive,
    WaveLoad,
    initial_state,
    pack_params,
)
from mf_envs.physics.ship.params import GyroParams, capacity_ratio, seakeeper_gyro, small_yacht
from mf_envs.physics.ship.waves import regular_heave_force, wave_table

DEFAULT_EFFECTS = (
    "gyroscopic",
    "gimbal_inertia",
    "added_inertia",
    "hydrostatic_restoring",
    "roll_damping",
    "wave_moment",
    "gimbal_limits",
)
_SK9 = seakeeper_gyro("9")
TORQUE_PHYSICS_DT = 0.025  # s, default physics step of the torque drive (end-stop stiffness)
OBS_HIGH = np.array([math.pi, 10.0, 10.0, 10.0, math.pi, 20.0], dtype=np.float32)


class GyroStabilizerEnv(MFEnv):
    """
    ## Description
    A ship rolling in waves, stabilized by gyros whose gimbal precession rate is the action.
    The hull (3 rotational DOF, surge/sway/heave with the `translation` effect) carries one gyro,
    or two counter-rotating ones (Rios 2017, ch. 3 Eqs. 98-113): a rotor spinning at a fixed
    rate psi' inside a gimbal that precesses about the ship's athwartships axis e_2. Precessing
    at phi' gives the roll moment -n H phi' cos(phi), H = J3 psi' (Eq. 123). The physics is the
    numba fast path of `mf_envs.physics.ship.kernels`, which agrees with the general multibody
    engine to round-off (`tests/test_ship_physics.py::test_fast_path_matches_engine`).
    Defaults: an 18 t, 12-13 m motor yacht
    (`physics.ship_params.small_yacht`: J44 = 45 850 kg m^2, A44 = 9 170 kg m^2,
    C44 = 158 900 N m/rad, natural roll period 3.70 s) with one Seakeeper 9 (Table 3-1:
    9 000 rpm, H = 9 000 N m s), beam seas at the roll resonance with a wave roll moment of
    8 000 N m, i.e. a capacity ratio M0 / (H w sin(phi_max)) = 0.60: the gyro can cancel it.
    With the rotor off the yacht rolls about +-15 degrees (RMS 11.2 deg); the `pid` and `lqr`
    baselines cut the RMS roll by 91 % and 96 % (`benchmarks/controllers/stabilizer.py`).
    The seed's model is `effects=("gyroscopic",)` (no hydrostatics, damping or waves; add
    "gimbal_inertia" for J2^(2) and "wave_moment" for M_e = M0 cos(2 pi t / T), Figs. 3-10/11).

    ## Action Space
    `Box(-1, 1, (1,), float32)`:

    | Num | Action                                        | Min | Max | Unit (scaled) |
    |-----|-----------------------------------------------|-----|-----|---------------|
    | 0   | precession-rate command / max_precession_rate | -1 | 1 | rad/s |

    The command is for gyro 1 (gyro 2 mirrors it), scaled by `max_precession_rate` (rad/s). A
    servo with time constant `servo_time_constant` follows it; with `gimbal_limits` it also
    enforces the rate limit and the end stops +-max_gimbal_angle. With `gimbal_drive="torque"`
    the gimbal is a degree of freedom and a velocity loop of gain `gimbal_loop_gain` (limited to
    `max_gimbal_torque`) must fight the gyroscopic torque H omega on the gimbal axis (a stiff
    loop needs a small `physics_dt`); with gain 0 and `gimbal_damping` it is a passive (braked)
    stabilizer that ignores the action.

    ## Observation Space
    `Box(float32)`, what a real controller measures:

    | Num | Observation                          | Min  | Max | Unit  |
    |-----|--------------------------------------|------|-----|-------|
    | 0   | roll angle (z-y-x Euler angle)       | -pi  | pi  | rad   |
    | 1   | roll rate omega_1 (body)             | -10  | 10  | rad/s |
    | 2   | pitch rate omega_2 (body)            | -10  | 10  | rad/s |
    | 3   | yaw rate omega_3 (body)              | -10  | 10  | rad/s |
    | 4   | gimbal angle phi of gyro 1, wrapped  | -pi  | pi  | rad   |
    | 5   | gimbal rate phi'                     | -20  | 20  | rad/s |

    ## Rewards
    `reward = roll + effort`, the terms in `info["reward_terms"]`: roll = -(roll / roll_scale)^2,
    effort = -effort_weight * action^2 (defaults roll_scale = 0.1745 rad = 10 deg,
    effort_weight = 0.01). `info` also has the API keys in SI (`gimbal_angle` unwrapped,
    `gyro_moment` = -n H phi' cos(phi), `wave_moment`) and `time` (s).

    ## Starting State
    Roll uniform in +-0.05 rad, roll rate in +-0.02 rad/s, pitch/yaw rates 0, gimbal at 0 and
    at rest, wave phase uniform in [0, 2 pi) (a new irregular sea each reset with
    `irregular_waves`). `reset(options=...)` overrides `roll`, `roll_rate`, `gimbal_angle`,
    `wave_phase`.

    ## Episode End
    Truncation after `episode_seconds` (default 30 s = 600 steps of 0.05 s). Termination only
    on a numerical failure (`info["numerical_failure"]`).

    ## Arguments
    | Argument | default | meaning |
    |---|---|---|
    | ship_inertia | (45 850, 148 781, 163 659) | hull (J1, J2, J3), kg m^2 |
    | n_gyros | 1 | 1 or 2 (counter-rotating pair) |
    | rotor_inertia | 9.549 | rotor polar J3^(3), kg m^2 (Seakeeper 9) |
    | gimbal_inertia | 9.549 | gimbal J2^(2), kg m^2 (assumed) |
    | rotor_speed | 942.5 | psi', rad/s (9 000 rpm) |
    | wave_moment_amplitude | 8 000 | M0, N m |
    | wave_period | None | s; None = natural roll period (resonance), 10 s without restoring |
    | roll_stiffness | 158 922 | C44 = rho g V GM, N m/rad |
    | roll_damping | 7 481 | linear B44, N m s/rad (quadratic term from the preset) |
    | max_precession_rate | 2.0 | rad/s |
    | max_gimbal_angle | pi/3 | rad (end stops) |
    | episode_seconds | 30 | s |
    | effects | see DEFAULT_EFFECTS | tuple of names from `SHIP_EFFECTS` |
    | control_dt | 0.05 | s |
    | physics_dt | None | s; None: min(0.05, servo_time_constant) servo, 0.025 torque drive |
    | form | "exact" | "seed": Eqs. 123-128 as printed |
    | servo_time_constant | 0.05 | s |
    | gimbal_drive | "servo" | "servo" (kinematic rate servo) or "torque" (gimbal DOF) |
    | gimbal_loop_gain | None | torque drive K_v, N m s/rad (None: (J_g + J_r1)/servo tau) |
    | max_gimbal_torque | 0 | torque drive limit, N m (0 = none) |
    | gimbal_damping | 0 | c_g, N m s/rad (effect `gimbal_damping`, torque drive) |
    | significant_wave_height | 0.6 | m (irregular_waves, JONSWAP, peak period = wave_period) |
    | effective_slope | 0.7 | r_eff of the wave roll moment (`physics.ship_waves`) |
    | roll_scale, effort_weight | 0.1745, 0.01 | reward terms |

    The default physics step is one RK4-Munthe-Kaas step per 0.05 s control step for the servo
    (physics_dt = 0.025 s, two steps, before the kernel was sped up; pass it to get that back):
    against a reference at 0.05/32 s over a 30 s episode of the default scene (seeds 0-2) the
    roll differs by 4.6e-6 rad RMS (7.3e-6 max; 0.03 % of the 1.8e-2 rad RMS roll) under the
    `pid` baseline and 3.4e-7...7.5e-7 rad RMS under `lqr` (returns within 5e-4 of about -7 and
    -2), and by 6.8e-5 rad RMS (0.04 % of the 0.18 rad RMS roll) with uniform random actions
    that drive the gimbal into its end stops; physics_dt = 0.025 cuts these 20-25 fold (4th
    order). The torque drive keeps 0.025 s: its end-stop spring (k_stop = 1e5 N m/rad on the
    14.3 kg m^2 gimbal, 84 rad/s) is beyond RK4's stability limit at 0.05 s.

    ## Version History
    - v0: initial release.
    """

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 20}

    def __init__(
        self,
        ship_inertia: Iterable[float] | None = None,
        n_gyros: int = 1,
        rotor_inertia: float = _SK9.rotor_inertia,
        gimbal_inertia: float = _SK9.gimbal_inertia,
        rotor_speed: float = _SK9.rotor_speed,
        wave_moment_amplitude: float = 8000.0,
        wave_period: float | None = None,
        roll_stiffness: float | None = None,
        roll_damping: float | None = None,
        max_precession_rate: float = 2.0,
        max_gimbal_angle: float = math.pi / 3,
        episode_seconds: float = 30.0,
        effects: Iterable[str] | str | None = None,
        control_dt: float = 0.05,
        physics_dt: float | None = None,
        form: str = "exact",
        servo_time_constant: float = 0.05,
        gimbal_drive: str = "servo",
        gimbal_loop_gain: float | None = None,
        max_gimbal_torque: float = 0.0,
        gimbal_damping: float = 0.0,
        significant_wave_height: float = 0.6,
        effective_slope: float = 0.7,
        roll_scale: float = 0.1745,
        effort_weight: float = 0.01,
        render_mode: str | None = None,
    ) -> None:
        check_choice("gimbal_drive", gimbal_drive, ("servo", "torque"))
        if physics_dt is None:  # see the class docstring for the accuracy of these defaults
            tau_s = float(check_positive("servo_time_constant", servo_time_constant))
            physics_dt = TORQUE_PHYSICS_DT if gimbal_drive == "torque" else min(0.05, tau_s)
        super().__init__(
            effects=effects,
            available_effects=SHIP_EFFECTS,
            default_effects=DEFAULT_EFFECTS,
            control_dt=control_dt,
            physics_dt=physics_dt,
            render_mode=render_mode,
        )
        ship = small_yacht()
        over: dict[str, Any] = {}
        if ship_inertia is not None:
            over["inertia"] = tuple(
                float(v) for v in np.ravel(check_positive("ship_inertia", ship_inertia))
            )
        if roll_stiffness is not None:
            over["roll_stiffness"] = float(roll_stiffness)
        if roll_damping is not None:
            over["roll_damping"] = float(roll_damping)
        self.ship = dataclasses.replace(ship, **over)
        self.gyro = GyroParams(float(rotor_inertia), float(gimbal_inertia), float(rotor_speed))
        self.n_gyros = check_int("n_gyros", n_gyros, 1, 2)
        self.max_precession_rate = float(check_positive("max_precession_rate", max_precession_rate))
        self.max_gimbal_angle = float(check_positive("max_gimbal_angle", max_gimbal_angle))
        self.episode_seconds = float(check_positive("episode_seconds", episode_seconds))
        self.form = check_choice("form", form, ("exact", "seed"))
        self.wave_moment_amplitude = float(
            check_finite("wave_moment_amplitude", wave_moment_amplitude)
        )
        if wave_period is None:
            wave_period = self.ship.natural_roll_period("added_inertia" in self.effects)
            if "hydrostatic_restoring" not in self.effects or not math.isfinite(wave_period):
                wave_period = 10.0  # no restoring, no resonance: the seed's cases use T = 10 s
        self.wave_period = float(check_positive("wave_period", wave_period))
        self.significant_wave_height = float(
            check_positive("significant_wave_height", significant_wave_height)
        )
        self.effective_slope = float(check_positive("effective_slope", effective_slope))
        self.roll_scale = float(check_positive("roll_scale", roll_scale))
        self.effort_weight = float(check_finite("effort_weight", effort_weight))
        d2 = self.gyro.gimbal_inertia + self.gyro.rotor_j1
        if gimbal_loop_gain is None:
            gimbal_loop_gain = d2 / servo_time_constant if gimbal_drive == "torque" else 0.0
        if gimbal_drive == "torque" and gimbal_loop_gain * self.physics_dt / d2 > 1.5:
            raise ValueError(
                f"physics_dt: the torque drive's loop gain {gimbal_loop_gain:g} N m s/rad needs "
                f"physics_dt <= {1.5 * d2 / gimbal_loop_gain:.3g} s (RK4 stability)"
            )
        self.drive = GimbalDrive(
            gimbal_drive,
            servo_time_constant=servo_time_constant,
            max_rate=self.max_precession_rate,
            max_angle=self.max_gimbal_angle,
            loop_gain=float(check_finite("gimbal_loop_gain", gimbal_loop_gain)),
            max_torque=float(check_finite("max_gimbal_torque", max_gimbal_torque)),
            damping=float(check_finite("gimbal_damping", gimbal_damping)),
        )
        self.action_space = spaces.Box(-1.0, 1.0, (1,), np.float32)
        self.observation_space = spaces.Box(-OBS_HIGH, OBS_HIGH, dtype=np.float32)
        self._table_dt = min(0.5 * self.physics_dt, 0.01)
        self._P = self._pack(0.0)
        self._tab = np.zeros((1, 2))
        self._out = np.zeros(2)
        self._obs = np.zeros(6, dtype=np.float32)
        self._high = OBS_HIGH.astype(np.float64)
        self._y, self._R = initial_state()
        self._t = 0.0

    # ------------------------------------------------------------------ physics wiring
    def _pack(self, phase: float) -> np.ndarray:
        wave = WaveLoad(
            self.wave_moment_amplitude,
            self.wave_period,
            phase,
            regular_heave_force(
                self.wave_moment_amplitude,
                self.wave_period,
                self.ship.roll_stiffness,
                self.ship.heave_stiffness,
                self.effective_slope,
            ),
        )
        return pack_params(
            self.ship,
            self.gyro,
            self.n_gyros,
            self.effects,
            self.drive,
            wave,
            self.form,
            self._table_dt,
        )

    def _irregular_table(self) -> np.ndarray:
        from mf_envs.physics.waves import IrregularSea, jonswap_spectrum

        sea = IrregularSea(
            jonswap_spectrum, self.significant_wave_height, self.wave_period, 64, self.np_random
        )
        a, w, eps = sea.components
        return wave_table(
            a,
            w,
            eps,
            self.ship.roll_stiffness,
            self.ship.heave_stiffness,
            self.episode_seconds + 1.0,
            self._table_dt,
            self.effective_slope,
        )

    @property
    def angular_momentum(self) -> float:
        """H = J3^(3) psi' of one rotor (N m s); 0 when `gyroscopic` is off."""
        return self.gyro.angular_momentum if "gyroscopic" in self.effects else 0.0

    def capacity(self) -> float:
        """M0 / (n H w sin(max_gimbal_angle)) for the regular wave (docs/design.md bound)."""
        return capacity_ratio(
            self.wave_moment_amplitude,
            self.gyro.angular_momentum,
            2.0 * math.pi / self.wave_period,
            self.n_gyros,
            self.max_gimbal_angle,
        )

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        a0 = self._scalar_action(action)
        self._t, ok = K.env_advance(
            self._t,
            self._y,
            self._R,
            a0 * self.max_precession_rate,
            self.physics_dt,
            self.n_substeps,
            self._P,
            self._tab,
            self._out,
            self._obs,
            self._high,
        )
        obs = self._obs.copy()  # already clipped to the observation bounds
        reward, terms = self._get_rew(float(obs[0]), a0)
        info = self._get_info(terms)
        truncated = self._t >= self.episode_seconds - 1e-9
        if not (ok and math.isfinite(reward)):
            return self._finish_step(obs, reward, False, truncated, info, False)
        info["numerical_failure"] = False  # MFEnv._finish_step contract, without its overhead
        self._last_obs = obs
        if self.render_mode is not None:  # what render() draws if the state later blows up
            self._frame_state = (self._R.copy(), float(self._y[3]), self._t)
        return obs, reward, False, truncated, info

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        opts = dict(options or {})
        rng = self.np_random
        roll = float(opts.pop("roll", rng.uniform(-0.05, 0.05)))
        roll_rate = float(opts.pop("roll_rate", rng.uniform(-0.02, 0.02)))
        gimbal = float(opts.pop("gimbal_angle", 0.0))
        phase = float(opts.pop("wave_phase", rng.uniform(0.0, 2.0 * math.pi)))
        if opts:
            raise ValueError(
                f"options: unknown keys {sorted(opts)}; known: roll, roll_rate, "
                "gimbal_angle, wave_phase"
            )
        for name, v in (
            ("roll", roll),
            ("roll_rate", roll_rate),
            ("gimbal_angle", gimbal),
            ("wave_phase", phase),
        ):
            check_finite(name, v)
        self._P = self._pack(phase)
        self._tab = (
            self._irregular_table() if "irregular_waves" in self.effects else np.zeros((1, 2))
        )
        self._y, self._R = initial_state(roll, (roll_rate, 0.0, 0.0), gimbal)
        self._t = 0.0
        mw = K.external_moment(0.0, self._y, self._R, self._P, self._tab)[3]
        self._out[:] = (0.0, mw)
        info = self._get_info({"roll": 0.0, "effort": 0.0})
        self._frame_state = (self._R.copy(), float(self._y[3]), self._t)
        return self._finish_reset(self._get_obs()), info

    # ------------------------------------------------------------------ observation, reward
    def _get_obs(self) -> np.ndarray:
        y, R = self._y, self._R
        phi = (y[3] + math.pi) % (2.0 * math.pi) - math.pi
        return np.array(
            [math.atan2(R[2, 1], R[2, 2]), y[0], y[1], y[2], phi, y[4]], dtype=np.float32
        )

    def _get_rew(self, roll: float, action: float) -> tuple[float, dict[str, float]]:
        q = roll / self.roll_scale
        terms = {
            "roll": -(q * q),  # q * q, not q ** 2: libm pow, which numpy would not match
            "effort": -self.effort_weight * action * action,
        }
        return terms["roll"] + terms["effort"], terms

    def _get_info(self, terms: dict[str, float]) -> dict[str, Any]:
        y, R = self._y, self._R
        info = {
            "roll": math.atan2(R[2, 1], R[2, 2]),
            "roll_rate": float(y[0]),
            "pitch_rate": float(y[1]),
            "yaw_rate": float(y[2]),
            "gimbal_angle": float(y[3]),
            "gimbal_rate": float(y[4]),
            "gyro_moment": float(self._out[0]),
            "wave_moment": float(self._out[1]),
            "time": self._t,
        }
        info["reward_terms"] = terms  # the convention shared by every env: terms sum to reward
        return info

    # ------------------------------------------------------------------ rendering
    def _draw_frame(self) -> np.ndarray:
        from mf_envs.render import draw_ship

        R, phi, t = self._R, float(self._y[3]), self._t
        note = ""
        if not (np.all(np.isfinite(R)) and math.isfinite(phi)):  # after a numerical failure
            R, phi, t = self._frame_state
            note = "  (last finite state)"
        psi = math.fmod(self.gyro.rotor_speed * t, 2.0 * math.pi)
        angles = (phi,) if self.n_gyros == 1 else (phi, -phi)
        rotors = (psi,) if self.n_gyros == 1 else (psi, -psi)
        roll = math.degrees(math.atan2(R[2, 1], R[2, 2]))
        return draw_ship(
            ship_R=R.copy(),
            gimbal_angles=angles,
            rotor_angles=rotors,
            text=f"t = {t:5.2f} s  roll = {roll:+5.1f} deg  "
            f"gimbal = {math.degrees(phi):+5.1f} deg{note}",
        )
