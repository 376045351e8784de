"""The handle of a clearance joint in an Exudyn system (:class:`ClearanceJointHandle`):
its item numbers, its physics (replaceable between runs), and what its last run left
(contact states, impacts, outputs).  It talks to its kernel through a backend
(:mod:`exuclear.engine.backends`), the same methods for the compiled and the Python one."""
from __future__ import annotations

import itertools
import math
import warnings
import weakref
from dataclasses import dataclass
from typing import Any

import exudyn as exu
import numpy as np

from ..checks import check_nonnegative
from ..convergence import joint_refinement
from ..exceptions import AccuracyWarning
from ..history import ContactState, ImpactRecord, merge_overlapping
from ..joint import ClearanceJoint
from ..settings import NEWTON_RTOL_DEFAULT, RATE_LIMIT_DEFAULT
from ..spatial import FACE_SIDES, ShoulderGeometry, slice_centres
from ..timescales import STEPS_PER_CONTACT_PERIOD
from . import outputs as _outputs
from .backends import make_backend
from .layout import MAIN, PROBE, RUN_START_DEFAULT, TORQUE, RunStart, parameters, read, uses_bearing_motion
from .newton import ABSOLUTE_TOLERANCE, explicit_solver, steer_newton, vote_jacobian

_TOKENS = itertools.count(1)
#: ``mbs.variables`` key of the joints created in a system (for exuclear.simulate).
REGISTRY_KEY = "exuclear.joints"


