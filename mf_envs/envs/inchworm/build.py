"""Inchworm-v0's kwargs -> typed physics parameters, never the env (errors name the kwarg).

`build(kw)`: the `Scene` (body, actuation range, reward weight, start noise, control points,
soil, actuator and feet); `drive_kwargs`: `make_driven`'s arguments once the effects and the
physics step are known; `DEFAULT_EPISODE_STEPS`: the default episode length.

`beam_params`: the body (length, section, material, mesh). `robot_params`: the
actuator and feet kwargs `actuator_time_constant` [s], `actuator_rate_limit` [1/(m s)],
`grip_time_constant` [s] and `friction_coefficients` become the physics' `ActuatorParams` and
`FrictionParams` (`mf_envs.physics.actuators.curvature`,
`mf_envs.physics.beam.contact.friction`).
"""

from __future__ import annotations

import dataclasses
from typing import Any

from mf_envs._validate import check_choice, check_int, check_range
from mf_envs.envs.inchworm.spec import CURVATURE_OBS_LIMIT
from mf_envs.physics.actuators.curvature import SMA_RATE_LIMIT, SMA_TIME_CONSTANT, ActuatorParams
from mf_envs.physics.actuators.sizing import size_wires
from mf_envs.physics.actuators.sma import (  # noqa: F401  (MAX_WIRE_TEMPERATURE: the env's default)
    FLEXINOL_HT,
    FLEXINOL_LT,
    MAX_WIRE_TEMPERATURE,
    SMAWireParams,
    flexinol_wire,
)
from mf_envs.physics.beam.contact.friction import FrictionParams
from mf_envs.physics.beam.contact.grip import GripFeetParams, GripLaw
from mf_envs.physics.inchworm import InchwormParams
from mf_envs.physics.inchworm.presets import V_GRIP, V_SLIDE
from mf_envs.physics.inchworm.wires import SMAWires
from mf_envs.physics.terrain import SOILS

# the seed's scene (§4.10): kinematic anchors (Eq. 102), kappa# as commanded, quasi-static
SEED_SCENE_EFFECTS = ("gravity", "shear_deformation", "anchor_switching")
# the lag-friction robot: the seed's body with a lag actuator and Coulomb friction feet
LAG_FRICTION_EFFECTS = (*SEED_SCENE_EFFECTS, "actuator_dynamics", "friction")
# the seed's body (§4.10, Eqs. 99-103): gym.make("Inchworm-v0", **RIOS2017_SCENE) is the
# dissertation's scene, bit for bit as before the SMA robot became the default
RIOS2017_BODY = {
    "length": 0.3, "width": 0.02, "height": 0.01, "youngs_modulus": 2.4e9,
    "shear_modulus": 0.96e9, "mass_per_length": 0.278, "max_curvature": 13.0,
}  # fmt: skip
RIOS2017_SCENE = {**RIOS2017_BODY, "effects": SEED_SCENE_EFFECTS}
# the lag-friction robot's default robot (the seed's body on friction feet through a lag actuator)
LAG_FRICTION_SCENE = {**RIOS2017_BODY, "effects": LAG_FRICTION_EFFECTS, "grip_time_constant": 0.2}
# the default body: PDMS after Wang et al. 2014 (physics.inchworm.presets.BuildableInchworm)
PDMS_E = 1.5e6  # Pa
PDMS_G = PDMS_E / (2.0 * (1.0 + 0.49))  # Pa, Poisson 0.49
PDMS_MASS = 1030.0 * 0.010 * 0.003  # kg/m: density x 10 x 3 mm
MAX_INCREMENTS = 200  # increments (or Newmark steps) of a full-range step: a step stays fast
FRICTION_KEYS = ("grip_forward", "grip_backward", "slide_forward", "slide_backward")
GRIP_TIME_CONSTANT = 0.5  # s, the feet's engage/release time (presets.GRIP_TIME)
DEFAULT_EPISODE_STEPS = 400
ALLOYS = {"HT": FLEXINOL_HT, "LT": FLEXINOL_LT}
# default effort weight with `sma_wires`: MECHANICAL_EFFORT_SCALE x SMA_EFFORT_SCALE /
# (m_A g L^2) per joule of electrical energy (docs/inchworm.md, "The buildable robot": an SMA
# crawler's electrical cost of transport is ~4e3, so the mechanical scenes' weight would drown
# the progress). Sized so that every wire at full duty for a whole default episode costs less
# than the progress of a crawl at ~0.1 mm/s: a policy that crawls faster returns more than
# any that stands still, whatever it spends
SMA_EFFORT_SCALE = 2e-5
# the mechanical scenes' weight is MECHANICAL_EFFORT_SCALE / (m_A g L^2) and the wires' this
# times SMA_EFFORT_SCALE: a tenth of the lifting-equivalent weight, so that the return ranks the
# gaits as their speed does (heat_cool and seed_uniform crawl within 1 % of each other)
MECHANICAL_EFFORT_SCALE = 0.1
__all__ = [
    "DEFAULT_EPISODE_STEPS",
    "GRIP_TIME_CONSTANT",
    "SMA_RATE_LIMIT",
    "SMA_TIME_CONSTANT",
    "Scene",
    "beam_params",
    "build",
    "drive_kwargs",
    "robot_params",
    "step_budget",
]


