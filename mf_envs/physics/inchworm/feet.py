"""Feet that grip by friction: the inchworm's `friction` effect (Rios 2017 §4.5 III, §4.10).

The seed's scene holds the gripping foot kinematically (Eq. 102: its x-velocity is zero) and lets
the other slide without friction. Here both end nodes (tail S = 0, head S = L) rest on the ground
(z2 = 0, Eq. 100a, the vertical reaction N >= 0 is the foot's normal load, i.e. its share of the
weight) and are held in x only by dry (Coulomb) friction:

* engagement g in [0, 1] of each foot (0 released: the smooth PDMS face of the seed's robot,
  1 gripping: its rough PI film) follows the command g_c in {0, 1} with first-order dynamics,
  dg/dt = (g_c - g) / tau_g (tau_g = engage or release time constant), solved exactly; so
  |dg/dt| <= 1 / tau_g at all times: gripping and releasing take time;
* friction coefficient, anisotropic (different for slipping forward, +x, and backward, -x, like
  the directional hooks of a caterpillar's prolegs):
  mu(g, s) = mu_slide(s) + g (mu_grip(s) - mu_slide(s)), s = +1 forward, -1 backward;
* holding limit F_hold = mu(g, s) N (Coulomb, equal static and kinetic coefficients), N the
  normal load at the foot. A foot sticks (its x held) while the ground force R_x it needs stays
  within the limit for the direction it is pulled in (s = -sign R_x); when |R_x| would exceed
  it, the foot slips in the direction s with the ground force R_x = -s F_hold.

Quasi-static active set (hand-written; no library solves stick-slip on this beam): each
actuation increment is first solved with both feet stuck; if a foot's force exceeds its
holding limit, the onset lambda* inside the increment is located by regula falsi on the stuck
solutions (so slip begins exactly where |R_x| = F_hold), and the rest of the increment is solved
with that foot free under its friction force (a dead load, refreshed once with the normal load
at the end). With only the two feet carrying horizontal forces (gravity is vertical and the feet
sit on the line z = 0, so the friction forces do not change N), the ground forces on the feet are
equal and opposite, so at most one foot slips: the one whose limit is exceeded first.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mf_envs._validate import check_nonnegative, check_positive
from mf_envs.physics.beam import BeamModel, NewtonSettings, PathStats, solve_static_path

FORWARD, BACKWARD = 1, -1
TIE_TOLERANCE = 1e-2  # accepted relative excess of the other foot in a near tie


class NoQuasiStaticEquilibrium(RuntimeError):
    """Both feet would slip: the quasi-static model has no equilibrium (the body would
    accelerate)."""


@dataclass(frozen=True)
class FrictionParams:
    """Coulomb coefficients (dimensionless) of a gripping (g = 1) and a released (g = 0) foot for
    slipping forward (+x) and backward (-x); engage/release time constants [s].

    Defaults (our choice, order of magnitude of polymer films on a dry surface): gripping foot
    0.6 forward / 1.0 backward (a directional pad that resists being pushed back), released
    smooth foot 0.1 / 0.15. Time constants 0.2 s: the seed's robot switches feet by warping the
    foot sections with transverse SMA wires, the same ~1 s-class wires as the body (3 tau ~ the
    0.5-1 s wire response, see `actuators`).
    """

    grip_forward: float = 0.6
    grip_backward: float = 1.0
    slide_forward: float = 0.1
    slide_backward: float = 0.15
    engage_time: float = 0.2
    release_time: float = 0.2

    def __post_init__(self) -> None:
        for name in ("grip_forward", "grip_backward", "slide_forward", "slide_backward"):
            check_nonnegative(f"friction_coefficients['{name}']", getattr(self, name))
        check_positive("grip_time_constant", self.engage_time)
        check_positive("grip_time_constant", self.release_time)

    def mu(self, g: float, direction: int) -> float:
        """Friction coefficient of a foot with engagement g slipping in `direction` (+1/-1)."""
        if direction == FORWARD:
            return self.slide_forward + g * (self.grip_forward - self.slide_forward)
        return self.slide_backward + g * (self.grip_backward - self.slide_backward)

    def holding_limit(self, g: float, direction: int, normal: float) -> float:
        """F_hold = mu(g, direction) max(N, 0) [N] (normal load N [N], positive pressing)."""
        return self.mu(g, direction) * max(float(normal), 0.0)


def grip_response(g: np.ndarray, command: np.ndarray, t, params: FrictionParams) -> np.ndarray:
    """Exact engagement at time t [s] (broadcasts) from g under the held command (0/1)."""
    g, command = np.asarray(g, float), np.asarray(command, float)
    tau = np.where(command > g, params.engage_time, params.release_time)
    return command + (g - command) * np.exp(-np.asarray(t, float) / tau)


@dataclass
class FootReport:
    """One actuation step: slip (2,) [m] x-slip of tail, head; friction_work [J] (<= 0);
    ground_x, normal (2,) [N] at the end; slipping (2,) direction 0 / +1 / -1 at the end."""

    slip: np.ndarray = field(default_factory=lambda: np.zeros(2))
    friction_work: float = 0.0
    ground_x: np.ndarray = field(default_factory=lambda: np.zeros(2))
    normal: np.ndarray = field(default_factory=lambda: np.zeros(2))
    slipping: np.ndarray = field(default_factory=lambda: np.zeros(2, int))
    onsets: list[float] = field(default_factory=list)  # lambda* of each slip onset
    iterations: int = 0  # Newton iterations of all the solves


class FrictionFeet:
    """Tail and head feet of `model` holding by friction (module docstring)."""

    def __init__(
        self, model: BeamModel, params: FrictionParams, settings: NewtonSettings | None = None
    ) -> None:
        self.model, self.params = model, params
        self.settings = settings or NewtonSettings(1e-9, 1e-9, 8, 12)
        self.nodes = (0, model.n_elements)
        self.x_dofs = np.array([model.dof(n, "z1") for n in self.nodes])
        self.z_dofs = np.array([model.dof(n, "z2") for n in self.nodes])
        self.reset()

    def reset(self, engagement: tuple[float, float] = (0.0, 1.0)) -> None:
        """Feet at rest, stuck; engagement (tail, head) in [0, 1]."""
        self.g = np.clip(np.asarray(engagement, float), 0.0, 1.0)
        self.slipping = np.zeros(2, int)
        self.iterations = 0

    # ------------------------------------------------------------------ forces
    def fixed_mask(self, stuck: np.ndarray) -> np.ndarray:
        """Prescribed dofs: z2 of both feet (Eq. 100a) and x of the stuck feet."""
        fixed = np.zeros(self.model.n_dof, bool)
        fixed[self.z_dofs] = True
        fixed[self.x_dofs[np.asarray(stuck, bool)]] = True
        return fixed

    def ground_forces(
        self, d: np.ndarray, kappa: np.ndarray, f_ext: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """(R_x (2,), N (2,)) [N]: ground forces on the feet in x and z (N up = normal load):
        the residual P(d) - F_ext at their dofs (f_ext includes any friction load applied)."""
        f_int, _ = self.model.internal(d, kappa, tangent=False)
        r = f_int - f_ext
        return r[self.x_dofs], r[self.z_dofs]

    def excess(self, rx: np.ndarray, n: np.ndarray, g: np.ndarray) -> np.ndarray:
        """|R_x| - F_hold per foot [N], for the direction each foot is pulled in."""
        s = np.where(rx > 0.0, BACKWARD, FORWARD)  # the ground pushes +x: the foot is pulled -x
        lim = [self.params.holding_limit(g[i], s[i], n[i]) for i in range(2)]
        return np.abs(rx) - np.array(lim)

    # ------------------------------------------------------------------ solves
    def _path(self, d, k0, k1, f_ext, stuck, lam0=0.0, lam1=1.0, f_fric=None):
        """Quasi-static solve along kappa# = k0 + lam (k1 - k0), lam from lam0 to lam1, with the
        stuck feet held and the friction load f_fric = (start, end) (n_dof,) on the others."""
        fixed = self.fixed_mask(stuck)
        zero = np.zeros(self.model.n_dof)
        fa, fb = f_fric if f_fric is not None else (zero, zero)

        def load_at(mu: float):
            lam = lam0 + mu * (lam1 - lam0)
            return k0 + lam * (k1 - k0), f_ext + fa + mu * (fb - fa)

        stats = PathStats()
        out = solve_static_path(self.model, d, load_at, fixed, self.settings, stats=stats)
        self.iterations += stats.iterations
        return out

    def _pull_excess(self, rx: float, n: float, g: float, s: int) -> float:
        """-s R_x - F_hold(s) [N] of a foot pulled towards s (+1/-1): > 0 once it would slip."""
        return -s * rx - self.params.holding_limit(g, s, n)

    def _friction_load(self, i: int, s: int, g: float, normal: float) -> np.ndarray:
        """Nodal load (n_dof,) of the ground on foot i slipping towards s: -s F_hold(s)."""
        f = np.zeros(self.model.n_dof)
        f[self.x_dofs[i]] = -s * self.params.holding_limit(g, s, normal)
        return f

    def _onset(self, d, k0, k1, f_ext, g0, g1, i, s, e1) -> tuple[float, np.ndarray]:
        """lambda* in [0, 1] where foot i, pulled towards s, reaches its holding limit on the
        stuck path (regula falsi on the pull excess, which is < 0 at the start unless the foot
        already slips that way, and e1 > 0 at lambda = 1)."""
        both = np.ones(2, bool)
        rx, n = self.ground_forces(d, k0, f_ext)
        lo, e_lo, hi, e_hi = 0.0, self._pull_excess(rx[i], n[i], g0[i], s), 1.0, e1
        if self.slipping[i] == s or e_lo >= 0.0:
            return 0.0, d
        d_lo, best = d, (abs(e_lo), 0.0, d)
        for _ in range(30):
            lam = lo + (hi - lo) * e_lo / (e_lo - e_hi)
            lam = min(max(lam, lo + 1e-3 * (hi - lo)), hi - 1e-3 * (hi - lo))
            dl = self._path(d_lo, k0, k1, f_ext, both, lo, lam)
            rx, n = self.ground_forces(dl, k0 + lam * (k1 - k0), f_ext)
            e = self._pull_excess(rx[i], n[i], g0[i] + lam * (g1[i] - g0[i]), s)
            best = min(best, (abs(e), lam, dl), key=lambda b: b[0])
            if e <= 0.0:
                lo, e_lo, d_lo = lam, e, dl
            else:
                hi, e_hi = lam, e
            if abs(e) < 1e-9 * max(abs(n[i]), 1e-12) or hi - lo < 1e-12:
                break
        return best[1], best[2]

    def _slip(self, i, s, lam, d_star, k0, k1, f_ext, g0, g1, n_trial):
        """Foot i slips towards s from lambda to 1, the other stuck: (d1, R_x, N, fa, fb,
        violation of the other foot's limit [N])."""
        stuck = np.ones(2, bool)
        stuck[i] = False
        _, n0 = self.ground_forces(d_star, k0 + lam * (k1 - k0), f_ext)
        fa = self._friction_load(i, s, g0[i] + lam * (g1[i] - g0[i]), n0[i])
        fb = self._friction_load(i, s, g1[i], n_trial)
        d1 = self._path(d_star, k0, k1, f_ext, stuck, lam, 1.0, (fa, fb))
        rx1, n1 = self.ground_forces(d1, k1, f_ext + fb)
        if abs(n1[i] - n_trial) > 1e-9 * max(abs(n_trial), 1e-12):  # refresh N at the end once
            fb = self._friction_load(i, s, g1[i], n1[i])
            d1 = self._path(d_star, k0, k1, f_ext, stuck, lam, 1.0, (fa, fb))
            rx1, n1 = self.ground_forces(d1, k1, f_ext + fb)
        rx1[i] = fb[self.x_dofs[i]]  # the ground force on the slipping foot is the friction
        j = 1 - i
        return d1, rx1, n1, fa, fb, float(self.excess(rx1, n1, g1)[j])

    def increment(
        self,
        d: np.ndarray,
        k0: np.ndarray,
        k1: np.ndarray,
        f_ext: np.ndarray,
        g0: np.ndarray,
        g1: np.ndarray,
        report: FootReport,
    ) -> np.ndarray:
        """One actuation increment kappa# k0 -> k1 (n_el, 4) [1/m] with the engagements g0 -> g1
        (2,) (linear in between); d converged at k0. Returns d at k1; accumulates `report`.

        Stick if both stuck forces stay within their limits; else each foot over its limit is a
        candidate, the one whose onset comes first slips (the other's force must then stay
        within its limit, else the next candidate). Near a tie (both feet at their limits,
        where a quasi-static body has no unique answer) the smaller violation is accepted if
        it is below TIE_TOLERANCE of the limit; beyond: NoQuasiStaticEquilibrium."""
        both = np.ones(2, bool)
        trial = self._path(d, k0, k1, f_ext, both)
        rx, n = self.ground_forces(trial, k1, f_ext)
        e = self.excess(rx, n, g1)
        if np.all(e <= 0.0):
            self.slipping[:] = 0
            self._finish(report, rx, n)
            return trial
        pulls = np.where(rx > 0.0, BACKWARD, FORWARD)
        found = []
        for i in np.flatnonzero(e > 0.0):
            lam, d_star = self._onset(d, k0, k1, f_ext, g0, g1, i, pulls[i], float(e[i]))
            found.append((lam, int(i), d_star))
        best = None
        for lam, i, d_star in sorted(found, key=lambda c: c[0]):
            out = self._slip(i, pulls[i], lam, d_star, k0, k1, f_ext, g0, g1, n[i])
            limit = abs(out[1][1 - i]) - out[5]
            if best is None or out[5] / max(limit, 1e-300) < best[0]:
                best = (out[5] / max(limit, 1e-300), lam, i, d_star, out)
            if out[5] <= 1e-9 * max(abs(out[2][1 - i]), 1e-12):
                break
        rel, lam, i, d_star, (d1, rx1, n1, fa, fb, _) = best
        if rel > TIE_TOLERANCE:
            raise NoQuasiStaticEquilibrium("both feet exceed their holding limits")
        if self.slipping[i] != pulls[i]:
            report.onsets.append(lam)
        dx = d1[self.x_dofs[i]] - d_star[self.x_dofs[i]]
        report.slip[i] += dx
        report.friction_work += 0.5 * (fa[self.x_dofs[i]] + fb[self.x_dofs[i]]) * dx
        self.slipping[:] = 0
        self.slipping[i] = pulls[i]
        self._finish(report, rx1, n1)
        return d1

    def step(
        self,
        d: np.ndarray,
        kappas: list[np.ndarray],
        f_ext: np.ndarray,
        command: np.ndarray,
        dt: float,
    ) -> tuple[list[np.ndarray], FootReport]:
        """Increments kappas[0] -> kappas[1] -> ... (each (n_el, 4) [1/m]) over dt [s] in equal
        time substeps while the engagements follow `command` (2,) (0 release, 1 grip) exactly.
        Returns the configurations at the end of every increment and the step's report."""
        n = len(kappas) - 1
        times = dt * np.arange(n + 1)[:, None] / n
        gs = grip_response(self.g, np.asarray(command, float), times, self.params)
        report, out = FootReport(), []
        self.iterations = 0
        for j in range(n):
            d = self.increment(d, kappas[j], kappas[j + 1], f_ext, gs[j], gs[j + 1], report)
            out.append(d)
        self.g = gs[-1].copy()
        report.iterations = self.iterations
        return out, report

    def _finish(self, report: FootReport, rx: np.ndarray, n: np.ndarray) -> None:
        report.ground_x, report.normal = rx.copy(), n.copy()
        report.slipping = self.slipping.copy()
