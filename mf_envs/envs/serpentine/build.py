"""Serpentine-v0's kwargs -> typed physics parameters, never the env (errors name the kwarg).

`build(kw, effects)` returns the `Scene`: the rod (`physics.serpentine.rod_params`), the ground
law (`BellyFriction`: anisotropic Coulomb with `friction`, viscous with `viscous_ground`, none
without either), the actuation range and control points, the reward weight and the start
noise. `interpolation` and `control_points` are the fixed maps between the control points and
the beam; `initial_dofs` the start shape (a curve of given curvature and heading, at rest).

Defaults: PyElastica's continuum snake (Gazzola et al. 2018, `docs/serpentine.md`): L = 0.35 m,
radius 0.011 L, E = 1 MPa, G = E / 1.5, rho = 1000 kg/m^3, friction coefficients
(mu, 1.5 mu, 2 mu) with mu = L / (T^2 g Fr) at the Froude number Fr = 0.1 and T = 2 s.
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from mf_envs._validate import check_int, check_range
from mf_envs.envs.serpentine.spec import CURVATURE_OBS_LIMIT
from mf_envs.physics.beam import element as el
from mf_envs.physics.beam.solver import BeamParams
from mf_envs.physics.constants import G
from mf_envs.physics.serpentine import BellyFriction, rod_params

LENGTH = 0.35  # m
RADIUS = 0.011 * LENGTH  # m
FROUDE, REFERENCE_PERIOD = 0.1, 2.0  # the friction's Froude number at this gait period [s]
MU = LENGTH / (REFERENCE_PERIOD**2 * G * FROUDE)  # 0.892: forward Coulomb coefficient
# effort weight x (body weight x length): effort = 0.01 x cost of transport x progress, a
# regulariser: with 0.1 the effort outweighed the progress of the open-loop gaits and the return
# ranked controllers unlike their speed (Spearman 0.37 over the zero, random and classical
# controllers on test seeds 20000-20003; 1.0 at 0.01: docs/benchmark.md, "Reward and score")
EFFORT_SCALE = 0.01


@dataclasses.dataclass(frozen=True)
class RobotScene:
    """What every beam robot's kwargs become (SI units, validated: `robot_fields`)."""

    params: BeamParams
    max_curvature: float  # 1/m, action scale
    n_ctrl: int
    effort_weight: float  # 1/J
    reset_noise_scale: float
    initial_heading_range: float  # rad

    @property
    def length(self) -> float:
        return self.params.length


@dataclasses.dataclass(frozen=True)
class Scene(RobotScene):
    """What the env's kwargs become (SI units), validated; the env reads its parameters here."""

    ground: BellyFriction
    gravity: float  # m/s^2, normal to the ground
    material_damping: float  # s, Kelvin-Voigt retardation time of the body
    actuator_time_constant: float  # s, first-order lag of the muscles (0: first-order hold)
    actuator_rate_limit: float  # 1/(m s), the muscles' largest curvature rate

    @property
    def weight(self) -> float:
        """Body weight m_A g L [N]."""
        return self.params.mass_per_length * self.gravity * self.params.length


def _rod(kw: dict[str, Any]) -> BeamParams:
    length = check_range("length", kw["length"], 0.01, 10.0)
    radius = check_range("radius", RADIUS if kw["radius"] is None else kw["radius"], 1e-5, 1.0)
    if radius > length / 10:
        raise ValueError(f"radius: must be <= length / 10 (a slender body), got {radius!r}")
    e, g, rho = material(kw)
    n_el = check_int("n_elements", kw["n_elements"], low=2, high=64)
    return rod_params(length, radius, e, g, rho, n_el)


def material(kw: dict[str, Any]) -> tuple[float, float, float]:
    """(E, G, rho) of a beam robot's kwargs (G = E / 1.5 unless given), validated."""
    e = check_range("youngs_modulus", kw["youngs_modulus"], 1e3, 1e12)
    g = e / 1.5 if kw["shear_modulus"] is None else kw["shear_modulus"]
    g = check_range("shear_modulus", g, 1e3, 1e12)
    return e, g, check_range("density", kw["density"], 1.0, 1e5)


