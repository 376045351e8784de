"""A joint with several contacts in the impulse contact mode (:mod:`~exuclear.engine.impulse`):
the translational joints' corners (:mod:`~exuclear.engine.impulse_guide`) and the spatial
revolute joint's slices and end faces (:class:`~exuclear.engine.impulse_pairs.SlicePair`,
:class:`~exuclear.engine.impulse_pairs.FacePair`).

Each contact is a one-contact pair of the mode (:mod:`~exuclear.engine.impulse_pairs`) with
its own :class:`~exuclear.engine.impulse.ImpulseJointHandle`: its own condition and its own
carrier, whose post-Newton function runs the mode's decisions for that contact.  Exudyn's
discontinuous iteration calls every carrier's function after each Newton solve and computes
the step again while one asks for it; conditions held in the same step are solved together
by Newton with the whole system, which is Moreau-Jean's joint solve of simultaneous
contacts (two corners of a slider thrown flat at a wall hit in one step; a slider resting
flat holds two corners, a box four; a journal resting flat, all its slices).
:class:`_Contacts` keeps the conditions of one joint apart where they would be solved
wrongly one by one; :class:`ImpulsePairsHandle` is the joint: the pairs, their impacts named
by contact, their outputs and notes.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Any, NamedTuple, get_type_hints

import exudyn as exu
import numpy as np

from ..contact.law import ContactLaw
from ..contact.stiffness import GivenStiffness
from ..joint import ClearanceJoint
from ..spatial import FACE_SIDES, ShoulderGeometry, slice_centres
from ..timescales import closed_form_impact
from ..vectors import cross, norm
from .condition import MarkerState, VelocityCondition, request_jacobian
from .impulse import CROSSING, ClosedFormImpact, ImpulseJointHandle
from .impulse_friction import tangents
from .impulse_pairs import ContactPair, Eccentricity, FacePair, SlicePair, contact_arms
from .impulse_run import gains_note
from .settling import solve_of
from .state import start_of_step

#: A held contact whose wrench lies closer than this share of its length to the span of the
#: wrenches chosen to act (:meth:`_Contacts.select`, moments over the contacts' longest arm)
#: is held by them and its condition stays off.  The wrenches at one state of a rigid body's
#: contacts on a face or a line (a box's corners on a wall, a journal's slices along its
#: bearing) are exactly dependent; a journal tilted within its clearance turns its slices'
#: normals apart by its tilt over the clearance, so that three slices are nearly dependent,
#: their distance about that turn.  Held together, their conditions give Newton's matrix
#: ``G M^-1 G^T`` an eigenvalue of the order of the distance squared, and the end rates each
#: contact aims at (from its own gap) are never exactly a rigid motion's: the multipliers
#: grow as that mismatch over the eigenvalue, with opposite signs, until Newton diverges.
#: Left off, a nearly dependent contact's rate is its holders' combined, off by at most this
#: share of the twist: it is followed, and it acts again as soon as it is independent.
#: (The conditions' rows are not compared: each is
#: measured where its step is predicted to end, and rows a step apart are independent to
#: about the turn of a step.)
DEPENDENT_WRENCHES = 1e-2
#: A contact whose eccentricity is longer than this share of the play takes its normal
#: from the present state (:meth:`_GroupCondition.wrench`): near the wall ``e`` points along
#: the normal, and so does a corner's always (its ``e`` is half the slider's height); a
#: journal's slice near the bearing's centre (an impact set at its step's start) takes the
#: normal its rows hold.  (Normals held since different steps differ by the bodies' turn over
#: a step, and contacts that are dependent at one state would pass as independent.)
NEAR = 0.5
#: Two held contacts whose normals' cosine is below this are on opposite walls (a box
#: across its guide, a journal across its bearing): a body wedged between them.
OPPOSITE = -0.5


class ClosedFormPairImpact(NamedTuple("_ClosedFormPairImpactFields",
                                      [*get_type_hints(ClosedFormImpact).items(), ("pair", str)])):
    """One impact of a joint with several contacts in the impulse mode: the
    :class:`~exuclear.engine.impulse.ClosedFormImpact` fields, then ``pair``, the contact
    (``"corner front-lower / lower wall"``, as the compliant joint's
    :class:`exuclear.history.PairImpact`; ``"slice 1 at z = -0.005 m"``)."""

    __slots__ = ()


class _Contacts:
    """The conditions of one joint's contacts, held together: which of them acts in Exudyn,
    and the reactions they share.

    Contacts held at once can be more than the joint's relative motion has directions: a
    box flat on a wall touches it at four corners, whose rows span three (the velocity
    across the wall and the two turns about the wall's axes), three held corners of a
    planar slider span its two, and a journal resting flat touches at every slice, which
    span two.  Exudyn's Newton iteration cannot solve dependent conditions (a singular
    matrix), nor nearly dependent ones (:data:`DEPENDENT_WRENCHES`).  A contact whose
    wrench is a combination of the acting contacts' is held by them (its rate is then
    theirs combined: the contacts of a rigid face or line are affine in its motion, and so
    are their rates and gaps) and its condition stays off in Exudyn.
    The reactions of such a set are statically indeterminate; the mode reports the
    least-squares split (:meth:`reaction`), the one that equally compliant contacts take
    (the analytic split of a box flat on its wall: ``m g / 4`` each)."""

    def __init__(self, state: MarkerState) -> None:
        self.state = state  # the joint's two markers, read once per state for all its contacts
        self.conditions: list[_GroupCondition] = []
        self._sweep: tuple[float, float, int] | None = None  # the Newton solve the contacts last decided after
        self._redo = False  # whether a contact asked for it to be computed again
        self._accepted: list[_GroupPair] = []  # the contacts that accepted it
        self._shares: tuple[Any, dict[int, float]] = (None, {})  # the reactions of a Newton solve, by condition
        self.last_held: _Held | None = None  # the held contacts of the last Newton solve

    def forget(self) -> None:
        """A new run: nothing of the last one's solves."""
        self._sweep, self._shares, self.last_held = None, (None, {}), None

    def decided(self, mbs: exu.MainSystem, handle: _GroupPair, error: float) -> None:
        """After ``handle`` decided on a Newton solve (``error`` > 0: compute the step again).
        A contact that accepts a step sets its condition for the next one; where another
        contact has Exudyn compute the step again, the computation must hold the accepting
        contacts' conditions of this step, or each would ask for it again in turn (two
        corners hitting in one step, the second only after the first's jump): their
        conditions go back to this step's."""
        sweep = solve_of(mbs)
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

    def select(self, mbs: exu.MainSystem) -> None:
        """The held contacts whose conditions act in Exudyn: a rank-revealing choice of their
        wrenches (:meth:`_GroupCondition.wrench`, all at the present state; Gram-Schmidt
        with pivoting), the moments over the held contacts' longest arm (force and moment
        parts of one size, whatever the body's size: unscaled, two slices 7.5 mm apart would
        differ by 7.5e-3 of a length 1).  Each pick is the contact whose wrench lies
        farthest, as a share of its length, from the span of those picked, while that share
        exceeds :data:`DEPENDENT_WRENCHES`: the first an acting one (a contact stays on while
        it is independent), then the best spread (a journal's end slices, not two
        neighbours that would hold its tilt with a short lever).  One choice over the whole
        set: switched on one at a time against those acting then, a contact checked while
        its holders were off would stay on beside them, and a nearly dependent set act."""
        held = sorted((c for c in self.conditions if c.plan.active), key=lambda c: not c.acting)
        picked: set[int] = set()
        if held:
            wrenches = np.array([c.wrench(mbs) for c in held])
            wrenches[:, 3:] /= max(float(np.linalg.norm(w[3:])) for w in wrenches) or 1.0
            sizes = np.linalg.norm(wrenches, axis=1)
            rest = wrenches.copy()  # each wrench's part off the span of those picked
            while True:
                shares = np.linalg.norm(rest, axis=1) / sizes
                k = int(np.argmax(shares))  # the first of equals: an acting one
                if shares[k] <= DEPENDENT_WRENCHES:
                    break
                picked.add(k)
                unit = rest[k] / float(np.linalg.norm(rest[k]))
                rest -= np.outer(rest @ unit, unit)
        for k, condition in enumerate(held):
            if (k in picked) != condition.acting:
                condition.act(mbs, k in picked)
        for condition in self.conditions:
            if condition.acting and not condition.plan.active:
                condition.act(mbs, False)

    def reaction(self, mbs: exu.MainSystem, condition: _GroupCondition) -> float:
        """``condition``'s share [N] of the held contacts' load in the Newton solve just done:
        the least-squares (minimum norm) multipliers ``lambda`` of all contacts held in it
        with ``W^T lambda = W_a^T lambda_a``, the wrench the acting ones' multipliers
        ``lambda_a`` apply (``W`` the contacts' unit wrenches); the acting multipliers
        themselves where none is held by others.  Computed at the first contact's call after
        the solve, before any contact sets its condition for the next computation."""
        solve = solve_of(mbs)
        if self._shares[0] != solve:
            held = [c for c in self.conditions if c.plan.active]
            forces = np.array([c.own_multiplier(mbs) for c in held])
            if held and not all(c.acting for c in held):
                wrenches = np.array([c.wrench(mbs) for c in held])
                load = wrenches.T @ forces  # the off conditions' multipliers are 0
                forces = np.linalg.lstsq(wrenches.T, load, rcond=None)[0]
            self._shares = (solve, {id(c): float(f) for c, f in zip(held, forces)})
            self.last_held = _held(mbs, held, forces)
        return self._shares[1].get(id(condition), 0.0)


