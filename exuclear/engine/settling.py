"""The step-to-step alternation the trapezoidal rule leaves in a system's velocities and
accelerations, taken out at each accepted step of the impulse contact mode
(:mod:`~exuclear.engine.impulse`).

Under generalized-alpha with spectral radius 1 (the trapezoidal rule, which the mode needs
for exact jumps) Exudyn integrates ``v1 = v0 + h (a0 + a1) / 2`` and
``q1 = q0 + h (v0 + v1) / 2``.  An error ``d`` in a step's start accelerations along a
condition that fixes the step's end (an impact's or a held contact's onset starts the next
step from accelerations not consistent with the velocities after the jump or with the new
condition) returns as ``a1 = ... - d``: ``(-1)^n d`` in every later step, undamped, and
with it in every Lagrange multiplier of the model (a held contact's reaction, a crank
drive's moment, an ideal pin's force).  A position-level joint keeps ``G q = 0`` at each
step's end, so ``G (v0 + v1) = 0`` up to the joint's curvature: a velocity across the joint
(the curvature's share of a jump) also returns with its sign flipped each step, and drives
an alternation ``2 G v / h`` in the accelerations.  Neither moves the positions; both move
the multipliers, and the mode's decisions read them.

:class:`Settling` takes both out of the state each step ends at, from the states the steps
since the last jump ended at (the ones the following steps started from):

- at the first step after a jump, the accelerations are the mean of the jump's and the
  step's own (the middle of ``d`` and ``-d``; a smooth ``a`` moves by ``h a' / 2``, once a
  jump);
- from the fourth step on, the accelerations and the velocities less :data:`SHARE` times
  their third difference (a smooth motion moves by ``h^3 a''' / 28`` and ``h^3 v''' / 28``:
  second order kept; a second difference, ``h^2 a'' / 9`` a step, left the zoo's 3D
  four-bar's path four times as far from the converged run at its example's step); the
  velocities, in the held steps more than :data:`SETTLING_STEPS` after the jump (or a held
  contact's release), :data:`HELD_SHARE` times theirs.

The filter is causal and its phase lags: on an undamped oscillation of 3 to 12 steps a
period, which the trapezoidal rule keeps, it acts as a negative damping, up to 6.3 % a step
at 4 steps at :data:`SHARE` (the largest root of its recursion).  On the velocities of every
held step it grew such an oscillation in the multiplier of a contact held by
:mod:`~exuclear.engine.impulse_hold` until the hold handed the contact over (the zoo's planar
double pendulum, generic joint chain and 3D four-bar; docs/design/native_hold.md).  Long
after a jump, the velocities' alternation is what each held step adds (a position-level
joint's curvature), which a small share keeps down (without any, the 3D double pendulum's
held contact rang as well); the accelerations keep the full share, their alternation comes
back each step (Newton's residual, the multipliers).

A jump (an impact, a contact's onset) starts the history anew: the filters never reach
across it.  One :class:`Settling` serves a system (:func:`settling_of`): each of the mode's
contacts accepts the step, and the first settles it.  With friction
(:mod:`~exuclear.engine.impulse_friction`), a settled end multiplier is the contact's
force, and the filters, linear in the accelerations, carry the end forces into the next
step alike: the sliding load is ``mu`` times the end normal multiplier and the friction
cone holds per end force.  A system with a joint of several contacts with friction (a
box's corners, a slider's, a spatial journal's slices: :mod:`~exuclear.engine.impulse_group`)
is not settled: its contacts share the load indeterminately, their end multipliers split it
differently from one computation of a step to the next, settled, and the sliding loads did
not converge (a box sliding on its four corners slowed at ``mu g`` only to 4e-4).  Nor is a
system with a flexible body (a beam, an ANCF cable: any body not in :data:`RIGID_BODIES`):
its stiff modes alternate from step to step under the trapezoidal rule of themselves (a
mode with ``omega h >> 1`` has the factor ``-1`` a step), which the filters would damp, and
the zoo's beam pendulum then chattered on its wall.  Nor is a system with a force element
that has stiffness (a spring-damper, a compliant clearance joint, a contact: any item of
:func:`force_element`): a stiff spring's mode alternates the same way (a bar held by a
spring of 1e9 N/m at 1e-4 s chattered on the clearance joint's wall, settled, 45 impacts
in 0.2 s against none).
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple, TypeVar

import exudyn as exu
import numpy as np

T = TypeVar("T", float, np.ndarray)

#: ``mbs.variables`` key of a system's :class:`Settling`.
SETTLING_KEY = "exuclear.settling"
#: The share of the accelerations' and velocities' third difference taken off.  An error
#: ``e`` in the state a step starts from returns as ``-e`` at its end; taking off the share
#: ``s`` leaves ``e_n = (4 s - 1) e_(n-1) - 3 s e_(n-2) + s e_(n-3)``, whose largest roots
#: are smallest, -1/2 twice (and 1/7), at ``s = 1/28``: the error halves a step without
#: ringing (``s = 1/8``, which removes a pure alternation at once, leaves complex roots of
#: modulus 0.74, which ring).
SHARE = 1.0 / 28.0
#: The share of the velocities' third difference taken off in a held step more than
#: :data:`SETTLING_STEPS` after the last jump: the filter's recursion then grows an undamped
#: oscillation of 3 to 12 steps a period by at most 0.44 % a step (:data:`SHARE`: 6.3 %) and
#: damps a velocity alternation by 1.8 % a step (module docstring).
HELD_SHARE = SHARE / 16.0
#: The shares of the third difference taken off the velocities (first row) and the
#: accelerations (second) of a step's end state, within :data:`SETTLING_STEPS` of the last
#: jump and after.
_SHARES = np.array([[SHARE], [SHARE]])
_HELD_SHARES = np.array([[HELD_SHARE], [SHARE]])
#: Exudyn's rigid bodies (``objectType``): a system whose bodies are all of these is settled.
RIGID_BODIES = frozenset({"RigidBody", "RigidBody2D", "MassPoint", "MassPoint2D", "Mass1D", "RotationalMass1D",
                          "KinematicTree"})
#: The beginnings of the ``objectType`` of Exudyn's objects that are not bodies.
NOT_BODIES = ("Connector", "Joint", "Contact", "Ground")
#: The force user functions of Exudyn's connectors (any one set makes a force element).
FORCE_FUNCTIONS = ("springForceUserFunction", "springForceTorqueUserFunction", "springTorqueUserFunction")
#: Two step ends closer than this (relative) are one step, accepted again.
SAME_END = 1e-12
#: Steps after a jump that are settled while no contact is held, and whose velocities lose
#: :data:`SHARE` of their third difference: the filters leave ``n 2^-n`` of a jump's
#: alternation after ``n`` steps, below 1e-17 after this many; a free flight after them reads
#: nothing.
SETTLING_STEPS = 64


class _End(NamedTuple):
    """The state a step ended at, as the next step starts from it."""

    solve: tuple[float, float, int]  # the step's end [s], its length [s], Exudyn's discontinuous iteration
    state: np.ndarray  # two rows: the velocities and the accelerations (one filter acts on both at once)


class Settling:
    """The ends of a system's accepted steps since the last jump, and the filters applied
    to a step's end (module docstring)."""

    def __init__(self) -> None:
        self.friction_groups = False  # a joint of several contacts with friction: no settling (module docstring)
        self.flexible = False  # a flexible body or a force element in the run's system: no settling (module docstring)
        self._ends: list[_End] = []
        self._count = 0  # the steps settled since the last jump
        self._settled: tuple[tuple[float, float, int], np.ndarray] | None = None  # a settled solve, its own velocities

    def forget(self, mbs: exu.MainSystem) -> None:
        """A new run of ``mbs``: no steps yet; whether it has a flexible body or a force
        element (module docstring)."""
        self._ends, self._settled, self._count = [], None, 0
        items = [mbs.GetObject(i) for i in range(mbs.systemData.NumberOfObjects())]
        self.flexible = any(force_element(item) or (not str(item["objectType"]).startswith(NOT_BODIES) and
                                                    str(item["objectType"]) not in RIGID_BODIES) for item in items)

    @property
    def active(self) -> bool:
        """Whether the run's system is settled (module docstring): no joint of several
        contacts with friction, no flexible body, no force element; else the mode's accepted
        steps leave it as it is, without reading Exudyn's solver or state."""
        return not (self.friction_groups or self.flexible)

    def restart(self, mbs: exu.MainSystem) -> None:
        """The step just accepted ends in a jump (its end state as the mode set it): the
        history starts from it."""
        if not self.active:
            return
        solve = solve_of(mbs)
        data = mbs.systemData
        if self._settled is not None and self._settled[0] == solve:
            # another contact settled this solve first: its jump's velocities back
            data.SetODE2Coordinates_t(self._settled[1])
        self._ends = [_End(solve, np.array((data.GetODE2Coordinates_t(), data.GetODE2Coordinates_tt())))]
        self._count = 0

    def reopen(self) -> None:
        """A held contact let go: the steps after it are settled as after a jump (its
        multiplier leaves the step's start accelerations), on the history so far."""
        self._count = 0

    def settle(self, mbs: exu.MainSystem, held: bool = True) -> None:
        """The step just accepted ends smoothly: its end velocities and accelerations less
        their alternation (once per Newton solve, whichever contact accepts it first; not
        at a step that ended in a jump).  A contact not ``held`` in the step asks for it only
        within :data:`SETTLING_STEPS` of the last jump (every jump, a contact's onset
        included, starts the history anew, so a held contact's steps find it current)."""
        if not self.active or (not held and self._count >= SETTLING_STEPS):
            return
        solve = solve_of(mbs)
        ends = self._ends
        if ends and ends[-1].solve == solve:
            return
        if ends and ends[-1].solve[0] >= solve[0] - SAME_END * max(1.0, abs(solve[0])):
            self._drop_from(solve[0])
            ends = self._ends
        data = mbs.systemData
        y = np.array((data.GetODE2Coordinates_t(), data.GetODE2Coordinates_tt()))
        self._settled = (solve, y[0])
        if len(ends) == 1:
            y[1] = 0.5 * (y[1] + ends[-1].state[1])
            data.SetODE2Coordinates_tt(y[1])
        elif len(ends) >= 3:
            # the accelerations less SHARE times their third difference, the velocities less
            # SHARE or HELD_SHARE times theirs (a jump's velocities across the joints, then what
            # each held step adds: module docstring)
            shares = _SHARES if self._count < SETTLING_STEPS else _HELD_SHARES
            y = y - shares * _third_difference(y, [e.state for e in ends[-3:]])
            data.SetODE2Coordinates_t(y[0])
            data.SetODE2Coordinates_tt(y[1])
        self._ends = [*ends[-2:], _End(solve, y)]
        self._count += 1

    def _drop_from(self, end: float) -> None:
        """Forget the steps that ended at or after ``end`` [s]: Exudyn computes them again."""
        limit = end - SAME_END * max(1.0, abs(end))
        self._ends = [e for e in self._ends if e.solve[0] < limit]


