"""Ground contact of the active beam (Rios 2017 §4.5): shared by every robot built on it.

friction     anisotropic Coulomb friction with engagement dynamics (the law; compiled)
feet         a beam on two friction feet at its end nodes: quasi-static stick-slip
stick_slip   the compiled form of `feet` (increments, slip onsets, status codes)
terrain      Bekker/Janosi soil line loads along the beam (soils: `mf_envs.physics.terrain`)
"""

from mf_envs.physics.beam.contact.feet import (
    FootReport,
    FrictionFeet,
    NoQuasiStaticEquilibrium,
    foot_report,
    grip_response,
    raise_status,
)
from mf_envs.physics.beam.contact.friction import BACKWARD, FORWARD, FrictionParams
from mf_envs.physics.beam.contact.terrain import BeamTerrain

__all__ = [
    "BACKWARD",
    "FORWARD",
    "BeamTerrain",
    "FootReport",
    "FrictionFeet",
    "FrictionParams",
    "NoQuasiStaticEquilibrium",
    "foot_report",
    "grip_response",
    "raise_status",
]
