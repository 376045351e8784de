"""What a clearance joint's model and runs are checked for, and the notes that say so.

Before a run (:func:`check_model`, called by :func:`exuclear.simulate`): a model that
cannot run names its likely cause: a body of a clearance joint without mass, a journal
that starts outside its bearing, a non-finite initial coordinate or velocity; and a
journal whose out-of-plane motion nothing holds warns (:func:`unheld_motion`).

After a run, the joint's notes (:func:`step_notes`, read by the handle's ``notes`` and
issued as :class:`~exuclear.exceptions.AccuracyWarning`): steps its step control could
not shorten enough, contact chatter that is a numerical artefact (:func:`chatter_note`:
contacts that ended in steps longer than :func:`~exuclear.engine.steering.separation_step`,
counted by the kernel in any implicit run, ``mbs.SolveDynamic`` as well), and a run
Exudyn's solver ended early (:func:`stopped_note`).

Tilt of an aligned journal (docs/physics.md section 9.8, :func:`tilt_note`).  A spatial
joint's journal that starts exactly aligned stays in its plane only as long as round-off
does: under a varying in-plane load (a swinging double pendulum) the tilt is an unstable
mode of the rigid bodies on the slices, and it grows from round-off (1e-17 to 1e-14 rad)
at some 30 to 60 per second.  A run in which such a journal tilted beyond a fraction of
``c / L`` says so.
"""
from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import exudyn as exu
import numpy as np

from ..exceptions import OutOfPlaneWarning
from ..settings import NEWTON_RTOL_DEFAULT
from ..timescales import STEPS_PER_CONTACT_PERIOD
from ._python_kernel.step_control import MIN_STEP_MARGIN
from .bodies import body_label, body_mass, joint_contact_period
from .placement import outside_bearing
from .registry import joints_of, label, simulate_settings
from .steering import ABSOLUTE_TOLERANCE, HELD_CONTACT_PERIODS, explicit_solver, solver_steps

if TYPE_CHECKING:
    from .handle import ClearanceJointHandle

#: Largest number of ODE2 coordinates for which :func:`unheld_motion` runs: it takes the
#: dense constraint Jacobian's SVD and one marker read per admissible direction (0.1 s
#: at a few hundred coordinates); a larger model is not checked.
UNHELD_MAX_COORDINATES = 1000
#: Step [coordinate units] along an admissible direction (a unit vector of ODE2
#: coordinates) at which the journal's axial and tilt motion are read: far below any
#: model's size, far above round-off of the positions.
_UNHELD_STEP = 1e-6
#: Axial displacement [m] or tilt [rad] per unit step below which a direction does not move
#: the journal out of the plane (round-off of a position of 10 m over the step: 1e-9).
_UNHELD_TOLERANCE = 1e-6
#: Singular values of the constraint Jacobian below this fraction of the largest count as
#: zero (Exudyn's ComputeSystemDegreeOfFreedom uses 1e-12).
_RANK_RTOL = 1e-10
#: Initial tilt [rad] up to which a spatial joint's journal counts as started aligned:
#: round-off of a rotation matrix (1e-16) with a wide margin, far below any misalignment
#: a model would set on purpose.
ALIGNED_TILT = 1e-12
#: Fraction of ``c / L`` (the tilt at which an edge of the journal crosses the clearance,
#: from centred) beyond which a journal that started aligned is named after the run: far
#: above round-off, far below the edge contact (issue 21's model: 0.16 of it in 1 s).
TILT_NOTE_FRACTION = 0.01
#: Relative angular velocity across the axis [rad/s] up to which a journal counts as
#: started without tilting: a journal set tumbling on purpose has far more.
ALIGNED_TILT_RATE = 1e-12


