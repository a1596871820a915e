"""The inchworm driven through its actuators and feet: one control step of the robot.

`DrivenInchworm` wraps an `Inchworm` (the active beam, Rios 2017 §4.10) with
* the curvature actuator of `mf_envs.physics.actuators` (effect `actuator_dynamics`): the
  commanded curvature at the control points reaches the beam through the rate-limited lag
  (A1); without it kappa# moves linearly from the old to the new command over the step (the
  seed's prescription);
* the friction feet of `mf_envs.physics.beam.contact.feet` (effect `friction`): the grip command
  engages one foot and releases the other, each holds by Coulomb friction; without it the
  seed's kinematic anchors of Eq. 102.
Each control step is split into substeps of equal time such that no control point's kappa#
changes by more than the increment limit in a substep (the lag is monotone within a step, so
the largest rate is the initial one); each substep is one quasi-static increment whose
actuation work is the trapezoid of (A2) (`curvature.increment_work`), accumulated by an
`EnergyMeter` (no regeneration). Quasi-static with `friction` (Coulomb friction in Newmark
dynamics would need a regularised or event-driven contact, not built).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from mf_envs.physics.actuators.curvature import (
    ActuatorParams,
    EnergyMeter,
    RateLimitedLag,
    increment_work,
    kappa_at_gauss,
)
from mf_envs.physics.beam import NewmarkState, NewtonDivergence, static
from mf_envs.physics.beam.contact import grip_feet as gf
from mf_envs.physics.beam.contact import stick_slip as ss
from mf_envs.physics.beam.contact.feet import (
    FootReport,
    FrictionFeet,
    foot_report,
    raise_status,
)
from mf_envs.physics.beam.contact.friction import FrictionParams
from mf_envs.physics.beam.contact.grip import GripFeetParams
from mf_envs.physics.inchworm import quasistatic as qs
from mf_envs.physics.inchworm.model import Inchworm, InchwormParams
from mf_envs.physics.inchworm.wires import SMAWires

DRIVE_EFFECTS = {
    "actuator_dynamics": "actuator lag + rate limit on kappa# (off = kappa# as commanded)",
    "friction": "feet holding by anisotropic Coulomb friction with grip dynamics (off = the "
    "kinematic anchors of Eq. 102; implies the weight)",
    "sma_wires": "kappa# from SMA wire groups heated by a commanded duty cycle (Joule heating, "
    "still-air cooling, martensite fraction with hysteresis); the effort is electrical energy",
    "gripping_feet": "feet that anchor only above an engagement threshold, regularised friction "
    "(implies the weight)",
}
GRIP_COMMANDS = {"head": (0.0, 1.0), "tail": (1.0, 0.0), None: (1.0, 1.0)}  # (tail, head)


@dataclass
class DriveReport:
    """One control step: kappa_sharp (n,) realised at the control points [1/m]; energy [J]
    drawn by the actuators (positive work / efficiency; with `sma_wires` the electrical
    energy); net_work [J] (signed, A2); wire_work [J]: the positive work of the bending moment
    EI kappa# on the body (`kernels.wire_work`, with gripping feet); increments and Newton
    iterations; slip (2,) [m] of tail, head (friction); ground_x, normal (2,) [N] of the feet
    at the end (friction feet); feet: the friction feet's report (None otherwise);
    mechanical_work [J]: the actuator's positive mechanical work (wire_work with gripping
    feet, else the positive work of A2)."""

    kappa_sharp: np.ndarray
    energy: float = 0.0
    net_work: float = 0.0
    wire_work: float = 0.0
    mechanical_work: float = 0.0
    increments: int = 0
    iterations: int = 0
    slip: np.ndarray = field(default_factory=lambda: np.zeros(2))
    ground_x: np.ndarray = field(default_factory=lambda: np.zeros(2))
    normal: np.ndarray = field(default_factory=lambda: np.zeros(2))
    feet: FootReport | None = None


class DrivenInchworm:
    """An `Inchworm` whose kappa# and grip go through actuator and foot dynamics."""

    def __init__(
        self,
        sim: Inchworm,
        S_ctrl: np.ndarray,
        actuator: ActuatorParams | None = None,
        friction: FrictionParams | None = None,
        wires: SMAWires | None = None,
        grip_feet: GripFeetParams | None = None,
    ) -> None:
        if friction is not None and ("inertia" in sim.effects or sim.terrain is not None):
            raise ValueError("effects: 'friction' is quasi-static and excludes inertia, terrain")
        if grip_feet is not None and ("inertia" in sim.effects or sim.terrain is not None):
            raise ValueError(
                "effects: 'gripping_feet' is quasi-static and excludes inertia, terrain"
            )
        if grip_feet is not None and friction is not None:
            raise ValueError("effects: 'friction' and 'gripping_feet' are two foot models")
        if wires is not None and actuator is not None:
            raise ValueError("effects: 'actuator_dynamics' and 'sma_wires' are two actuators")
        self.sim, self.S_ctrl = sim, np.asarray(S_ctrl, float)
        self.actuator = actuator
        self.lag = RateLimitedLag(actuator, len(S_ctrl)) if actuator is not None else None
        self.feet = FrictionFeet(sim.model, friction, sim.settings) if friction else None
        self.meter = EnergyMeter(actuator.efficiency if actuator is not None else 1.0)
        self.kappa_ctrl = np.zeros(len(S_ctrl))
        self.wires, self.grip_feet = wires, grip_feet
        self.sma = wires.state_for(self.kappa_ctrl) if wires is not None else None
        self.g = np.array([0.0, 1.0])  # gripping feet's engagement (tail, head)
        self.v_feet = np.zeros(2)  # their velocities in the last increment [m/s] (predictor)
        self.electrical_energy = 0.0  # J, with sma_wires
        self.wire_work = 0.0  # J, positive work of EI kappa# on the body (gripping feet)
        if grip_feet is not None:
            model = sim.model
            nodes = (0, model.n_elements)
            self.foot_x = np.array([model.dof(n, "z1") for n in nodes])
            self.foot_z = np.array([model.dof(n, "z2") for n in nodes])
            self.grip_scratch = gf.scratch(model.n_elements)

    def reset(self, kappa_ctrl: np.ndarray, x_tail: float = 0.0) -> None:
        """Straight body at x_tail [m], actuated to kappa_ctrl (n,) [1/m] at rest with the head
        anchored (the seed's start); actuators at rest; head gripping, tail released."""
        self.sim.reset(x_tail=x_tail)
        self.sim.actuate(self._gauss(kappa_ctrl), anchor="head")
        self.kappa_ctrl = np.array(kappa_ctrl, float)
        if self.lag is not None:
            self.lag.reset(self.kappa_ctrl)
        if self.feet is not None:
            self.feet.reset(GRIP_COMMANDS["head"])
        if self.wires is not None:
            self.sma = self.wires.state_for(self.kappa_ctrl)
        self.g = np.array(GRIP_COMMANDS["head"], float)
        self.v_feet = np.zeros(2)
        self.electrical_energy = self.wire_work = 0.0
        self.meter = EnergyMeter(self.meter.efficiency)

    @property
    def grip(self) -> np.ndarray:
        """Engagement (tail, head) in [0, 1]: the feet's state with `friction`, else 1 for the
        kinematically anchored foot."""
        if self.feet is not None:
            return self.feet.g.copy()
        if self.grip_feet is not None:
            return self.g.copy()
        return np.array([self.sim.anchor == "tail", self.sim.anchor == "head"], float)

    @property
    def wire_temperature(self) -> np.ndarray:
        """Temperature [degC] of each control point's wire group (NaN without `sma_wires`)."""
        if self.sma is None:
            return np.full(len(self.S_ctrl), np.nan)
        return self.sma[qs.SMA_T].copy()

    def _gauss(self, kappa_ctrl: np.ndarray) -> np.ndarray:
        return kappa_at_gauss(self.S_ctrl, kappa_ctrl, self.sim.model.gauss_S)

    def _path(self, command: np.ndarray, dt: float, min_substeps: int) -> np.ndarray:
        """kappa# at the control points at the substep ends, (n_sub + 1, n) [1/m] (with
        `sma_wires` command is the duty cycle; the wires' state advances)."""
        limit = self.sim.increment_factor * self.sim.params.max_dkappa
        if self.wires is not None:
            thermal, tt, p_full, k_full, _gp = self.wires.kernel_args()
            end, work = np.empty(len(command)), self.sma.copy()
            qs.sma_advance(work, command, dt, thermal, tt, p_full, k_full, end)
            n = int(np.ceil(np.max(np.abs(end - self.kappa_ctrl)) / limit - 1e-12))
            n = max(n, min_substeps, 1)
            path = np.empty((n + 1, len(command)))
            path[0] = self.kappa_ctrl
            for j in range(1, n + 1):
                qs.sma_advance(self.sma, command, dt / n, thermal, tt, p_full, k_full, path[j])
            return path
        if self.lag is None:
            n = int(np.ceil(np.max(np.abs(command - self.kappa_ctrl)) / limit - 1e-12))
            n = max(n, min_substeps, 1)
            lam = np.linspace(0.0, 1.0, n + 1)[:, None]
            return self.kappa_ctrl + lam * (command - self.kappa_ctrl)
        rate0 = float(np.max(np.abs(self.lag.rate(self.lag.kappa, command))))
        n = max(1, min_substeps, int(np.ceil(rate0 * dt / limit - 1e-12)))
        path = self.lag.trajectory(command, np.linspace(0.0, dt, n + 1))
        path[0] = self.lag.kappa
        return path

    def step(
        self,
        command: np.ndarray,
        anchor: str | None,
        dt: float,
        min_substeps: int = 1,
        grip: np.ndarray | None = None,
    ) -> DriveReport:
        """Hold the commanded kappa# (n,) [1/m] (with `sma_wires`: the duty cycles (n,) in
        [0, 1]) and the grip (`anchor`: "head"/"tail" grips, None: both with friction, Eq. 102
        with kinematic anchors) for dt [s], in at least min_substeps substeps (e.g. the Newmark
        steps of `inertia`). With gripping feet `grip` (2,) in [0, 1] overrides the engagement
        command of `anchor` (the feet still follow it with their time constants).
        Raises NewtonDivergence / NoQuasiStaticEquilibrium when the physics fails."""
        command = np.asarray(command, float).reshape(self.kappa_ctrl.shape)
        if self.feet is not None:
            return self._frictional(command, anchor, dt, min_substeps)
        if self.grip_feet is not None:
            grip = GRIP_COMMANDS[anchor] if grip is None else grip
            return self._gripping(command, np.asarray(grip, float), dt, min_substeps, anchor)
        path = self._path(command, dt, min_substeps)
        gauss = [self._gauss(k) for k in path]
        n = len(path) - 1
        energy0, net0 = self.meter.input_energy, self.meter.net
        rep = DriveReport(kappa_sharp=path[-1].copy(), increments=n)
        rep.iterations = self._kinematic(gauss, anchor, dt)
        if self.lag is not None:
            self.lag.advance(command, dt)
        self.kappa_ctrl = path[-1].copy()
        rep.energy = self.meter.input_energy - energy0
        rep.net_work = self.meter.net - net0
        rep.mechanical_work = rep.energy * self.meter.efficiency
        if self.wires is not None:
            rep.energy = float(np.sum(command)) * self.wires.group_power * dt
            self.electrical_energy += rep.energy
        return rep

    def grip_kernel_args(self) -> tuple:
        """(act, feet, S_ctrl, gauss_S, f_ext, beam constants) of `quasistatic.grip_step`."""
        key = (self.sim.settings, self.sim.increment_factor)
        if getattr(self, "_grip_key", None) != key:
            self._grip_args, self._grip_key = self._grip_kernel_args(), key
        return self._grip_args

    def _grip_kernel_args(self) -> tuple:
        sim, lag, gp = self.sim, self.lag, self.grip_feet
        tau, rate = (lag.params.time_constant, lag.params.rate_limit) if lag else (1.0, 1.0)
        mode = qs.ACT_SMA if self.wires else (qs.ACT_LAG if lag else qs.ACT_DIRECT)
        if self.wires is not None:
            thermal, tt, p_full, k_full, group = self.wires.kernel_args()
        else:
            thermal, tt, p_full, k_full, group = (
                (1.0, 1.0, 0.0),
                (1.0, 2.0, 1.0, 0.0, 0.0),
                0.0,
                1.0,
                0.0,
            )
        limit = sim.increment_factor * sim.params.max_dkappa
        act = (mode, tau, rate, limit, sim.model.params.EI, thermal, tt, p_full, k_full, group)
        feet = (self.foot_x, self.foot_z, gp.law.kernel_args(), gp.engage_time, gp.release_time)
        bc = static.constants(sim.model, sim.settings)
        return act, feet, self.S_ctrl, sim.model.gauss_S, sim.f_ext, bc

    def _gripping(
        self, command: np.ndarray, grip: np.ndarray, dt: float, min_substeps: int, anchor
    ) -> DriveReport:
        """One step on gripping feet in the compiled `quasistatic.grip_step`."""
        sim = self.sim
        d = sim.state.d.copy()
        lag_k = self.lag.kappa if self.lag is not None else self.kappa_ctrl.copy()
        sma = self.sma if self.sma is not None else np.zeros((5, len(command)))
        feet = np.concatenate([self.g, self.v_feet])
        state = (d, lag_k, self.kappa_ctrl, feet, sma)
        rep = np.zeros(qs.N_GRIP_REPORT)
        status = qs.grip_step(
            state, command, grip, dt, min_substeps, *self.grip_kernel_args(),
            self.grip_scratch, rep,
        )  # fmt: skip
        if status != gf.OK:
            raise NewtonDivergence("Newton failed even after halving the increment")
        self.g, self.v_feet = feet[:2].copy(), feet[2:].copy()
        if self.lag is not None:
            self.lag.command = command.copy()
        self.meter.add_totals(rep[qs.REP_A2POS], rep[qs.REP_A2NET])
        out = DriveReport(kappa_sharp=self.kappa_ctrl.copy(), increments=int(rep[qs.REP_SUBSTEPS]))
        out.iterations = int(rep[gf.REP_ITER])
        out.slip = rep[gf.REP_SLIP : gf.REP_SLIP + 2].copy()
        out.ground_x = rep[gf.REP_GX : gf.REP_GX + 2].copy()
        out.normal = rep[gf.REP_N : gf.REP_N + 2].copy()
        out.net_work = float(rep[qs.REP_A2NET])
        out.wire_work = out.mechanical_work = float(rep[qs.REP_WIRE])
        self.wire_work += out.wire_work
        if self.wires is not None:
            out.energy = float(rep[qs.REP_ELEC])
            self.electrical_energy += out.energy
        else:
            out.energy = rep[qs.REP_A2POS] / self.meter.efficiency
        self._settle(d, anchor, dt)
        return out

    def _kinematic(self, gauss: list[np.ndarray], anchor: str | None, dt: float) -> int:
        sim, n, iterations = self.sim, len(gauss) - 1, 0
        for j in range(n):
            d_a = sim.state.d.copy()  # M3 is invariant to a re-centring of x in actuate
            iterations += sim.actuate(gauss[j + 1], dt=dt / n, anchor=anchor).iterations
            self.meter.add(increment_work(sim.model, d_a, sim.state.d, gauss[j], gauss[j + 1]))
        return iterations

    def _settle(self, d: np.ndarray, anchor: str | None, dt: float) -> None:
        """The beam at rest in configuration d after a compiled step of dt (quasi-static: no
        velocity), its Gauss-point actuation the realised curvature, re-centred on the tail."""
        sim = self.sim
        z = np.zeros_like(d)
        sim.state = NewmarkState(d, z, z.copy(), sim.state.t + dt)
        sim.kappa = self._gauss(self.kappa_ctrl)
        sim.anchor = anchor or "head"
        sim._recenter()  # noqa: SLF001 - same package: the local origin follows the tail

    def kernel_args(self) -> tuple:
        """(act, feet, S_ctrl, gauss_S, f_ext, beam constants) of `quasistatic.drive_step`
        (rebuilt when the Newton settings or the increment factor change)."""
        sim = self.sim
        key = (sim.settings, sim.increment_factor)
        if getattr(self, "_args_key", None) != key:
            self._args, self._args_key = self._kernel_args(), key
        return self._args

    def _kernel_args(self) -> tuple:
        sim, lag = self.sim, self.lag
        tau, rate = (lag.params.time_constant, lag.params.rate_limit) if lag else (1.0, 1.0)
        limit = sim.increment_factor * sim.params.max_dkappa
        act = (lag is not None, tau, rate, limit, sim.model.params.EI)
        bc = static.constants(sim.model, sim.settings)
        return act, self.feet.kernel_args(), self.S_ctrl, sim.model.gauss_S, sim.f_ext, bc

    def _frictional(
        self, command: np.ndarray, anchor: str | None, dt: float, min_substeps: int
    ) -> DriveReport:
        """One step on friction feet in the compiled `quasistatic.drive_step`."""
        sim, feet = self.sim, self.feet
        feet.settings = sim.settings  # one Newton budget for the whole robot
        d = sim.state.d.copy()
        lag_k = self.lag.kappa if self.lag is not None else self.kappa_ctrl.copy()
        state = (d, lag_k, self.kappa_ctrl, feet.g, feet.slipping)
        grip = np.array(GRIP_COMMANDS[anchor])
        rep = np.zeros(ss.N_REPORT)
        status = qs.drive_step(
            state, command, grip, dt, min_substeps, *self.kernel_args(), feet.scratch, rep
        )
        raise_status(status)
        if self.lag is not None:
            self.lag.command = command.copy()
        self.meter.add_totals(rep[ss.REP_POS], rep[ss.REP_NET])
        out = DriveReport(kappa_sharp=self.kappa_ctrl.copy(), increments=int(rep[ss.REP_INC]))
        out.feet = foot_report(rep)
        out.iterations, out.slip = out.feet.iterations, out.feet.slip.copy()
        out.energy = rep[ss.REP_POS] / self.meter.efficiency
        out.net_work = float(rep[ss.REP_NET])
        out.mechanical_work = float(rep[ss.REP_POS])
        self._settle(d, anchor, dt)
        return out


def make_driven(
    params: InchwormParams,
    effects: frozenset[str],
    n_control_points: int,
    actuator: ActuatorParams,
    friction: FrictionParams,
    increment_factor: float = 1.0,
    soil: str = "dry_sand",
    wires: SMAWires | None = None,
    grip_feet: GripFeetParams | None = None,
) -> DrivenInchworm:
    """A DrivenInchworm with control points evenly spaced from tail to head; `effects` may name
    the beam's effects and those of DRIVE_EFFECTS (which switch actuator and friction on).
    `friction` implies the weight (Coulomb friction needs a normal load, like `terrain`)."""
    beam_effects = frozenset(effects) - set(DRIVE_EFFECTS)
    if "friction" in effects or "gripping_feet" in effects:
        beam_effects |= {"gravity"}
    sim = Inchworm(
        params,
        beam_effects,
        increment_factor=increment_factor,
        soil=soil,
    )
    return DrivenInchworm(
        sim,
        np.linspace(0.0, params.length, n_control_points),
        actuator if "actuator_dynamics" in effects else None,
        friction if "friction" in effects else None,
        wires if "sma_wires" in effects else None,
        grip_feet if "gripping_feet" in effects else None,
    )