class ClearanceJointHandle:
    """A clearance joint in an Exudyn system; returned by :func:`CreateClearanceJoint`.

    Attributes (Exudyn indices)
    ---------------------------
    objectNumber : the joint's connector; ``SensorObject`` on it with ``ForceLocal`` /
        ``TorqueLocal`` records ``-F_i`` and ``-M_i`` (the loads on the bearing from the
        journal, in the bearing's joint frame).
    nodeNumber : the ``NodeGenericData`` with :data:`exuclear.engine.layout.DATA_COLUMNS`
        after every accepted step.
    markerNumbers : [bearing marker, journal marker].
    sensorNumber : the sensor that records the data node (None with ``record=False``).
    probeNumber, torqueNumber : the bearing-spin probe and torque connectors (None where
        the bearing is the ground).
    constraintNumber : the ``ObjectJointGeneric`` of ``constrainAxial=True``, else None.
    drawingNumber : the ground object whose graphics function draws journal and bearing
        (``show=True``), else None.
    """

    # The system keeps its joints (mbs.variables, for exuclear.simulate), and a handle refers to
    # its system: with strong references both ways that is a cycle through Exudyn's C++, which
    # Python's garbage collector cannot see, so no model would ever be freed.  The system keeps
    # a view instead: the same handle (one shared attribute dict) without the strong reference
    # (slot ``_system``), reaching its system through a weak reference.
    __slots__ = ("__dict__", "_system")

    def __init__(self, mbs: exu.MainSystem, joint: ClearanceJoint, name: str, backend: str,
                 max_penetration: float, slices: int = 0,
                 axis_journal: tuple[float, float, float] = (0.0, 0.0, 1.0),
                 shoulders: ShoulderGeometry | None = None) -> None:
        self._system = mbs  # the user's handle keeps its system alive; the system's view of it does not
        self._mbs = weakref.ref(mbs)
        self.name, self.backend, self.max_penetration = name, backend, max_penetration
        self._joint = joint
        self.slices, self.axis_journal, self.shoulders = slices, axis_journal, shoulders
        self._backend = make_backend(backend, joint, slices, axis_journal, shoulders)
        self.joint_id = self._backend.joint_id
        self.objectNumber: Any = None
        self.nodeNumber: Any = None
        self.markerNumbers: list = []
        self.sensorNumber: Any = None
        self.probeNumber: Any = None
        self.torqueNumber: Any = None
        self.constraintNumber: Any = None
        self.drawingNumber: Any = None
        self._axis_local: np.ndarray | None = None  # the bearing axis in marker 0's frame
        self._drawing: dict = {}  # CreateClearanceJoint's drawing sizes (engine/drawing.py)
        self.loadSensorNumbers: list = []  # a spatial joint's ForceLocal and TorqueLocal sensors (outputs())
        self._impact_step = 0.0
        self._rate_limit = RATE_LIMIT_DEFAULT
        #: Whether the joint sets the Newton settings of the implicit runs it starts
        #: (:mod:`exuclear.engine.newton`); ``newton_changes``: what it set in the last run.
        self.steer_newton = True
        self.newton_changes: dict[str, tuple[Any, Any]] = {}
        self.token = next(_TOKENS)  # identifies the handle's connector in its system (see is_live)
        self._reported_run, self._notes = 0, []
        self._told_run, self._told = 0, set()  # the run, and the kinds of notes already warned of
        self._backend.set_run_start(_RunStart(mbs, self.token))

    @property
    def mbs(self) -> exu.MainSystem:
        """The joint's system."""
        try:
            return self._system
        except AttributeError:  # the system's view of the handle
            mbs = self._mbs()
            if mbs is None:
                raise RuntimeError(f"the system of joint {self.name!r} no longer exists") from None
            return mbs

    def _system_view(self) -> ClearanceJointHandle:
        """This handle as its system keeps it: the same attributes, no strong reference to the system."""
        view = object.__new__(ClearanceJointHandle)
        view.__dict__ = self.__dict__
        return view

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ClearanceJointHandle) and other.__dict__ is self.__dict__

    def __hash__(self) -> int:
        return id(self.__dict__)

    @property
    def frame(self) -> np.ndarray:
        """The joint frame in global coordinates in the reference configuration (3 x 3,
        columns x, y and z = the bearing axis): the frame of the connector's ``ForceLocal``
        and ``TorqueLocal`` and of the outputs ``ecc_x``, ``ecc_y``, ``tilt_x``, ``tilt_y``.
        :func:`CreateClearanceJoint` takes that of ``mbs.CreateRevoluteJoint`` (for axis z:
        x = -y_global, y = x_global); :func:`AddClearanceJoint` marker 0's frame, turned so
        that z is the axis (marker 0's own frame for axis z)."""
        rot = self.mbs.GetMarkerOutput(self.markerNumbers[0], exu.OutputVariableType.RotationMatrix,
                                       configuration=exu.ConfigurationType.Reference)
        return np.asarray(rot, dtype=float).reshape(3, 3) @ np.asarray(
            self.mbs.GetObject(self.objectNumber)["rotationMarker0"], dtype=float)

    def user_functions(self) -> dict[str, Any]:
        """The user functions of the joint's connector, probe and torque connector."""
        return self._backend.user_functions()

    # -- the physics, replaceable between runs ---------------------------------------------
    @property
    def joint(self) -> ClearanceJoint:
        """The joint's physics (geometry, contact law, friction law)."""
        return self._joint

    @joint.setter
    def joint(self, joint: ClearanceJoint) -> None:
        if not isinstance(joint, ClearanceJoint):
            raise ValueError(f"`joint` must be a ClearanceJoint, got {type(joint).__name__}")
        if (joint.film is None) != (self._joint.film is None):
            raise ValueError("a joint cannot change between dry and lubricated (its data node's size depends on it); "
                             "create a new clearance joint")
        self._joint = joint
        self._backend.set_joint(joint)
        self._write_parameters()

    def set_impact_step(self, impact_step: float) -> None:
        """Redo a step in which a contact begins with this step [s] (implicit solvers); 0: off."""
        self._impact_step = float(impact_step)
        self._write_parameters()

    @property
    def rate_limit(self) -> float:
        """KAPPA of the joint's own step control (README, "The joint steers the step"): a step
        in contact may change the penetration rate by at most this fraction of
        ``max(|v0|, v_min)``; default :data:`exuclear.settings.RATE_LIMIT_DEFAULT` (0.1, about
        20 steps per velocity reversal); smaller is more accurate and costs steps; 0 turns the
        criterion off.  Takes effect in the next run."""
        return self._rate_limit

    @rate_limit.setter
    def rate_limit(self, value: float) -> None:
        self._rate_limit = check_nonnegative("rate_limit", value)
        self._write_parameters()

    def parameters(self, role: int = MAIN) -> list[list[float]]:
        """The parameter matrix of the connector of ``role`` (:data:`exuclear.engine.layout.LAYOUT`)."""
        return parameters(self._joint, self.joint_id, role, self.max_penetration, self._impact_step,
                          self._rate_limit, compiled=self._backend.compiled, slices=self.slices, axis_journal=self.axis_journal,
                          shoulders=self.shoulders, token=self.token)

    def _write_parameters(self) -> None:
        for number, role in ((self.objectNumber, MAIN), (self.probeNumber, PROBE), (self.torqueNumber, TORQUE)):
            if number is not None:
                self.mbs.SetObjectParameter(number, "stiffness", self.parameters(role))
        # the probe and torque connectors run only where the loads use the bearing's spin
        active = uses_bearing_motion(self._joint, self.slices)
        for number in (self.probeNumber, self.torqueNumber):
            if number is not None:
                self.mbs.SetObjectParameter(number, "activeConnector", active)

    def is_live(self) -> bool:
        """Whether the joint's connector is still in its system (not removed by ``mbs.Reset()``)."""
        try:
            stiffness = self.mbs.GetObjectParameter(self.objectNumber, "stiffness")
            return read(stiffness, "token") == float(self.token)
        except Exception:  # the index no longer exists, or is another kind of object
            return False

    # -- state ---------------------------------------------------------------------------
    def reset(self) -> None:
        """Forget the contact history (a run also does so when it starts from its initial time)."""
        self._backend.reset()

    def state(self) -> ContactState:
        """The contact history after the last accepted step (a spatial joint: that of its
        most penetrated slice or end face)."""
        states = self._backend.states()
        return max(states, key=lambda s: s.delta) if states else ContactState()  # before a run: no state

    def slice_states(self, which: str = "current") -> list[ContactState]:
        """A spatial joint's slice histories after the last accepted step (``which=
        "initial"``: at the run's initial state), slice 0 at ``z = -L/2``."""
        self._check_slices()
        return self._backend.states(which)[:self.slices]

    def face_states(self, which: str = "current") -> list[ContactState]:
        """The end faces' contact histories (docs/physics.md section 9.6), face 0 at
        ``z = -L/2``; ``delta`` is the axial penetration."""
        self._check_faces()
        return self._backend.states(which)[self.slices:]

    def _check_slices(self) -> None:
        if not self.slices:
            raise ValueError(f"joint {self.name!r} is planar (slices=None): it has no slices")

    def _check_faces(self) -> None:
        if self.shoulders is None:
            raise ValueError(f"joint {self.name!r} has no axial clearance (axial_clearance=None): it has no end faces")

    @property
    def slice_positions(self) -> np.ndarray:
        """Axial positions ``z_k`` [m] of a spatial joint's slice planes in the bearing's
        joint frame (docs/physics.md eq. (33))."""
        self._check_slices()
        return np.array(slice_centres(self._joint.geometry.length, self.slices))

    def slice_impacts(self) -> list[list[ImpactRecord]]:
        """A spatial joint's ended contacts, per slice."""
        self._check_slices()
        return self._backend.records()[:self.slices]

    def face_impacts(self) -> list[list[ImpactRecord]]:
        """The end faces' ended contacts (axial impacts), per face (face 0 at ``z = -L/2``)."""
        self._check_faces()
        return self._backend.records()[self.slices:]

    def impacts(self) -> list[ImpactRecord]:
        """Records of the contacts that ended in the last run, in order; a contact still
        going on at the end is :meth:`state` (``in_contact``).  A spatial joint: its
        physical impacts, the slices' records that overlap in time merged into one
        (:func:`exuclear.history.merge_overlapping`; per slice: :meth:`slice_impacts`),
        and the end faces' records with an axial clearance (:meth:`face_impacts`)."""
        self._report()
        records = self._backend.records()
        if self.slices:
            records = [merge_overlapping([r for rs in records[:self.slices] for r in rs]), *records[self.slices:]]
        return sorted((r for rs in records for r in rs), key=lambda r: r.onset_time)

    @property
    def nodes(self) -> list[int]:
        """The nodes of the bearing's and the journal's bodies (where a body has one node), or of their node markers."""
        found = []
        for marker in self.markerNumbers:
            m = self.mbs.GetMarker(marker)
            body = m.get("bodyNumber", m.get("objectNumber"))
            node = self.mbs.GetObject(body).get("nodeNumber") if body is not None else m.get("nodeNumber")
            if node is not None and int(node) >= 0:
                found.append(int(node))
        return found

    @property
    def history(self) -> JointHistory:
        """The contact history of the last run: the state after the last accepted step, the
        records of the ended contacts, and every onset time."""
        state, impacts = self.state(), self.impacts()
        onset_times = [r.onset_time for r in impacts] + ([state.onset_time] if state.in_contact else [])
        return JointHistory(state, impacts, onset_times)

    def failure(self) -> tuple[str, float]:
        """Why and when the joint stopped the last run (``""`` if it did not)."""
        self._report()
        return self._backend.failure()

    @property
    def counts(self) -> dict[str, int]:
        """What the joint counted in the last run, so that a user of a plain
        ``mbs.SolveDynamic`` needs no solver internals: ``impacts`` (contacts begun, as
        :attr:`history`'s ``onsets``), ``rejected_steps`` (steps the joint's step control
        sent back shorter), ``unresolved_steps`` (steps it could not have shortened enough:
        see :attr:`notes`) and ``over_limit_steps`` (accepted with a penetration beyond
        ``maxPenetration``)."""
        control = self._backend.step_control()
        return {"impacts": self.history.onsets, "rejected_steps": int(control["rejected"]),
                "unresolved_steps": int(control["unresolved"]), "over_limit_steps": int(control["over_limit"])}

    @property
    def notes(self) -> list[str]:
        """What the joint's own step control could not do in the last run (steps it could not
        resolve, a penetration beyond the limit), each with the joint's name, the time, the
        step and the step to use; empty if the run was resolved.  Each note is also issued
        once as an :class:`~exuclear.engine.solver.AccuracyWarning`, at the first access to
        the joint's results after the run."""
        self._report()
        return list(self._notes)

    def _report(self, running: bool = False) -> None:
        """Turn the kernel's step-control counters into notes, and warn of each kind of note
        once per run: at once where the kernel tells (``running``, during the run), else at
        the first access to the joint's results after the run."""
        control = self._backend.step_control()
        runs = control["runs"]
        if runs != self._told_run:
            self._told_run, self._told = runs, set()
        if not running:
            if runs == self._reported_run:
                return
            self._reported_run = runs
        notes = _step_notes(self, control, running)
        self._notes = [text for _kind, text in notes]
        fresh = [text for kind, text in notes if kind not in self._told]
        self._told.update(kind for kind, _text in notes)
        if fresh:
            for note in fresh:
                warnings.warn(note, AccuracyWarning, stacklevel=3)

    def outputs(self) -> dict[str, np.ndarray]:
        """Recorded outputs: ``time`` and :data:`OUTPUT_COLUMNS`, SI units (a spatial joint:
        see :func:`exuclear.engine.outputs.assemble`, with the joint-level
        :data:`~exuclear.engine.outputs.SPATIAL_JOINT_OUTPUTS`; a lubricated joint's also
        :data:`~exuclear.engine.outputs.FILM_OUTPUT_COLUMNS`).

        Recorded at Exudyn's sensor write period (``solution.sensors.writePeriod``) from
        the data node, i.e. at accepted steps; the first row is the run's initial state.
        """
        self._report()
        if self.sensorNumber is None:
            raise RuntimeError(f"joint {self.name!r} was created with record=False: nothing was recorded")
        try:
            data = np.asarray(self.mbs.GetSensorStoredData(self.sensorNumber), dtype=float)
        except Exception:  # Exudyn raises when the sensor has no data yet
            data = np.zeros((0, 0))
        if data.ndim != 2 or data.shape[0] == 0:
            raise RuntimeError(f"joint {self.name!r} has no outputs yet: run a simulation first")
        if self._backend.started():
            initial = self._backend.states("initial")
            if data[0, 0] == initial[0].time:  # the data node holds no state before the first step
                data = data.copy()
                data[0, 1:] = _outputs.initial_data(self.slices, initial, *self._backend.initial_pose(),
                                                    lubricated=self._joint.film is not None)
        loads = [np.asarray(self.mbs.GetSensorStoredData(n), dtype=float) for n in self.loadSensorNumbers]
        return _outputs.assemble(data, self.slices, len(FACE_SIDES) if self.shoulders is not None else 0,
                                 self._joint.film, loads)