def robot_fields(kw: dict[str, Any], length: float, effort_scale: float) -> dict[str, Any]:
    """The `RobotScene` fields of a beam robot's kwargs but its params, validated (ValueError
    naming the kwarg): max_curvature (max_curvature x length within the curvature observation's
    bound), n_ctrl, effort_weight (None: effort_scale), reset_noise_scale,
    initial_heading_range."""
    max_curvature = check_range("max_curvature", kw["max_curvature"], 1e-6)
    if max_curvature * length > CURVATURE_OBS_LIMIT:
        raise ValueError(
            f"max_curvature: max_curvature * length must be <= {CURVATURE_OBS_LIMIT:g} (the "
            f"curvature observation bound), got {max_curvature:g} 1/m x {length:g} m"
        )
    effort = effort_scale if kw["effort_weight"] is None else kw["effort_weight"]
    return {
        "max_curvature": max_curvature,
        "n_ctrl": check_int("n_control_points", kw["n_control_points"], low=2, high=64),
        "effort_weight": check_range("effort_weight", effort, 0.0, 1e9),
        "reset_noise_scale": check_range("reset_noise_scale", kw["reset_noise_scale"], 0.0, 1.0),
        "initial_heading_range": check_range(
            "initial_heading_range", kw["initial_heading_range"], 0.0, np.pi
        ),
    }


def ground_law(kw: dict[str, Any], effects: frozenset, mass_per_length: float) -> BellyFriction:
    """The belly law of the effects (every kwarg validated whatever the effects); a preset's
    damper (`apply_preset`) adds its drag on every velocity and its couple on the frame rate."""
    mu = check_range("friction_coefficient", kw["friction_coefficient"], 0.0, 10.0)
    back = check_range("backward_ratio", kw["backward_ratio"], 0.0, 100.0)
    lat = check_range("lateral_ratio", kw["lateral_ratio"], 0.0, 100.0)
    slip = check_range("slip_speed", kw["slip_speed"], 1e-7, 1.0)
    c_t = check_range("viscous_tangential", kw["viscous_tangential"], 0.0, 1e6)
    c_n = check_range("viscous_normal", kw["viscous_normal"], 0.0, 1e6)
    if "friction" in effects and "viscous_ground" in effects:
        raise ValueError("effects: friction and viscous_ground are exclusive (one ground law)")
    if "viscous_ground" in effects:
        return BellyFriction(0.0, 0.0, 0.0, slip, True, c_t, c_n)
    if "friction" in effects:
        damper = kw.get("damper", 0.0)
        return BellyFriction(mu, back * mu, lat * mu, slip, drag_rate=damper,
                             couple_damping=damper * mass_per_length)  # fmt: skip
    return BellyFriction(0.0, 0.0, 0.0, slip)  # frictionless: the ground force is 0


def build(kw: dict[str, Any], effects: frozenset) -> Scene:
    """The `Scene` of the env's kwargs `kw` under these effects; ValueError names the kwarg."""
    params = _rod(kw)
    L = params.length
    weight = params.mass_per_length * G * L
    tau_a = kw["actuator_time_constant"]
    check_range("actuator_time_constant", tau_a, 1e-4, 100.0)  # validated whatever the effects
    rate_a = check_range("actuator_rate_limit", kw["actuator_rate_limit"], 1e-3, 1e6)
    return Scene(
        params=params,
        **robot_fields(kw, L, EFFORT_SCALE / (weight * L)),
        ground=ground_law(kw, effects, params.mass_per_length),
        gravity=G,
        material_damping=check_range("material_damping", kw["material_damping"], 0.0, 10.0),
        actuator_time_constant=(
            check_range("actuator_time_constant", tau_a, 1e-4, 100.0)
            if "actuator_dynamics" in effects
            else 0.0
        ),
        actuator_rate_limit=rate_a,
    )


def control_points(length: float, n_ctrl: int, n_el: int) -> tuple[np.ndarray, np.ndarray]:
    """(element (n,) int, local xi (n,)) of the control points S_j = j L / (n - 1)."""
    s = np.linspace(0.0, 1.0, n_ctrl) * n_el
    e = np.minimum(np.floor(s).astype(np.int64), n_el - 1)
    return e, s - e


