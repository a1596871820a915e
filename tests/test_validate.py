"""`_validate.check_fields`: the table-driven check the parameter dataclasses share."""

from dataclasses import dataclass

import pytest

from mf_envs._validate import check_fields
from mf_envs.physics.actuators.curvature import ActuatorParams
from mf_envs.physics.beam.contact.friction import FrictionParams
from mf_envs.physics.ship.drive import DriveParams


@dataclass(frozen=True)
class _Params:
    a: float = 1.0
    b: float = 0.0
    c: float = -1.0


def test_each_kind_names_the_field():
    check_fields(_Params(), positive=("a",), nonnegative=("a", "b"), finite=("a", "b", "c"))
    with pytest.raises(ValueError, match=r"^b: must be > 0, got 0\.0$"):
        check_fields(_Params(), positive=("a", "b"))
    with pytest.raises(ValueError, match=r"^c: must be >= 0"):
        check_fields(_Params(), nonnegative=("b", "c"))
    with pytest.raises(ValueError, match=r"^a: must be finite"):
        check_fields(_Params(a=float("nan")), finite=("a",))


def test_checks_run_in_the_order_given_and_the_label_names_the_public_parameter():
    bad = _Params(a=-1.0, b=-1.0)
    with pytest.raises(ValueError, match=r"^b: "):
        check_fields(bad, nonnegative=("b",), positive=("a",))
    with pytest.raises(ValueError, match=r"^gains\['a'\]: must be > 0"):
        check_fields(bad, label="gains['{}']", positive=("a",))
    with pytest.raises(TypeError, match="bounded"):
        check_fields(bad, bounded=("a",))


@pytest.mark.parametrize(
    ("cls", "kwargs", "message"),
    [
        (FrictionParams, {"slide_backward": -0.1}, "friction_coefficients['slide_backward']"),
        (FrictionParams, {"release_time": 0.0}, "grip_time_constant"),
        (ActuatorParams, {"rate_limit": -1.0}, "actuator_rate_limit"),
        (DriveParams, {"stop_damping": -1.0}, "stop_damping"),
        (DriveParams, {"bandwidth": 0.0}, "bandwidth"),
    ],
)
def test_dataclasses_still_name_their_public_parameter(cls, kwargs, message):
    with pytest.raises(ValueError) as err:
        cls(**kwargs)
    assert str(err.value).startswith(message + ":")