class _Held(NamedTuple):
    """The held contacts of a Newton solve, for the notes of a run that ends there."""

    time: float  # the end of the step [s]
    names: list[str]
    largest: float  # the largest held force [N]
    net: float  # the size of their resultant force [N]
    wedged: bool  # two normal conditions on opposite walls


def _held(mbs: exu.MainSystem, held: Sequence[_GroupCondition], forces: np.ndarray) -> _Held:
    """The record of the contacts ``held`` in the Newton solve just done, with their forces."""
    directions = np.array([c.wrench(mbs)[:3] for c in held]).reshape(-1, 3)
    normals = directions[[not isinstance(c, _GroupStick) for c in held]]
    wedged = bool(len(normals)) and float((normals @ normals.T).min()) < OPPOSITE
    names = [c.label.split(": ", 1)[-1] for c in held]  # without the joint's name
    return _Held(float(mbs.systemData.GetTime()), names, float(np.abs(forces).max(initial=0.0)),
                 float(np.linalg.norm(directions.T @ forces)), wedged)


class _GroupCondition(VelocityCondition):
    """A contact's condition, on in Exudyn only where the acting contacts do not hold it
    (:class:`_Contacts`)."""

    def __init__(self, mbs: exu.MainSystem, name: str, contacts: _Contacts, pair: ContactPair) -> None:
        super().__init__(mbs, contacts.state, name)
        self.contacts, self.pair, self.acting, self.label = contacts, pair, False, name
        self.normal = np.zeros(3)
        self._wrench: tuple[Any, Any, np.ndarray] | None = None  # the last wrench, with the poses and normal it is of
        contacts.conditions.append(self)

    def measure(self, mbs: exu.MainSystem, normal: np.ndarray, arms: Sequence[Any] = (None, None)) -> float:
        self.normal = np.asarray(normal, dtype=float)  # the normal of the rows, which a plan holds
        return super().measure(mbs, normal, arms)

    def wrench(self, mbs: exu.MainSystem) -> np.ndarray:
        """The unit wrench of the contact at the present state, ``(n, S x n)`` (global): the
        normal ``n = e / |e|`` at the outer body's point ``S`` (from marker 0's point), or,
        where ``|e|`` is below :data:`NEAR` of the play (a journal's slice near the bearing's
        centre), the normal the condition's rows hold.  A condition's rows are this wrench mapped onto the two bodies'
        coordinates by one map for all of a joint's contacts (the inner body's point and
        ``S`` lie along ``n``), so the contacts' conditions are dependent where their
        wrenches are."""
        poses = self.state.poses(mbs, self.pair.rotations)
        if self._wrench is not None and self._wrench[0] is poses and self._wrench[1] is self.normal:
            return self._wrench[2]  # the contacts ask for each other's wrenches several times a state
        ecc = self.pair.eccentricity(poses)
        n = self.present_normal(ecc)
        wrench = np.array((*n, *(cross(ecc.arm, n) if ecc.arm is not None else (0.0, 0.0, 0.0))))
        self._wrench = (poses, self.normal, wrench)
        return wrench

    def present_normal(self, ecc: Eccentricity) -> np.ndarray:
        """The contact's normal for its eccentricity at the present state (:meth:`wrench`)."""
        length = norm(ecc.e)
        return ecc.e / length if length > NEAR * self.pair.clearance else self.normal

    def switch(self, mbs: exu.MainSystem, on: bool) -> None:
        """On where the plan holds the contact and the acting contacts do not
        (:meth:`_Contacts.select`, which lets a contact they held act again where they no
        longer hold it)."""
        if not on and self.acting:
            self.act(mbs, False)
        self.contacts.select(mbs)
        request_jacobian(mbs)  # its rows or rate changed where it stays on

    def act(self, mbs: exu.MainSystem, on: bool) -> None:
        self.acting = on
        super().switch(mbs, on)

    def own_multiplier(self, mbs: exu.MainSystem) -> float:
        """The multiplier of the condition in Exudyn [N] (0 where it is off)."""
        return super().multiplier(mbs) if self.acting else 0.0

    def multiplier(self, mbs: exu.MainSystem) -> float:
        return self.contacts.reaction(mbs, self) if self.plan.active else 0.0


