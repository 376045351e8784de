"""The translational joints in the impulse contact mode (:mod:`~exuclear.engine.impulse`): a
slider's corners against its guide's walls, each a one-contact pair of the mode.

A corner against the two opposite walls across one axis ``a`` of the guide's joint frame
(the planar slider: y; the spatial box: y and z, separately) is a contact pair as the mode
sees it (:mod:`~exuclear.engine.impulse_pairs`): its eccentricity is ``e = d_a a``, with
``d`` the corner's offset from the guide's centre point in the guide's frame, so that
``|e|`` is the corner's distance from the guide's mid-plane across ``a``; it touches a wall
at ``|e| = w`` (``w = H/2 + c`` across y, ``B/2 + c_z`` across z: the wall's distance from
the mid-plane, docs/physics.md section 14), its normal ``sign(d_a) a`` points into the wall
it approaches, and its gap's rate is the corner's velocity (a point of the slider's body,
``v + omega x r``) against that of the guide's material point ``S`` at the corner's foot on
the mid-plane.  The gap ``|e| - w`` is the compliant joint's penetration of that corner on
that wall (:func:`exuclear.prismatic.corner_kinematics`).

Each pair is one :class:`~exuclear.engine.impulse.ImpulseJointHandle`: its own condition
and its own carrier, whose post-Newton function runs the mode's decisions for that corner.
Exudyn's discontinuous iteration calls every carrier's function after each Newton solve
and computes the step again while one asks for it; conditions held in the same step are
solved together by Newton with the whole system, which is Moreau-Jean's joint solve of
simultaneous contacts (two corners of a slider thrown flat at a wall hit in one step; a
slider resting flat holds two corners, a box four).  :class:`ImpulseGuideHandle` is the
joint: the pairs, their impacts named by corner and wall, their outputs and notes.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple, get_type_hints

import exudyn as exu
import numpy as np

from ..joint import ClearanceJoint
from ..prismatic import (
    BOX_CORNER_NAMES,
    BOX_CORNER_SIGNS,
    BOX_WALL_NAMES,
    BOX_WALLS,
    CORNER_NAMES,
    CORNER_SIGNS,
    WALL_NAMES,
    WALL_SIDES,
    GuideGeometry,
)
from .impulse import ClosedFormImpact, ImpulseJointHandle
from .condition import VelocityCondition
from .impulse_pairs import Eccentricity

#: The guide's axes a pair acts across, as the joint frame's column, with their walls' names.
Y, Z = 1, 2


@dataclass(frozen=True)
class CornerPair:
    """A slider's corner against the guide's two walls across the joint frame's axis
    ``axis`` (:data:`Y` or :data:`Z`): ``corner`` [m] the corner in the slider's joint frame
    (marker 1's), ``reach`` [m] the walls' distance from the guide's mid-plane, ``clearance``
    [m] the play across ``axis`` (module docstring)."""

    corner: np.ndarray
    axis: int
    reach: float
    clearance: float

    def offset(self, mbs: exu.MainSystem, markers: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The corner's offset ``d`` from the guide's centre point in the guide's frame, the
        guide's frame (global columns) and the corner's arm from marker 1's point (global)."""
        ov = exu.OutputVariableType
        r0, r1 = (np.asarray(mbs.GetMarkerOutput(m, ov.RotationMatrix), dtype=float).reshape(3, 3) for m in markers)
        p0, p1 = (np.asarray(mbs.GetMarkerOutput(m, ov.Position), dtype=float) for m in markers)
        arm = r1 @ self.corner
        return r0.T @ (p1 + arm - p0), r0, arm

    def eccentricity(self, mbs: exu.MainSystem, markers: Any) -> Eccentricity:
        d, frame, arm = self.offset(mbs, markers)
        foot = d.copy()
        foot[self.axis] = 0.0  # S: the corner's foot on the mid-plane, a point of the guide's body
        return Eccentricity(d[self.axis] * frame[:, self.axis], frame @ foot, arm)

    def side(self, mbs: exu.MainSystem, markers: Any) -> float:
        """The sign of the corner's offset across the axis: the wall it is nearest, -1 (lower
        or far) or +1 (upper or near)."""
        return 1.0 if self.offset(mbs, markers)[0][self.axis] >= 0.0 else -1.0


def corner_pairs(geometry: GuideGeometry) -> list[tuple[str, str, int, CornerPair]]:
    """The pairs of a slider in its guide: (the corner's name, the pair's name, the axis,
    the pair); the planar slider's four corners across y, the box's eight across y, then
    across z."""
    half = np.array([0.5 * geometry.slider_length, geometry.inner_radius, geometry.half_width])
    if not geometry.spatial:
        corners = [(name, np.array([sx, sy, 0.0]) * half) for name, (sx, sy) in zip(CORNER_NAMES, CORNER_SIGNS)]
        axes = [(Y, geometry.outer_radius, geometry.guide_clearance)]
    else:
        corners = [(name, np.array(signs) * half) for name, signs in zip(BOX_CORNER_NAMES, BOX_CORNER_SIGNS)]
        axes = [(Y, geometry.outer_radius, geometry.guide_clearance),
                (Z, geometry.channel_half_width, float(geometry.clearance_width))]
    return [(name, f"corner {name} / {' and '.join(_walls(geometry, axis))} walls", axis,
             CornerPair(corner, axis, reach, play)) for axis, reach, play in axes for name, corner in corners]


def _walls(geometry: GuideGeometry, axis: int) -> tuple[str, str]:
    """The names of the walls across ``axis``, the one at -w, then the one at +w."""
    if not geometry.spatial:
        return WALL_NAMES[WALL_SIDES.index(-1.0)], WALL_NAMES[WALL_SIDES.index(1.0)]
    return tuple(BOX_WALL_NAMES[BOX_WALLS.index((axis, s))] for s in (-1.0, 1.0))  # type: ignore[return-value]


class ClosedFormPairImpact(NamedTuple("_ClosedFormPairImpactFields",
                                      [*get_type_hints(ClosedFormImpact).items(), ("pair", str)])):
    """One impact of a translational joint in the impulse mode: the
    :class:`~exuclear.engine.impulse.ClosedFormImpact` fields, then ``pair``, the corner and
    the wall it hit (``"corner front-lower / lower wall"``, as the compliant joint's
    :class:`exuclear.history.PairImpact`)."""

    __slots__ = ()


class _Corners:
    """The conditions of one slider's corners, held together: which of them acts in Exudyn,
    and the reactions they share.

    Corners held at once can be more than the slider's motion has directions: a box flat on
    a wall touches it at four corners, whose rows span three (the velocity across the wall
    and the two turns about the wall's axes), and three held corners of a planar slider
    span its two.  Exudyn's Newton iteration cannot solve dependent conditions (a singular
    matrix).  A corner whose rows are a combination of the acting corners' is held by them
    (its rate is then theirs combined: the corners of a rigid face are affine in its motion,
    and so are their rates and gaps) and its condition stays off in Exudyn.  The reactions
    of such a set are statically indeterminate; the mode reports the least-squares split
    (:meth:`reaction`), the one that equally compliant corners take (the analytic split of a
    box flat on its wall: ``m g / 4`` each)."""

    def __init__(self) -> None:
        self.conditions: list[_CornerCondition] = []
        self._sweep: tuple[float, float, int] | None = None  # the Newton solve the corners last decided after
        self._redo = False  # whether a corner asked for it to be computed again
        self._accepted: list[_CornerHandle] = []  # the corners that accepted it
        self._shares: tuple[Any, dict[int, float]] = (None, {})  # the reactions of a Newton solve, by condition

    def forget(self) -> None:
        """A new run: nothing of the last one's solves."""
        self._sweep, self._shares = None, (None, {})

    @staticmethod
    def solve_of(mbs: exu.MainSystem) -> tuple[float, float, int]:
        """The Newton solve just done: the step's end [s], its length [s] and Exudyn's
        discontinuous iteration."""
        it = mbs.sys["dynamicSolver"].it
        return float(mbs.systemData.GetTime()), float(it.currentStepSize), int(it.discontinuousIteration)

    def decided(self, mbs: exu.MainSystem, handle: _CornerHandle, error: float) -> None:
        """After ``handle`` decided on a Newton solve (``error`` > 0: compute the step again).
        A corner that accepts a step sets its condition for the next one; where another
        corner has Exudyn compute the step again, the computation must hold the accepting
        corners' conditions of this step, or each would ask for it again in turn (two
        corners hitting in one step, the second only after the first's jump):
        their conditions go back to this step's."""
        sweep = self.solve_of(mbs)
        if sweep != self._sweep:
            self._sweep, self._redo, self._accepted = sweep, False, []
        if error > 0.0:
            if not self._redo:
                for accepted in self._accepted:
                    accepted.take_back(mbs)
            self._redo = True
        elif self._redo:
            handle.take_back(mbs)
        else:
            self._accepted.append(handle)

    def dependent(self, mbs: exu.MainSystem, condition: _CornerCondition) -> bool:
        """Whether ``condition``'s corner's wrench is a combination of the wrenches of the
        other corners acting now (:meth:`_CornerCondition.wrench`, all at the present state)."""
        others = [c.wrench(mbs) for c in self.conditions if c is not condition and c.acting]
        if not others:
            return False
        wrench = condition.wrench(mbs)
        basis = np.array(others)
        share = np.linalg.lstsq(basis.T, wrench, rcond=None)[0]
        return float(np.linalg.norm(basis.T @ share - wrench)) <= DEPENDENT_WRENCHES * float(np.linalg.norm(wrench))

    def settle(self, mbs: exu.MainSystem) -> None:
        """A held corner whose condition was off because others held it acts again where
        they no longer do."""
        for condition in self.conditions:
            if condition.plan.active and not condition.acting and not self.dependent(mbs, condition):
                condition.act(mbs, True)

    def reaction(self, mbs: exu.MainSystem, condition: _CornerCondition) -> float:
        """``condition``'s share [N] of the held corners' load in the Newton solve just done:
        the least-squares (minimum norm) multipliers ``lambda`` of all corners held in it
        with ``W^T lambda = W_a^T lambda_a``, the wrench the acting ones' multipliers
        ``lambda_a`` apply (``W`` the corners' unit wrenches); the acting multipliers
        themselves where none is held by others.  Computed at the first corner's call after
        the solve, before any corner sets its condition for the next computation."""
        solve = self.solve_of(mbs)
        if self._shares[0] != solve:
            held = [c for c in self.conditions if c.plan.active]
            forces = np.array([c.own_multiplier(mbs) for c in held])
            if held and not all(c.acting for c in held):
                wrenches = np.array([c.wrench(mbs) for c in held])
                load = wrenches.T @ forces  # the off conditions' multipliers are 0
                forces = np.linalg.lstsq(wrenches.T, load, rcond=None)[0]
            self._shares = (solve, {id(c): float(f) for c, f in zip(held, forces)})
        return self._shares[1].get(id(condition), 0.0)


#: A corner's wrench whose distance from the span of the acting corners' wrenches is below
#: this share of its length is a combination of them: the wrenches at one state of a rigid
#: slider's corners on a face are exactly dependent (round-off), and an independent one's
#: distance is of the order of its own terms over the slider's size.  (The conditions' rows
#: are not compared: each is measured where its step is predicted to end, and rows a step
#: apart are independent to about the turn of a step, a near-singular matrix for Newton.)
DEPENDENT_WRENCHES = 1e-9


class _CornerCondition(VelocityCondition):
    """A corner's condition, on in Exudyn only where the acting corners do not hold it
    (:class:`_Corners`)."""

    def __init__(self, mbs: exu.MainSystem, markers: Sequence[Any], name: str, corners: _Corners,
                 pair: CornerPair) -> None:
        super().__init__(mbs, markers, name)
        self.corners, self.pair, self.acting = corners, pair, False
        corners.conditions.append(self)

    def wrench(self, mbs: exu.MainSystem) -> np.ndarray:
        """The unit wrench of the corner's contact in the guide's frame at the present state,
        ``(n, d x n)``: the normal ``n`` into the wall it is nearest at the corner's offset
        ``d``.  A condition's rows are this wrench mapped onto the two bodies' coordinates by
        one map for all corners (the corner and its foot on the guide lie along ``n``), so
        the corners' conditions are dependent where their wrenches are."""
        d = self.pair.offset(mbs, self.markers)[0]
        n = np.zeros(3)
        n[self.pair.axis] = 1.0 if d[self.pair.axis] >= 0.0 else -1.0
        return np.concatenate((n, np.cross(d, n)))

    def switch(self, mbs: exu.MainSystem, on: bool) -> None:
        """On where the plan holds the corner and the acting corners do not; off, letting
        a corner they held act again where they no longer hold it."""
        self.act(mbs, on and not self.corners.dependent(mbs, self))
        if not on:
            self.corners.settle(mbs)

    def act(self, mbs: exu.MainSystem, on: bool) -> None:
        self.acting = on
        super().switch(mbs, on)

    def own_multiplier(self, mbs: exu.MainSystem) -> float:
        """The multiplier of the condition in Exudyn [N] (0 where it is off)."""
        return super().multiplier(mbs) if self.acting else 0.0

    def multiplier(self, mbs: exu.MainSystem) -> float:
        return self.corners.reaction(mbs, self) if self.plan.active else 0.0


class _CornerHandle(ImpulseJointHandle):
    """One corner-axis pair in the mode; remembers the wall each of its contacts began on."""

    def __init__(self, *args: Any, corner: str, walls: tuple[str, str], corners: _Corners) -> None:
        self.corner, self.walls, self._corners = corner, walls, corners
        self._sides: dict[float, float] = {}  # onset time [s] -> the wall's side
        super().__init__(*args)

    def _new_condition(self, mbs: exu.MainSystem, name: str) -> VelocityCondition:
        return _CornerCondition(mbs, self.markerNumbers, name, self._corners, self._pair)

    def _reset(self) -> None:
        super()._reset()
        self._corners.forget()

    def _post_newton(self, mbs: exu.MainSystem, t: float, item: int, data: Any, *frame: Any) -> list:
        out = super()._post_newton(mbs, t, item, data, *frame)
        self._corners.decided(mbs, self, out[0])
        return out

    def take_back(self, mbs: exu.MainSystem) -> None:
        """The condition of the step just accepted back (:meth:`_Corners.decided`): Exudyn
        computes it again."""
        if self._saved is not None:
            self._condition.set(mbs, self._saved["plan"])

    def _contact(self, mbs: exu.MainSystem, t: float, h: float, end: np.ndarray, end_gap: float) -> bool:
        side = self._pair.side(mbs, self.markerNumbers)  # at the step's end, in the wall
        began = super()._contact(mbs, t, h, end, end_gap)
        if began:
            self._sides[t] = side
        return began

    def wall(self, onset_time: float) -> str:
        return self.walls[self._sides.get(onset_time, 1.0) > 0.0]


class ImpulseGuideHandle:
    """A translational clearance joint in the impulse mode; returned by
    :func:`exuclear.CreatePrismaticClearanceJoint` with ``contact_mode="impulse"``.

    Attributes
    ----------
    pairs : dict
        The corner-axis pairs by name (``"corner front-lower / lower and upper walls"``),
        each an :class:`~exuclear.engine.impulse.ImpulseJointHandle` with its condition
        (``objectNumber``) and carrier (``carrierNumber``).
    objectNumbers, carrierNumbers : list
        The pairs' conditions and carriers, in the order of :attr:`pairs`.
    markerNumbers : list
        [guide marker, slider marker], both at the slider's centre with the joint frame.
    contact_mode : str
        ``"impulse"``.
    """

    contact_mode = "impulse"

    def __init__(self, mbs: exu.MainSystem, joint: ClearanceJoint, name: str, markers: Sequence[Any]) -> None:
        self.name, self._joint = name, joint
        self.markerNumbers = list(markers)
        self.pairs: dict[str, _CornerHandle] = {}
        corners = _Corners()
        for corner, pair_name, axis, pair in corner_pairs(joint.geometry):
            label = f"{name or '(unnamed)'}: {pair_name}"
            self.pairs[pair_name] = _CornerHandle(mbs, joint, label, self.markerNumbers, pair, corner=corner,
                                                  walls=_walls(joint.geometry, axis), corners=corners)
        self.objectNumbers = [p.objectNumber for p in self.pairs.values()]
        self.carrierNumbers = [p.carrierNumber for p in self.pairs.values()]

    @property
    def joint(self) -> ClearanceJoint:
        return self._joint

    @property
    def problem(self) -> str:
        """Why the mode refused or stopped the last run ('' where it did not)."""
        return next((p._problem for p in self.pairs.values() if p._problem), "")

    def impacts(self) -> list[ClosedFormPairImpact]:
        """The impacts of the last run of every corner, in time (resting contacts' onsets
        included, restitution 0), each naming its corner and wall
        (:class:`ClosedFormPairImpact`; the closed form as
        :meth:`~exuclear.engine.impulse.ImpulseJointHandle.impacts`)."""
        out = [ClosedFormPairImpact(*impact, f"corner {pair.corner} / {pair.wall(impact.onset_time)} wall")
               for pair in self.pairs.values() for impact in pair.impacts()]
        return sorted(out, key=lambda impact: impact.onset_time)

    def outputs(self) -> dict[str, dict[str, np.ndarray]]:
        """Each pair's outputs by its name
        (:meth:`~exuclear.engine.impulse.ImpulseJointHandle.outputs`: ``ecc_x``, ``ecc_y``,
        ``ecc_z`` the eccentricity ``d_a a``, global; ``penetration`` ``|e| - w``, the
        corner's penetration of the wall it is nearest; ``normal_force`` its held reaction)."""
        return {name: pair.outputs() for name, pair in self.pairs.items()}

    @property
    def notes(self) -> list[str]:
        """The pairs' notes (:attr:`~exuclear.engine.impulse.ImpulseJointHandle.notes`), each
        headed by its pair's name."""
        return [f"{name}: {note}" for name, pair in self.pairs.items() for note in pair.notes]


def add_impulse_guide(mbs: exu.MainSystem, joint: ClearanceJoint, name: str,
                      markers: Sequence[Any]) -> ImpulseGuideHandle:
    """The impulse mode's items for a slider in its guide between ``markers`` [guide, slider],
    both carrying the joint frame: a condition and a carrier per corner-axis pair."""
    return ImpulseGuideHandle(mbs, joint, name, markers)
