"""One contact of a joint (:class:`Contact`): a slice of the spatial joint, the planar joint's
one slice, an end face, the spherical joint's ball, or a slider's corner against a wall.  One :meth:`Contact.response` (onset velocity, normal force,
friction; :mod:`.laws`) serves them all; the kind of contact decides the stiffness, the slip
that friction acts against and where the loads go.  The compiled kernel's ``contacts.hpp``."""
from __future__ import annotations

from collections.abc import Callable
from typing import Any, NamedTuple

from ...friction import FrictionLaw
from ...history import ContactState
from ...joint import ClearanceJoint
from ...spatial import ShoulderGeometry
from . import laws
from .kinematics import (
    V3,
    BallKinematics,
    BoxCornerKinematics,
    ContactKinematics,
    CornerKinematics,
    FaceKinematics,
    Kinematics,
    SliceKinematics,
    SlotKinematics,
    add_ball_loads,
    add_box_corner_loads,
    add_corner_loads,
    add_face_loads,
    add_slice_loads,
    friction_components,
    joint_loads,
)
from .laws import ContactResponse


class _Accepted(NamedTuple):
    """A contact's kinematics as :meth:`ContactState.accept` reads them; ``v_t`` is the slip
    the contact's friction acts against (and its output ``slip_velocity``)."""

    delta: float
    delta_dot: float
    ex: float
    ey: float
    v_t: float



class Contact:
    """One contact of a joint: its normal law ``normal_force(delta, delta_dot, v0)``, its
    share of it, and the joint's friction law.  Subclasses say which slip friction acts
    against and where the loads go (the compiled kernel's ``ContactKind``)."""

    def __init__(self, normal_force: Callable[[float, float, float], float], friction: FrictionLaw,
                 share: float = 1.0) -> None:
        self.normal_force, self.friction, self.share = normal_force, friction, share

    def slip(self, kin: Kinematics) -> float:
        """The slip [m/s] friction acts against: the signed circumferential ``v_t``."""
        return kin.v_t

    def accepted(self, kin: Kinematics) -> _Accepted:
        """What :meth:`response` and :meth:`ContactState.accept` read of this contact's kinematics."""
        return _Accepted(kin.delta, kin.delta_dot, kin.ex, kin.ey, self.slip(kin))

    def response(self, kin: _Accepted, history: ContactState) -> ContactResponse:
        """Forces of the contact state ``kin`` given its last accepted ``history``
        (:func:`exuclear.joint.contact_response`)."""
        return laws.contact_response(self.normal_force, self.friction, kin.delta, kin.delta_dot, kin.v_t, history,
                                self.share)

    def add_loads(self, loads: list[float], u: V3, kin: Any, r: ContactResponse) -> None:
        raise NotImplementedError


class PlanarSlice(Contact):
    """The planar joint's one slice: the whole law, friction along the tangent (eq. (20))
    against the signed slip ``v_T``.  Its kinematics and loads are those of a spatial slice
    for the motion projected on the plane normal to the axis, evaluated in the reduced form
    they take there, eqs. (1)-(8) and (24)-(26) (:func:`exuclear.geometry.contact_kinematics`,
    :func:`exuclear.geometry.joint_loads`): the planar joint keeps its results bit for bit
    (some scenes change course on a last-bit change of the force)."""

    def __init__(self, joint: ClearanceJoint) -> None:
        super().__init__(joint.law.normal_force, joint.friction)
        self.geometry = joint.geometry

    def add_loads(self, loads: list[float], u: V3, kin: ContactKinematics, r: ContactResponse) -> None:
        """``F = -F_i``, ``T = -M_i`` and the bearing's moment beyond ``T``, ``m_j + m_i``
        (the whole of it: no ``p x F`` is added for the planar joint)."""
        fx, fy, m_i, m_j = joint_loads(self.geometry, kin, r.f_n, r.f_t)
        loads[0] += -fx
        loads[1] += -fy
        loads[5] += -m_i
        loads[8] += m_j + m_i


