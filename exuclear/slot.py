"""A pin in a slot: the pin-in-slot clearance joint's contact (Skrinjar, Slavic, Boltezar,
Nonlinear Dyn. 88 (2017) 131-143: the slot as a stadium-shaped hole).

Pure Python, no exudyn, plain float arithmetic (it runs inside the force callback; the
compiled kernel ``exuclear/_kernel/kinematics.hpp`` and ``contacts.hpp`` write the same
formulas in the same order, with the same names).  The joint is planar, in the slot's joint
frame J0: ``x`` along the slot, ``z`` normal to the plane of motion.

A slot of width ``W`` whose end centres lie ``slot_length`` apart along x is the set of
points within ``W/2`` of its centre segment ``[-a, a] x {0}``, ``a = slot_length / 2``.  The
pin (radius ``R_P``) touches it where its centre is farther than ``W/2 - R_P`` from the
segment: one formula for the flat sides and the round ends.  The pair is the pin's centre
``p`` against the segment's nearest point ``S = (clamp(p_x, -a, a), 0)``, and its
kinematics are the revolute joint's (:func:`exuclear.geometry.contact_kinematics`, eqs.
(1)-(8)) of a journal of radius ``R_P`` in a bearing of radius ``W/2`` centred at ``S``:
``delta = |p - S| - (W/2 - R_P)``.  ``S`` moves with the slot, so the slot's spin ``w_j``
adds ``w_j x S`` to the slot's velocity there; its load's moment about the slot's centre
gains ``S x F``.  At ``slot_length = 0``, ``S`` is the centre and the joint is the
revolute clearance joint, to the last bit.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar, NamedTuple, get_type_hints

from .checks import check_nonnegative
from .geometry import BearingGeometry, ContactKinematics, contact_kinematics


@dataclass(frozen=True)
class SlotGeometry(BearingGeometry):
    """A pin of radius ``journal_radius`` (R_P) in a slot of width ``2 bearing_radius`` (W)
    whose end centres lie ``slot_length`` [m] apart; ``length`` is the pin's length in
    contact (the line-contact stiffness models read it), SI units."""

    slot_length: float = 0.0
    joint_type: ClassVar[str] = "pin-slot"

    def __post_init__(self) -> None:
        super().__post_init__()
        check_nonnegative("slot_length", self.slot_length)


class SlotKinematics(NamedTuple("_SlotFields", [*get_type_hints(ContactKinematics).items(), ("segment", float)])):
    """The revolute joint's :class:`~exuclear.geometry.ContactKinematics` of the pin against
    the segment's nearest point (its fields, read by the same names), then that point's
    position ``segment`` along x [m] (``ecc_x``, ``ecc_y`` are ``p - S``)."""

    __slots__ = ()


def segment_point(px: float, half_length: float) -> float:
    """The position along x [m] of the centre segment's point nearest to a pin centre at
    ``px`` [m]: ``S_x = clamp(p_x, -a, a)``, ``a = half_length`` (module docstring)."""
    return min(max(px, -half_length), half_length)


def slot_kinematics(geometry: BearingGeometry, half_length: float, px: float, py: float, dvx: float, dvy: float,
                    omega_i: float, omega_j: float) -> SlotKinematics:
    """The pin at ``(px, py)`` with relative velocity ``(dvx, dvy)`` in the slot of half-length
    ``half_length`` (module docstring); ``omega_i``, ``omega_j`` the pin's and the slot's spin."""
    sx = segment_point(px, half_length)                        # the segment's nearest point
    # the slot's point S moves at w_j x S = (0, w_j sx) relative to its centre
    kin = contact_kinematics(geometry, px, py, dvx, dvy, omega_i, sx, 0.0, 0.0, omega_j * sx, omega_j)
    return SlotKinematics(*kin, sx)
