"""The seam between joint types: laws over a contact geometry, the parameter matrix's joint type."""
from __future__ import annotations

import math
from dataclasses import dataclass

import pytest

from exuclear.contact import STIFFNESS_MODELS, contact_law
from exuclear.contact.pair import ContactGeometry
from exuclear.engine.layout import FIELDS, JOINT_TYPE_CODES, parameters, read
from exuclear.geometry import BearingGeometry
from exuclear.joint import make_joint

E_STAR = 1.15e11  # steel on steel [Pa]


@dataclass(frozen=True)
class _Point(ContactGeometry):
    """A point contact of two radii, as a joint type without a length declares it."""

    r_in: float
    r_out: float
    joint_type = "test-point"
    length = None

    @property
    def inner_radius(self) -> float:
        return self.r_in

    @property
    def outer_radius(self) -> float:
        return self.r_out


def test_hertz_takes_the_radii_of_any_contact_geometry():
    # docs/physics.md eq. (13): K = 4/3 E* sqrt(R_o R_i / (R_o - R_i)), the same for a bore and a point
    law = contact_law("hertz", _Point(9.9e-3, 10e-3), E_STAR)
    k = 4.0 / 3.0 * E_STAR * math.sqrt(10e-3 * 9.9e-3 / (10e-3 - 9.9e-3))
    assert law.stiffness_model.k0 == pytest.approx(k, rel=1e-14)  # the same formula: round-off only
    bore = contact_law("hertz", BearingGeometry(9.9e-3, 10e-3, 15e-3), E_STAR)
    assert bore.stiffness_model.k0 == law.stiffness_model.k0  # the length does not enter Hertz's point contact


@pytest.mark.parametrize("model", sorted(set(STIFFNESS_MODELS) - {"hertz"}))
def test_line_contact_models_refuse_a_point_contact_naming_the_joint_type(model):
    with pytest.raises(ValueError, match=rf"{model}.*line-contact.*test-point joint's contact is a point.*hertz"):
        contact_law(f"{model}+lankarani-nikravesh", _Point(9.9e-3, 10e-3), E_STAR, cr=0.9)


def test_the_parameter_matrix_carries_the_joint_type_and_the_pair_radii():
    joint = make_joint(journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, law="wang-liu", cr=0.9)
    p = parameters(joint, 0, 0, 1e-4)
    assert read(p, "joint_type") == JOINT_TYPE_CODES["revolute"]
    assert (read(p, "inner_radius"), read(p, "outer_radius")) == (9.9e-3, 10e-3)
    assert "token" not in FIELDS  # the handle's mark lives in the connector's damping matrix (layout.TOKEN_ENTRY)