def _constraint_jacobian(mbs: exu.MainSystem) -> np.ndarray:
    """The constraint Jacobian C_q (constraints x ODE2 coordinates) at the initial state,
    as Exudyn's ``ComputeSystemDegreeOfFreedom`` reads it (no joint force is evaluated)."""
    settings = exu.SimulationSettings()
    settings.staticSolver.verboseMode = 0
    settings.solution.file.write = False
    settings.solution.sensors.active = False  # no sensor records from this evaluation
    solver = exu.MainSolverStatic()
    solver.InitializeSolver(mbs, settings)
    try:
        n2, n1, n_ae = solver.GetODE2size(), solver.GetODE1size(), solver.GetAEsize()
        if n_ae == 0:
            return np.zeros((0, n2))
        size = n2 + n1 + n_ae  # the matrix is not zeroed by InitializeSolver, and ComputeJacobianAE fills its part
        solver.SetSystemJacobian(np.zeros((size, size)))
        solver.ComputeJacobianAE(mbs, scalarFactor_ODE2=1.0, scalarFactor_ODE2_t=0.0, scalarFactor_ODE1=1.0,
                                 velocityLevel=False)
        jacobian = np.asarray(solver.GetSystemJacobian())
        return jacobian[:n2, n2 + n1:].T
    finally:
        solver.FinalizeSolver(mbs, settings)


def _relative_pose(mbs: exu.MainSystem, handle: ClearanceJointHandle, frame: np.ndarray) -> np.ndarray:
    """Journal centre along the bearing axis [m] and the journal axis's x, y in the bearing's
    joint frame, in the current configuration."""
    cur, ov = exu.ConfigurationType.Current, exu.OutputVariableType
    b, j = handle.markerNumbers
    a_b = np.asarray(mbs.GetMarkerOutput(b, ov.RotationMatrix, configuration=cur), dtype=float).reshape(3, 3) @ frame
    a_j = np.asarray(mbs.GetMarkerOutput(j, ov.RotationMatrix, configuration=cur), dtype=float).reshape(3, 3)
    d = np.asarray(mbs.GetMarkerOutput(j, ov.Position, configuration=cur), dtype=float) - np.asarray(
        mbs.GetMarkerOutput(b, ov.Position, configuration=cur), dtype=float)
    axis = a_b.T @ a_j @ np.asarray(handle.axis_journal, dtype=float)
    return np.array([a_b[:, 2] @ d, axis[0], axis[1]])


def unheld_motion(mbs: exu.MainSystem, joints: Sequence[ClearanceJointHandle] | None = None) -> dict[Any, list[str]]:
    """The motions a clearance joint leaves free that nothing in the model holds: for each
    joint (by name, or connector number where unnamed) the list of ``"axial translation"``
    and ``"tilt"`` its journal can make relative to its bearing without violating any of
    the model's constraints (a planar joint: both, unless ``constrainAxial``; a spatial
    one: the axial translation, unless ``constrainAxial`` or ``axial_clearance``).  Only
    3D bodies can; the replaced revolute joint held both.  Call after ``mbs.Assemble()``.

    Method: the admissible velocities are the null space of the constraint Jacobian at the
    initial state; the journal is moved a small step (:data:`_UNHELD_STEP`) along each
    and its axial displacement and tilt are read from the markers.  Models with more than
    :data:`UNHELD_MAX_COORDINATES` coordinates are not checked (an empty result).
    """
    joints = list(joints_of(mbs) if joints is None else joints)
    # a spherical joint leaves the rotations free as the ideal one does, and its ball holds the translation
    checked = [h for h in joints if h.joint_type == "revolute" and h.constraintNumber is None
               and not (h.slices and h.shoulders is not None)]
    if not checked:
        return {}
    init, cur = exu.ConfigurationType.Initial, exu.ConfigurationType.Current
    q0 = np.asarray(mbs.systemData.GetODE2Coordinates(configuration=init), dtype=float)
    if not 0 < q0.size <= UNHELD_MAX_COORDINATES:
        return {}
    saved = np.asarray(mbs.systemData.GetODE2Coordinates(configuration=cur), dtype=float)
    jacobian = _constraint_jacobian(mbs)
    if not np.all(np.isfinite(jacobian)):  # a constraint without a finite Jacobian: nothing to say
        return {}
    if jacobian.shape[0]:
        _, sv, vt = np.linalg.svd(jacobian)
        rank = int(np.sum(sv > _RANK_RTOL * sv[0])) if sv.size and sv[0] > 0.0 else 0
        directions = vt[rank:]
    else:
        directions = np.eye(q0.size)
    frames = {h: np.asarray(mbs.GetObject(h.objectNumber)["rotationMarker0"], dtype=float) for h in checked}
    found: dict[Any, list[str]] = {}
    try:
        mbs.systemData.SetODE2Coordinates(q0.tolist(), configuration=cur)
        base = {h: _relative_pose(mbs, h, frames[h]) for h in checked}
        moved = {h: np.zeros(3) for h in checked}
        for n in directions:
            mbs.systemData.SetODE2Coordinates((q0 + _UNHELD_STEP * n).tolist(), configuration=cur)
            for h in checked:
                moved[h] = np.maximum(moved[h], np.abs(_relative_pose(mbs, h, frames[h]) - base[h]) / _UNHELD_STEP)
    finally:
        mbs.systemData.SetODE2Coordinates(saved.tolist(), configuration=cur)
    for h in checked:
        free = []
        if moved[h][0] > _UNHELD_TOLERANCE:
            free.append("axial translation")
        if not h.slices and max(moved[h][1:]) > _UNHELD_TOLERANCE:
            free.append("tilt")
        if free:
            found[h.name or h.objectNumber] = free
    return found