class _GroupStick(_GroupCondition):
    """A contact's sticking condition along its ``tangent`` (the index of
    :func:`~exuclear.engine.impulse_friction.tangents`), held with the joint's other
    conditions: a slider sticking flat on its wall holds its two corners along the guide's
    axis in one direction, one condition on in Exudyn, the other held by it, the friction
    split as the reactions are (:meth:`_Contacts.reaction`)."""

    def __init__(self, mbs: exu.MainSystem, name: str, contacts: _Contacts, pair: ContactPair, tangent: int,
                 normal: _GroupCondition) -> None:
        super().__init__(mbs, name, contacts, pair)
        self.tangent, self.normal_condition = tangent, normal

    def wrench(self, mbs: exu.MainSystem) -> np.ndarray:
        """The unit wrench ``(t, P x t)`` of the friction along the tangent at the contact
        point ``P`` (from marker 0's point), at the present state as the normal conditions'
        (a sticking condition's rows are measured where its step starts or ends, and wrenches
        of different states make a dependent set pass as independent); an end face's, the
        couple ``(0, u)`` about the journal's axis."""
        ecc = self.pair.eccentricity(self.state.poses(mbs, self.pair.rotations))
        if isinstance(self.pair, FacePair):  # an end face's friction: a couple about the journal's axis
            return np.concatenate((np.zeros(3), self.pair.spin_axis(ecc)))
        n = self.normal_condition.present_normal(ecc)
        if self.pair.plane is None:  # its own tangent, carried into the present tangent plane
            t = self.normal - (self.normal @ n) * n
            t = t / float(np.linalg.norm(t))
        else:
            t = tangents(mbs, self.pair, self.markers, n)[self.tangent]
        return np.concatenate((t, np.cross(contact_arms(self.pair, n, ecc)[0], t)))