@dataclasses.dataclass(frozen=True)
class Scene:
    """What the env's kwargs become (SI units), validated; the env reads its parameters here."""

    params: InchwormParams
    max_curvature: float  # 1/m, the actuation range kappa0#
    effort_weight: float  # 1 / (J) per step: default 1 / (body weight x length)
    reset_noise_scale: float
    increment_factor: float  # quasi-static increments of increment_factor x 2 h / L^2
    n_ctrl: int  # control points
    soil: str
    actuator_rate_limit: float  # 1/(m s), with `actuator_dynamics`
    actuator_params: ActuatorParams
    feet: FrictionParams
    # the feet's coefficients resolved, FRICTION_KEYS -> mu (the env's `friction_coefficients`:
    # the nominal that `train.randomize` scales)
    friction_coefficients: dict[str, float] = dataclasses.field(hash=False)
    grip_feet: GripFeetParams  # the feet with `gripping_feet`
    wires: SMAWires | None  # the wire groups with `sma_wires` (sized to the body)
    ambient: float  # degC, still air around the wires (`ambient_temperature`)

    @property
    def weight(self) -> float:
        """Body weight m_A g L (N)."""
        p = self.params
        return p.mass_per_length * p.gravity * p.length


def build(kw: dict[str, Any], effects: frozenset, n_substeps: int) -> Scene:
    """The `Scene` of the env's kwargs `kw` under these effects and physics substeps per control
    step; ValueError names the kwarg."""
    params = beam_params(kw["length"], kw["width"], kw["height"], kw["youngs_modulus"],
                         kw["shear_modulus"], kw["mass_per_length"], kw["n_elements"])  # fmt: skip
    L = params.length
    max_curvature = check_range("max_curvature", kw["max_curvature"], 1e-9)
    if max_curvature * L > CURVATURE_OBS_LIMIT:
        raise ValueError(
            f"max_curvature: max_curvature * length must be <= {CURVATURE_OBS_LIMIT:g} (the "
            f"curvature observation bound), got {max_curvature:g} 1/m x {L:g} m"
        )
    effort = kw["effort_weight"]
    if effort is None:
        effort = MECHANICAL_EFFORT_SCALE / (params.mass_per_length * params.gravity * L * L)
        if "sma_wires" in effects:
            effort *= SMA_EFFORT_SCALE
    head = dict(
        params=params,
        max_curvature=max_curvature,
        effort_weight=check_range("effort_weight", effort, 0.0, 1e6),
        reset_noise_scale=check_range("reset_noise_scale", kw["reset_noise_scale"], 0.0, 1.0),
        increment_factor=step_budget(
            kw["increment_factor"], max_curvature, params, n_substeps, effects
        ),  # fmt: skip
        n_ctrl=check_int("n_control_points", kw["n_control_points"], low=2, high=64),
        soil=check_choice("soil", kw["soil"], tuple(SOILS)),
    )
    act, feet = robot_params(kw["actuator_time_constant"], kw["actuator_rate_limit"],
                             kw["grip_time_constant"], kw["friction_coefficients"])  # fmt: skip
    grip = grip_feet_params(feet, kw["grip_threshold"])
    wires = wire_groups(kw, params, max_curvature, head["n_ctrl"], "sma_wires" in effects)
    ambient = check_range("ambient_temperature", kw["ambient_temperature"], -40.0, 60.0)
    mu = dict(zip(FRICTION_KEYS, map(float, feet.coefficients)))
    return Scene(**head, actuator_rate_limit=act.rate_limit, actuator_params=act, feet=feet,
                 friction_coefficients=mu, grip_feet=grip, wires=wires,
                 ambient=ambient)  # fmt: skip


