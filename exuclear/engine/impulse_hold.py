"""A held contact of the impulse contact mode through a native Exudyn constraint
(:mod:`~exuclear.engine.impulse`): where the contact is a centre distance (the planar
revolute joint's journal, the spherical joint's ball: :data:`NATIVE_PAIRS`) and the joint has
no friction, a resting or sliding contact is an ``ObjectConnectorDistance`` between the two
markers, ``|p_1 - p_0| = d``, switched on with ``activeConnector``.

Exudyn forms its Jacobian in C++ at each Newton iterate, at the step's end: the rows the
velocity-level condition (:mod:`~exuclear.engine.condition`) has to probe coordinate by
coordinate and predict for the step's end, and compute again where the journal slid further
than predicted, come at no cost from Python.  The constraint is at position level (index 3):
under generalized-alpha with spectral radius 1 it keeps ``|e|`` at ``d`` at each step's end,
which with the trapezoidal rule keeps the normal rate's mean over each step at
``(d_1 - d_0) / h``; a normal rate at the hold's start alternates in sign from step to step
after it, and with it the multiplier (docs/design/native_hold.md).

The distance starts at the eccentricity the hold's onset step reached (the velocity-level
condition holds the onset step, which carries the approach's impulse), not at the clearance:
that would push out in one step the penetration the onset left.  From then on it takes back
:data:`~exuclear.engine.impulse.RATE_GAIN` of what is left of that penetration each step, the
velocity-level hold's share, so the journal ends on its wall.  Each step's distance is set
from the normal rate the step before ended at, measured: a normal rate the state carries
(a step-size change, the settling's filters, a joint's curvature) is then taken out in the
next step, as the velocity-level condition does, instead of alternating from step to step
(docs/design/native_hold.md).

The planar journal's eccentricity is in the bearing's plane and the constraint's distance is
in 3D: the hold applies while the axial offset of the markers is below :data:`AXIAL_SHARE` of
the clearance (a planar model's, or one held axially), else the velocity-level condition
holds the contact.  It applies between rigid bodies in a system the settling acts on, every
step of it settled (unsettled, its multiplier alternates by more than the reaction), and
hands the contact to the velocity-level condition where its multiplier rings
(:data:`HAND_OVER`).
"""
from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import exudyn as exu
from exudyn.itemInterface import ObjectConnectorDistance, VObjectConnectorDistance

from ..vectors import norm
from .bodies import coordinate_owner
from .condition import request_jacobian, scalar_force
from .settling import RIGID_BODIES

#: The pair types (:mod:`~exuclear.engine.impulse_pairs`) whose contact is a centre distance.
NATIVE_PAIRS = frozenset({"PlanarPair", "BallPair"})
#: The largest axial offset, as a share of the clearance, at which the 3D distance holds a
#: planar journal: the in-plane gap then differs from the distance's by at most half its
#: square (5e-13 of the clearance), and the constraint's axial force is that share of its
#: normal force.
AXIAL_SHARE = 1e-6


#: A hold whose multiplier rings, its ring (a quarter of its second difference from step to
#: step where that changes sign: the amplitude of an alternation) beyond this share of its
#: three-step mean at a step Exudyn shortened or after growing (:data:`RING_GROWTH`), hands
#: the contact to the velocity-level condition: an oscillation the trapezoidal rule keeps
#: undamped (in the zoo's 3D four-bar, whose clearance joint closes the loop, one of five to
#: six steps a period grew from about 1 % to more than the reaction over 400 held steps, and
#: the contact was let go; docs/design/native_hold.md).  Settled, a sliding held journal's
#: multiplier alternates by less than 2e-5 m g (``python -m validation.cost native_hold``).
HAND_OVER = 0.25
#: The held steps over which the ring's size is its largest.  A journal rocking on its wall
#: rings its multiplier without growing (the four-bar kinematic tree beyond the zoo: by up to
#: 0.9 of a mean of 50 N from the three-step mean, some six steps a period); a window of
#: several such periods keeps their size.
RING_STEPS = 32
#: The factor by which a window's largest ring exceeds the one before where the ring grows
#: (the 3D four-bar's grew by 1.45 a window of :data:`RING_STEPS` over 400 steps).
RING_GROWTH = 1.25
#: The windows in a row over which a ring grows before the hold hands the contact over: the
#: surges of a load (a journal's sliding along its wall speeding up and stopping, as the
#: zoo's piston engine's once a turn) rang up over four windows in a row, the 3D four-bar's
#: ring grew over twelve.
RING_WINDOWS = 5
#: The windows' rings before any: this window's largest, the last one's (none grows from an
#: infinite ring), the windows in a row before this one that grew, this window's steps.
_NO_RING = (0.0, math.inf, 0, 0)