def unheld_note(found: dict[Any, list[str]], joints: Sequence[ClearanceJointHandle] = ()) -> str:
    """The warning of :func:`check_model` for the result of :func:`unheld_motion`, or ``""``;
    the ``joints`` it was found for name themselves as messages do (:func:`label`)."""
    if not found:
        return ""
    labels = {h.name or h.objectNumber: label(h) for h in joints}
    which = "; ".join(f"joint {labels.get(name, repr(name))}: {' and '.join(free)}" for name, free in found.items())
    return (f"nothing in the model holds the journal's out-of-plane motion that the replaced revolute joint held "
            f"({which}): the clearance joint acts in the plane normal to its axis only, so the journal may drift "
            "along the axis or tilt until the contact gives way. Give constrainAxial=True to the clearance joint (or "
            "hold the motion by other joints, or use the spatial joint with axial_clearance)")


def check_model(mbs: exu.MainSystem, joints: Sequence[ClearanceJointHandle]) -> None:
    """``ValueError`` naming the likely cause for a model that cannot run (module docstring);
    an :class:`OutOfPlaneWarning` where a journal's out-of-plane motion is held by nothing."""
    for handle in joints:
        name = label(handle)
        for role, marker in zip(("bearing", "journal"), handle.markerNumbers):
            mass = body_mass(mbs, marker)
            if mass <= 0.0:  # NaN (a body type whose mass is not read here) passes
                raise ValueError(f"clearance joint {name}: its {role} body ({body_label(mbs, marker)}) has mass {mass}; every body "
                                 "of a clearance joint needs a positive mass (the contact force would accelerate "
                                 "it without bound)")
        outside = outside_bearing(mbs, handle)
        if outside:
            raise ValueError(f"clearance joint {name}: {outside}")
    ref = exu.ConfigurationType.Initial
    for kind, values in (("coordinate", mbs.systemData.GetODE2Coordinates(configuration=ref)),
                          ("velocity", mbs.systemData.GetODE2Coordinates_t(configuration=ref))):
        bad = [k for k, v in enumerate(np.asarray(values, dtype=float)) if not math.isfinite(v)]
        if bad:
            raise ValueError(f"initial {kind} {bad[0]} (ODE2 index; node {_node_of(mbs, bad[0])}) is {values[bad[0]]}: "
                             f"every initial {kind} must be finite")
    note = unheld_note(unheld_motion(mbs, joints), joints)
    if note:
        warnings.warn(note, OutOfPlaneWarning, stacklevel=3)