@dataclass(frozen=True)
class JointHistory:
    """A joint's contact history after a run (:attr:`ClearanceJointHandle.history`)."""

    state: ContactState
    impacts: list[ImpactRecord]
    onset_times: list[float]

    @property
    def onsets(self) -> int:
        """Contacts begun in the run (impacts)."""
        return len(self.onset_times)

    @property
    def in_contact(self) -> bool:
        return self.state.in_contact

    @property
    def v0(self) -> float:
        return self.state.v0

    @property
    def delta(self) -> float:
        return self.state.delta


def label(handle: ClearanceJointHandle) -> str:
    """How messages name a joint: its name, else its connector's object number."""
    return repr(handle.name) if handle.name else str(handle.objectNumber)


def solver_steps(mbs: exu.MainSystem) -> tuple[bool, float, str, bool]:
    """Whether the solver of the run ``mbs.SolveDynamic`` is starting redoes a step that a
    post-Newton function rejects with a shorter one, its minimum step [s], if not, why, and
    whether the joint's rate criterion applies (SolveDynamic stores its settings and solver
    in ``mbs.sys`` before solving).  The rate criterion is off where an explicit solver
    controls its step by its error estimate (DOPRI5 and the like): that control resolves
    the contact (the paper's numbers come from it), and the criterion would only add
    rejected steps.  Unknown settings (a solver run without SolveDynamic) count as able to
    shorten: a step that comes back unshortened is then accepted and reported."""
    try:
        ti = mbs.sys["simulationSettings"].timeIntegration
        solver = mbs.sys["dynamicSolver"]
        explicit = explicit_solver(solver)
    except Exception:  # no SolveDynamic run: the kernel's defaults
        return True, 0.0, "", True
    if explicit:
        try:
            error_control = bool(ti.automaticStepSize) and bool(solver.HasAutomaticStepSizeControl(
                mbs, mbs.sys["simulationSettings"]))
        except Exception:  # an Exudyn without the query: keep the criterion
            error_control = False
        return (bool(ti.automaticStepSize), float(ti.minimumStepSize),
                "" if ti.automaticStepSize else "timeIntegration.automaticStepSize is False", not error_control)
    return (bool(ti.adaptiveStep), float(ti.minimumStepSize),
            "" if ti.adaptiveStep else "timeIntegration.adaptiveStep is False", True)


