"""FloatingGOWEC-v0's kwargs -> typed physics parameters, never the env: `build(kw)` validates the
sea, the power take-off and the limits into a `Scene`; `floating_model` makes the buoy's
`FloatingModel` (hull, gyroscope pair, PTO, radiation and viscous damping per the effects).
The grouped kwargs `sea=` (`Sea`), `pto=` (`PTO`) and their flat aliases: `GROUPS`
(`envs._groups`)."""

from __future__ import annotations

import dataclasses
import math
from typing import Any

import numpy as np
from gymnasium import spaces

from mf_envs._validate import check_choice, check_int, check_range
from mf_envs.envs._groups import Group
from mf_envs.envs.gowec import build as gowec_build
from mf_envs.envs.gowec_v1 import spec
from mf_envs.physics import waves
from mf_envs.physics.gowec import GOWECParams
from mf_envs.physics.gowec.hydro import HullCoefficients, load_hull
from mf_envs.physics.gowec.hydro.devices import DEVICES, FloatingDevice
from mf_envs.physics.gowec.hydro.model import FloatingModel

SPECTRA = {"jonswap": waves.jonswap_spectrum, "pierson_moskowitz": waves.pierson_moskowitz_spectrum}
# the kwargs a device fills when they are None (`devices.FloatingDevice` fields)
EPISODE_SECONDS = 120.0  # s, the default episode (6000 steps of the default 0.02 s)
DEVICE_KWARGS = ("rotor_inertia", "rotor_speed", "gyro_units", "generator_efficiency",
                 "max_generator_torque", "max_generator_power", "rotor_loss",
                 "drag_coefficient", "pitch_limit", "wave_ramp")  # fmt: skip


@dataclasses.dataclass(frozen=True)
class Sea(gowec_build.Sea):
    """FloatingGOWEC-v0's sea (the `sea=` kwarg): GOWEC-v0's regular wave (amplitude m, period s,
    direction rad) or, when `significant_wave_height` (m) is set, an irregular sea of that Hs
    and `peak_period` (s) from `spectrum` ("jonswap" with peak enhancement `gamma`, or
    "pierson_moskowitz") in `n_components` components. Validated by `build` (the ValueError
    names the field's flat alias, `SEA`)."""

    significant_wave_height: float | None = None
    peak_period: float = 6.0
    spectrum: str = "jonswap"


@dataclasses.dataclass(frozen=True)
class PTO:
    """FloatingGOWEC-v0's power take-off hardware (the `pto=` kwarg; its control law is
    `set_pto`): generator and motor efficiencies, torque (N m) and power (W) limits per unit,
    the running loss of all units while spinning (W). None: the device's value (`DEVICE_KWARGS`;
    motor_efficiency: the generator's)."""

    generator_efficiency: float | None = None
    motor_efficiency: float | None = None
    max_torque: float | None = None
    max_power: float | None = None
    rotor_loss: float | None = None


IRREGULAR = ("significant_wave_height", "peak_period", "spectrum")
SEA = Group("sea", Sea, {**gowec_build.SEA.aliases, **{name: name for name in IRREGULAR}})
PTO_GROUP = Group(
    "pto",
    PTO,
    {"generator_efficiency": "generator_efficiency", "motor_efficiency": "motor_efficiency",
     "max_generator_torque": "max_torque", "max_generator_power": "max_power",
     "rotor_loss": "rotor_loss"},
)  # fmt: skip
GROUPS = (SEA, PTO_GROUP)


@dataclasses.dataclass(frozen=True)
class Scene:
    """What the env's kwargs become (SI units), validated; the env reads its parameters here."""

    wave_amplitude: float  # m (irregular sea: Hs / (2 sqrt 2), the equivalent regular wave)
    wave_direction: float  # rad
    hs_given: bool  # significant_wave_height was given (an irregular sea)
    wave_period: float  # s (irregular sea: the peak period)
    spectrum: str
    gamma: float
    n_components: int
    eta_g: float  # generator efficiency
    eta_m: float  # motor efficiency
    max_generator_torque: float  # N m
    max_generator_power: float  # W, per unit (the drive's limit, set in the model)
    rotor_loss: float | None  # W, all units (None: the device's `flywheel_loss` at the speed)
    max_gimbal_rate: float  # rad/s
    device: str  # `devices.DEVICES` key
    drag_coefficient: float  # quadratic drag C_d (0 = none)
    pitch_limit: float  # rad: |theta| or |rho| beyond it puts the device in survival
    wave_ramp: float  # s: the incident wave ramps in over it