def _node_of(mbs: exu.MainSystem, index: int) -> Any:
    for n in range(mbs.systemData.NumberOfNodes()):
        try:
            start = mbs.GetNodeODE2Index(n)
        except Exception:  # nodes without ODE2 coordinates (ground, data nodes)
            continue
        size = len(np.atleast_1d(mbs.GetNodeOutput(n, exu.OutputVariableType.Coordinates,
                                                   configuration=exu.ConfigurationType.Initial)))
        if start <= index < start + size:
            return n
    return "?"


def started_aligned(mbs: exu.MainSystem, handle: ClearanceJointHandle) -> bool:
    """Whether a spatial joint's journal starts aligned and not tilting: its axis within
    :data:`ALIGNED_TILT` of the bearing axis, and the relative angular velocity across the
    axis within :data:`ALIGNED_TILT_RATE`, in the initial configuration."""
    if not handle.slices:
        return False
    ref, ov = exu.ConfigurationType.Initial, exu.OutputVariableType
    b, j = handle.markerNumbers
    frame = np.asarray(mbs.GetObject(handle.objectNumber)["rotationMarker0"], dtype=float)
    a_b = np.asarray(mbs.GetMarkerOutput(b, ov.RotationMatrix, configuration=ref), dtype=float).reshape(3, 3) @ frame
    a_j = np.asarray(mbs.GetMarkerOutput(j, ov.RotationMatrix, configuration=ref), dtype=float).reshape(3, 3)
    axis = a_b.T @ a_j @ np.asarray(handle.axis_journal, dtype=float)
    rate = a_b.T @ (np.asarray(mbs.GetMarkerOutput(j, ov.AngularVelocity, configuration=ref), dtype=float)
                    - np.asarray(mbs.GetMarkerOutput(b, ov.AngularVelocity, configuration=ref), dtype=float))
    return bool(math.hypot(axis[0], axis[1]) <= ALIGNED_TILT and math.hypot(rate[0], rate[1]) <= ALIGNED_TILT_RATE)


def tilt_note(handle: ClearanceJointHandle, aligned: bool) -> str:
    """A sentence if a spatial joint whose journal started aligned (``aligned``, from
    :func:`started_aligned`) tilted beyond :data:`TILT_NOTE_FRACTION` of ``c / L`` (module
    docstring), else ``""``.  Reads the recorded outputs: nothing without ``record``."""
    if not aligned or handle.sensorNumber is None:
        return ""
    out = handle.outputs()
    if len(out["time"]) == 0:
        return ""
    tilt = np.hypot(out["tilt_x"], out["tilt_y"])
    k = int(np.argmax(tilt))
    geometry = handle.joint.geometry
    scale = geometry.clearance / geometry.length
    if not tilt[k] > TILT_NOTE_FRACTION * scale:
        return ""
    return (f"joint {label(handle)}: the journal started aligned and tilted to {tilt[k]:.2g} rad "
            f"({tilt[k] / scale:.2g} c/L) at t = {out['time'][k]:.4g} s. If nothing in the model loads it out of its "
            "plane, this is the unstable tilt mode of the sliced joint under a varying in-plane load, grown from "
            "round-off (docs/physics.md section 9.8): its growth rate is the model's, its size at a given time is set "
            "by round-off. "
            "For a model meant to stay planar, use the planar joint (no `slices`) with constrainAxial=True, which "
            "holds the tilt")