#: A step grown in free flight lasts at most this many of the joint's contact periods (under
#: its weight, exuclear.timescales): the contact that ends the flight starts from a step its
#: rate criterion cuts to the contact's resolution in one or two attempts (a tenth each),
#: where a longer one took more Newton solves at steps far too long.  Averages over three
#: restitutions (0.89 to 0.91), zoo models: exuclear.simulate's double pendulum, whose
#: largest step is 20 contact periods, 9964 -> 6162 steps; the own-settings runs, whose
#: steps are at most 8 periods (but the beam pendulum's, 59), within the scatter that any
#: change of a bounce gives these chaotic models (the piston engine: 4694 and 10472 steps
#: at restitutions 0.90 and 0.91).
GROWTH_CONTACT_PERIODS = 10.0


def _separation_step(mbs: exu.MainSystem, period: float) -> float:
    """The longest step [s] in which a contact of a joint of contact ``period`` [s] ends
    resolved, in the implicit run ``mbs.SolveDynamic`` is starting: a tenth of the period
    (:data:`~exuclear.timescales.STEPS_PER_CONTACT_PERIOD`); inf where nothing is counted (an
    explicit solver: its error control, or the joint's rate criterion at fixed steps, resolves
    separations; an unknown period).  A contact that ends in a longer step of an implicit
    method rings and leaves the wall without a physical cause (a resting pendulum at steps of
    1e-3 s, 2.9 of its contact periods, leaves the wall 68 times in 2 s where DOPRI5 and
    physics give one contact): the joint counts such separations and its notes say so
    (:func:`_step_notes`)."""
    try:
        explicit = explicit_solver(mbs.sys["dynamicSolver"])
    except Exception:  # no SolveDynamic run: nothing to count against
        return math.inf
    return period / STEPS_PER_CONTACT_PERIOD if period > 0.0 and not explicit else math.inf