def _third_difference(x: np.ndarray, before: list[np.ndarray]) -> np.ndarray:
    """``x_n - 3 x_(n-1) + 3 x_(n-2) - x_(n-3)``, ``before`` = [x_(n-3), x_(n-2), x_(n-1)]."""
    return x - 3.0 * before[2] + 3.0 * before[1] - before[0]


def held_mean(ends: Sequence[T]) -> T:
    """What a held contact's end multipliers (or its friction's end forces) ``ends`` say of
    its force, the last end last, from the first held step after the onset: the last alone,
    the mean of two, or of the last three with weights 1/4, 1/2, 1/4.  The multiplier
    alternates about the force in the first steps after a jump (while the settling takes the
    alternation out), and undamped where the system is not settled, with an amplitude that
    drifts (with Newton's residual and the mechanism's configuration): a two-step mean keeps
    half the change of one step, the three-step mean also cancels an amplitude that changes
    linearly from step to step."""
    if len(ends) >= 3:
        return 0.25 * (ends[-3] + 2.0 * ends[-2] + ends[-1])
    return 0.5 * (ends[0] + ends[1]) if len(ends) == 2 else ends[-1]


def force_element(item: dict) -> bool:
    """Whether an Exudyn object (its ``mbs.GetObject`` dictionary) acts with stiffness: a
    contact, or a connector with a nonzero ``stiffness`` or a force user function (the mode's
    own carriers have neither)."""
    kind = str(item["objectType"])
    if kind.startswith("Contact"):
        return True
    if not kind.startswith("Connector"):
        return False
    stiff = np.any(np.asarray(item.get("stiffness", 0.0), dtype=float) != 0.0)
    return bool(stiff) or any(not isinstance(item.get(key, 0), int) for key in FORCE_FUNCTIONS)


def solve_of(mbs: exu.MainSystem) -> tuple[float, float, int]:
    """The Newton solve just done: the step's end [s], its length [s] and Exudyn's
    discontinuous iteration."""
    it = mbs.sys["dynamicSolver"].it
    return float(mbs.systemData.GetTime()), float(it.currentStepSize), int(it.discontinuousIteration)


def settling_of(mbs: exu.MainSystem) -> Settling:
    """The :class:`Settling` of ``mbs`` (one per system, kept in ``mbs.variables``)."""
    settling = mbs.variables.get(SETTLING_KEY)
    if settling is None:
        settling = mbs.variables[SETTLING_KEY] = Settling()
    return settling