def step_notes(handle: ClearanceJointHandle, control: dict[str, Any], running: bool = False) -> list[tuple[str, str]]:
    """(kind, sentence) for what the joint's step control could not do in the last run: each names
    the joint, what happened (time, step, penetration / c) and the fixed step to use: the
    smaller of the kernel's recommendation at the worst step and a tenth of the joint's
    contact period under its weight (exuclear.timescales, as ``step="auto"``; an impact can
    be faster than that scale, and the kernel's recommendation then is shorter).  Letting the solver shorten steps is cheaper."""
    stopped = [] if running else stopped_note(handle) + chatter_note(handle, control)
    if not control["unresolved"] and not control["over_limit"] and not control["held_long"]:
        return stopped
    can, min_step, why, _rate = solver_steps(handle.mbs)
    period = math.nan
    try:
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
             f"{handle.max_penetration / c:.3g} c", "4 shorter attempts did not remove it"),
            ("held", control["held_long"], control["held_time"], control["held_step"], control["contact_cap"],
             f"held the contact through more than {HELD_CONTACT_PERIODS:g} of the joint's contact periods (there "
             "the contact's stiff mode is neither resolved nor damped, and its ringing can move the joint by "
             "clearances)", "the same step came back unshortened")):
        if not count:
            continue
        if period > 0.0 and kind != "held":  # a tenth of the contact period under the weight, as step="auto";
            advice = min(advice, period / 10)  # an impact is faster: the kernel's worst step is then shorter
        notes.append((kind, f"joint {name}: at t = {when:.6g} s a step of {step:.3g} s {what}, in {count} step(s) "
                     f"of the run{' so far' if running else ''}, which could not be shortened enough "
                     f"({_in_user_terms(handle.mbs, why) or otherwise}); the results may be inaccurate: "
                     f"{_step_remedy(handle.mbs, step, advice, can, min_step)}"))
    return notes + stopped


def _in_user_terms(mbs: exu.MainSystem, why: str) -> str:
    """Why the solver could not shorten a step (:func:`solver_steps`), in the settings of
    :func:`exuclear.simulate` where it runs the model."""
    settings = simulate_settings(mbs)
    if settings is None or not why:
        return why
    if "adaptiveStep" in why:
        return "the steps are fixed: joint_steps=False"
    return f"method {settings.method!r} takes fixed steps"


def _step_remedy(mbs: exu.MainSystem, step: float, advice: float, can_shorten: bool, min_step: float) -> str:
    """What resolves a contact that a step of ``step`` [s] did not, where the joint's estimate
    asks for at most ``advice`` [s]: that step, set where the user sets it, and where the
    solver could not shorten steps, the setting that lets it (never one already in force).
    Where ``step`` was already within ``advice``, no step the run allows would: the joint
    shortens steps no further than :data:`MIN_STEP_MARGIN` times the solver's minimum step
    ``min_step`` [s] (where Exudyn's Newton iteration fails), so the sentence names the
    minimum step where that bound held the step, else the model as the likely cause."""
    settings = simulate_settings(mbs)
    if not advice < step * (1.0 - 1e-9):
        floor = MIN_STEP_MARGIN * min_step
        if can_shorten and step <= floor * (1.0 + 1e-6):
            where = "`min_step`" if settings is not None else "timeIntegration.minimumStepSize"
            return (f"the step was already at the shortest the joint takes, {MIN_STEP_MARGIN:g} times the solver's "
                    f"minimum step ({min_step:.3g} s, near which Exudyn's Newton iteration fails), so no step this "
                    f"run allows resolves it: a smaller minimum step ({where}) lets the joint shorten further")
        return (f"the step was already within the {advice:.3g} s the joint's estimates ask for, so a shorter step "
                "alone will not resolve it; so abrupt a contact points at the model: units (E in Pa, lengths in m), "
                "a journal placed outside its bearing, a body of the joint without its mass, or a `rate_limit` far "
                "tighter than its default")
    where = "`step`" if settings is not None else "timeIntegration.numberOfSteps"
    remedy = f"use a step of at most {advice:.3g} s ({where})"
    if can_shorten:
        return remedy
    try:
        explicit = explicit_solver(mbs.sys["dynamicSolver"])
    except Exception:  # no solver to ask: the implicit methods' setting
        explicit = False
    if settings is not None:
        shorten = "method='dopri5', whose error control shortens steps" if explicit else "joint_steps=True"
    else:
        shorten = "timeIntegration.automaticStepSize = True" if explicit else "timeIntegration.adaptiveStep = True"
    return f"{remedy}, or let the solver shorten steps ({shorten})"