class _RunStart:
    """The kernel's run-start callback: returns the joint's
    :class:`~exuclear.engine.layout.RunStart` record for the run the solver is starting
    (whether the solver can shorten steps, its minimum step, the joint's label, how many
    clearance joints the system has, the factor on its ``rate_limit`` for the run, below 1
    inside :func:`exuclear.convergence.refined_joints`, the longest step its free flight may
    grow to, :data:`GROWTH_CONTACT_PERIODS`, the step above which it asks for a Jacobian per
    step, :func:`~exuclear.engine.newton.steer_newton`, where finite it asks at the run's
    first step, the step above which a contact's end counts as unresolved,
    :func:`_separation_step`, and the effective mass of its impacts, the reduced mass of its
    two bodies); its ``grow(step)`` lets the solver's next step grow, its
    ``jacobian_per_step(wanted)`` passes the joint's ask on.  It holds its system weakly and
    finds its handle by token: the kernel's table outlives no handle through it."""

    def __init__(self, mbs: exu.MainSystem, token: int) -> None:
        self._mbs, self._token = weakref.ref(mbs), token

    def __call__(self) -> RunStart:
        mbs = self._mbs()
        if mbs is None:
            return RUN_START_DEFAULT
        can_shorten, min_step, _why, rate = solver_steps(mbs)
        handle = self._handle(mbs)
        period, mass, jacobian_step = math.nan, math.nan, math.inf
        if handle is not None:
            from ._diagnostics import joint_contact_period, joint_mass  # the diagnostics import this module

            try:
                mass = joint_mass(mbs, handle)
                period = joint_contact_period(mbs, handle)
            except Exception:  # a body whose mass is not read: no Jacobian per step, no cap on growth
                period = math.nan
            if handle.steer_newton:
                handle.newton_changes, jacobian_step = steer_newton(mbs, period, self._token)
        growth_cap = GROWTH_CONTACT_PERIODS * period if period > 0.0 else math.inf
        # inside check_convergence's tighter plain run the joints refine their own steps too
        rate_scale = 1.0 / joint_refinement()
        return RunStart(can_shorten, min_step, label(handle) if handle is not None else "", rate, len(joints_of(mbs)),
                        rate_scale, growth_cap, jacobian_step, _separation_step(mbs, period), mass)

    def jacobian_per_step(self, wanted: bool) -> None:
        """The joint asks for a Jacobian per step (``wanted``) or no longer (its kernel's
        ``steer_jacobian``, where its ask changes): :func:`~exuclear.engine.newton.vote_jacobian`."""
        mbs = self._mbs()
        if mbs is not None:
            vote_jacobian(mbs, self._token, wanted)

    def grow(self, step: float) -> None:
        """The joints' free flight allows ``step`` [s] next (the kernel's ``report_growth``):
        lengthen the solver's next step to it, within the solver's largest step.  Exudyn's
        implicit solver takes ``it.currentStepSize`` for its next step (and redoes a rejected
        one shorter, or doubles it after its recovery steps, from there)."""
        mbs = self._mbs()
        try:
            it = mbs.sys["dynamicSolver"].it
            step = min(step, it.maxStepSize)
            if step > it.currentStepSize:
                it.currentStepSize = step
        except Exception:  # no SolveDynamic solver (a solver run by hand): Exudyn's own rule
            pass

    def _handle(self, mbs: exu.MainSystem) -> ClearanceJointHandle | None:
        return next((h for h in mbs.variables.get(REGISTRY_KEY, []) if h.token == self._token), None)

    def note(self) -> None:
        """The kernel's first unresolved step of a kind in this run: warn now (the run may
        still be stopped by Exudyn, after which nobody might ask the joint)."""
        mbs = self._mbs()
        handle = self._handle(mbs) if mbs is not None else None
        if handle is not None:
            handle._report(running=True)


