"""A joint type's contact as the impulse contact mode sees it (:mod:`~exuclear.engine.impulse`).

The mode holds one contact: the centre of the inner body (the journal's, the ball's, the
pin's) at an eccentricity ``e`` from the nearest point of the outer body's centre locus
(the bearing's axis, the socket's centre, the slot's centre segment), touching where
``|e|`` reaches the clearance ``c``.  Its normal is ``e / |e|``, its gap (penetration)
``|e| - c``, and the rate of the gap ``n . (v_1 - v_0(S))``, the inner centre's velocity
against that of the outer body's point ``S`` at the locus (a point of the slot's segment
slides along the segment, across the normal, so the gap's rate is that of the body's
material point there).  A joint type is what gives ``e`` and ``S``; the mode's decisions
(impacts, resting, the normal's turn along the wall) do not know the type:

- ``"revolute"`` (planar): ``e`` the journal's centre minus the bearing's, in the bearing's
  plane (its part along the axis taken out); ``S`` the bearing's centre;
- ``"spherical"``: ``e`` the ball's centre minus the socket's, in 3D (docs/physics.md
  section 13); ``S`` the socket's centre;
- ``"pin-slot"``: ``e`` the pin's centre minus the slot's centre-segment point nearest to it
  (:func:`exuclear.slot.segment_point`), in the plane; ``S`` that point, which is fixed at
  an end centre while the pin rolls around the end cap and the normal turns;
- a slice of the spatial revolute joint (:class:`SlicePair`, one of the joint's several
  contacts, :mod:`~exuclear.engine.impulse_group`): ``e`` the journal axis's crossing of the
  slice's plane minus the bearing axis's point there, ``S``;
- an end face of the spatial revolute joint (:class:`FacePair`, two more of its contacts):
  ``e`` along the face's normal, the bearing axis, whose length less ``reach`` is the
  shoulder's axial penetration; ``S`` the bearing's point at the shoulder's centre.

A pair also says where its friction acts (:mod:`~exuclear.engine.impulse_friction`):
``plane``, the normal (in marker 0's frame) of the plane a planar contact slides in, whose
tangent is ``t = n x plane`` (None: a ball's or a box corner's, whose slip has a tangent
plane), and
``radius``, the inner body's radius at the contact (the journal's, the pin's; 0 for a
corner), which puts the contact point ``radius n`` beyond the inner centre.

The markers' state is read through Exudyn's marker outputs (position and rotation of the
two rigid markers, :class:`~exuclear.engine.condition.Poses`), so any body with a rigid
marker takes the mode.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar, NamedTuple, Protocol

import numpy as np

from ..contact.law import ContactLaw
from ..contact.pair import ContactGeometry
from ..slot import segment_point
from ..vectors import V3, dot
from .condition import Poses


class Eccentricity(NamedTuple):
    """The contact's eccentricity ``e`` [m] (global, 3 components) and the arm [m] (global)
    from marker 0's point to the outer body's point ``S`` that ``e`` starts from (None where
    ``S`` is marker 0's point); ``inner_arm`` the arm from marker 1's point to the inner
    body's point that touches (None: marker 1's point, the centre of a journal, ball or pin);
    ``wall`` False where no wall lies under that point (a corner beyond a finite guide's end,
    :mod:`~exuclear.engine.impulse_guide`): the pair is open, whatever ``e``."""

    e: np.ndarray
    arm: np.ndarray | None
    inner_arm: np.ndarray | None = None
    wall: bool = True


class ContactPair(Protocol):
    """What the mode reads of a joint type (module docstring): ``reach`` [m], the ``|e|`` at
    which the bodies touch, and ``clearance`` [m], the play, the length the mode's
    tolerances on the gap are shares of (both the joint's clearance ``c`` for a centre in
    its clearance); for its friction ``plane`` (unit, marker 0's frame, or None) and
    ``radius`` [m]."""

    reach: float
    clearance: float
    radius: float
    #: the rotation matrices of markers [outer, inner] it reads
    rotations: ClassVar[tuple[bool, bool]]

    @property
    def plane(self) -> np.ndarray | None:
        """The normal of the plane the contact slides in, in marker 0's frame (None: a tangent plane)."""

    def eccentricity(self, poses: Poses) -> Eccentricity:
        """At the markers' ``poses`` [outer, inner]."""


def contact_arms(pair: ContactPair, normal: np.ndarray, ecc: Eccentricity) -> tuple[np.ndarray, np.ndarray]:
    """The arms (global) from the two markers' points to the contact points, where friction
    acts and slip is measured: on the outer body ``S + (reach + radius) n`` (the wall's point,
    the bearing's at ``R_B n`` from its centre), on the inner body ``radius n`` from its
    centre (the journal's or pin's surface; a corner itself), eq. (8)'s points."""
    outer = (pair.reach + pair.radius) * normal
    inner = pair.radius * normal
    return (outer if ecc.arm is None else ecc.arm + outer), (inner if ecc.inner_arm is None else ecc.inner_arm + inner)


@dataclass(frozen=True)
class _CentrePair:
    """A centre in its clearance ``clearance`` [m], touching at ``|e| = clearance``; the
    inner body's radius ``radius`` [m]."""

    clearance: float
    radius: float

    @property
    def reach(self) -> float:
        return self.clearance


@dataclass(frozen=True)
class PlanarPair(_CentrePair):
    """A journal in its bearing: ``axis`` the bearing axis (unit) in marker 0's frame."""

    body: ClassVar[str] = "journal"
    rotations: ClassVar[tuple[bool, bool]] = (True, False)

    axis: np.ndarray

    @property
    def plane(self) -> np.ndarray:
        return self.axis

    def eccentricity(self, poses: Poses) -> Eccentricity:
        (p0, p1), (rotation, _) = poses
        axis = rotation @ self.axis
        e = p1 - p0
        return Eccentricity(e - (e @ axis) * axis, None)

    def centre_offset(self, d: list[float], rotation: list[float] | None) -> tuple[V3, float]:
        """``e`` (as :meth:`eccentricity`) and the axial offset ``d . axis`` [m] from the
        markers' relative position ``d = p1 - p0`` and marker 0's rotation matrix (9 numbers,
        by rows), on floats."""
        a, r = self.axis, rotation
        axis = (r[0] * a[0] + r[1] * a[1] + r[2] * a[2], r[3] * a[0] + r[4] * a[1] + r[5] * a[2],
                r[6] * a[0] + r[7] * a[1] + r[8] * a[2])
        axial = dot(d, axis)
        return (d[0] - axial * axis[0], d[1] - axial * axis[1], d[2] - axial * axis[2]), axial


@dataclass(frozen=True)
class BallPair(_CentrePair):
    """A ball in its socket: no projection."""

    body: ClassVar[str] = "ball"
    plane: ClassVar[None] = None  # a ball slides in its tangent plane
    rotations: ClassVar[tuple[bool, bool]] = (False, False)

    def eccentricity(self, poses: Poses) -> Eccentricity:
        p0, p1 = poses.positions
        return Eccentricity(p1 - p0, None)

    def centre_offset(self, d: list[float], rotation: None) -> tuple[V3, float]:
        """``e`` (as :meth:`eccentricity`) from the markers' relative position ``d = p1 - p0``;
        no axial offset."""
        return (d[0], d[1], d[2]), 0.0


@dataclass(frozen=True)
class SlotPair(_CentrePair):
    """A pin in its slot: ``frame`` the joint frame in marker 0's frame (columns: x along
    the slot, z the plane's normal), ``half_length`` [m] half the distance of the slot's end
    centres."""

    body: ClassVar[str] = "pin"
    rotations: ClassVar[tuple[bool, bool]] = (True, False)

    frame: np.ndarray
    half_length: float

    @property
    def plane(self) -> np.ndarray:
        return self.frame[:, 2]

    def eccentricity(self, poses: Poses) -> Eccentricity:
        (p0, p1), (rotation, _) = poses
        frame = rotation @ self.frame  # the slot's frame, global
        px, py, _ = frame.T @ (p1 - p0)  # the pin's centre in the slot's frame (its part along z out)
        sx = segment_point(float(px), self.half_length)
        return Eccentricity(frame @ np.array([px - sx, py, 0.0]), sx * frame[:, 0])


@dataclass(frozen=True)
class SlicePair(_CentrePair):
    """A slice of a spatial journal in its bearing (docs/physics.md section 9): the journal's
    axis where it crosses the slice's plane ``z`` [m] along the bearing axis, against the
    bearing axis's point there.  ``frame`` the joint frame in marker 0's frame (z the bearing
    axis), ``journal_axis`` the journal's axis in marker 1's frame, ``name`` the slice's,
    ``share`` its share ``w / L`` of the law (eq. (41)), ``axial`` whether its friction
    acts along the axis too (:attr:`plane`);
    ``S`` the bearing axis's point at ``z``, the inner body's point the crossing, at ``s u``
    from marker 1's point (eq. (35): ``s = (z - p . a) / (u . a)``)."""

    frame: np.ndarray
    journal_axis: np.ndarray
    z: float
    name: str
    share: float
    axial: bool = True
    rotations: ClassVar[tuple[bool, bool]] = (True, True)

    @property
    def plane(self) -> np.ndarray | None:
        """None: the slice slides in its tangent plane, around and along the axis, as the
        compliant slice's friction acts against both (docs/physics.md eq. (42)); the
        bearing's axis where the model holds the journal axially (``axial`` False:
        ``constrainAxial``), whose friction is then circumferential, ``t = n x a`` (a
        sticking condition along the axis would repeat the model's constraint, a singular
        matrix for Newton)."""
        return None if self.axial else self.frame[:, 2]

    def eccentricity(self, poses: Poses) -> Eccentricity:
        (p0, p1), (rotation, turned) = poses
        axis = rotation @ self.frame[:, 2]
        u = turned @ self.journal_axis
        p = p1 - p0
        s = (self.z - p @ axis) / (u @ axis)
        crossing = p + s * u
        return Eccentricity(crossing - self.z * axis, self.z * axis, s * u)

    def contact_name(self, poses: Poses) -> str:
        return self.name

    @property
    def body(self) -> str:
        return f"journal's {self.name}"

    #: the slice's law is the joint's, at its share
    law: ClassVar[None] = None


@dataclass(frozen=True)
class FacePair:
    """A shoulder of a spatial journal against the bearing's end face ``side`` (-1: the face
    at ``z = -L/2``, +1: at ``+L/2``; docs/physics.md section 9.6).  ``frame`` the joint
    frame in marker 0's frame (z the bearing axis ``a``), ``journal_axis`` ``u`` in marker 1's
    frame, ``length`` L [m] the bearing's, ``clearance`` g [m] the axial play, ``name`` the
    face's, ``law`` the face's own: the flat punch ``K_f delta`` (eq. (52)) with the joint
    law's damping, which gives the joint law's restitution (eq. (53)).

    The shoulder's centre is ``c_f = p + s_f u``, ``s_f = f (L + g) / 2`` (eq. (48)), its
    penetration ``delta_f = L/2 - f c_f . a`` (eq. (49)); the normal is ``-f a`` (the face's,
    into the bearing) and ``e = (reach + delta_f) (-f a)``, ``reach`` a length that keeps
    ``|e|`` positive, so that the mode's gap ``|e| - reach`` is ``delta_f`` and its rate
    ``-f a . (v_1(c_f) - v_0(c_f))``, eq. (50)'s.  Its friction acts on the journal's spin at
    the friction radius ``friction_radius`` R_e [m] (eq. (51)), a couple
    (:class:`~exuclear.engine.impulse_friction.SpinFriction`)."""

    frame: np.ndarray
    journal_axis: np.ndarray
    length: float
    clearance: float
    side: int
    name: str
    law: ContactLaw
    friction_radius: float
    share: ClassVar[float] = 1.0
    radius: ClassVar[float] = 0.0
    plane: ClassVar[None] = None
    rotations: ClassVar[tuple[bool, bool]] = (True, True)

    @property
    def reach(self) -> float:
        """``L + 2 g``: ``|e| = L + 2 g + delta_f`` stays above ``L + g`` (``delta_f >= -g``
        for an aligned journal), away from 0 where a normal ``e / |e|`` is lost."""
        return self.length + 2.0 * self.clearance

    def eccentricity(self, poses: Poses) -> Eccentricity:
        (p0, p1), (rotation, turned) = poses
        axis = rotation @ self.frame[:, 2]
        s = self.side * 0.5 * (self.length + self.clearance)        # eq. (48)
        arm = s * (turned @ self.journal_axis)
        centre = p1 - p0 + arm                                      # c_f, from the bearing's centre
        delta = 0.5 * self.length - self.side * float(centre @ axis)  # eq. (49)
        return Eccentricity((self.reach + delta) * -self.side * axis, centre, arm)

    def spin_axis(self, ecc: Eccentricity) -> np.ndarray:
        """The journal's axis ``u`` (global) at the state of ``ecc`` (its inner arm ``s_f u``)."""
        return ecc.inner_arm / (self.side * 0.5 * (self.length + self.clearance))

    def contact_name(self, poses: Poses) -> str:
        return self.name

    @property
    def body(self) -> str:
        return f"journal's shoulder at the {self.name}"


#: The pair of each joint type the mode holds, from the type's geometry and the joint frame
#: (columns: the joint's axes) in marker 0's frame.
PAIRS: dict[str, Callable[[Any, np.ndarray], ContactPair]] = {
    "revolute": lambda geometry, frame: PlanarPair(geometry.clearance, geometry.journal_radius, frame[:, 2].copy()),
    "spherical": lambda geometry, frame: BallPair(geometry.clearance, geometry.ball_radius),
    "pin-slot": lambda geometry, frame: SlotPair(geometry.clearance, geometry.journal_radius, frame.copy(),
                                                    0.5 * geometry.slot_length),
}


def contact_pair(geometry: ContactGeometry, frame: np.ndarray) -> ContactPair:
    """The pair (:data:`PAIRS`) of a joint of ``geometry``'s type whose joint frame is
    ``frame`` in marker 0's frame."""
    return PAIRS[geometry.joint_type](geometry, np.asarray(frame, dtype=float))
