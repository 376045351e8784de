"""The geometry a contact law reads of a joint's contact pair (:class:`ContactGeometry`).

A stiffness model needs the two surfaces' radii of curvature and, for a line contact, the
length along which they touch; nothing else of the joint.  Each joint type's geometry
(:class:`exuclear.geometry.BearingGeometry` of the revolute joint, a journal in its bore;
:class:`exuclear.spherical.SphereGeometry` of the spherical joint, a ball in its socket)
is one of these, so that one law library serves every type.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar


class ContactGeometry(ABC):
    """A convex body (radius ``inner_radius``) inside a conforming concave one (radius
    ``outer_radius``), SI units.

    ``joint_type`` names the joint type, for messages; ``length`` [m] is the length of a line
    contact (a cylinder in a bore), None for a point contact (a ball in a socket).
    """

    joint_type: ClassVar[str] = ""
    #: Length [m] of a line contact; None for a point contact (a field or property of each type).
    length: float | None

    @property
    @abstractmethod
    def inner_radius(self) -> float:
        """Radius [m] of the convex body (journal, ball)."""

    @property
    @abstractmethod
    def outer_radius(self) -> float:
        """Radius [m] of the concave body (bearing, socket)."""

    @property
    def clearance(self) -> float:
        """The radial clearance ``c = R_outer - R_inner`` [m]."""
        return self.outer_radius - self.inner_radius

    @property
    def relative_curvature(self) -> float:
        """``1/R_inner - 1/R_outer = c / (R_inner R_outer)`` [1/m], how much more the convex
        surface curves than the concave one (``1/R_inner`` against a flat)."""
        return self.clearance / (self.inner_radius * self.outer_radius)


def line_length(geometry: ContactGeometry, model: str) -> float:
    """The length of ``geometry``'s line contact, which the stiffness model ``model`` needs;
    ``ValueError`` naming the joint type where its contact is a point."""
    if geometry.length is None:
        raise ValueError(f"stiffness model {model!r} is a line-contact law and needs a contact length; the "
                         f"{geometry.joint_type} joint's contact is a point: use stiffness 'hertz' "
                         f"(e.g. law='hertz+lankarani-nikravesh')")
    return geometry.length