def _step_notes(handle: ClearanceJointHandle, control: dict[str, Any], running: bool = False) -> list[tuple[str, str]]:
    """(kind, sentence) for what the joint's step control could not do in the last run: each names
    the joint, what happened (time, step, penetration / c) and the fixed step to use: the
    smaller of the kernel's recommendation at the worst step and a tenth of the joint's
    contact period under its weight (exuclear.timescales, as ``step="auto"``; an impact
    can be faster than that scale, measured on the journal impact: 2.1e-5 s against the
    5.1e-6 s the impact needs).  Letting the solver shorten steps is cheaper."""
    stopped = [] if running else _stopped_note(handle) + _chatter_note(handle, control)
    if not control["unresolved"] and not control["over_limit"]:
        return stopped
    _can, _min, why, _rate = solver_steps(handle.mbs)
    period = math.nan
    try:
        from ._diagnostics import joint_contact_period

        period = joint_contact_period(handle.mbs, handle)
    except Exception:  # a body whose mass is not read: the kernel's recommendation stands
        pass
    name, c = label(handle), handle.joint.geometry.clearance
    notes = []
    for kind, count, when, step, advice, what, otherwise in (
            ("unresolved", control["unresolved"], control["unresolved_time"], control["unresolved_step"],
             control["unresolved_advice"], "did not resolve the contact (the penetration rate changed by more than "
                                           "the joint's step control allows)", "the same step came back unshortened"),
            ("over_limit", control["over_limit"], control["over_time"], control["over_step"], control["over_step"] / 4,
             f"let the penetration reach {control['deepest'] / c:.3g} c, beyond the joint's limit "
             f"{handle.max_penetration / c:.3g} c", "4 shorter attempts did not remove it")):
        if not count:
            continue
        if period > 0.0:  # a tenth of the contact period under the weight, as step="auto"; an
            advice = min(advice, period / 10)  # impact is faster: the kernel's worst step is then shorter
        notes.append((kind, f"joint {name}: at t = {when:.6g} s a step of {step:.3g} s {what}, in {count} step(s) "
                     f"of the run{' so far' if running else ''}, which could not be shortened enough "
                     f"({why or otherwise}); the results may be inaccurate: use a step of at most {advice:.3g} s, "
                     "or let the solver shorten steps (timeIntegration.adaptiveStep = True for implicit, "
                     "automaticStepSize = True for explicit solvers)"))
    return notes + stopped


