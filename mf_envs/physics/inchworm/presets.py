"""A buildable inchworm: a soft PDMS-like body bent by Flexinol wires sized to the
moment they must deliver (`mf_envs.physics.actuators.sizing`). Numbers and their sources; not
the default robot of Inchworm-v0 (docs/inchworm.md, "A buildable robot", has the table).

The seed's section (E = 2.4 GPa, 20 x 10 mm) needs 52 N m for its full curvature kappa0# = 13 1/m
(thousands of wires) and a 6.5 % surface strain. Here the body is an elastomer, thin enough that
two wires hold its hump, and the wires sit close to the neutral axis so that their strain stays
inside the repeatable range. The curvature kappa L = 3.0 rad gives the published stride of a
third of the body (chord of a circular arc).
"""

from __future__ import annotations

from dataclasses import dataclass

from mf_envs.physics.actuators.sizing import WireSizing, size_wires
from mf_envs.physics.actuators.sma import FLEXINOL_HT, SMAAlloy, SMAWireParams
from mf_envs.physics.beam.contact.grip import GripFeetParams, GripLaw
from mf_envs.physics.inchworm.model import InchwormParams

# the feet's law for a robot crawling at mm/s (`grip.GripLaw`): regularisation speeds of the
# order of its foot speeds divided by 10 (sliding) and 100 (gripping): a gripping foot creeps
# ~1 % of the stroke, our choice; threshold 0.7, width 0.2 and the coefficients of `GripLaw`
V_SLIDE, V_GRIP = 5e-3, 5e-4  # m/s
GRIP_TIME = 0.5  # s: engage/release time constant, 3 tau ~ the 0.15 mm HT wire's 1.3 s relaxation

SOURCES = {
    "youngs_modulus": "Sylgard 184 bulk tension: 1.32-2.97 MPa by curing temperature (Johnston "
    "et al. 2014, J. Micromech. Microeng. 24 035017; abstract only); 1.5 MPa: a room-cured 10:1 "
    "mix, the low end",
    "density": "Sylgard 184 specific gravity ~1.03 (Dow data sheet; not verified here)",
    "poisson": "0.49, nearly incompressible elastomer (our choice)",
    "length": "calibrated: 50 mm, so that the fastest heat/cool gait crawls within 30 % of Wang "
    "et al. 2014's 3.6 mm/s (4.12 mm/s on the benchmark's seeds, +14 %; 60 mm gave 5.06, "
    "+41 %); their dimensions: full "
    "text not reached (abstract only), so the length is fitted to their speed, not measured",
    "section": "our choice: 10 x 3 mm",
    "kappa": "60 1/m (kappa L = 3.0 rad): a circular arc of that angle has a chord of 2/3 L, "
    "i.e. the kinematic stride of 1/3 body length Wang et al. 2014 report (abstract); chosen "
    "from the published stride, so the stride's agreement is partly by construction",
    "wire": "Flexinol HT 0.15 mm: 0.4 A for a 1 s contraction, 1.2 s cooling (Dynalloy F1140 "
    "wire table as quoted; mf_envs.physics.actuators.sma.FLEXINOL_WIRES)",
    "lever_arm": "our choice: 0.6 mm below the neutral axis, wire strain kappa e = 3 % inside "
    "the 2-6 % repeatable range (F1140)",
}


@dataclass(frozen=True)
class BuildableInchworm:
    """Body (SI units): length, width, height [m], Young's modulus [Pa], density [kg/m^3],
    Poisson ratio; target curvature kappa [1/m]; wires: diameter [m], lever arm [m] below the
    neutral axis, alloy. `SOURCES` says where each number comes from."""

    length: float = 0.05
    width: float = 0.010
    height: float = 0.003
    youngs_modulus: float = 1.5e6
    density: float = 1030.0
    poisson: float = 0.49
    kappa: float = 60.0
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

    def wire_group(self, n_groups: int, ambient: float = 20.0) -> SMAWireParams:
        """One of n_groups independently driven groups along the body (one per control
        point): the sized count of wires over a length L / n_groups."""
        s = self.sizing()
        return SMAWireParams(
            diameter=self.wire_diameter, length=self.length / n_groups, n_wires=s.count,
            alloy=self.alloy, strain_max=s.wire_strain, ambient=ambient,
            name="buildable inchworm body wires",
        )  # fmt: skip

    def grip_feet(self, grip_time: float = GRIP_TIME) -> GripFeetParams:
        """The feet (`grip.GripLaw` with V_SLIDE, V_GRIP; engage/release time grip_time [s])."""
        law = GripLaw(v_slide=V_SLIDE, v_grip=V_GRIP)
        return GripFeetParams(law, grip_time, grip_time)

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