class SlotSlice(PlanarSlice):
    """The pin-in-slot joint's one contact (:mod:`exuclear.slot`): the planar slice of a pin
    against the slot's nearest centre-segment point ``S``, whose loads on the slot gain the
    moment ``S x (-F_i)`` about the slot's centre."""

    def add_loads(self, loads: list[float], u: V3, kin: SlotKinematics, r: ContactResponse) -> None:
        super().add_loads(loads, u, kin, r)
        fy = -r.f_n * kin.ny + r.f_t * kin.nx  # F_i's y, eq. (24)
        loads[8] -= kin.segment * fy


class Slice(Contact):
    """A slice of the spatial joint: its share ``w / L`` of the law (eq. (41)), friction
    against the slip speed ``|v_s|``, along the slip (eq. (42))."""

    def __init__(self, joint: ClearanceJoint, share: float) -> None:
        super().__init__(joint.law.normal_force, joint.friction, share)
        self.r_j = joint.geometry.journal_radius

    def slip(self, kin: SliceKinematics) -> float:
        """The slip speed ``|v_s|`` of the contact points (eq. (42))."""
        return kin.speed

    def add_loads(self, loads: list[float], u: V3, kin: SliceKinematics, r: ContactResponse) -> None:
        f_t, f_a = friction_components(r.f_t, kin)                                        # eq. (42)
        add_slice_loads(loads, self.r_j, u, kin, r.f_n, f_t, f_a)


class Face(Contact):
    """An end face (docs/physics.md section 9.6): eq. (9) with the flat-punch stiffness
    ``K_f delta`` and the law's ``D`` and ``v_min`` (eq. (53)), friction against the
    circumferential slip at the friction radius, loads of eq. (54)."""

    def __init__(self, joint: ClearanceJoint, shoulders: ShoulderGeometry) -> None:
        law = joint.law
        self.k_face = shoulders.face_stiffness(law.E_star)                              # eq. (52)
        self.damping_factor, self.v_min = law.damping_factor, law.v_min
        self.friction_radius = shoulders.friction_radius                                # eq. (51)
        super().__init__(self._normal_force, joint.friction)

    def _normal_force(self, delta: float, delta_dot: float, v0: float) -> float:
        return laws.face_normal_force(self.k_face, self.damping_factor, self.v_min, delta, delta_dot, v0)

    def add_loads(self, loads: list[float], u: V3, kin: FaceKinematics, r: ContactResponse) -> None:
        add_face_loads(loads, self.friction_radius, u, kin, r.f_n, r.f_t)                # eq. (54)


class Ball(Contact):
    """The spherical joint's one contact, a ball in its socket (docs/physics.md section 13):
    the whole law, friction against the slip speed across the normal (eq. (96)), loads of
    eqs. (97), (98)."""

    def __init__(self, joint: ClearanceJoint) -> None:
        super().__init__(joint.law.normal_force, joint.friction)
        self.r_b = joint.geometry.inner_radius

    def add_loads(self, loads: list[float], u: V3, kin: BallKinematics, r: ContactResponse) -> None:
        add_ball_loads(loads, self.r_b, kin, r.f_n, r.f_t)                                 # eqs. (97), (98)


class Corner(Contact):
    """One corner-wall pair of the translational joint (:mod:`exuclear.prismatic`): the
    whole law, friction along the wall against the corner's signed slip ``v_t``, loads on
    the guide and the slider's moment about its centre."""

    def __init__(self, joint: ClearanceJoint) -> None:
        super().__init__(joint.law.normal_force, joint.friction)

    def add_loads(self, loads: list[float], u: V3, kin: CornerKinematics, r: ContactResponse) -> None:
        add_corner_loads(loads, kin, r.f_n, r.f_t)


class BoxCorner(Corner):
    """One corner-wall pair of the spatial translational joint (:mod:`exuclear.prismatic`):
    the whole law, friction against the corner's slip speed ``|v_s|`` over the wall, along
    the slip; loads on the guide and the slider's moment about its centre."""

    def add_loads(self, loads: list[float], u: V3, kin: BoxCornerKinematics, r: ContactResponse) -> None:
        add_box_corner_loads(loads, kin, r.f_n, r.f_t)