def interpolation(gauss_s: np.ndarray, length: float, n_ctrl: int) -> np.ndarray:
    """(n_el * 4, n) weights: kappa#(S_gauss) = W @ kappa# at the control points (linear)."""
    s_ctrl = np.linspace(0.0, length, n_ctrl)
    eye = np.eye(n_ctrl)
    return np.stack([np.interp(gauss_s.ravel(), s_ctrl, eye[j]) for j in range(n_ctrl)], 1)


def initial_dofs(params: BeamParams, kappa: np.ndarray, heading: float) -> np.ndarray:
    """(n_dof,) dofs of the curve with curvature kappa (n,) [1/m] at the control points (linear
    between), mean frame angle `heading` [rad] and centre of mass at the origin."""
    n_el, L = params.n_elements, params.length
    fine = np.linspace(0.0, L, 64 * n_el + 1)
    k = np.interp(fine, np.linspace(0.0, L, len(kappa)), kappa)
    psi = np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * np.diff(fine))])
    psi += heading - np.trapezoid(psi, fine) / L  # exact for piecewise-linear kappa
    c, s = np.cos(psi), np.sin(psi)
    seg = np.diff(fine)
    x = np.concatenate([[0.0], np.cumsum(0.5 * (c[1:] + c[:-1]) * seg)])
    y = np.concatenate([[0.0], np.cumsum(0.5 * (s[1:] + s[:-1]) * seg)])
    x -= np.trapezoid(x, fine) / L
    y -= np.trapezoid(y, fine) / L
    d = np.zeros(el.n_dof(n_el))
    nodes = np.arange(n_el + 1) * 64
    for name, arr in enumerate((x, c, y, s, psi)):
        d[name::6] = arr[nodes]
    d[5::6] = psi[nodes[:-1] + 32]  # mid-node frame angles
    return d


# preset="pyelastica": PyElastica 1.0's continuum snake (examples/ContinuumSnakeCase/
# continuum_snake.py; Gazzola et al. 2018) through gym.make: its rod (L = 0.35 m, r = 0.011 L,
# E = 1 MPa, G = E / 1.5, rho = 1000 kg/m^3, friction (mu, 1.5 mu, 2 mu) at Fr = 0.1 and T = 2 s:
# the defaults) on 10 elements at 10 ms with the action every physics step, the muscles as
# kappa# at 61 control points (its spline envelope sampled finely enough for the linear map to
# the beam; 7 points left it at 0.90 of PyElastica's speed), no Kelvin-Voigt body and no
# actuator lag (PyElastica has neither), friction only, and the equivalents of its
# AnalyticalLinearDamper (damping constant 2e-3: a drag 2e-3 1/s on every velocity and a line
# couple -2e-3 m_A psi', `benchmarks.speed.snake_elastica`). docs/serpentine.md, "PyElastica
# side by side".
PRESETS = ("pyelastica",)
PYELASTICA_SCENE = {
    "n_elements": 10,
    "n_control_points": 61,
    "control_dt": 0.01,
    "physics_dt": 0.01,
    "max_curvature": 30.0,  # the muscles reach 24 1/m: no clipping
    "slip_speed": 1e-4,
    "material_damping": 0.0,
    "effects": ("friction",),
}
PYELASTICA_DAMPER = 2e-3  # 1/s


def apply_preset(kw: dict[str, Any], defaults: dict[str, Any]) -> dict[str, Any]:
    """The kwargs `kw` (with `preset`) as the scene sees them: a preset's values in place of the
    defaults (`defaults`: the env's signature); ValueError naming `preset` if unknown, or a
    kwarg the preset sets that was given as well."""
    kw = dict(kw)
    preset = kw.pop("preset")
    if preset is None:
        return kw
    if not isinstance(preset, str) or preset not in PRESETS:
        raise ValueError(f"preset: must be one of {PRESETS} or None, got {preset!r}")
    for key, value in PYELASTICA_SCENE.items():
        if kw[key] != defaults[key]:
            raise ValueError(f"{key}: preset='pyelastica' sets it ({value!r}); leave it out")
        kw[key] = value
    kw["damper"] = PYELASTICA_DAMPER
    return kw
