"""The handle of a clearance joint in an Exudyn system (:class:`ClearanceJointHandle`):
its item numbers, its physics (replaceable between runs), and what its last run left
(contact states, impacts, outputs).  It talks to its kernel through a backend
(:mod:`exuclear.engine.backends`), the same methods for the compiled and the Python one."""
from __future__ import annotations

import itertools
import warnings
import weakref
from dataclasses import dataclass
from typing import Any

import exudyn as exu
import numpy as np

from ..checks import check_nonnegative
from ..exceptions import AccuracyWarning
from ..history import ContactState, ImpactRecord, PairImpact, merge_overlapping
from ..joint import ClearanceJoint
from ..prismatic import pair_name
from ..settings import RATE_LIMIT_DEFAULT
from ..spatial import FACE_SIDES, ShoulderGeometry, slice_centres
from ..wear.profile import WearProfile
from . import outputs as _outputs
from .arguments import check_wear
from .backends import make_backend
from .diagnostics import step_notes
from .layout import MAIN, PROBE, TORQUE, TOKEN_ENTRY, parameters, second_parameters, uses_bearing_motion
from .placement import PLACED_BY_MARKERS
from .registry import label
from .steering import _RunStart

_TOKENS = itertools.count(1)


class ClearanceJointHandle:
    """A clearance joint in an Exudyn system; returned by :func:`CreateClearanceJoint`.

    The attributes are Exudyn indices.

    Attributes
    ----------
    objectNumber : int
        The joint's connector; ``SensorObject`` on it with ``ForceLocal`` / ``TorqueLocal``
        records ``-F_i`` and ``-M_i`` (the loads on the bearing from the journal, in the
        bearing's joint frame).
    nodeNumber : int
        The ``NodeGenericData`` with :data:`exuclear.engine.layout.DATA_COLUMNS` after every
        accepted step.
    markerNumbers : list of int
        [bearing marker, journal marker].
    sensorNumber : int or None
        The sensor that records the data node (None with ``record=False``).
    probeNumber, torqueNumber : int or None
        The bearing-spin probe and torque connectors (None where the bearing is the ground).
    constraintNumber : int or None
        The ``ObjectJointGeneric`` of ``constrainAxial=True``, else None.
    drawingNumber : int or None
        The ground object whose graphics function draws journal and bearing (``show=True``),
        else None.
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
        #: What placed the journal in its bearing, for the refusal of one that starts outside (engine.placement)
        self.placed_by = PLACED_BY_MARKERS
        self._axis_local: np.ndarray | None = None  # the bearing axis in marker 0's frame
        self._drawing: dict = {}  # CreateClearanceJoint's drawing sizes (engine/drawing.py)
        self.loadSensorNumbers: list = []  # a spatial joint's ForceLocal and TorqueLocal sensors (outputs())
        self._impact_step = 0.0
        self._rate_limit = RATE_LIMIT_DEFAULT
        #: Whether the joint sets the Newton settings of the implicit runs it starts
        #: (:mod:`exuclear.engine.steering`); ``newton_changes``: what it set in the last run.
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
                raise RuntimeError(f"the system of joint {self.name or self.objectNumber!r} no longer exists") from None
            return mbs

    def _system_view(self) -> ClearanceJointHandle:
        """This handle as its system keeps it: the same attributes, no strong reference to the system."""
        view = object.__new__(ClearanceJointHandle)
        view.__dict__ = self.__dict__
        return view

    def __repr__(self) -> str:
        kind = f"spatial, {self.slices} slices" if self.slices else "planar"
        try:
            name = label(self)
        except Exception:  # a handle being built: no system view yet
            name = repr(self.name)
        return (f"<ClearanceJointHandle {name}: {kind}, clearance {self._joint.geometry.clearance:.4g} m, "
                f"{type(self._joint.law).__name__} law, objectNumber {self.objectNumber}, markerNumbers "
                f"{list(self.markerNumbers)}, backend {self.backend!r}>")

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ClearanceJointHandle) and other.__dict__ is self.__dict__

    def __hash__(self) -> int:
        return id(self.__dict__)

    @property
    def joint_type(self) -> str:
        """The type of the joint's contact pair (its geometry's ``joint_type``), one of
        ``"revolute"``, ``"spherical"``, ``"prismatic"`` and ``"pin-slot"``."""
        return self._joint.geometry.joint_type

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
        if joint.geometry.joint_type != self.joint_type:
            raise ValueError(f"a {self.joint_type} joint cannot take the physics of a {joint.geometry.joint_type} "
                             "joint; create a new clearance joint")
        if getattr(joint.geometry, "spatial", False) != getattr(self._joint.geometry, "spatial", False):
            raise ValueError("a translational joint cannot change between planar and spatial (its pairs and its "
                             "markers' frame depend on it); create a new clearance joint")
        if (joint.film is None) != (self._joint.film is None):
            raise ValueError("a joint cannot change between dry and lubricated (its data node's size depends on it); "
                             "create a new clearance joint")
        check_wear(joint, self.slices, self.backend)  # a spatial joint's starting profiles: one row per slice
        self._joint = joint
        self._backend.set_joint(joint)
        self._write_parameters()

    def set_impact_step(self, impact_step: float) -> None:
        """Redo a step in which a contact begins with this step [s] (implicit solvers); 0: off."""
        self._impact_step = float(impact_step)
        self._write_parameters()

    @property
    def rate_limit(self) -> float:
        """KAPPA of the joint's own step control (docs/guide/solver_path.md, "What the joint does to your steps").  A step
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
                          shoulders=self.shoulders)

    def _write_parameters(self) -> None:
        for number, role in ((self.objectNumber, MAIN), (self.probeNumber, PROBE), (self.torqueNumber, TORQUE)):
            if number is not None:
                self.mbs.SetObjectParameter(number, "stiffness", self.parameters(role))
        self.mbs.SetObjectParameter(self.objectNumber, "damping", second_parameters(self._joint, self.token))
        # the probe and torque connectors run only where the loads use the bearing's spin
        active = uses_bearing_motion(self._joint, self.slices)
        for number in (self.probeNumber, self.torqueNumber):
            if number is not None:
                self.mbs.SetObjectParameter(number, "activeConnector", active)

    def is_live(self) -> bool:
        """Whether the joint's connector is still in its system (not removed by ``mbs.Reset()``)."""
        try:
            mark = self.mbs.GetObjectParameter(self.objectNumber, "damping")
            return float(np.asarray(mark)[TOKEN_ENTRY]) == float(self.token)
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
            raise ValueError(f"joint {label(self)} is planar (slices=None): it has no slices")

    def _check_faces(self) -> None:
        if self.shoulders is None:
            raise ValueError(f"joint {label(self)} has no axial clearance (axial_clearance=None): it has no end faces")

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
        and the end faces' records with an axial clearance (:meth:`face_impacts`).  A
        translational joint: each record a :class:`~exuclear.history.PairImpact`, which also
        names its corner and wall (``pair``); per pair: :meth:`pair_states`."""
        self._report()
        records = self._backend.records()
        if self.joint_type == "prismatic":
            records = [[PairImpact(*r, pair_name(k, self._joint.geometry.spatial)) for r in rs]
                       for k, rs in enumerate(records)]
        if self.slices:
            records = [merge_overlapping([r for rs in records[:self.slices] for r in rs]), *records[self.slices:]]
        return sorted((r for rs in records for r in rs), key=lambda r: r.onset_time)

    def pair_states(self, which: str = "current") -> list[ContactState]:
        """A translational joint's corner-wall pairs' histories after the last accepted step
        (``which="initial"``: at the run's initial state), in the order of
        :data:`exuclear.prismatic.PAIRS` (the spatial joint's :data:`~exuclear.prismatic.BOX_PAIRS`)."""
        self._check_pairs()
        return self._backend.states(which)

    def _check_pairs(self) -> None:
        if self.joint_type != "prismatic":
            raise ValueError(f"joint {label(self)} is a {self.joint_type} joint: it has no corner-wall pairs")

    def wear_profile(self) -> WearProfile:
        """The worn profiles after the last accepted step (before a run: those the joint's
        :class:`exuclear.Wear` starts from); docs/physics.md section 11.  A spatial joint's
        profiles are slices x nodes, one row per slice (section 11.7; :class:`WearProfile`)."""
        wear = self._joint.wear
        if wear is None:
            raise ValueError(f"joint {label(self)} has no wear: give `wear=exuclear.Wear(coefficient=...)` to the joint")
        g = self._joint.geometry
        p = self._backend.wear_profiles()
        return WearProfile(2.0 * np.pi * np.arange(wear.nodes) / wear.nodes, *(np.array(p[k]) for k in (
            "bearing", "journal", "slip", "stability")), g.journal_radius, g.bearing_radius, g.length)

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
        """The contact history of the last run, with the state after the last accepted step, the
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
        see :attr:`notes`), ``over_limit_steps`` (accepted with a penetration beyond
        ``maxPenetration``) and ``held_long_steps`` (accepted through a held contact although
        longer than :data:`~exuclear.engine.steering.HELD_CONTACT_PERIODS` contact periods)."""
        control = self._backend.step_control()
        return {"impacts": self.history.onsets, "rejected_steps": int(control["rejected"]),
                "unresolved_steps": int(control["unresolved"]), "over_limit_steps": int(control["over_limit"]),
                "held_long_steps": int(control["held_long"])}

    @property
    def notes(self) -> list[str]:
        """What the joint's own step control could not do in the last run (steps it could not
        resolve, a penetration beyond the limit), each with the joint's name, the time, the
        step and the step to use; empty if the run was resolved.  Each note is also issued
        once as an :class:`~exuclear.exceptions.AccuracyWarning`: at its first step during
        the run where the kernel tells, the rest (chatter, a stopped run) at the step that
        reaches the run's end time, or at the first access to the joint's results after a
        run that ended early."""
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
        notes = step_notes(self, control, running)
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
            raise RuntimeError(f"joint {label(self)} was created with record=False: nothing was recorded")
        try:
            data = np.asarray(self.mbs.GetSensorStoredData(self.sensorNumber), dtype=float)
        except Exception:  # Exudyn raises when the sensor has no data yet
            data = np.zeros((0, 0))
        if data.ndim != 2 or data.shape[0] == 0:
            raise RuntimeError(f"joint {label(self)} has no outputs yet: run a simulation first")
        if self._backend.started():
            initial = self._backend.states("initial")
            if data[0, 0] == initial[0].time:  # the data node holds no state before the first step
                data = data.copy()
                data[0, 1:] = _outputs.initial_data(self.slices, initial, *self._backend.initial_pose(),
                                                    lubricated=self._joint.film is not None,
                                                    joint_type=self.joint_type)
        loads = [np.asarray(self.mbs.GetSensorStoredData(n), dtype=float) for n in self.loadSensorNumbers]
        if self.joint_type == "spherical":
            return _outputs.assemble_ball(data, loads)
        if self.joint_type == "prismatic":
            return _outputs.assemble_pairs(data, len(self._joint.geometry.pairs), loads)
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
