"""Inchworm-v0: an active C1-beam inchworm crawling by its actuation curvature (Rios 2017 §4.10)."""

from __future__ import annotations

from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_range
from mf_envs.envs._spec import check_curvature_option
from mf_envs.envs.base import MFEnv
from mf_envs.envs.inchworm import build, render, spec
from mf_envs.envs.inchworm.build import PDMS_E, PDMS_G, PDMS_MASS, SEED_SCENE_EFFECTS
from mf_envs.physics.beam import NewtonDivergence
from mf_envs.physics.beam.contact.feet import NoQuasiStaticEquilibrium
from mf_envs.physics.inchworm import INCHWORM_EFFECTS
from mf_envs.physics.inchworm.drive import DRIVE_EFFECTS, make_driven

AVAILABLE_EFFECTS = {**INCHWORM_EFFECTS, **DRIVE_EFFECTS}
# the buildable robot's SMA wires and feet that must grip
DEFAULT_EFFECTS = (*SEED_SCENE_EFFECTS, "sma_wires", "gripping_feet")
CURVATURE_OBS_LIMIT = spec.CURVATURE_OBS_LIMIT
REACTION_OBS_LIMIT = spec.REACTION_OBS_LIMIT
# what a diverging solve raises: a failed step ends the episode (numerical_failure)
SOLVER_ERRORS = (NewtonDivergence, NoQuasiStaticEquilibrium, np.linalg.LinAlgError)
SOLVER_ERRORS += (FloatingPointError, OverflowError)