class _GroupPair(ImpulseJointHandle):
    """One contact of a joint with several in the mode; remembers the name of each of its
    contacts' onsets (``pair.contact_name``: a corner's wall)."""

    settled_with_friction = False  # the contacts share the load indeterminately (exuclear.engine.settling)

    def __init__(self, *args: Any, contacts: _Contacts) -> None:
        self._contacts = contacts
        self._names: dict[float, str] = {}  # onset time [s] -> the contact's name
        super().__init__(*args)

    def _marker_state(self, mbs: exu.MainSystem) -> MarkerState:
        return self._contacts.state

    def _new_condition(self, mbs: exu.MainSystem, name: str, tangent: int | None = None) -> VelocityCondition:
        if tangent is None:
            return _GroupCondition(mbs, name, self._contacts, self._pair)
        return _GroupStick(mbs, name, self._contacts, self._pair, tangent, self._condition)

    def _reset(self) -> None:
        super()._reset()
        self._contacts.forget()

    def _post_newton(self, mbs: exu.MainSystem, t: float, item: int, data: Any, *frame: Any) -> list:
        out = super()._post_newton(mbs, t, item, data, *frame)
        self._contacts.decided(mbs, self, out[0])
        return out

    def take_back(self, mbs: exu.MainSystem) -> None:
        """The condition and the friction of the step just accepted back
        (:meth:`_Contacts.decided`): Exudyn computes it again."""
        if self._saved is not None:
            self._condition.set(mbs, self._saved["plan"])
            self._friction.restore(mbs, self._saved["friction"])

    def _contact(self, mbs: exu.MainSystem, t: float, h: float, end: np.ndarray, end_gap: float) -> bool:
        if end_gap > CROSSING * self._pair.clearance:
            with start_of_step(mbs, accelerations=False):
                before = self._pair.eccentricity(self._markers.poses(mbs, self._pair.rotations))
            if not before.wall and norm(before.e) > self._pair.reach:  # beyond a guide's end, below its wall's level
                self._stop(t, f"the {self._pair.body} came back into the guide {end_gap:.3g} m into its wall: it "
                              "struck the guide's end, which the joint does not model (its walls end there)")
        name = self._pair.contact_name(self._markers.poses(mbs, self._pair.rotations))  # at the step's end, in the wall
        began = super()._contact(mbs, t, h, end, end_gap)
        if began:
            self._names[t] = name
        return began

    def contact_name(self, onset_time: float) -> str:
        return self._names.get(onset_time, "")

    def _held_contacts(self) -> str:
        """The contacts held in the last Newton solve and their forces, and a body wedged
        between opposite walls, for the error of a run whose Newton iteration failed there."""
        held = self._contacts.last_held
        if held is None or not held.names:
            return ""
        note = (f"; the contacts held in its last solve (t = {held.time:.6g} s): {', '.join(held.names)}, with forces "
                f"up to {held.largest:.3g} N against their resultant {held.net:.3g} N")
        if held.wedged:
            note += (": the body is wedged between opposite walls, held on both, where rigid contacts with friction "
                     "need not have a unique solution (Painleve's paradox)")
        return note

    def impacts(self) -> list[ClosedFormImpact]:
        """As :meth:`~exuclear.engine.impulse.ImpulseJointHandle.impacts`, for a contact with
        the share ``f`` of the law (a slice's ``w / L``): its force ``f F(delta)`` on its
        share ``m`` of the mass is the whole law's on ``m / f`` times ``f``, the same duration
        and penetration; for a contact with a law of its own (``pair.law``: an end face's flat
        punch), that law's."""
        share, law = self._pair.share, self._pair.law
        out = super().impacts()
        if share == 1.0 and law is None:
            return out
        scaled = []
        for impact in out:
            if impact.effective_mass > 0.0 and impact.onset_velocity > 0.0:
                peak, duration, depth = closed_form_impact(law or self._joint.law, impact.effective_mass / share,
                                                           impact.onset_velocity)
                impact = impact._replace(peak_force=share * peak, duration=duration, max_penetration=depth)
            scaled.append(impact)
        return scaled


