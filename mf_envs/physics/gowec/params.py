"""Parameters of one GOWEC gyroscope (Rios 2017 ch. 3 Sec. 3.2): a frozen SI dataclass."""

from __future__ import annotations

from dataclasses import dataclass

from mf_envs._validate import check_finite, check_nonnegative, check_positive, check_shape
from mf_envs.physics.constants import RPM


@dataclass(frozen=True)
class GOWECParams:
    """Inertias (kg m^2) and rotor speed (rad/s) of one gyroscope of the GOWEC.

    Defaults: Seakeeper 26 (Table 3-1: H = 26000 N m s at 5000 rpm, so Ja = H / psi'), thin disk
    (Jt = Ja/2, Eq. 79), gimbal inertia about its axes `gimbal_inertia` (used when the
    `gimbal_inertia` effect is on).
    """

    rotor_inertia: float = 26000.0 / (5000.0 * RPM)  # Ja = J3^(3), kg m^2
    rotor_speed: float = 5000.0 * RPM  # psi', rad/s
    rotor_transverse_inertia: float | None = None  # Jt = J1^(3) = J2^(3); None = Ja/2
    gimbal_inertia: tuple[float, float, float] = (5.0, 5.0, 5.0)  # (Jg1, Jg2, Jg3), kg m^2

    def __post_init__(self) -> None:
        check_positive("rotor_inertia", self.rotor_inertia)
        check_finite("rotor_speed", self.rotor_speed)
        if self.rotor_transverse_inertia is not None:
            check_positive("rotor_transverse_inertia", self.rotor_transverse_inertia)
        check_nonnegative(
            "gimbal_inertia", check_shape("gimbal_inertia", self.gimbal_inertia, (3,))
        )

    @property
    def transverse(self) -> float:
        """Jt (kg m^2): rotor inertia about a diameter."""
        r = self.rotor_transverse_inertia
        return 0.5 * self.rotor_inertia if r is None else float(r)

    @property
    def angular_momentum(self) -> float:
        """H = Ja psi' (N m s)."""
        return self.rotor_inertia * self.rotor_speed
