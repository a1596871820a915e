"""Inchworm-v0: an active C1-beam inchworm crawling by its actuation curvature (Rios 2017 §4.10)."""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_finite, check_int, check_nonnegative, check_positive
from mf_envs.envs.base import MFEnv
from mf_envs.physics.beam import NewtonDivergence
from mf_envs.physics.inchworm import INCHWORM_EFFECTS, Inchworm, InchwormParams, kappa_at_gauss

DEFAULT_EFFECTS = ("gravity", "shear_deformation", "anchor_switching")
CURVATURE_OBS_LIMIT = 20.0  # |kappa L| bound of the observation
REACTION_OBS_LIMIT = 20.0  # |ground reaction| / body weight bound


class InchwormEnv(MFEnv):
    """
    ## Description
    A slender soft robot (the seed's SMA/PDMS inchworm, §4.10) modelled as a planar geometrically
    exact active beam with three-node C1 elements (Eqs. 68-83). The agent sets the actuation
    curvature kappa#(S) (the pre-curvature of the active law M3 = EI (kappa - kappa#), Eq. 53);
    the body's shape follows from equilibrium (quasi-static by default, as in the seed; Newmark
    dynamics with the `inertia` effect). Both ends rest on the ground (z = 0, sliding simple
    supports, Eq. 100); with `anchor_switching` the agent chooses which foot grips (its x is
    held, Eq. 102). With `terrain` the body instead rests on Bekker/Janosi soil (Eqs. 56-57):
    no kinematic supports, and the anchor choice gives the gripping half of the body the soil's
    shear strength while the other half slides (slick foot), so the grip comes out of the
    contact law (`terrain` implies the weight). Curling with the head anchored pulls the tail
    forward; uncurling with the tail anchored pushes the head forward. Goal: crawl forward
    (+x) with little actuation effort.

    ## Action Space
    `Box(-1, 1, (n_control_points + 1,), float32)` with `anchor_switching`, else
    `(n_control_points,)`:

    kappa# = -max_curvature (a + 1) / 2, i.e. in [-max_curvature, 0] (the body humps up).

    | Num | Action | Scaling |
    |-----|--------|---------|
    | 0..n-1 | kappa# at control points S = 0 .. L (tail to head), linear between | [1/m] |
    | n | anchor choice | a > 0: head grips, a <= 0: tail grips |

    ## Observation Space
    `Box(float32, (2 n + 6,))`, what an on-board robot can sense:

    | Num | Observation | Unit / bound |
    |-----|-------------|--------------|
    | 0..n-1 | measured curvature kappa L at the control points (strain gauges) | [-20, 20] |
    | n..2n-1 | commanded kappa# / max_curvature at the control points | [-1, 1] |
    | 2n, 2n+1 | frame angle psi at tail, head (foot IMUs) | rad, [-2 pi, 2 pi] |
    | 2n+2 | head-tail distance / L | [-1.5, 1.5] |
    | 2n+3 | gripping foot: +1 head, -1 tail | |
    | 2n+4, 2n+5 | ground reaction at tail, head (halves with `terrain`) / body weight | [-20, 20] |

    ## Rewards
    `reward = progress + effort`, the terms in `info["reward_terms"]`:
    `progress` = tail advance this step / L;
    `effort` = -effort_weight * mean((Delta kappa# / max_curvature)^2) over the control points.

    ## Starting State
    Straight body at rest, tail at x = 0, head gripping, with a small random initial actuation
    kappa# = -max_curvature * U(0, reset_noise_scale) per control point, settled to equilibrium.
    `reset(options={"kappa": (n,) [1/m], "x_tail": m})` overrides.

    ## Episode End
    Truncation after `max_episode_steps` steps. Termination when Newton-Raphson fails even after
    step halving (info["numerical_failure"] = True); render() then draws the last finite state.
    The physics is translation invariant to round-off at any distance crawled (local
    coordinates re-centred on the tail, see `mf_envs.physics.inchworm`).

    ## Arguments
    | Argument | Default | Meaning |
    |----------|---------|---------|
    | length | 0.3 | body length L [m] (our choice; seed section below) |
    | width, height | 0.02, 0.01 | cross-section b, h [m] |
    | youngs_modulus, shear_modulus | 2.4e9, 0.96e9 | E, G [Pa] |
    | mass_per_length | 0.278 | m_A [kg/m] (J_3C from m_A h^2 / 12) |
    | n_elements | 12 | C1 elements |
    | max_curvature | 13.0 | largest abs(kappa#) [1/m] (the seed's kappa0#) |
    | n_control_points | 3 | actuation control points |
    | control_dt, physics_dt | 0.1, 0.1 | s per step; Newmark step with `inertia` |
    | max_episode_steps | 400 | 10 seed gait cycles |
    | effort_weight | 0.05 | weight of the effort term |
    | increment_factor | 4.0 | increments up to factor * 2h/L^2 (seed: 1; same equilibria) |
    | reset_noise_scale | 0.05 | initial actuation noise |
    | soil | "dry_sand" | soil preset for `terrain` (Wong 2008 Table 2.3 values) |
    | effects | gravity, shear_deformation, anchor_switching | also: inertia, terrain |

    ## Version History
    * v0: initial release (kinematic anchoring of Eq. 102; quasi-static by default).
    """

    metadata = {"render_modes": ["rgb_array", "human"], "render_fps": 10}

    def __init__(
        self,
        length: float = 0.3,
        width: float = 0.02,
        height: float = 0.01,
        youngs_modulus: float = 2.4e9,
        shear_modulus: float = 0.96e9,
        mass_per_length: float = 0.278,
        n_elements: int = 12,
        max_curvature: float = 13.0,
        effects: Any = None,
        n_control_points: int = 3,
        control_dt: float = 0.1,
        physics_dt: float = 0.1,
        max_episode_steps: int = 400,
        effort_weight: float = 0.05,
        increment_factor: float = 4.0,
        reset_noise_scale: float = 0.05,
        soil: str = "dry_sand",
        render_mode: str | None = None,
    ) -> None:
        super().__init__(
            effects=effects,
            available_effects=INCHWORM_EFFECTS,
            default_effects=DEFAULT_EFFECTS,
            control_dt=control_dt,
            physics_dt=physics_dt,
            render_mode=render_mode,
        )
        check_positive("max_curvature", max_curvature)
        check_nonnegative("effort_weight", effort_weight)
        check_nonnegative("reset_noise_scale", reset_noise_scale)
        self.n_ctrl = check_int("n_control_points", n_control_points, low=2, high=64)
        self.max_episode_steps = check_int("max_episode_steps", max_episode_steps, low=1)
        self.max_curvature = float(max_curvature)
        self.effort_weight = float(effort_weight)
        self.reset_noise_scale = float(reset_noise_scale)
        self.params = dataclasses.replace(
            InchwormParams(),
            length=float(length),
            width=float(width),
            height=float(height),
            youngs_modulus=float(youngs_modulus),
            shear_modulus=float(shear_modulus),
            mass_per_length=float(mass_per_length),
            rotary_inertia=float(mass_per_length) * float(height) ** 2 / 12.0,
            n_elements=check_int("n_elements", n_elements, low=1, high=1000),
        )
        self.sim = Inchworm(self.params, self.effects, increment_factor=increment_factor, soil=soil)
        self.S_ctrl = np.linspace(0.0, self.params.length, self.n_ctrl)
        self.switching = "anchor_switching" in self.effects
        n_act = self.n_ctrl + (1 if self.switching else 0)
        self.action_space = spaces.Box(-1.0, 1.0, (n_act,), np.float32)
        hi = np.concatenate(
            [
                np.full(self.n_ctrl, CURVATURE_OBS_LIMIT),
                np.ones(self.n_ctrl),
                [2 * np.pi, 2 * np.pi, 1.5, 1.0, REACTION_OBS_LIMIT, REACTION_OBS_LIMIT],
            ]
        ).astype(np.float32)
        self.observation_space = spaces.Box(-hi, hi, dtype=np.float32)
        self._weight = self.params.mass_per_length * self.params.gravity * self.params.length
        self._kappa_ctrl = np.zeros(self.n_ctrl)
        self._steps = 0
        self._frame_state: dict[str, Any] | None = None  # last finite state, for render()

    # ------------------------------------------------------------------ API
    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        a = self._validate_action(action)
        kappa_new = -self.max_curvature * 0.5 * (a[: self.n_ctrl] + 1.0)
        anchor = None
        if self.switching:
            anchor = "head" if a[-1] > 0.0 else "tail"
        x_tail_old, kappa_old = self.sim.x_tail, self._kappa_ctrl
        ok, report = True, None
        try:
            report = self.sim.actuate(
                kappa_at_gauss(self.S_ctrl, kappa_new, self.sim.model.gauss_S),
                dt=self.control_dt,
                anchor=anchor,
                min_increments=self.n_substeps if "inertia" in self.effects else 1,
            )
            self._kappa_ctrl = kappa_new
        except NewtonDivergence:
            ok = False
        self._steps += 1
        reward, terms = self._get_rew(x_tail_old, kappa_old, kappa_new)
        obs = self._get_obs() if ok else np.full(self.observation_space.shape, np.nan)
        info = self._get_info(terms, report)
        if ok:
            self._remember_frame(info)
        truncated = self._steps >= self.max_episode_steps
        return self._finish_step(obs, reward, False, truncated, info, ok)

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[np.ndarray, dict[str, Any]]:
        super().reset(seed=seed)
        options = options or {}
        kappa = -self.max_curvature * self.np_random.uniform(
            0.0, self.reset_noise_scale, self.n_ctrl
        )
        if "kappa" in options:
            kappa = np.asarray(options["kappa"], float).reshape(self.n_ctrl)
            if not np.all(np.isfinite(kappa)) or np.any(np.abs(kappa) > self.max_curvature):
                raise ValueError("options['kappa']: must be finite and within max_curvature")
        self.sim.reset(x_tail=float(check_finite("options['x_tail']", options.get("x_tail", 0.0))))
        self.sim.actuate(kappa_at_gauss(self.S_ctrl, kappa, self.sim.model.gauss_S), anchor="head")
        self._kappa_ctrl = kappa
        self._steps = 0
        info = self._get_info({"progress": 0.0, "effort": 0.0}, None)
        self._frame_state = None
        self._remember_frame(info)
        return self._finish_reset(self._get_obs()), info

    # ------------------------------------------------------------------ helpers
    def _get_obs(self) -> np.ndarray:
        sim, L = self.sim, self.params.length
        psi_t, psi_h = sim.end_angles()
        r_t, r_h = sim.support_reactions()
        return np.concatenate(
            [
                sim.curvature_at(self.S_ctrl) * L,
                self._kappa_ctrl / self.max_curvature,
                [
                    psi_t,
                    psi_h,
                    (sim.x_head - sim.x_tail) / L,
                    1.0 if sim.anchor == "head" else -1.0,
                ],
                [r_t / self._weight, r_h / self._weight],
            ]
        ).astype(np.float32)

    def _get_rew(
        self, x_tail_old: float, kappa_old: np.ndarray, kappa_new: np.ndarray
    ) -> tuple[float, dict[str, float]]:
        progress = (self.sim.x_tail - x_tail_old) / self.params.length
        rate = (kappa_new - kappa_old) / self.max_curvature
        effort = -self.effort_weight * float(np.mean(rate**2))
        return progress + effort, {"progress": float(progress), "effort": effort}

    def _get_info(self, terms: dict[str, float], report: Any) -> dict[str, Any]:
        sim = self.sim
        info: dict[str, Any] = {
            "x_head": sim.x_head,
            "x_tail": sim.x_tail,
            "centerline": sim.centerline(),
            "anchor": sim.anchor,
            "kappa_sharp": self._kappa_ctrl.copy(),
            "elastic_energy": sim.elastic_energy(),
            "newton_iterations": 0 if report is None else report.iterations,
            "increments": 0 if report is None else report.increments,
        }
        info["reward_terms"] = terms  # the convention shared by every env: terms sum to reward
        return info

    # ------------------------------------------------------------------ rendering
    def _remember_frame(self, info: dict[str, Any]) -> None:
        """Keep the drawable state if it is finite (after a numerical failure the physics state
        may be NaN; render() then shows the last finite one)."""
        keys = ("centerline", "x_head", "x_tail")
        if all(np.all(np.isfinite(info[k])) for k in keys):
            self._frame_state = {k: info[k] for k in (*keys, "anchor")}
            self._frame_state["step"] = self._steps

    def _draw_frame(self) -> np.ndarray:
        from mf_envs.render import draw_inchworm

        if self._frame_state is None:  # before the first reset: the constructed state
            sim = self.sim
            info = {"centerline": sim.centerline(), "x_head": sim.x_head, "x_tail": sim.x_tail}
            self._remember_frame({**info, "anchor": sim.anchor})
        fs = self._frame_state
        note = "" if fs["step"] == self._steps else "  (last finite state)"
        return draw_inchworm(
            centerline=fs["centerline"],
            x_head=fs["x_head"],
            x_tail=fs["x_tail"],
            text=f"step {fs['step']}  tail x = {fs['x_tail']:+.3f} m  grip: {fs['anchor']}{note}",
        )