class InchwormEnv(MFEnv):
    """
    ## Description
    A soft robot as a planar geometrically exact active beam with C1 elements (Rios 2017
    §4.7-4.10): kappa#(S) is the pre-curvature of the active law M3 = EI (kappa - kappa#) (Eq.
    53); the shape follows from equilibrium (quasi-static; Newmark dynamics with `inertia`). Both
    ends rest on the ground (Eq. 100); with `anchor_switching` the agent chooses which foot
    grips. Goal: crawl forward (+x) with little energy. Default: a buildable robot
    after Wang et al. 2014, a 60 x 10 x 3 mm PDMS body bent by Flexinol wires sized to the moment
    (`physics.inchworm.presets`); `sma_wires`: one wire group per control point heated by the
    commanded duty cycle (Joule heat, still-air cooling, martensite fraction with hysteresis;
    `physics.actuators.sma`), kappa# = -max_curvature (1 - xi), effort = electrical energy;
    `gripping_feet`: a foot anchors only above `grip_threshold`, below it slides on its smooth
    face, regularised friction solved with the beam (`physics.beam.contact.grip_feet`). The
    dissertation's scene: `gym.make("Inchworm-v0", **RIOS2017_SCENE)` (kinematic anchors of
    Eq. 102, kappa# as commanded); the lag-friction robot (lag actuator, Coulomb feet):
    `**LAG_FRICTION_SCENE` (both in `mf_envs.envs.inchworm`); `terrain`: Bekker/Janosi soil. The
    wires contract in 2.9 s at the rated current and relax in 1.3 s: a gait cycle needs tens of
    0.1 s steps. `info["quasi_static_error"]`: the neglected inertia over the feet's friction.

    ## Action Space
    `Box(-1, 1, (n_control_points + 1,), float32)` with `anchor_switching`, else
    `(n_control_points,)`:

    | Num | Action | Scaling |
    |-----|--------|---------|
    | 0..n-1 | duty of each control point's wire group (`sma_wires`) | (a + 1) / 2 in [0, 1] |
    |   | else kappa# at S = 0 .. L, linear between | -max_curvature (a + 1) / 2 [1/m] |
    | n | anchor / grip choice | a > 0: head grips, a <= 0: tail (the other foot releases) |

    ## Observation Space
    `Box(float32, (2 n + 6,))`, what an on-board robot can sense, laid out by
    `mf_envs.envs.inchworm.spec.observation_layout(n, sma)` (the env's `obs_layout`; read slots
    by name: `obs_layout.slice("curvature")`, `obs_layout.index("grip")`); without `sma_wires`
    the slots n..2n-1 are `curvature_command` (kappa# / max_curvature; spreads: docs/inchworm.md):

    | Num | Name | Observation | Bound | Unit |
    |---|---|---|---|---|
    | 0..n-1 | curvature | measured kappa L at the control points (strain gauges) | +-20 | |
    | n..2n-1 | wire_temperature | (T - T_amb) / (Af - T_amb) of each wire group | +-4 | |
    | 2n | tail_angle | frame angle psi at the tail (foot IMU) | +-2 pi | rad |
    | 2n+1 | head_angle | frame angle psi at the head (foot IMU) | +-2 pi | rad |
    | 2n+2 | head_tail_distance | (x_head - x_tail) / L | +-1.5 | |
    | 2n+3 | grip | gripping foot: +1 head, -1 tail | +-1 | |
    | 2n+4 | tail_reaction | ground reaction at the tail (`terrain`: half) / weight | +-20 | |
    | 2n+5 | head_reaction | ground reaction at the head / weight | +-20 | |

    ## Rewards
    `reward = progress + effort`, the terms in `info["reward_terms"]`:
    `progress` = tail advance this step / L (computed in the body's local coordinates, exact at
    any distance); `effort` = -effort_weight * energy of the step [J]: with `sma_wires` the
    electrical energy duty I^2 R' l of the wires (default weight 2e-6 / (m_A g L * L)), else the
    positive mechanical actuation work of P = -int M3 d kappa#/dt dS (no regeneration; default
    weight 0.1 / (m_A g L * L)). Info keys: `spec.INFO_KEYS` (`time` = steps x control_dt;
    `kappa_sharp` = realised actuation curvature at the control points [1/m], `actuation_power`
    = mean mechanical actuation power of the step [W], `actuation_energy` [J] (the effort's),
    `electrical_energy` [J], `mechanical_work` [J] (with gripping feet the work of the wires'
    moment EI kappa# on the body: its strain energy), `wire_temperature` [degC], `duty`,
    `grip` = the feet's engagement (tail, head) in [0, 1], `foot_slip` (tail, head) [m],
    `quasi_static_error` (inertia / friction, `spec.quasi_static_error`; above
    `spec.QUASI_STATIC_LIMIT` the quasi-static model is off)).

    ## Starting State
    Straight body at rest, tail at x = 0, head gripping, with a small random initial actuation
    kappa# = -max_curvature * U(0, reset_noise_scale) per control point, settled to equilibrium
    (with `sma_wires` the wires are warm on their heating branch where they hold it, at ambient
    when kappa# = 0). `reset(options={"kappa": (n,) [1/m] within +-max_curvature (sma_wires:
    [-max_curvature, 0]), "x_tail": m, |.| <= 1e6})` overrides; any other key or value raises
    ValueError naming it (and draws nothing).

    ## Episode End
    Truncation after `max_episode_steps` (default 400 steps, 40 s of 0.1 s) or
    `episode_seconds` (docs/api.md, "Episode length"). Termination when Newton-Raphson fails even
    after step halving (info["numerical_failure"] = True), or when both Coulomb feet would slip
    at once (no quasi-static equilibrium); render() then draws the last finite state. Translation
    invariant to round-off at any distance crawled (local coordinates, `mf_envs.physics.inchworm`).

    ## Arguments
    | Argument | Default | Meaning |
    |----------|---------|---------|
    | length | 0.05 | body length L [m] in [0.01, 10] (RIOS2017_BODY: 0.3) |
    | width, height | 0.010, 0.003 | cross-section b, h [m] in [1e-4, 1], h <= L / 5 |
    | youngs_modulus, shear_modulus | 1.5e6, 5.03e5 | E, G [Pa] in [1e3, 1e13] (PDMS, nu 0.49) |
    | mass_per_length | 0.0309 | m_A [kg/m] in [1e-6, 1e4] (1030 kg/m^3; J_3C = m_A h^2 / 12) |
    | n_elements | 12 | C1 elements, 1..64 |
    | max_curvature | 60.0 | largest abs(kappa#) [1/m] (sma_wires: full stroke), <= 20 / L |
    | n_control_points | 3 | actuation control points (wire groups), 2..64 |
    | control_dt, physics_dt | 0.1, 0.1 | s per step; Newmark step with `inertia` |
    | episode_seconds | None | episode length [s]; None: max_episode_steps steps |
    | max_episode_steps | None | steps per episode; None: 400 (or from episode_seconds) |
    | effort_weight | None | weight of the effort term [1/J], >= 0; None: see Rewards |
    | actuator_time_constant | 0.3 | tau [s] of the lag (`actuator_dynamics`) |
    | actuator_rate_limit | 13.0 | largest abs(d kappa#/dt) [1/(m s)] (`actuator_dynamics`) |
    | grip_time_constant | 0.5 | feet's engage/release time constant [s] (LAG_FRICTION_SCENE: 0.2) |
    | friction_coefficients | None | dict grip_forward, grip_backward, slide_forward, |
    |  |  | slide_backward (defaults 0.6, 1.0, 0.1, 0.15) or 4 numbers in that order |
    |  |  | (gripping feet: slide_forward is the isotropic smooth face) |
    | grip_threshold | 0.7 | engagement below which a gripping foot slides, in [0, 0.8] |
    | wire_diameter | 1.5e-4 | Flexinol wire diameter [m] (a row of the maker's table) |
    | wire_lever_arm | 6e-4 | wires below the neutral axis [m], <= height / 2 |
    | wire_alloy | "HT" | "HT" (90 degC) or "LT" (70 degC) Flexinol |
    | ambient_temperature, max_wire_temperature | 20, 150 | still air (< Mf), wire limit [degC] |
    | increment_factor | 4.0 | increments up to factor * 2h/L^2 (seed: 1; same equilibria) |
    |  |  | at most 200 increments (or Newmark steps) per step |
    | reset_noise_scale | 0.05 | initial actuation noise, in [0, 1] |
    | soil | "dry_sand" | soil preset for `terrain` (Wong 2008 Table 2.3 values) |
    | effects | gravity, shear_deformation, anchor_switching, | also: inertia, terrain, |
    |  | sma_wires, gripping_feet | actuator_dynamics, friction (exclusive pairs: ValueError) |

    With `sma_wires`, max_curvature x wire_lever_arm within the alloy's 6 % (else ValueError).

    ## Version History
    * v0: initial release (kinematic anchoring of Eq. 102; quasi-static by default); then
      actuator dynamics, friction feet and the energy effort term by default; the PDMS robot
      with SMA wires and gripping feet by default, the seed's scene as `RIOS2017_SCENE`; the
      wires' default effort weight 5x lower (2e-6 / (m_A g L^2); rewards change, not states).
    """

    RESET_OPTIONS = spec.RESET_OPTIONS  # the keys reset(options=...) takes
    AVAILABLE_EFFECTS, DEFAULT_EFFECTS = AVAILABLE_EFFECTS, DEFAULT_EFFECTS

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 10}
    exclusive_effects = (
        ("friction", "inertia"), ("friction", "terrain"), ("inertia", "gripping_feet"),
        ("terrain", "gripping_feet"), ("friction", "gripping_feet"),
        ("actuator_dynamics", "sma_wires"),
    )  # ValueError  # fmt: skip

    def __init__(
        self,
        length: float = 0.05,
        width: float = 0.010,
        height: float = 0.003,
        youngs_modulus: float = PDMS_E,
        shear_modulus: float = PDMS_G,
        mass_per_length: float = PDMS_MASS,
        n_elements: int = 12,
        max_curvature: float = 60.0,
        effects: Any = None,
        n_control_points: int = 3,
        control_dt: float = 0.1,
        physics_dt: float = 0.1,
        max_episode_steps: int | None = None,
        effort_weight: float | None = None,
        increment_factor: float = 4.0,
        reset_noise_scale: float = 0.05,
        soil: str = "dry_sand",
        episode_seconds: float | None = None,
        actuator_time_constant: float = build.SMA_TIME_CONSTANT,
        actuator_rate_limit: float = build.SMA_RATE_LIMIT,
        grip_time_constant: float = build.GRIP_TIME_CONSTANT,
        friction_coefficients: Any = None,
        grip_threshold: float = 0.7,
        wire_diameter: float = 150e-6,
        wire_lever_arm: float = 0.6e-3,
        wire_alloy: str = "HT",
        ambient_temperature: float = 20.0,
        max_wire_temperature: float = build.MAX_WIRE_TEMPERATURE,
        render_mode: str | None = None,
    ) -> None:
        kw = {k: v for k, v in locals().items() if k not in ("self", "render_mode", "__class__")}
        super().__init__(effects=effects, control_dt=control_dt, physics_dt=physics_dt,
                         render_mode=render_mode)  # fmt: skip
        self._set_scene(build.build(kw, self.effects, self.n_substeps))  # kwargs as physics params
        own, default = self._own_seconds(episode_seconds), build.DEFAULT_EPISODE_STEPS
        self.max_steps = self._episode_length(max_episode_steps, own, default)
        self.episode_seconds = self.max_steps * self.control_dt
        self.actuator = self.actuator_params if "actuator_dynamics" in self.effects else None
        self.sma = "sma_wires" in self.effects
        self._drive = build.drive_kwargs(self.scene, self.effects)
        try:
            self.driven = make_driven(**self._drive)
        except SOLVER_ERRORS as exc:
            raise ValueError(
                "length, youngs_modulus, shear_modulus, mass_per_length, height: the body finds "
                f"no static equilibrium under its own weight ({exc}); stiffen or shorten it, or "
                "bring shear_modulus nearer youngs_modulus / 3"
            ) from None
        self.sim = self.driven.sim
        self.S_ctrl = self.driven.S_ctrl
        self.obs_geometry = spec.observe_geometry(self.sim, self.S_ctrl)
        self.switching = "anchor_switching" in self.effects
        n_act = self.n_ctrl + (1 if self.switching else 0)
        self.action_space = spaces.Box(-1.0, 1.0, (n_act,), np.float32)
        self.obs_layout = spec.observation_layout(self.n_ctrl, self.sma)
        hi = self.obs_layout.high()
        self.observation_space = spaces.Box(-hi, hi, dtype=np.float32)
        self.kappa_command = np.zeros(self.n_ctrl)
        self.duty = np.zeros(self.n_ctrl)  # the wire groups' duty cycles (sma_wires)
        self._foot_dx = np.zeros(2)  # the feet's x-displacements of the last step [m]
        self._steps = 0
        self._frame_state: dict[str, Any] | None = None  # last finite state, for render()

    def drive_config(self) -> tuple:
        """Hashable configuration of the physics (make_driven's arguments, control_dt,
        max_curvature): what an open-loop gait tuner needs to rebuild this robot."""
        cfg = dict(self._drive, control_dt=self.control_dt, max_curvature=self.max_curvature)
        return tuple(cfg.items())

    # ------------------------------------------------------------------ API
    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        a = self._validate_action(action)
        kappa_new = -self.max_curvature * 0.5 * (a[: self.n_ctrl] + 1.0)
        duty = 0.5 * (a[: self.n_ctrl] + 1.0)
        anchor = None
        if self.switching:
            anchor = "head" if a[-1] > 0.0 else "tail"
        tail_old = spec.tail_position(self.sim)
        feet_old = (self.sim.x_tail, self.sim.x_head)
        ok, report = True, None
        try:
            n_min = self.n_substeps if "inertia" in self.effects else 1
            report = self.driven.step(duty if self.sma else kappa_new, anchor, self.control_dt,
                                      n_min)  # fmt: skip
            self.kappa_command = kappa_new
            self.duty = duty
        except SOLVER_ERRORS:
            ok = False
        self._steps += 1
        energy = 0.0 if report is None else report.energy
        terms = spec.reward_terms(
            tail_old, spec.tail_position(self.sim), self.params.length, energy, self.effort_weight
        )
        obs = self._observe() if ok else np.full(self.observation_space.shape, np.nan)
        dx = np.array([self.sim.x_tail - feet_old[0], self.sim.x_head - feet_old[1]])
        qse = self._quasi_static_error(dx, report) if ok else 0.0
        self._foot_dx = dx if ok else np.zeros(2)
        info = self._get_info(terms, report, qse)
        if ok:
            self._remember_frame(info)
        truncated = self._steps >= self.max_steps
        reward = terms["progress"] + terms["effort"]
        return self._finish_step(obs, reward, False, truncated, info, ok)

    def _check_reset_options(self, opts: dict[str, Any]) -> dict[str, Any]:
        x_tail = check_range("x_tail", opts.get("x_tail", 0.0), -spec.MAX_X_TAIL, spec.MAX_X_TAIL)
        kappa = None
        if "kappa" in opts:
            kappa = check_curvature_option(opts["kappa"], self.n_ctrl, self.max_curvature)
            if self.sma and np.any(kappa > 0.0):
                raise ValueError(
                    "kappa: the SMA wires only curl the body: kappa# in [-max_curvature, 0]"
                )
        return {"x_tail": x_tail, "kappa": kappa}

    def _start(self, opts: dict[str, Any]) -> tuple[np.ndarray, dict[str, Any]]:
        x_tail, kappa = opts["x_tail"], opts["kappa"]
        noise = self.np_random.uniform(0.0, self.reset_noise_scale, self.n_ctrl)
        drawn, kappa = kappa is None, -self.max_curvature * noise if kappa is None else kappa
        for _ in range(8 if drawn else 1):  # a drawn start without equilibrium is halved
            try:
                self.driven.reset(kappa, x_tail=x_tail)
                break
            except SOLVER_ERRORS:
                kappa = 0.5 * kappa
        else:
            if not drawn:
                raise ValueError("kappa: no equilibrium for this initial actuation")
            kappa = np.zeros(self.n_ctrl)  # the flat body is always an equilibrium
            self.driven.reset(kappa, x_tail=x_tail)
        self.kappa_command = kappa
        self.duty = np.zeros(self.n_ctrl)
        self._foot_dx = np.zeros(2)
        info = self._get_info({"progress": 0.0, "effort": 0.0}, None)
        self._frame_state = None
        self._remember_frame(info)
        return self._observe(), info

    # ------------------------------------------------------------------ helpers
    def _observe(self) -> np.ndarray:
        if self.sma:  # the wires' temperatures in the command slots (spec.observation_layout)
            temp = spec.wire_temperature_obs(self.driven.wire_temperature, self.scene.wires)
            return spec.observe(self.sim, self.obs_geometry, temp, 1.0, self.scene.weight)
        args = (self.obs_geometry, self.kappa_command, self.max_curvature, self.scene.weight)
        return spec.observe(self.sim, *args)

    def _quasi_static_error(self, dx: np.ndarray, report: Any) -> float:
        """`spec.step_quasi_static_error` of this step (0 without friction or gripping feet)."""
        return spec.step_quasi_static_error(
            self.driven, self.scene, report, dx, self._foot_dx, self.control_dt
        )

    def _get_info(self, terms: dict[str, float], report: Any, qse: float = 0.0) -> dict[str, Any]:
        sim = self.sim
        info: dict[str, Any] = {
            "x_head": sim.x_head,
            "x_tail": sim.x_tail,
            "centerline": sim.centerline(),
            "anchor": sim.anchor,
            "kappa_sharp": self.driven.kappa_ctrl.copy(),
            "kappa_command": self.kappa_command.copy(),
            "actuation_power": 0.0 if report is None else report.net_work / self.control_dt,
            "actuation_energy": 0.0 if report is None else report.energy,
            "grip": self.driven.grip.copy(),
            "foot_slip": np.zeros(2) if report is None else report.slip.copy(),
            "elastic_energy": sim.elastic_energy(),
            "newton_iterations": 0 if report is None else report.iterations,
            "increments": 0 if report is None else report.increments,
            "time": self._steps * self.control_dt,
            "electrical_energy": 0.0 if report is None or not self.sma else report.energy,
            "mechanical_work": 0.0 if report is None else report.mechanical_work,
            "wire_temperature": self.driven.wire_temperature
            if self.sma
            else np.full(self.n_ctrl, self.scene.ambient),
            "duty": self.duty.copy(),
            "quasi_static_error": qse,
        }
        info["reward_terms"] = terms  # the convention shared by every env: terms sum to reward
        return info

    # ------------------------------------------------------------------ rendering
    def _remember_frame(self, info: dict[str, Any]) -> None:
        """Keep the drawable state if it is finite (`render.frame_state`)."""
        fs = render.frame_state(info, self._steps)
        if fs is not None:
            self._frame_state = fs

    def _draw_frame(self) -> np.ndarray:
        if self._frame_state is None:  # before the first reset: the constructed state
            self._remember_frame(render.sim_state(self.sim))
        return render.draw(self._frame_state, self._steps)