def chatter_note(handle: ClearanceJointHandle, control: dict[str, Any]) -> list[tuple[str, str]]:
    """("chatter", sentence) where contacts of the last run ended in steps longer than a tenth
    of the joint's contact period (the kernel's ``long_separations``, :func:`_separation_step`):
    its contact onsets may be numerical chatter."""
    long, step = control["long_separations"], control["separation_step"]
    if not long:
        return []
    return [("chatter", f"joint {label(handle)}: {long} of its {control['separations']} contacts ended in a step "
             f"longer than a tenth of its contact period ({step * STEPS_PER_CONTACT_PERIOD:.2g} s, estimated); such "
             f"separations are not resolved, and the {handle.history.onsets} contact onsets may be numerical "
             f"chatter, not physics: use steps of at most {step:.2g} s where contacts open ("
             + ("`step`, or step='auto', which takes a tenth of the contact period" if simulate_settings(handle.mbs)
                is not None else "timeIntegration.numberOfSteps, which bounds the steps")
             + "), or an explicit adaptive method where the model has no constraints")]


def regime(handle: ClearanceJointHandle) -> str:
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


def stop_cause(solver: Any, adaptive: bool, min_step: float) -> str:
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


def stopped_note(handle: ClearanceJointHandle) -> list[tuple[str, str]]:
    """("stopped", sentence) where Exudyn's solver ended the last run before its end time,
    whatever the joint's regime: Exudyn then says only "SolveDynamic terminated".  The
    sentence names the joint, the time, the joint's regime and |e|/c (:func:`regime`), the
    cause (:func:`stop_cause`) and, for a failed Newton, what to try: the tolerances in
    effect (the solver's copy, after :func:`~exuclear.engine.steering.steer_newton`) where they
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
    if handle._backend.failure()[0]:  # the joint stopped the run itself: its error said why (joint.failure())
        return []
    cause = stop_cause(solver, adaptive, min_step)
    if solver.output.finishedSuccessfully and not cause.startswith("stopped"):
        return []  # a finished run whose time is not this solver's (e.g. a static solve since)
    simulating = simulate_settings(mbs) is not None
    if simulating:
        cause = cause.replace("timeIntegration.adaptiveStep is False", "joint_steps=False")
    note = (f"joint {label(handle)}: Exudyn's solver ended the run at t = {t:.6g} s of {end:g} s: {cause}; the joint "
            f"was then {regime(handle)}")
    if "Newton" not in cause and "singular" not in cause:
        return [("stopped", note)]
    advice = []
    if newton is not None:
        rtol, atol = float(newton.relativeTolerance), float(newton.absoluteTolerance)
        if rtol < NEWTON_RTOL_DEFAULT or atol < ABSOLUTE_TOLERANCE:
            # the joint raises only Exudyn's default absolute tolerance: a tighter one is the user's
            rtol_name, atol_name = (("newton_rtol", "newton_atol") if simulating else
                                    ("timeIntegration.newton.relativeTolerance", "absoluteTolerance"))
            advice.append(f"Newton tolerances the residual can reach ({rtol_name} >= {NEWTON_RTOL_DEFAULT:g}, now "
                          f"{rtol:g}; {atol_name} >= {ABSOLUTE_TOLERANCE:g}, now {atol:g}; the joint keeps "
                          "tolerances the user set)")
    if not adaptive:
        advice.append(("joint_steps=True" if simulating else "timeIntegration.adaptiveStep = True")
                      + " (Exudyn then shortens a step whose Newton fails)")
    advice.append(f"a shorter step; where Newton's residual stalls at every step length "
                  f"({'verbose=2' if simulating else 'timeIntegration.verboseMode = 2'} shows it), look for a "
                  "singular position of the mechanism")
    return [("stopped", note + "; try " + ", or ".join(advice))]