def grip_feet_params(feet: FrictionParams, threshold: Any) -> GripFeetParams:
    """The gripping feet (`grip.GripLaw`): the threshold, the gripping coefficients of
    `friction_coefficients`, its slide_forward as the isotropic smooth face (slide_backward is
    not used), the regularisation speeds of the preset, the grip time constant."""
    th = check_range("grip_threshold", threshold, 0.0, 0.8)
    if min(feet.grip_forward, feet.grip_backward) < feet.slide_forward:
        raise ValueError(
            "friction_coefficients: the gripping coefficients must not be below slide_forward"
        )
    law = GripLaw(threshold=th, width=0.2, mu_slide=feet.slide_forward,
                  grip_forward=feet.grip_forward, grip_backward=feet.grip_backward,
                  v_slide=V_SLIDE, v_grip=V_GRIP)  # fmt: skip
    return GripFeetParams(law, feet.engage_time, feet.release_time)


def wire_groups(
    kw: dict[str, Any], params: InchwormParams, max_curvature: float, n_ctrl: int, on: bool
) -> SMAWires | None:
    """The SMA wire groups (one per control point, `wires.SMAWires`) sized to the body: the
    wires at `wire_lever_arm` must hold EI max_curvature at the maker's 172 MPa
    (`sizing.size_wires`) with their strain max_curvature x lever arm inside the alloy's
    repeatable range; and the temperature the wires approach at full duty of the rated current
    (`SMAWireParams.steady_temperature`, which no duty sequence exceeds) must stay at or below
    `max_wire_temperature`. The wire kwargs are checked always, the sizing with `sma_wires`
    only (None without it)."""
    diameter = check_range("wire_diameter", kw["wire_diameter"], 1e-6, 1e-2)
    try:
        flexinol_wire(diameter)
    except ValueError as exc:
        raise ValueError(f"wire_diameter: {str(exc).split(': ', 1)[1]}") from None
    lever = check_range("wire_lever_arm", kw["wire_lever_arm"], 1e-6, 1.0)
    alloy = ALLOYS[check_choice("wire_alloy", kw["wire_alloy"], tuple(ALLOYS))]
    ambient = check_range("ambient_temperature", kw["ambient_temperature"], -40.0, 60.0)
    t_max = check_range("max_wire_temperature", kw["max_wire_temperature"], -40.0, 1000.0)
    if not on:
        return None
    if t_max <= alloy.austenite_finish:
        raise ValueError(
            f"max_wire_temperature: {t_max:g} degC is not above Af = {alloy.austenite_finish} "
            f"degC of {alloy.name} (the wires could never finish contracting)"
        )
    if lever > params.height / 2.0:
        raise ValueError(
            f"wire_lever_arm: {lever} m puts the wires outside the section (height / 2)"
        )
    try:
        sizing = size_wires(params.youngs_modulus, params.width, params.height, max_curvature,
                            diameter, lever, alloy)  # fmt: skip
    except ValueError:
        raise ValueError(
            f"max_curvature, wire_lever_arm: the wires' strain max_curvature x wire_lever_arm "
            f"= {max_curvature * lever:.4f} exceeds the repeatable {alloy.repeatable_strain[1]} "
            f"of {alloy.name} (lower one of them)"
        ) from None
    if ambient >= alloy.martensite_finish:
        raise ValueError(
            f"ambient_temperature: {ambient} degC is not below Mf = {alloy.martensite_finish} "
            f"degC of {alloy.name} (the wires would never relax)"
        )
    group = SMAWireParams(
        diameter=diameter, length=params.length / n_ctrl, n_wires=sizing.count, alloy=alloy,
        strain_max=sizing.wire_strain, ambient=ambient, name="Inchworm-v0 body wires",
    )  # fmt: skip
    hottest = group.steady_temperature(1.0)
    if hottest > t_max:
        raise ValueError(
            f"ambient_temperature, wire_diameter: the wires would reach {hottest:.1f} degC at "
            f"full duty of the rated current ({ambient:g} degC still air, {diameter:g} m wire), "
            f"above max_wire_temperature = {t_max:g} degC"
        )
    return SMAWires(group, max_curvature, n_ctrl)


