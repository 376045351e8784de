"""The clearance joint's fields of the scenes, described once (exuclear.models._joint_fields)."""
from __future__ import annotations

import dataclasses
import typing

import pytest

from exuclear.models._joint_fields import JOINT_FIELDS, LENGTH_NAMES, joint_field, joint_fields, scene_joint, scene_params
from exuclear.models._params import check_fields, param, positive
from exuclear.models.four_bar import FourBarParams
from exuclear.models.journal_bearing import JournalBearingParams
from exuclear.models.misaligned_shaft import ShaftParams
from exuclear.models.slider_crank import SliderCrankParams

SCENES = (SliderCrankParams, FourBarParams, JournalBearingParams, ShaftParams)

#: Where a scene's help text says more than the shared one: which bearing it is.
OWN_HELP = {("FourBarParams", "bearing_radius"), ("JournalBearingParams", "viscosity"),
            ("ShaftParams", "bearing_radius"), ("ShaftParams", "length")}


@scene_params
class Toy:
    mass: float = dataclasses.field(metadata=param("mass [kg]", positive))
    _joint_fields = joint_fields("bearing_radius", "clearance", "bearing_length", help={"clearance": "gap [m]"})
    law: str = joint_field("law")
    cr: float = joint_field("cr")
    speed: float = dataclasses.field(default=1.0, metadata=param("speed [m/s]"))
    _more_joint_fields = joint_fields("v_min", "max_penetration")

    def __post_init__(self) -> None:
        check_fields(self)


def test_a_run_of_joint_fields_stands_where_it_is_written_with_its_types_and_defaults():
    names = [f.name for f in dataclasses.fields(Toy)]
    assert names == ["mass", "bearing_radius", "clearance", "bearing_length", "law", "cr", "speed", "v_min",
                     "max_penetration"]
    hints = typing.get_type_hints(Toy)
    assert hints["bearing_radius"] is float and hints["law"] is str and hints["max_penetration"] == float | None
    toy = Toy(mass=1.0, bearing_radius=10e-3, clearance=1e-4, bearing_length=15e-3, law="hertz", cr=1.0)
    assert toy.v_min == JOINT_FIELDS["v_min"].default and toy.max_penetration is None
    assert not hasattr(Toy, "_joint_fields") and dataclasses.is_dataclass(toy)
    with pytest.raises(dataclasses.FrozenInstanceError):
        toy.mass = 2.0
    meta = {f.name: f.metadata for f in dataclasses.fields(Toy)}
    assert meta["clearance"]["help"] == "gap [m]" and meta["bearing_length"]["option"] == "length"
    with pytest.raises(ValueError, match="`bearing_radius` must be positive"):
        dataclasses.replace(toy, bearing_radius=-1.0)
    assert scene_joint(toy).geometry.journal_radius == pytest.approx(10e-3 - 1e-4)
    with pytest.raises(ValueError, match="`clearance` must be smaller than `bearing_radius`"):
        scene_joint(dataclasses.replace(toy, clearance=0.02))


def test_unknown_names_and_fields_without_a_value_are_refused_where_the_class_is_written():
    with pytest.raises(KeyError, match="no joint field 'radius'"):
        joint_fields("radius")
    with pytest.raises(KeyError, match="help for"):
        joint_fields("law", help={"cr": "restitution"})
    with pytest.raises(TypeError, match="give the fields mass a value"):
        @scene_params
        class NoValue:
            mass: float
            _joint_fields = joint_fields("law")


@pytest.mark.parametrize("cls", SCENES, ids=lambda c: c.__name__)
def test_every_scene_s_joint_fields_are_the_shared_ones(cls):
    # the same help, rule, options and default in every scene; a scene's own help only where it names its bearing
    for f in dataclasses.fields(cls):
        if f.name not in JOINT_FIELDS and f.name not in LENGTH_NAMES:
            continue
        described = JOINT_FIELDS["length" if f.name in LENGTH_NAMES else f.name]
        assert f.metadata["check"] is described.check and f.metadata["cli"] == described.cli, f.name
        assert f.default is described.default or f.default == described.default, f.name
        if (cls.__name__, f.name) not in OWN_HELP:
            assert f.metadata["help"] == described.help, f.name
