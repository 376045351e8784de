"""Contact history of a clearance joint: the state after each accepted time step.

Pure Python (no exudyn).  A :class:`ContactState` is immutable: :meth:`ContactState.accept`
returns the state after the next accepted step, and the record of a contact that ended
in it.  The engine keeps two of them per contact (at the start and at the end of the last
step) so that a step that is computed again starts from the right history.  The compiled
kernel (``exuclear/_kernel/contacts.hpp``) states the same rules in its
``History``, ``onset_velocity`` and ``accept``, in the same order, with mutable C++ structs
instead of immutable states; ``tests/test_connector.py`` keeps the two equal to round-off.

Onset velocity (docs/physics.md, section 2.3, eqs. (18)-(19)): ``v0`` is the penetration rate at the
instant ``delta`` crossed zero.  In the step where contact begins, ``delta`` goes from
``d0 <= 0`` (last accepted state) to ``d1 > 0`` (this state), and ``delta_dot`` is
interpolated linearly in ``delta`` to ``delta = 0``:
``v0 = dd0 + (dd1 - dd0) d0 / (d0 - d1)``.  This is exact when the contact starts at an
accepted state (``d0 = 0``, the journal-bearing scene), with an error of order
step^2 * acceleration otherwise.  The onset and end times are interpolated the same way.
"""
from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any, NamedTuple, get_type_hints

NO_STATE = float("-inf")  # ``delta`` before the first accepted state


class ImpactRecord(NamedTuple):
    """One contact, from onset to separation (SI units).

    ``onset_time`` and the end (``onset_time + duration``) are interpolated between the
    accepted steps around them; ``peak_force`` and ``max_penetration`` are the largest
    values at accepted steps.
    """

    onset_time: float
    onset_velocity: float
    peak_force: float
    duration: float
    max_penetration: float


class PairImpact(NamedTuple("_PairImpactFields", [*get_type_hints(ImpactRecord).items(), ("pair", str)])):
    """One contact of a joint with several contact pairs (the translational joint's corners
    against its walls): the :class:`ImpactRecord` fields, then ``pair``, the pair's name
    (``"corner front-lower / lower wall"``, :func:`exuclear.prismatic.pair_name`).  Read by
    name as an :class:`ImpactRecord` is."""

    __slots__ = ()


@dataclass(frozen=True)
class ContactState:
    """The contact history after an accepted state, and the joint's outputs there.

    ``time`` [s] of the state; ``delta``, ``delta_dot`` its penetration and rate
    (``delta = -inf``: no accepted state yet); ``in_contact`` and ``v0`` the current
    contact's onset velocity; ``onsets`` the contacts begun and ``closed`` those ended
    since the run began; ``onset_time``, ``peak_force`` and ``max_penetration`` describe
    the current (or last) contact; ``normal_force``, ``tangential_force``,
    ``slip_velocity``, ``ecc_x``, ``ecc_y`` are the outputs at this state; ``film_fx``,
    ``film_fy``, ``film_torque`` the film's force on the journal and its viscous moment on
    the journal there (a lubricated joint's; the kernel sets them, :meth:`accept` keeps 0).
    """

    time: float = 0.0
    delta: float = NO_STATE
    delta_dot: float = 0.0
    in_contact: bool = False
    v0: float = 0.0
    onsets: int = 0
    closed: int = 0
    onset_time: float = 0.0
    peak_force: float = 0.0
    max_penetration: float = 0.0
    normal_force: float = 0.0
    tangential_force: float = 0.0
    slip_velocity: float = 0.0
    ecc_x: float = 0.0
    ecc_y: float = 0.0
    film_fx: float = 0.0
    film_fy: float = 0.0
    film_torque: float = 0.0

    def onset_velocity(self, delta: float, delta_dot: float) -> float:
        """``v0`` for a state (``delta > 0``) of the coming step; no side effects."""
        if self.in_contact:
            return self.v0
        d0 = self.delta
        if d0 == NO_STATE:  # no accepted state yet: the joint starts in contact
            return delta_dot
        return self.delta_dot + (delta_dot - self.delta_dot) * d0 / (d0 - delta)

    def accept(self, kin: Any, joint: Any, time: float) -> tuple[ContactState, ImpactRecord | None]:
        """The state after accepting the contact kinematics ``kin`` at ``time``.

        ``joint`` (anything with ``response(kin, history)``: a :class:`exuclear.ClearanceJoint`,
        or a spatial slice or end face) gives the forces recorded as outputs.  Returns the
        new state and, when a contact ended in this step, its record.
        """
        delta, delta_dot = kin.delta, kin.delta_dot
        new = {}
        record = None
        if delta > 0.0:
            if not self.in_contact:
                d0 = self.delta
                share = d0 / (d0 - delta) if d0 != NO_STATE else 0.0
                new.update(v0=self.onset_velocity(delta, delta_dot), in_contact=True, onsets=self.onsets + 1,
                           onset_time=self.time + share * (time - self.time), peak_force=0.0, max_penetration=0.0)
        else:
            new["in_contact"] = False
            if self.in_contact:  # the contact ended within this step
                share = self.delta / (self.delta - delta)
                end = self.time + share * (time - self.time)
                record = ImpactRecord(self.onset_time, self.v0, self.peak_force, end - self.onset_time,
                                      self.max_penetration)
                new["closed"] = self.closed + 1
        if delta > 0.0:
            # from this state: in contact its v0, at an onset the same interpolation as new["v0"]
            response = joint.response(kin, self)
            f_n, peak, deepest = response.f_n, new.get("peak_force", self.peak_force), new.get("max_penetration",
                                                                                                  self.max_penetration)
            new.update(normal_force=f_n, tangential_force=response.f_t, peak_force=f_n if f_n > peak else peak,
                       max_penetration=delta if delta > deepest else deepest)
        else:
            new.update(normal_force=0.0, tangential_force=0.0)
        return replace(self, delta=delta, delta_dot=delta_dot, time=time, ecc_x=kin.ex, ecc_y=kin.ey,
                       slip_velocity=kin.v_t, **new), record


def merge_overlapping(records: list[ImpactRecord]) -> list[ImpactRecord]:
    """Physical impacts from the contacts of a spatial joint's slices: records whose
    intervals ``[onset_time, onset_time + duration]`` overlap (directly or through others)
    are one impact of the journal, which a tilted or aligned journal makes on several
    slices at once.  The merged record: the earliest onset and its onset velocity (the
    first slice to touch), the union of the intervals, the largest penetration, and as
    ``peak_force`` the sum of the slices' peak forces: the resultant's peak where the
    slices peak at one step (an aligned journal: exactly the planar joint's), an upper
    bound of it otherwise.  In onset order.
    """
    merged: list[ImpactRecord] = []
    end = -float("inf")
    for r in sorted(records, key=lambda r: r.onset_time):
        r_end = r.onset_time + r.duration
        if merged and r.onset_time <= end:
            m = merged[-1]
            end = max(end, r_end)
            merged[-1] = ImpactRecord(m.onset_time, m.onset_velocity, m.peak_force + r.peak_force,
                                      end - m.onset_time, max(m.max_penetration, r.max_penetration))
        else:
            merged.append(r)
            end = r_end
    return merged