def drive_kwargs(scene: Scene, effects: frozenset) -> dict[str, Any]:
    """`make_driven`'s arguments: the scene's robot with these effects."""
    return dict(params=scene.params, effects=effects, n_control_points=scene.n_ctrl,
                actuator=scene.actuator_params, friction=scene.feet,
                increment_factor=scene.increment_factor, soil=scene.soil,
                wires=scene.wires, grip_feet=scene.grip_feet)  # fmt: skip


def step_budget(
    increment_factor: Any, max_curvature: float, params: InchwormParams, n_substeps: int, effects
) -> float:
    """The validated increment_factor; a full-range step must take <= MAX_INCREMENTS quasi-static
    increments of increment_factor * 2h/L^2 (or Newmark steps with `inertia`)."""
    increment_factor = check_range("increment_factor", increment_factor, 1e-3, 1e6)
    if max_curvature / (increment_factor * params.max_dkappa) > MAX_INCREMENTS:
        raise ValueError(
            f"increment_factor: a full-range step (max_curvature {max_curvature:g} 1/m) "
            f"would take more than {MAX_INCREMENTS} increments of "
            f"increment_factor * 2 height / length^2; raise increment_factor"
        )
    if "inertia" in effects and n_substeps > MAX_INCREMENTS:
        raise ValueError(
            f"physics_dt: with `inertia` a step takes control_dt / physics_dt Newmark steps, "
            f"at most {MAX_INCREMENTS}; got {n_substeps}"
        )
    return increment_factor


def beam_params(length, width, height, youngs, shear, mass, n_elements) -> InchwormParams:
    """The beam parameters from the public arguments (errors name them)."""
    L = check_range("length", length, 0.01, 10.0)
    h = check_range("height", height, 1e-4, 1.0)
    if h > L / 5:
        raise ValueError(f"height: must be <= length / 5 (a slender beam), got {height!r}")
    m = check_range("mass_per_length", mass, 1e-6, 1e4)
    return dataclasses.replace(
        InchwormParams(),
        length=L,
        width=check_range("width", width, 1e-4, 1.0),
        height=h,
        youngs_modulus=check_range("youngs_modulus", youngs, 1e3, 1e13),
        shear_modulus=check_range("shear_modulus", shear, 1e3, 1e13),
        mass_per_length=m,
        rotary_inertia=m * h**2 / 12.0,
        n_elements=check_int("n_elements", n_elements, low=1, high=64),
    )


def _friction(coefficients: Any, grip_time: float) -> FrictionParams:
    """FrictionParams from a mapping of FRICTION_KEYS (missing keys keep their defaults) or a
    4-sequence in that order."""
    if coefficients is None:
        coefficients = {}
    elif not isinstance(coefficients, dict):
        try:
            values = tuple(coefficients)
        except TypeError:
            values = ()
        if len(values) != 4:
            raise ValueError(
                f"friction_coefficients: expected a dict of {FRICTION_KEYS} or 4 numbers, "
                f"got {coefficients!r}"
            )
        coefficients = dict(zip(FRICTION_KEYS, values))
    bad = sorted(set(coefficients) - set(FRICTION_KEYS))
    if bad:
        raise ValueError(f"friction_coefficients: unknown {bad}; known {FRICTION_KEYS}")
    mu = {
        k: check_range(f"friction_coefficients[{k!r}]", v, 0.0, 10.0)
        for k, v in coefficients.items()
    }
    return dataclasses.replace(
        FrictionParams(), **mu, engage_time=grip_time, release_time=grip_time
    )


def robot_params(
    actuator_time_constant: Any,
    actuator_rate_limit: Any,
    grip_time_constant: Any,
    friction_coefficients: Any,
) -> tuple[ActuatorParams, FrictionParams]:
    """(ActuatorParams, FrictionParams) from the env's kwargs; ValueError names the kwarg."""
    tau = check_range("actuator_time_constant", actuator_time_constant, 1e-4, 1e3)
    rate = check_range("actuator_rate_limit", actuator_rate_limit, 1e-6, 1e6)
    grip = check_range("grip_time_constant", grip_time_constant, 1e-4, 1e3)
    return ActuatorParams(tau, rate), _friction(friction_coefficients, grip)
