"""The control step, step info, centreline and frame shared by the planar beam robots on a
distributed load (`Serpentine-v0` on the ground, `Eel-v0` in water). Each env provides its
compiled row step (`_advance`), its heading (`_heading`) and its drawing (`_draw`); the rows
report into `rep` by the slots below (`envs.serpentine.rows`, `envs.eel.rows`)."""

from __future__ import annotations

import math
from abc import ABCMeta, abstractmethod
from typing import Any

import numpy as np

from mf_envs.envs.serpentine import spec

REP_OK, REP_ENERGY, REP_ITER, REP_X0, REP_Y0, REP_NET = range(6)


class BeamRobotMixin(metaclass=ABCMeta):
    """`step`, `_info`, `centerline` and `_draw_frame` of a beam robot (put before `MFEnv`); an
    env that lacks one of the three hooks below cannot be instantiated (TypeError)."""

    @abstractmethod
    def _advance(self, action: np.ndarray, rep: np.ndarray) -> None:
        """One control step of the robot's compiled row with the validated action, reporting
        into rep by the REP_* slots."""

    @abstractmethod
    def _heading(self) -> float:
        """The body's heading (rad)."""

    @abstractmethod
    def _draw(self, line: np.ndarray, text: str) -> np.ndarray:
        """The rgb frame of the centreline `line` (N, 2) with the caption `text`."""

    def step(self, action: Any) -> tuple[np.ndarray, float, bool, bool, dict[str, Any]]:
        a = self._validate_action(action)
        rep = self._rep
        self._advance(a, rep)
        self._steps += 1
        ok = rep[REP_OK] > 0.0 and bool(np.isfinite(self.state).all())
        dx = self._body[0] - rep[REP_X0], self._body[1] - rep[REP_Y0]
        c, s = math.cos(self.target_direction), math.sin(self.target_direction)
        along = c * dx[0] + s * dx[1]
        energy = float(rep[REP_ENERGY])
        terms = {"progress": along / self.scene.length, "effort": -self.effort_weight * energy}
        info = self._info(along / self.control_dt, energy, int(rep[REP_ITER]), terms)
        info["actuation_net_work"] = float(rep[REP_NET])
        if ok:
            self._track.append((self._body[0], self._body[1]))
        reward = terms["progress"] + terms["effort"]
        trunc = self._steps >= self.max_steps
        return self._finish_step(self._obs.copy(), reward, False, trunc, info, ok)

    def _info(self, speed: float, energy: float, its: int, terms: dict) -> dict[str, Any]:
        return spec.step_info(
            float(self._body[0]), float(self._body[1]), self._heading(), float(speed),
            self.cmd.copy(), energy, 0.0, self.control_dt, its,
            self._steps * self.control_dt, terms,
        )  # fmt: skip

    def centerline(self, per_element: int = 8) -> np.ndarray:
        """(N, 2) points of the body's centreline [m], tail to head."""
        return self.model.centerline(self.state[0], per_element)

    def _draw_frame(self) -> np.ndarray:
        line = self.centerline()
        if not np.isfinite(line).all():  # after a numerical failure: the last finite track
            line = np.array([self._track[-1], self._track[-1]]) + [[0.0, 0.0], [1e-9, 0.0]]
        x, y = self._track[-1] if self._track else (0.0, 0.0)
        text = f"t = {self._steps * self.control_dt:.2f} s  com ({x:+.3f}, {y:+.3f}) m"
        return self._draw(line, text)