def _chatter_note(handle: ClearanceJointHandle, control: dict[str, Any]) -> list[tuple[str, str]]:
    """("chatter", sentence) where contacts of the last run ended in steps longer than a tenth
    of the joint's contact period (the kernel's ``long_separations``, :func:`_separation_step`):
    its contact onsets may be numerical chatter."""
    long, step = control["long_separations"], control["separation_step"]
    if not long:
        return []
    return [("chatter", f"joint {label(handle)}: {long} of its {control['separations']} contacts ended in a step "
             f"longer than a tenth of its contact period ({step * STEPS_PER_CONTACT_PERIOD:.2g} s, estimated); such "
             f"separations are not resolved, and the {handle.history.onsets} contact onsets may be numerical "
             f"chatter, not physics: use steps of at most {step:.2g} s where contacts open "
             "(timeIntegration.numberOfSteps, or exuclear.simulate's `step`), or an explicit adaptive method where "
             "the model allows")]


def _regime(handle: ClearanceJointHandle) -> str:
    """The joint's regime after the last accepted step, with its eccentricity ratio |e|/c:
    free flight or metal contact (with the penetration), and for a lubricated joint the film
    alone (eps <= eps_film), the film's blend near the wall (eq. (70)) or metal contact under
    the film (:data:`~exuclear.engine.outputs.REGIME_FILM` and the others).  A spatial joint:
    its most penetrated slice or end face (:meth:`ClearanceJointHandle.state`)."""
    state, c = handle.state(), handle.joint.geometry.clearance
    eps = f"|e|/c = {math.hypot(state.ecc_x, state.ecc_y) / c:.6g}"
    film = handle.joint.film
    if state.in_contact or state.delta > 0.0:
        where = "in metal contact under the film" if film is not None else "in metal contact"
        return f"{where} ({eps}, penetration {state.delta / c:.3g} c)"
    if film is None:
        return f"in free flight ({eps}, {-state.delta / c:.3g} c from the wall)"
    if math.hypot(state.ecc_x, state.ecc_y) / c > film.eps_film:
        return f"in the film's blend near the wall ({eps} > eps_film = {film.eps_film:g})"
    return f"carried by the film ({eps} <= eps_film = {film.eps_film:g})"


