"""A buildable inchworm (issue 31): a soft PDMS-like body bent by Flexinol wires sized to the
moment they must deliver (`mf_envs.physics.actuators.sizing`). Numbers and their sources; not
wired into the env (docs/inchworm.md, "A buildable robot", has the table).

The seed's section (E = 2.4 GPa, 20 x 10 mm) needs 52 N m for its full curvature kappa0# = 13 1/m
(thousands of wires) and a 6.5 % surface strain. Here the body is an elastomer, thin enough that
two wires hold its hump, and the wires sit close to the neutral axis so that their strain stays
inside the repeatable range. The curvature keeps the seed's kappa0# L = 3.9 rad.
"""

from __future__ import annotations

from dataclasses import dataclass

from mf_envs.physics.actuators.sizing import WireSizing, size_wires
from mf_envs.physics.actuators.sma import FLEXINOL_HT, SMAAlloy, SMAWireParams
from mf_envs.physics.inchworm.model import InchwormParams

SOURCES = {
    "youngs_modulus": "Sylgard 184 bulk tension: 1.32-2.97 MPa by curing temperature (Johnston "
    "et al. 2014, J. Micromech. Microeng. 24 035017; abstract only); 1.5 MPa: a room-cured 10:1 "
    "mix, the low end",
    "density": "Sylgard 184 specific gravity ~1.03 (Dow data sheet; not verified here)",
    "poisson": "0.49, nearly incompressible elastomer (our choice)",
    "length": "our choice: 60 mm, a body the size of Wang et al. 2014's class of SMA-in-polymer "
    "crawlers (their dimensions: full text not reached, abstract only)",
    "section": "our choice: 10 x 3 mm",
    "kappa": "kappa L = 3.9 rad as in the seed (Rios 2017 §4.10: kappa0# = 13 1/m, L = 0.3 m)",
    "wire": "Flexinol HT 0.15 mm: 0.4 A for a 1 s contraction, 1.2 s cooling (Dynalloy F1140 "
    "wire table as quoted; mf_envs.physics.actuators.sma.FLEXINOL_WIRES)",
    "lever_arm": "our choice: 0.6 mm below the neutral axis, wire strain kappa e = 3.9 % inside "
    "the 2-6 % repeatable range (F1140)",
}


@dataclass(frozen=True)
class BuildableInchworm:
    """Body (SI units): length, width, height [m], Young's modulus [Pa], density [kg/m^3],
    Poisson ratio; target curvature kappa [1/m]; wires: diameter [m], lever arm [m] below the
    neutral axis, alloy. `SOURCES` says where each number comes from."""

    length: float = 0.06
    width: float = 0.010
    height: float = 0.003
    youngs_modulus: float = 1.5e6
    density: float = 1030.0
    poisson: float = 0.49
    kappa: float = 65.0
    wire_diameter: float = 150e-6
    lever_arm: float = 0.6e-3
    alloy: SMAAlloy = FLEXINOL_HT

    def sizing(self) -> WireSizing:
        """Moment, wire force and count, strains and reset margin (`sizing.size_wires`)."""
        return size_wires(
            self.youngs_modulus, self.width, self.height, self.kappa, self.wire_diameter,
            self.lever_arm, self.alloy,
        )  # fmt: skip

    def wires(self) -> SMAWireParams:
        """The wire group: the sized count along the body, strain_max = kappa e."""
        s = self.sizing()
        return SMAWireParams(
            diameter=self.wire_diameter, length=self.length, n_wires=s.count, alloy=self.alloy,
            strain_max=s.wire_strain, name="buildable inchworm body wires",
        )  # fmt: skip

    def beam(self, n_elements: int = 16) -> InchwormParams:
        """The body as the inchworm's active beam (wires' own stiffness and mass neglected)."""
        area = self.width * self.height
        return InchwormParams(
            length=self.length, width=self.width, height=self.height,
            youngs_modulus=self.youngs_modulus,
            shear_modulus=self.youngs_modulus / (2.0 * (1.0 + self.poisson)),
            mass_per_length=self.density * area,
            rotary_inertia=self.density * self.width * self.height**3 / 12.0,
            n_elements=n_elements,
        )  # fmt: skip