def device_of(kw: dict[str, Any]) -> FloatingDevice:
    """The named device of kw["device"]; its fields fill the kwargs left None (in place)."""
    dev = DEVICES[check_choice("device", kw["device"], DEVICES)]
    for k in DEVICE_KWARGS:
        if kw[k] is None:
            kw[k] = getattr(dev, k)
    return dev


def build(kw: dict[str, Any]) -> Scene:
    """The `Scene` of the env's kwargs `kw` (None = the device's value); ValueError names the
    kwarg."""
    device_of(kw)
    amplitude = check_range("wave_amplitude", kw["wave_amplitude"], 1e-6, 30.0)
    direction = check_range("wave_direction", kw["wave_direction"], -10.0, 10.0)
    irregular = kw["significant_wave_height"] is not None
    if irregular:
        hs = check_range("significant_wave_height", kw["significant_wave_height"], 1e-6, 30.0)
        amplitude = hs / (2.0 * math.sqrt(2.0))
    # both periods are checked whichever sea is used (a bad one is an error either way)
    periods = {n: check_range(n, kw[n], 0.5, 60.0) for n in ("wave_period", "peak_period")}
    spectrum = check_choice("spectrum", kw["spectrum"], SPECTRA)
    gamma = check_range("gamma", kw["gamma"], 1.0, 20.0)
    n_components = check_int("n_components", kw["n_components"], low=1, high=4096)
    eta_g = check_range("generator_efficiency", kw["generator_efficiency"], 1e-3, 1.0)
    eta_m = kw["motor_efficiency"]
    eta_m = eta_g if eta_m is None else check_range("motor_efficiency", eta_m, 1e-3, 1.0)
    return Scene(
        amplitude, direction, irregular, periods["peak_period" if irregular else "wave_period"],
        spectrum, gamma, n_components, eta_g, eta_m,
        check_range("max_generator_torque", kw["max_generator_torque"], 0.0),
        check_range("max_generator_power", kw["max_generator_power"], 0.0),
        None if kw["rotor_loss"] is None
        else check_range("rotor_loss", kw["rotor_loss"], 0.0, 1e7),
        check_range("max_gimbal_rate", kw["max_gimbal_rate"], 1e-6),
        kw["device"], check_range("drag_coefficient", kw["drag_coefficient"], 0.0, 100.0),
        check_range("pitch_limit", kw["pitch_limit"], 1e-3, 1.0),
        check_range("wave_ramp", kw["wave_ramp"], 0.0, 1e4),
    )  # fmt: skip


def draw_wave(irregular: bool, amplitude: float, period: float, direction: float, spectrum: str,
              gamma: float, n_components: int, omega_max: float,
              rng: np.random.Generator) -> waves.WaveField:  # fmt: skip
    """The sea of a reset: an irregular sea of Hs = 2 sqrt 2 a, peak period `period` and
    n_components between 0.3 x its peak frequency and omega_max (rad/s, the hull table's
    top), or a regular wave of a random phase."""
    if not irregular:
        return waves.regular_wave(amplitude, period, direction,
                                  phase=float(rng.uniform(0.0, 2.0 * math.pi)))  # fmt: skip
    fn = SPECTRA[spectrum]
    spec_fn = (lambda w, h, tp: fn(w, h, tp, gamma)) if spectrum == "jonswap" else fn
    return waves.IrregularSea(spec_fn, 2.0 * math.sqrt(2.0) * amplitude, period, n_components,
                              rng, direction, omega_range=(0.3 * 2 * math.pi / period,
                                                           omega_max))  # fmt: skip