def _stop_cause(solver: Any, adaptive: bool, min_step: float) -> str:
    """Why Exudyn's solver ended its run early, from its convergence and output flags
    (``CSolverBase::GetErrorString`` and ``FinalizeSolver`` read the same ones)."""
    output, conv = solver.output, solver.conv
    if output.simulationStoppedByUser or output.simulationStoppedByUserFunction:
        return "stopped by the user (a pre- or post-step function returned False, or Ctrl+C)"
    if output.simulationTimeout:
        return "stopped at exudyn.special.solver.timeout"
    if conv.linearSolverFailed:
        return "its linear solver failed (the Jacobian is singular)"
    if conv.newtonSolutionDiverged:
        return "its Newton iteration diverged"
    if conv.stepReductionFailed:
        if adaptive:
            return f"its Newton did not converge, and the step reduction reached the minimum step ({min_step:g} s)"
        return "its Newton did not converge at the fixed step (timeIntegration.adaptiveStep is False)"
    return "an error in a user function or in Exudyn (the solver gives no cause)"


def _stopped_note(handle: ClearanceJointHandle) -> list[tuple[str, str]]:
    """("stopped", sentence) where Exudyn's solver ended the last run before its end time,
    whatever the joint's regime: Exudyn then says only "SolveDynamic terminated".  The
    sentence names the joint, the time, the joint's regime and |e|/c (:func:`_regime`), the
    cause (:func:`_stop_cause`) and, for a failed Newton, what to try: the tolerances in
    effect (the solver's copy, after :func:`~exuclear.engine.newton.steer_newton`) where they
    are tighter than the contact's round-off allows, said to be the user's where the joint
    kept them."""
    mbs = handle.mbs
    try:
        solver, settings = mbs.sys["dynamicSolver"], mbs.sys["simulationSettings"]
        ti = settings.timeIntegration
        end, adaptive, min_step = float(ti.endTime), bool(ti.adaptiveStep), float(ti.minimumStepSize)
        newton = solver.newton if not explicit_solver(solver) else None
    except Exception:  # no SolveDynamic run (or another solver): nothing to say
        return []
    t = mbs.systemData.GetTime()
    if t >= end * (1.0 - 1e-12) or not handle._backend.started():
        return []
    cause = _stop_cause(solver, adaptive, min_step)
    if solver.output.finishedSuccessfully and not cause.startswith("stopped"):
        return []  # a finished run whose time is not this solver's (e.g. a static solve since)
    note = (f"joint {label(handle)}: Exudyn's solver ended the run at t = {t:.6g} s of {end:g} s: {cause}; the joint "
            f"was then {_regime(handle)}")
    if "Newton" not in cause and "singular" not in cause:
        return [("stopped", note)]
    advice = []
    if newton is not None:
        rtol, atol = float(newton.relativeTolerance), float(newton.absoluteTolerance)
        if rtol < NEWTON_RTOL_DEFAULT or atol < ABSOLUTE_TOLERANCE:
            # the joint raises only Exudyn's default absolute tolerance: a tighter one is the user's
            advice.append(f"Newton tolerances the residual can reach (timeIntegration.newton.relativeTolerance >= "
                          f"{NEWTON_RTOL_DEFAULT:g}, now {rtol:g}; absoluteTolerance >= {ABSOLUTE_TOLERANCE:g}, now "
                          f"{atol:g}; the joint keeps tolerances the user set)")
    if not adaptive:
        advice.append("timeIntegration.adaptiveStep = True (Exudyn then shortens a step whose Newton fails)")
    advice.append("a shorter step; where Newton's residual stalls at every step length (timeIntegration.verboseMode = 2 "
                  "shows it), look for a singular position of the mechanism")
    return [("stopped", note + "; try " + ", or ".join(advice))]


def register(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> None:
    """Keep ``handle`` with its system (:func:`joints_of`); the joints of an earlier build,
    before ``mbs.Reset()``, are let go (their kernel state is released with their handle)."""
    mbs.variables[REGISTRY_KEY] = [*joints_of(mbs), handle._system_view()]


def joints_of(mbs: exu.MainSystem) -> list[ClearanceJointHandle]:
    """The clearance joints live in ``mbs`` (those of an earlier build, before ``mbs.Reset()``, dropped)."""
    live = [h for h in mbs.variables.get(REGISTRY_KEY, []) if h.is_live()]
    mbs.variables[REGISTRY_KEY] = live
    return live
