"""Effects: named physical terms a scene switches on ("simulate only what the scene calls for").

Each model declares its effects as a mapping name -> one-line description, plus a default set.
`resolve_effects` turns the user's `effects=` argument into a frozenset, rejecting unknown names
with a ValueError that names them. Models branch on membership once per step (or compile a
specialised kernel per set), so an effect that is off is never evaluated.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

# Shared vocabulary (docs/design.md); models pick the subset that exists for them.
EFFECT_NAMES: dict[str, str] = {
    "gyroscopic": "rotor spin coupling (the gyroscopic moment J3 psi' x ...)",
    "gimbal_inertia": "inertia of the gimbal frame itself",
    "buoy_rocking": "prescribed wave-slope rocking of the buoy (ch. 3 Eqs. 77-78)",
    "wave_2d": "oblique (2-D) wave direction (ch. 3 Eqs. 89-93)",
    "irregular_waves": "irregular sea from a JONSWAP/Pierson-Moskowitz spectrum",
    "hydrostatic_restoring": "hydrostatic roll restoring moment rho g V GM (or GZ curve)",
    "roll_damping": "linear hull damping in roll, pitch and yaw (B44, B55, B66; the quadratic "
    "roll term is `quadratic_roll_damping`)",
    "added_inertia": "hydrodynamic added roll inertia",
    "wave_moment": "wave-induced roll moment on the hull",
    "gimbal_limits": "gimbal end stops and precession-rate limit",
    "translation": "ship surge/sway/heave",
    "gravity": "gravity",
    "inertia": "beam inertia (dynamics); off = quasi-static",
    "shear_deformation": "Timoshenko shear strain (off = shear-rigid)",
    "terrain": "Bekker pressure-sinkage / Janosi shear-slip ground contact",
    "anchor_switching": "kinematic head/tail anchor switching (ch. 4 Eq. 102)",
    "actuator_dynamics": "actuator lag and rate limit between commanded and realised kappa#",
    "friction": "feet holding by anisotropic Coulomb friction with grip dynamics",
    "sma_wires": "curvature from SMA wires heated by a duty cycle (Joule heat, cooling, phase)",
    "gripping_feet": "feet that anchor only above an engagement threshold (regularised friction)",
}


def resolve_effects(
    effects: str | Iterable[str] | None,
    available: Mapping[str, str] | Iterable[str],
    default: Iterable[str],
    *,
    param: str = "effects",
) -> frozenset[str]:
    """Validate `effects` against `available`; None gives `default`.

    A bare string is one effect name (not an iterable of characters).
    Raises ValueError naming every unknown effect and listing the available ones.
    """
    avail = tuple(available)
    if effects is None:
        chosen = tuple(default)
    elif isinstance(effects, str):
        chosen = (effects,)
    elif isinstance(effects, Mapping) or not isinstance(effects, Iterable):
        raise ValueError(f"{param}: expected a tuple of effect names, got {effects!r}")
    else:
        try:
            chosen = tuple(effects)
        except TypeError as exc:
            raise ValueError(f"{param}: expected a tuple of effect names, got {effects!r}") from exc
    bad = [e for e in chosen if not isinstance(e, str) or e not in avail]
    if bad:
        raise ValueError(f"{param}: unknown effect(s) {bad}; available: {', '.join(sorted(avail))}")
    return frozenset(chosen)