class ImpulsePairsHandle:
    """A clearance joint with several contacts in the impulse mode: returned by
    :func:`exuclear.CreatePrismaticClearanceJoint` (as its
    :class:`~exuclear.engine.impulse_guide.ImpulseGuideHandle`) and by
    :func:`exuclear.CreateClearanceJoint` with ``slices`` (and ``axial_clearance``: its end
    faces) and ``contact_mode="impulse"``.

    Attributes
    ----------
    pairs : dict
        The contacts by name (``"corner front-lower / lower and upper walls"``,
        ``"slice 1 at z = -0.005 m"``, ``"end face at z = 0.0075 m"``), each an
        :class:`~exuclear.engine.impulse.ImpulseJointHandle` with its condition
        (``objectNumber``) and carrier (``carrierNumber``).
    objectNumbers, carrierNumbers : list
        The pairs' conditions and carriers, in the order of :attr:`pairs`.
    markerNumbers : list
        [outer body's marker (guide, bearing), inner body's marker (slider, journal)].
    constraintNumber : int or None
        The ``ObjectJointGeneric`` of ``constrainAxial=True`` (the spatial revolute joint).
    contact_mode : str
        ``"impulse"``.
    """

    contact_mode = "impulse"

    def __init__(self, mbs: exu.MainSystem, joint: ClearanceJoint, name: str, markers: Sequence[Any],
                 pairs: Sequence[tuple[str, ContactPair]]) -> None:
        self.name, self._joint = name, joint
        self.markerNumbers = list(markers)
        self.constraintNumber: int | None = None
        self.pairs: dict[str, _GroupPair] = {}
        contacts = _Contacts(MarkerState(mbs, self.markerNumbers))
        for pair_name, pair in pairs:
            self.pairs[pair_name] = _GroupPair(mbs, joint, f"{name or '(unnamed)'}: {pair_name}", self.markerNumbers,
                                               pair, contacts=contacts)
            self.pairs[pair_name]._friction.tell_gains = False  # told for the pairs together (notes)
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
        """The impacts of the last run of every contact, in time (resting contacts' onsets
        included, restitution 0), each naming its contact (:class:`ClosedFormPairImpact`;
        the closed form as :meth:`~exuclear.engine.impulse.ImpulseJointHandle.impacts`, with
        the contact's share of the impulse)."""
        out = [ClosedFormPairImpact(*impact, pair.contact_name(impact.onset_time))
               for pair in self.pairs.values() for impact in pair.impacts()]
        return sorted(out, key=lambda impact: impact.onset_time)

    def outputs(self) -> dict[str, dict[str, np.ndarray]]:
        """Each pair's outputs by its name
        (:meth:`~exuclear.engine.impulse.ImpulseJointHandle.outputs`: ``ecc_x``, ``ecc_y``,
        ``ecc_z`` the pair's eccentricity, global; ``penetration``; ``normal_force`` its
        share of the held load)."""
        return {name: pair.outputs() for name, pair in self.pairs.items()}

    @property
    def notes(self) -> list[str]:
        """The pairs' notes (:attr:`~exuclear.engine.impulse.ImpulseJointHandle.notes`), each
        headed by its pair's name, and the impacts whose impulses added energy, the pairs' together."""
        own = [f"{name}: {note}" for name, pair in self.pairs.items() for note in pair.notes]
        # the energy the contacts' impulses added in a step, summed over them (impulse_run.gains_note)
        return own + gains_note([jump for pair in self.pairs.values() for jump in pair._friction.jumps])