def observation(max_gimbal_rate: float, wave_preview: Any) -> tuple[np.ndarray, spaces.Box]:
    """(preview times (s, (N_PREVIEW,) or empty), observation space): the layout's bounds and,
    when wave_preview > 0, N_PREVIEW elevation slots up to wave_preview s ahead."""
    hi = spec.OBS.high({"max_gimbal_rate": max_gimbal_rate})
    preview = check_range("wave_preview", wave_preview, 0.0, 120.0)
    times = preview * np.arange(1, spec.N_PREVIEW + 1) / spec.N_PREVIEW if preview else np.zeros(0)
    hi = np.concatenate([hi, np.full(times.size, spec.MAX_ELEVATION)]).astype(np.float32)
    return times, spaces.Box(-hi, hi, dtype=np.float32)


def default_effects(scene: Scene, hull: Any) -> tuple[str, ...]:
    """The device's default effects; with a user's `hull` (a pitch-only table) without
    "surge_heave", and without "quadratic_drag" when that table has no geometry (radius,
    draft, z_G): asking for either explicitly is a ValueError (`floating_model`)."""
    effects = DEVICES[scene.device].effects
    if hull is None:
        return effects
    drop = {"surge_heave"}
    h = hull if isinstance(hull, HullCoefficients) else None
    if h is not None and not all(math.isfinite(x) for x in (h.radius, h.draft, h.zg)):
        drop.add("quadratic_drag")
    return tuple(e for e in effects if e not in drop)


def floating_model(
    scene: Scene, kw: dict[str, Any], effects: frozenset
) -> tuple[HullCoefficients, FloatingModel]:
    """The hull (the device's, or `load_hull(kw["hull"])`) and its `FloatingModel`: the
    gyroscope units of rotor_inertia / rotor_speed (the device's gimbal frame), a PTO at zero
    gains within the scene's limits, the device's end stops, survival brake and supervisor
    (`gimbal`), radiation, a linear viscous damping (the device's fraction
    of critical unless viscous_damping is given), the quadratic drag and the wave ramp, per the
    effects."""
    dev = DEVICES[scene.device]
    three = dev.three_dof_table() if kw["hull"] is None else None
    hull = dev.hull() if kw["hull"] is None else load_hull(kw["hull"])
    gyro = GOWECParams(
        check_range("rotor_inertia", kw["rotor_inertia"], 1e-9, 1e6),
        check_range("rotor_speed", kw["rotor_speed"], -1e4, 1e4),
        gimbal_inertia=dev.gimbal_inertia,
    )
    pto = dict(damping=0.0, stiffness=0.0, max_torque=scene.max_generator_torque,
               max_power=scene.max_generator_power, eta_generator=scene.eta_g,
               eta_motor=scene.eta_m, brake_damping=dev.brake_damping,
               survival_tilt=scene.pitch_limit, survival_hold=dev.survival_hold,
               **dev.cushion(gyro.transverse + gyro.gimbal_inertia[1],
                             gyro.rotor_inertia * gyro.rotor_speed))  # fmt: skip
    units = check_int("gyro_units", kw["gyro_units"], low=1, high=2)
    model = FloatingModel(hull, gyro, pto, gyroscopic="gyroscopic" in effects, units=units,
                          three_dof=three)  # fmt: skip
    if "surge_heave" in effects:
        if three is None:
            raise ValueError(
                "effects: 'surge_heave' needs a hull with surge/heave/pitch data "
                "(device='iswec_class'); this hull rotates about a fixed G"
            )
        model.set_translation(True, dev.mooring_stiffness)
    crit = 2.0 * math.sqrt(hull.stiffness * (model.p.inertia[0]))
    bv = kw["viscous_damping"]
    bv = dev.viscous_fraction * crit if bv is None else bv
    bv = check_range("viscous_damping", bv, 0.0, 1e12)
    model.set_viscous(bv if "viscous_damping" in effects else 0.0)
    if "radiation" not in effects:
        model.set_radiation(False)
    model.set_ramp(scene.wave_ramp)
    if "quadratic_drag" in effects and scene.drag_coefficient > 0.0:
        model.set_drag(scene.drag_coefficient)
    return hull, model
