"""A beam on two feet that grip by friction: its tail (S = 0) and head (S = L) end nodes
(Rios 2017 §4.5 III, §4.10; the inchworm's `friction` effect).

The seed's scene holds the gripping foot kinematically (Eq. 102: its x-velocity is zero) and lets
the other slide without friction. Here both end nodes rest on the ground (z2 = 0, Eq. 100a, the
vertical reaction N >= 0 is the foot's normal load, i.e. its share of the weight) and are held
in x only by dry (Coulomb) friction with the law of `friction` (anisotropic coefficients,
engagement dynamics, holding limit F_hold = mu(g, s) N). A foot sticks (its x held) while the
ground force R_x it needs stays within the limit for the direction it is pulled in
(s = -sign R_x); when |R_x| would exceed it, the foot slips in the direction s with the ground
force R_x = -s F_hold. (Engagement 0: the smooth PDMS face of the seed's robot, 1: its rough PI
film.)

Quasi-static active set (hand-written; no library solves stick-slip on this beam): each
actuation increment is first solved with both feet stuck; if a foot's force exceeds its
holding limit, the onset lambda* inside the increment is located on the stuck path where
|R_x| = F_hold exactly: Newton on the stuck configuration and lambda together (the equilibrium
bordered by the onset condition, from regula falsi's first point), with regula falsi (Illinois)
on stuck solutions as the fallback (`stick_slip._onset`), and the rest of the increment
is solved with that foot free under its friction force (a dead load, refreshed once with the
normal load at the end). With only the two feet carrying horizontal forces (gravity is vertical
and the feet sit on the line z = 0, so the friction forces do not change N), the ground forces on
the feet are equal and opposite, so at most one foot slips: the one whose limit is exceeded
first. The compiled form is `stick_slip`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mf_envs.physics.beam import BeamModel, NewtonDivergence, NewtonSettings, static
from mf_envs.physics.beam.contact import friction
from mf_envs.physics.beam.contact import stick_slip as ss
from mf_envs.physics.beam.contact.friction import FrictionParams


class NoQuasiStaticEquilibrium(RuntimeError):
    """Both feet would slip: the quasi-static model has no equilibrium (the body would
    accelerate)."""


def grip_response(g: np.ndarray, command: np.ndarray, t, params: FrictionParams) -> np.ndarray:
    """Exact engagement (2,) of both feet at time t [s] from g (2,) under the held command
    (2,) (0/1); times t of shape (m,) or (m, 1) give (m, 2)."""
    g, command = np.asarray(g, float), np.asarray(command, float)
    t = np.asarray(t, float)
    out = np.empty((t.size, 2))
    for k, tk in enumerate(t.reshape(-1)):
        friction.grip_response(g, command, tk, params.engage_time, params.release_time, out[k])
    return out[0] if t.ndim == 0 else out


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
    """Tail and head feet of `model` holding by friction (module docstring); the increments
    run in the compiled `stick_slip` kernels."""

    def __init__(
        self, model: BeamModel, params: FrictionParams, settings: NewtonSettings | None = None
    ) -> None:
        self.model, self.params = model, params
        self.settings = settings or NewtonSettings(1e-9, 1e-9, 8, 12)
        self.nodes = (0, model.n_elements)
        self.x_dofs = np.array([model.dof(n, "z1") for n in self.nodes])
        self.z_dofs = np.array([model.dof(n, "z2") for n in self.nodes])
        self.scratch = ss.scratch(model.n_elements)
        self.reset()

    def reset(self, engagement: tuple[float, float] = (0.0, 1.0)) -> None:
        """Feet at rest, stuck; engagement (tail, head) in [0, 1]."""
        self.g = np.clip(np.asarray(engagement, float), 0.0, 1.0)
        self.slipping = np.zeros(2, np.int64)
        self.iterations = 0

    def kernel_args(self) -> tuple:
        """(x dofs, z dofs, coefficients, engage, release): the feet of `stick_slip`."""
        p = self.params
        return (self.x_dofs, self.z_dofs, p.coefficients, p.engage_time, p.release_time)

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
        Returns the configurations at the end of every increment and the step's report.
        Raises NewtonDivergence or NoQuasiStaticEquilibrium."""
        kg = np.ascontiguousarray(np.array(kappas, float))
        n = kg.shape[0] - 1
        times = dt * np.arange(n + 1)[:, None] / n
        gs = grip_response(self.g, np.asarray(command, float), times, self.params)
        rep = np.zeros(ss.N_REPORT + n)
        ds = np.empty((n, self.model.n_dof))
        bc = static.constants(self.model, self.settings)
        xd, zd, mu4 = self.kernel_args()[:3]
        status = ss.feet_step(
            np.asarray(d, float),
            kg,
            f_ext,
            gs,
            self.slipping,
            xd,
            zd,
            mu4,
            bc,
            self.scratch,
            rep,
            ds,
        )
        raise_status(status)
        self.g = gs[-1].copy()
        self.iterations = int(rep[ss.REP_ITER])
        return list(ds), foot_report(rep)


def foot_report(rep: np.ndarray) -> FootReport:
    """The FootReport of a `stick_slip` report array."""
    n_on = int(rep[ss.REP_ONSETS])
    return FootReport(
        slip=rep[ss.REP_SLIP : ss.REP_SLIP + 2].copy(),
        friction_work=float(rep[ss.REP_FWORK]),
        ground_x=rep[ss.REP_GX : ss.REP_GX + 2].copy(),
        normal=rep[ss.REP_N : ss.REP_N + 2].copy(),
        slipping=rep[ss.REP_SLIPPING : ss.REP_SLIPPING + 2].astype(int),
        onsets=[float(x) for x in rep[ss.N_REPORT : ss.N_REPORT + n_on]],
        iterations=int(rep[ss.REP_ITER]),
    )


def raise_status(status: int) -> None:
    """The exception of a `stick_slip` status code (none for OK)."""
    if status == ss.NEWTON_FAILED:
        raise NewtonDivergence("Newton failed even after step halving")
    if status == ss.NO_EQUILIBRIUM:
        raise NoQuasiStaticEquilibrium("both feet exceed their holding limits")