def add_impulse_slices(mbs: exu.MainSystem, joint: ClearanceJoint, name: str, markers: Sequence[Any],
                       frame: np.ndarray, journal_axis: np.ndarray, slices: int,
                       shoulders: ShoulderGeometry | None = None, axial: bool = True) -> ImpulsePairsHandle:
    """The impulse mode's items for a spatial revolute joint of ``slices`` slices between
    ``markers`` [bearing, journal]: a condition and a carrier per slice
    (:class:`~exuclear.engine.impulse_pairs.SlicePair`), then per end face where the joint
    has ``shoulders`` (:class:`~exuclear.engine.impulse_pairs.FacePair`, the order of the
    compliant joint's contacts), ``frame`` the joint frame in marker 0's frame,
    ``journal_axis`` the journal's axis in marker 1's frame; ``axial`` False where the model
    holds the journal axially (``constrainAxial``: the slices' friction only circumferential)."""
    frame, journal_axis = np.asarray(frame, dtype=float), np.asarray(journal_axis, dtype=float)
    geometry, pairs = joint.geometry, []
    for k, z in enumerate(slice_centres(geometry.length, slices)):
        label = f"slice {k + 1} at z = {z:.4g} m"
        pairs.append((label, SlicePair(geometry.clearance, geometry.journal_radius, frame, journal_axis, z, label,
                                       1.0 / slices, axial)))
    if shoulders is not None:
        # the face's flat punch with the joint law's damping (docs/physics.md eqs. (52)-(53))
        law = ContactLaw(GivenStiffness(geometry, 1.0, shoulders.face_stiffness(joint.law.E_star), 1.0),
                         joint.law.damping_model, joint.law.v_min)
        for side in FACE_SIDES:
            label = f"end face at z = {0.5 * side * geometry.length:.4g} m"
            pairs.append((label, FacePair(frame, journal_axis, geometry.length, shoulders.axial_clearance, side,
                                          label, law, shoulders.friction_radius)))
    return ImpulsePairsHandle(mbs, joint, name, markers, pairs)