def native_hold_fits(mbs: exu.MainSystem, markers: Sequence[Any], pair: Any, frictionless: bool) -> bool:
    """Whether a contact ``pair`` between ``markers`` of a joint without (``frictionless``)
    friction may be held by :class:`DistanceHold`: a centre distance between two rigid
    bodies (or a rigid body and the ground).  A flexible body's system is not settled, where
    the hold stays off (:meth:`DistanceHold.takes`), and its item is not added there: even
    off, a constraint's equation (its multiplier held at 0) changes Newton's iterates at
    round-off, and the paths of a contact that chatters with them (the zoo's ANCF pendulum:
    2579 impacts with the item, 1507 without, both off the converged compliant run)."""
    if not frictionless or type(pair).__name__ not in NATIVE_PAIRS:
        return False
    owners = [coordinate_owner(mbs, m) for m in markers]
    return all(kind == "object" and str(mbs.GetObject(k)["objectType"]) in RIGID_BODIES | {"Ground"}
               for kind, k in owners)


class DistanceHold:
    """``|p_1 - p_0| = d`` between ``markers`` [outer, inner] (any markers with a position:
    rigid bodies, beams' and ANCF cables' rigid markers), off until :meth:`hold`.

    Attributes
    ----------
    objectNumber : int
        The ``ObjectConnectorDistance``.
    distance : float
        The distance it holds [m] (0 where off).
    """

    def __init__(self, mbs: exu.MainSystem, markers: Sequence[Any], name: str, clearance: float) -> None:
        # (its distance a placeholder while off: Exudyn wants one greater than zero)
        self.objectNumber = mbs.AddObject(ObjectConnectorDistance(
            name=f"{name}:hold" if name else "", markerNumbers=list(markers), distance=clearance,
            activeConnector=False, visualization=VObjectConnectorDistance(show=False)))
        self.clearance = clearance
        self.distance = 0.0
        self.handed = False  # the contact handed to the velocity-level condition (:meth:`takes`)
        self._forces: tuple[float, ...] = ()  # the last four multipliers
        self._window = _NO_RING
        self._step = math.inf  # the length of the last held step [s]

    @property
    def active(self) -> bool:
        return self.distance > 0.0

    def setting(self) -> tuple[float, bool, tuple[Any, ...]]:
        """What the hold acts with, and its multiplier's history (:meth:`_rings_up`):
        :meth:`restore` takes both back."""
        return self.distance, self.handed, (self._forces, self._window, self._step)

    def takes(self, mbs: exu.MainSystem, settled: bool, axial: float, force: float, reaction: float | None,
              h: float) -> bool:
        """Whether it holds the coming step of a held contact whose last step (of length
        ``h`` [s]) ended at the axial offset ``axial`` [m] with the multiplier ``force`` [N]
        (its own, where on) and the reaction ``reaction`` [N] (the multiplier's mean over the
        last steps; None in the onset's settling steps, whose multiplier settles from the
        onset's impulse), in a system ``settled`` (:mod:`~exuclear.engine.settling`): not in
        a system the settling leaves as it is, not at an axial offset beyond
        :data:`AXIAL_SHARE`, and, once its multiplier rang (:meth:`_rings_up`), not until the
        contact is let go; off where it does not."""
        if self.active and self._rings_up(force, reaction, h):
            self.handed = True
        fits = settled and not self.handed and abs(axial) <= AXIAL_SHARE * self.clearance
        if not fits:
            self.release(mbs, hand_over=self.handed)
        return fits

    def _rings_up(self, force: float, reaction: float | None, h: float) -> bool:
        """Whether the multiplier, ``force`` [N] at the end of the last step (of length ``h``
        [s]), rings: its ring (a quarter of its second difference over the last three steps,
        where that changed sign from the step before: a load that changes smoothly has
        almost none, one that grows or falls fast, as a journal's sliding along its wall
        speeds up, none) beyond :data:`HAND_OVER` of the reaction ``reaction`` [N], at a step
        shorter than the one before (a velocity alternation across any position-level
        constraint drives the multipliers by about ``4 m v / h``: each halving after a failed
        Newton doubles it, and Newton fails again) or where the largest ring in the last
        :data:`RING_STEPS` steps was more than :data:`RING_GROWTH` times the largest in the
        window before, in the last :data:`RING_WINDOWS` windows in a row (a journal rocking on
        its wall rings as much without growing).  Not judged while ``reaction`` is None."""
        self._forces = (*self._forces[-3:], force)
        shortened, self._step = h < self._step, h
        if reaction is None or len(self._forces) < 4:
            return False
        f3, f2, f1, f0 = self._forces
        second, last_second = f0 - 2.0 * f1 + f2, f1 - 2.0 * f2 + f3
        ring = 0.25 * abs(second) if second * last_second < 0.0 else 0.0
        last, before, grown, steps = self._window
        last, steps = max(last, ring), steps + 1
        grows = last > RING_GROWTH * before
        self._window = (0.0, last, grown + 1 if grows else 0, 0) if steps == RING_STEPS else (last, before, grown, steps)
        return ring > HAND_OVER * abs(reaction) and (shortened or (grows and grown >= RING_WINDOWS - 1))

    def start(self, mbs: exu.MainSystem, distance: float) -> None:
        """On, from a state at ``distance`` [m]; :meth:`advance` sets its first step."""
        self.distance, self._forces, self._window, self._step = distance, (), _NO_RING, math.inf
        mbs.SetObjectParameter(self.objectNumber, "activeConnector", True)
        request_jacobian(mbs)

    def advance(self, mbs: exu.MainSystem, e: Sequence[float], end_rate: float, h: float) -> None:
        """The distance at the coming step's end (length ``h`` [s]) at which the trapezoidal
        rule ends it at the normal rate ``end_rate`` [m/s]: ``d + h (v0 + v1) / 2``, from the
        rate ``v0`` the step before ended at, measured along the eccentricity ``e`` it ended
        at (an unchanged distance would end it at ``-v0``, and the rate and the multiplier
        would alternate from step to step after it; a rate the hold only planned leaves any
        other rate the state carries to alternate so).  No call where the distance stays as
        it is."""
        v = mbs.GetObjectOutput(self.objectNumber, exu.OutputVariableType.Velocity).tolist()  # v1 - v0 of its markers
        start_rate = (e[0] * v[0] + e[1] * v[1] + e[2] * v[2]) / norm(e)
        distance = self.distance + 0.5 * h * (start_rate + end_rate)
        if distance != self.distance:
            self.distance = distance
            mbs.SetObjectParameter(self.objectNumber, "distance", distance)

    def release(self, mbs: exu.MainSystem, hand_over: bool = False) -> bool:
        """Off for the coming step (``hand_over``: the velocity-level condition holds the
        contact until it is let go); whether it was on."""
        self.handed = hand_over
        if not self.active:
            return False
        self.distance = 0.0
        mbs.SetObjectParameter(self.objectNumber, "activeConnector", False)
        request_jacobian(mbs)
        return True

    def restore(self, mbs: exu.MainSystem, setting: tuple[float, bool, tuple[Any, ...]]) -> bool:
        """The setting of :meth:`setting` back (the history always: a step computed again
        is judged once); whether what the hold acts with differs from the present one."""
        distance, handed, (self._forces, self._window, self._step) = setting
        if (distance, handed) == (self.distance, self.handed):
            return False
        if distance <= 0.0:
            self.release(mbs, hand_over=handed)
            return True
        was = self.active
        self.distance, self.handed = distance, handed
        mbs.SetObjectParameter(self.objectNumber, "distance", self.distance)
        if not was:
            mbs.SetObjectParameter(self.objectNumber, "activeConnector", True)
        request_jacobian(mbs)
        return True

    def multiplier(self, mbs: exu.MainSystem) -> float:
        """The constraint's multiplier [N] (0 where off): Exudyn's, whose force on the inner
        marker is ``-lambda (p_1 - p_0) / |p_1 - p_0|``, positive where the wall pushes the
        inner body back towards the centre, as the velocity-level condition's."""
        return scalar_force(mbs, self.objectNumber) if self.active else 0.0


def distance_of(e: Sequence[float], axial: float) -> float:
    """The 3D distance of two markers whose in-plane eccentricity is ``e`` and axial offset ``axial``."""
    return math.sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2] + axial * axial)
