"""The floating GOWEC's gimbal loads and its supervisor: generator, brake, cushioned end stops.

ISWEC's gimbal (the PTO axis) has a bounded stroke: the gyroscope swings about the PTO shaft
inside end stops, and a supervisor takes the device out of production when the sea or the
motion leaves its operating range. Here, per gyro unit, on the gimbal angle phi (rad) and rate
phi' (rad/s):

    operating:  M_g = clip(tau + c phi' + k phi)        generator (`pto_torque`; harvested)
    survival:   M_g = 0, M_b = c_b phi'                  PTO unloaded, gimbal braked (heat)
    always:     tau_s = cushion (`physics.end_stops`) engaging at +-a_s

and Q_phi = -n (M_g + M_b - tau_s) on the gimbal coordinate (n units). The flywheels keep
spinning in survival (their motors hold psi'). A stroke of a_s + d_max: the cushion is sized
(`end_stops.size_cushion`) to stop the gimbal within d_max; passing it is a physical failure
(the env ends the episode). The supervisor (`supervise`, once per control step) holds a timer
(s) in the state: a tilt |theta| or |rho| above the survival tilt or the gimbal in its cushion
(|phi| > a_s) puts the device in survival for `hold` s (re-armed while the trigger lasts);
the env latches it for the episode (`SURVIVAL_LATCHED`) when the sea is beyond the device's
operating range.
"""

from __future__ import annotations

import math

from mf_envs._jit import kernel
from mf_envs.physics.end_stops import cushion_torque

# the packed PTO vector `pto` (FloatingParams.pto): gains, drive limits, efficiencies, then the
# end stops (a_s rad, k_s N m/rad, c_s N m s/rad, the stroke a_s + d_max rad), the survival
# brake (c_b N m s/rad), the survival tilt (rad) and hold time (s)
(PTO_C, PTO_K, PTO_TMAX, PTO_PMAX, PTO_ETA_G, PTO_ETA_M, PTO_STOP, PTO_KS, PTO_CS, PTO_STROKE,
 PTO_BRAKE, PTO_TILT, PTO_HOLD) = range(13)  # fmt: skip
N_PTO = 13
SURVIVAL_LATCHED = 1.0e9  # s: the supervisor's timer for "the whole episode"


@kernel(forceinline=True)
def pto_torque(phi, phid, tau, pto):
    """M_g (N m): tau + c phi' + k phi, clipped to the torque limit and to |M_g phi'| <= P_max."""
    m = tau + pto[0] * phid + pto[1] * phi
    lim = pto[2]
    if abs(phid) * lim > pto[3]:
        lim = pto[3] / abs(phid)
    return min(max(m, -lim), lim)


@kernel(forceinline=True)
def gimbal_loads(phi, phid, tau, pto, survival):
    """(M_g generator, M_b brake, tau_s end stops) in N m on one gimbal (module doc); M_g and
    M_b resist phi' when positive, tau_s acts along phi."""
    if survival:
        mg, mb = 0.0, pto[PTO_BRAKE] * phid
    else:
        mg, mb = pto_torque(phi, phid, tau, pto), 0.0
    ms = cushion_torque(phi, phid, pto[PTO_STOP], pto[PTO_KS], pto[PTO_CS])
    return mg, mb, ms


@kernel(forceinline=True)
def stop_dissipation(phi, phid, ms, pto):
    """Power (W) the cushion of one gimbal dissipates: its work rate -tau_s phi' less the rate
    of change of its spring's energy k_s d d' (`end_stops.cushion_spring_energy`)."""
    d = abs(phi) - pto[PTO_STOP]
    spring = pto[PTO_KS] * d * (phid if phi > 0.0 else -phid) if d > 0.0 else 0.0
    return -ms * phid - spring


@kernel(forceinline=True)
def supervise(timer, theta, rho, phi, dtc, pto):
    """The supervisor's timer (s) after a control step of dtc (s) ending at the tilt (theta,
    rho) and gimbal angle phi (rad) (module doc): re-armed to the hold time on a trigger,
    else counted down to 0."""
    if max(abs(theta), abs(rho)) > pto[PTO_TILT] or abs(phi) > pto[PTO_STOP]:
        return max(timer, pto[PTO_HOLD])
    return max(timer - dtc, 0.0)


def stiffest_rate(pto, gimbal_inertia: float) -> float:
    """The fastest linear rate (1/s) of the gimbal's loads on a gimbal + rotor inertia I_g
    (kg m^2): the PTO's and the brake's and the cushion's damping c / I_g and 4 x the PTO's
    and the cushion's sqrt(k / I_g); explicit RK4 stays stable and accurate with rate dt <= 2
    (the env's substep)."""
    ig = gimbal_inertia
    damping = max(pto[PTO_C], pto[PTO_BRAKE], pto[PTO_CS]) / ig
    return max(damping, 4.0 * math.sqrt(max(abs(pto[PTO_K]), pto[PTO_KS]) / ig))


def pto_vector(fields: dict) -> list[float]:
    """The packed PTO vector (N_PTO,) from a dict of `model.PTO_FIELDS` (stops, brake and
    supervisor default to none: no stops, no stroke, survival never triggered)."""
    off = dict(stop_angle=math.inf, stop_stiffness=0.0, stop_damping=0.0, stroke=math.inf,
               brake_damping=0.0, survival_tilt=math.inf, survival_hold=0.0)  # fmt: skip
    return [float(fields.get(k, off.get(k))) for k in PTO_NAMES]


PTO_NAMES = ("damping", "stiffness", "max_torque", "max_power", "eta_generator", "eta_motor",
             "stop_angle", "stop_stiffness", "stop_damping", "stroke", "brake_damping",
             "survival_tilt", "survival_hold")  # fmt: skip
