"""Eel-v0's kwargs -> typed physics parameters, never the env (errors name the kwarg).

`build(kw, effects)` returns the `Scene`: the action mode (curvature commands, or the
parameters of an anguilliform wave: `HEAD_RATIO`, `WAVE_WAVELENGTH`, `WAVE_FREQUENCY`), the rod
(`physics.serpentine.rod_params`, a solid circular section of the body's diameter), the water
(`physics.swimmer.Water`: Taylor's resistive law with `resistive`, Lighthill's added mass and
tail force with `reactive`, the leading end's form drag with `form_drag`), the actuation
range, its rate limit, the muscles' power limit and control points, the reward weight and the
start noise.
The maps between the control points and the beam and the start shape are the serpentine's
(`envs.serpentine.build.interpolation`, `control_points`, `initial_dofs`).

Defaults: an American eel (Anguilla rostrata) of the size Tytell & Lauder (2004) filmed, L = 0.2
m, body diameter 0.06 L (a round section standing for the eel's), body density = water density
1000 kg/m^3 (neutral buoyancy), Young's modulus 1 MPa (soft tissue; docs/eel.md).
"""

from __future__ import annotations

import dataclasses
from typing import Any

from mf_envs._validate import check_int, check_range
from mf_envs.envs.serpentine.build import RobotScene, material, robot_fields
from mf_envs.physics.beam.solver import BeamParams
from mf_envs.physics.serpentine import rod_params
from mf_envs.physics.swimmer import Water

LENGTH = 0.2  # m
DIAMETER_RATIO = 0.06  # body diameter / L
ACTION_MODES = ("curvature", "wave")
# action_mode "wave": kappa#(S, t) = a (r + (1 - r) (L - S) / L) sin(2 pi (L - S) / lambda - phi),
# phi' = 2 pi f; the action's three numbers in [-1, 1] map linearly onto these ranges
HEAD_RATIO = 0.3  # curvature amplitude at the head / at the tail (anguilliform envelope)
WAVE_WAVELENGTH = (0.4, 2.0)  # lambda / L
WAVE_FREQUENCY = (0.5, 5.0)  # f [Hz]
# lightest body / water density: with the reactive force alone, bang-bang strokes failed the
# implicit step at 10-100 kg/m^3 in fresh water (3-14 of 400 steps) and never at 200 and above
MIN_DENSITY_RATIO = 0.25
# the muscles' power limit (effect `muscle_power`, docs/eel.md): the steady cyclic power of fish
# fast (white) muscle, 27.5 W/kg wet muscle in a 10 cm cod to 16.4 in a 60 cm one, ~ L^-0.29
# (Anderson & Johnston 1992, work loops at 8 C): 22 W/kg at L = 0.2 m; times the myotomal muscle's
# share of the body mass, 0.5 (Johnsrude & Webb 1985: 42.4 W/kg muscle = 0.64 W of one side's
# muscle in a 60.5 g trout, 15 g, a quarter of the body per side)
MUSCLE_POWER_DENSITY = 22.0  # W/kg of muscle
MUSCLE_MASS_FRACTION = 0.5
# effort weight x (body mass x (L / 1 s)^2): effort_weight = EFFORT_SCALE / (m L^2 / s^2); a
# regulariser small enough that the return ranks controllers as their speed does: over the zero,
# random and classical controllers on test seeds 20000-20019, Spearman's rho of return and
# speed was 0.57 at 0.002 (the `fast` gait's effort outweighed its progress), 0.96 at 0.0002
EFFORT_SCALE = 0.0002


@dataclasses.dataclass(frozen=True)
class Scene(RobotScene):
    """What the env's kwargs become (SI units), validated; the env reads its parameters here."""

    water: Water
    max_curvature_rate: float  # 1/(m s), muscle rate limit on the command
    stress_theta: float  # the stresses' theta point (physics.swimmer.kernels): > 1/2 damps
    action_mode: str  # "curvature" (kappa# at the control points) or "wave" (a, lambda, f)
    max_muscle_power: float  # W, the muscles' positive power limit (inf: none)

    @property
    def body_mass(self) -> float:
        """m_A L [kg]."""
        return self.params.mass_per_length * self.params.length


def _rod(kw: dict[str, Any]) -> tuple[BeamParams, float]:
    length = check_range("length", kw["length"], 0.01, 10.0)
    dia = DIAMETER_RATIO * length if kw["diameter"] is None else kw["diameter"]
    dia = check_range("diameter", dia, 1e-5, 2.0)
    if dia > length / 5:
        raise ValueError(f"diameter: must be <= length / 5 (a slender body), got {dia!r}")
    e, g, rho = material(kw)
    rho_w = check_range("water_density", kw["water_density"], 1.0, 1e5)
    if rho < MIN_DENSITY_RATIO * rho_w:
        raise ValueError(
            f"density: must be >= {MIN_DENSITY_RATIO} x water_density "
            f"({MIN_DENSITY_RATIO * rho_w:g} kg/m^3 here), got {rho!r}: a body that much lighter "
            "than the water it entrains (its added mass) makes the implicit step fail on hard "
            "strokes"
        )
    n_el = check_int("n_elements", kw["n_elements"], low=2, high=64)
    return rod_params(length, dia / 2, e, g, rho, n_el), dia


def water(kw: dict[str, Any], effects: frozenset, diameter: float) -> Water:
    """The fluid laws of the effects (every kwarg validated whatever the effects)."""
    return Water(
        density=check_range("water_density", kw["water_density"], 1.0, 1e5),
        diameter=diameter,
        c_normal=check_range("drag_normal", kw["drag_normal"], 0.0, 100.0),
        c_tangential=check_range("drag_tangential", kw["drag_tangential"], 0.0, 100.0),
        c_form=check_range("drag_form", kw["drag_form"], 0.0, 100.0),
        form_drag="form_drag" in effects,
        resistive="resistive" in effects,
        reactive="reactive" in effects,
    )


def max_muscle_power(kw: dict[str, Any], effects: frozenset, body_mass: float) -> float:
    """The muscles' power limit [W]: muscle_power_density x muscle_mass_fraction x body mass
    with the effect `muscle_power`, inf without it (both kwargs validated whatever the
    effects)."""
    density = check_range("muscle_power_density", kw["muscle_power_density"], 1e-6, 1e6)
    fraction = check_range("muscle_mass_fraction", kw["muscle_mass_fraction"], 1e-3, 1.0)
    return density * fraction * body_mass if "muscle_power" in effects else float("inf")


def action_mode(value: Any) -> str:
    """The validated `action_mode` (one of ACTION_MODES)."""
    if not isinstance(value, str) or value not in ACTION_MODES:
        raise ValueError(f"action_mode: must be one of {ACTION_MODES}, got {value!r}")
    return value


def build(kw: dict[str, Any], effects: frozenset) -> Scene:
    """The `Scene` of the env's kwargs `kw` under these effects; ValueError names the kwarg."""
    params, dia = _rod(kw)
    L = params.length
    mass = params.mass_per_length * L
    return Scene(
        params=params,
        **robot_fields(kw, L, EFFORT_SCALE / (mass * L**2)),
        water=water(kw, effects, dia),
        max_curvature_rate=check_range("max_curvature_rate", kw["max_curvature_rate"], 1e-6, 1e9),
        stress_theta=check_range("numerical_damping", kw["numerical_damping"], 0.0, 0.5) + 0.5,
        action_mode=action_mode(kw["action_mode"]),
        max_muscle_power=max_muscle_power(kw, effects, mass),
    )
