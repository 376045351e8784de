"""How a clearance joint steers the run that Exudyn's solver starts: one module for all
that the joint sets or asks of the solver, read by its kernel through the run-start record.

- **The run-start record.**  Once per run start the kernel calls :class:`_RunStart`, which
  returns the joint's :class:`~exuclear.engine.layout.RunStart`: whether the solver redoes a
  rejected step shorter and its minimum step (:func:`solver_steps`), the joint's label, the
  number of clearance joints of the system (the kernels' step group), the factor on the
  joint's ``rate_limit`` for the run (:func:`joint_refinement`: below 1 in a convergence
  check's tighter run), the longest step free flight may grow to
  (:data:`GROWTH_CONTACT_PERIODS`), the longest step a held contact may take
  (:data:`HELD_CONTACT_PERIODS`), the step above which the joint asks for a Jacobian per
  step (:func:`steer_newton`), the step in which a contact's end counts as unresolved
  (:func:`separation_step`) and the effective mass of its impacts
  (:func:`~exuclear.engine.bodies.joint_mass`).
- **Step growth.**  After free flight the kernel lets the solver's next step grow
  (:meth:`_RunStart.grow`).
- **The Jacobian vote.**  The kernel asks for a Jacobian per step while its steps are long
  against its contact period (:meth:`_RunStart.jacobian_per_step`, :func:`vote_jacobian`).
- **Newton's settings**, below.

Newton's settings
-----------------
Exudyn differentiates the joint's connector numerically (a connector with a user function
offers no analytic Jacobian), and its Newton settings are made for mechanisms, not for a
contact whose stiffness is far above the model's.  For the run it starts (the solver's own
copy of the settings; the user's ``SimulationSettings`` are not changed), the joint sets

- ``relativeEpsilon`` to at most :data:`RELATIVE_EPSILON`: Exudyn's increment of 1e-7 per
  metre of coordinate is the size of a resting journal's penetration, and the force's slope
  differenced over it is wrong by some 10 %, so Newton converges only linearly;
- ``modifiedNewtonJacUpdatePerStep`` to True while the step ``h`` is longer than
  :data:`JACOBIAN_PER_STEP_ABOVE` times the joint's contact period ``T_c``
  (:func:`exuclear.timescales.contact_period`, under the joint's weight), where the user
  runs Exudyn's modified Newton without a Jacobian per step: the contact stiffness over
  Newton's mass term ``M / (beta h^2)`` is ``beta (2 pi h / T_c)^2``, 2.5 at ``h = T_c / 2``,
  and a Jacobian of another contact state then stalls the iteration.  The joint's kernel
  switches it with the steps (:func:`vote_jacobian`): on after a step it accepts longer
  than ``T_c / 2``, off after a shorter one, and on for the step after one in which a
  contact opened or closed or that it redoes or lets grow (a step of another length, whose
  mass term an older Jacobian does not hold).  With several joints, the Jacobian comes per
  step while any of them asks for it;
- ``modifiedNewtonContractivity`` to at most :data:`CONTRACTIVITY`: in contact the force's
  slope changes fast with the state, an older Jacobian contracts the residual by only 0.2
  to 0.35 per iteration, and at Exudyn's 0.5 Newton iterates to its limit before it takes
  a new one;
- ``absoluteTolerance`` to :data:`ABSOLUTE_TOLERANCE` where the user left Exudyn's default
  (:data:`EXUDYN_ABSOLUTE_TOLERANCE`): in contact the residual's floor is the contact's
  stiffness times the coordinates' round-off, above 1e-10 N.  A tolerance the user set is
  kept, and the joint's note on a run Exudyn stops names it
  (:func:`exuclear.engine.diagnostics.stopped_note`); the relative tolerance is left as set.

docs/validation/step_control.md has the measurements behind each value.
``joint.steer_newton = False`` leaves the solver as the user set it.
"""
from __future__ import annotations

import math
import weakref
from typing import TYPE_CHECKING, Any

import exudyn as exu

from ..settings import NEWTON_ATOL_DEFAULT
from ..timescales import STEPS_PER_CONTACT_PERIOD
from .bodies import joint_contact_period, joint_mass
from .layout import RUN_START_DEFAULT, RunStart
from .placement import outside_bearing
from .registry import handle_of, joints_of, label

if TYPE_CHECKING:
    from .handle import ClearanceJointHandle

#: The largest ``numericalDifferentiation.relativeEpsilon`` the joint lets an implicit run
#: use (module docstring).
RELATIVE_EPSILON = 1e-9
#: A Jacobian at the start of each step while the step exceeds this fraction of the joint's
#: contact period (module docstring).
JACOBIAN_PER_STEP_ABOVE = 0.5
#: The largest ``modifiedNewtonContractivity`` the joint lets an implicit run use (module docstring).
CONTRACTIVITY = 0.2


#: Exudyn's default ``newton.absoluteTolerance`` (1e-10): the value the joint takes for "not set".
EXUDYN_ABSOLUTE_TOLERANCE = exu.SimulationSettings().timeIntegration.newton.absoluteTolerance
#: The absolute Newton tolerance the joint sets where the user left Exudyn's default: above the
#: residual floor of a stiff contact, stiffness x coordinate round-off (module docstring).
ABSOLUTE_TOLERANCE = NEWTON_ATOL_DEFAULT


#: ``mbs.variables`` key of the run's Jacobian votes: ``[weak reference to the solver, the
#: user's modifiedNewtonJacUpdatePerStep, {joint token: a Jacobian per step wanted}]`` (weak:
#: the system's variables neither keep a finished run's solver nor stop a deep copy).
JACOBIAN_VOTES_KEY = "exuclear.jacobian_per_step"


def explicit_solver(solver: Any) -> bool:
    """Whether an Exudyn dynamic solver object is one of the explicit methods (no Newton)."""
    return "Explicit" in type(solver).__name__


def steer_newton(mbs: exu.MainSystem, contact_period: float, token: int = 0) -> tuple[dict[str, tuple[Any, Any]], float]:
    """Set the Newton settings of the implicit solver ``mbs.SolveDynamic`` is starting (module
    docstring) for the joint ``token`` of ``contact_period`` [s] (NaN: unknown, no Jacobian per
    step).  Returns what changed, ``{setting: (before, after)}``, empty where nothing did (an
    explicit solver, a run not started by ``SolveDynamic``, settings already as needed), and
    the step [s] above which the joint asks for a Jacobian per step (:func:`vote_jacobian`;
    inf where it never does)."""
    try:
        solver = mbs.sys["dynamicSolver"]
        newton = solver.newton
    except Exception:  # no SolveDynamic run, or an explicit solver (no Newton)
        return {}, math.inf
    if explicit_solver(solver):
        return {}, math.inf
    changed: dict[str, tuple[Any, Any]] = {}
    differentiation = newton.numericalDifferentiation
    if differentiation.relativeEpsilon > RELATIVE_EPSILON:
        changed["numericalDifferentiation.relativeEpsilon"] = (differentiation.relativeEpsilon, RELATIVE_EPSILON)
        differentiation.relativeEpsilon = RELATIVE_EPSILON
    if newton.absoluteTolerance < ABSOLUTE_TOLERANCE and _users_absolute_tolerance(mbs) == EXUDYN_ABSOLUTE_TOLERANCE:
        changed["absoluteTolerance"] = (newton.absoluteTolerance, ABSOLUTE_TOLERANCE)
        newton.absoluteTolerance = ABSOLUTE_TOLERANCE
    if newton.useModifiedNewton and newton.modifiedNewtonContractivity > CONTRACTIVITY:
        changed["modifiedNewtonContractivity"] = (newton.modifiedNewtonContractivity, CONTRACTIVITY)
        newton.modifiedNewtonContractivity = CONTRACTIVITY
    votes = mbs.variables.get(JACOBIAN_VOTES_KEY)
    if votes is None or votes[0]() is not solver:  # the run's first joint: the user's setting is still there
        votes = mbs.variables[JACOBIAN_VOTES_KEY] = [weakref.ref(solver), bool(newton.modifiedNewtonJacUpdatePerStep),
                                                     {}]
    step = JACOBIAN_PER_STEP_ABOVE * contact_period
    if not (newton.useModifiedNewton and not votes[1] and solver.it.maxStepSize > step):  # NaN: False
        return changed, math.inf
    changed["modifiedNewtonJacUpdatePerStep"] = (False, f"while the step exceeds {step:.3g} s")
    vote_jacobian(mbs, token, True)  # the run's first step is its largest (Exudyn's currentStepSize is still 0 here)
    return changed, step


def _users_absolute_tolerance(mbs: exu.MainSystem) -> float:
    """The absolute Newton tolerance of the user's settings of the run being started (the
    solver's copy may already hold another joint's change); NaN where they are not known."""
    try:
        return float(mbs.sys["simulationSettings"].timeIntegration.newton.absoluteTolerance)
    except Exception:  # a solver run without SolveDynamic: leave the tolerance alone
        return math.nan


def vote_jacobian(mbs: exu.MainSystem, token: int, wanted: bool) -> None:
    """Joint ``token`` asks for a Jacobian per step (``wanted``) or no longer: the solver's
    ``modifiedNewtonJacUpdatePerStep`` is set while any joint of the run asks for it."""
    votes = mbs.variables.get(JACOBIAN_VOTES_KEY)
    if votes is None:
        return
    votes[2][token] = wanted
    solver = votes[0]()
    if solver is not None:  # else gone with its run: nothing to steer; the user's True stays
        solver.newton.modifiedNewtonJacUpdatePerStep = votes[1] or any(votes[2].values())


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
#: its weight, exuclear.timescales): the contact that ends the flight then starts from a step
#: its rate criterion cuts to the contact's resolution in one or two attempts
#: (docs/validation/step_control.md).
GROWTH_CONTACT_PERIODS = 10.0
#: A step through which a contact is held (in contact at both its ends) lasts at most this
#: many of the joint's contact periods (under its weight; divided like ``rate_limit`` in a
#: convergence check's tighter run): the joint's step control redoes a longer one at this
#: length.  At a step of many contact periods generalized-alpha neither resolves the held
#: contact's stiff mode nor damps it much, and the load's change between the step's ends sets
#: it ringing; shorter caps reach the steps of examples that rest on the wall at 2 contact
#: periods (``python -m validation.held_contact``, docs/validation/step_control.md).
HELD_CONTACT_PERIODS = 3.0


class RefinedSimulationSettings(exu.SimulationSettings):
    """``exu.SimulationSettings`` of a convergence check's tighter run: Exudyn's settings, and
    :attr:`joint_refinement`, the factor by which the clearance joints of the run divide their
    ``rate_limit`` (their own step control, which Exudyn's settings do not hold).  Exudyn's
    ``SolveDynamic`` takes them as any settings and keeps them in ``mbs.sys``, where each
    joint reads the factor at its run's start (:func:`joint_refinement`); the joints' own
    ``rate_limit`` is not changed.  Made by :func:`exuclear.convergence.refined_settings`."""

    def __init__(self, settings: exu.SimulationSettings, joint_refinement: float) -> None:
        super().__init__()
        self.SetDictionary(settings.GetDictionary())
        self.joint_refinement = float(joint_refinement)

    def __deepcopy__(self, memo: dict) -> RefinedSimulationSettings:
        return RefinedSimulationSettings(self, self.joint_refinement)


def joint_refinement(mbs: exu.MainSystem) -> float:
    """The factor by which the clearance joints of the run ``mbs.SolveDynamic`` is starting
    divide their ``rate_limit``: that of its :class:`RefinedSimulationSettings`, else 1."""
    try:
        settings = mbs.sys["simulationSettings"]
    except Exception:  # no SolveDynamic run: the joints' own rate_limit
        return 1.0
    return float(getattr(settings, "joint_refinement", 1.0))


def separation_step(mbs: exu.MainSystem, period: float) -> float:
    """The longest step [s] in which a contact of a joint of contact ``period`` [s] ends
    resolved, in the implicit run ``mbs.SolveDynamic`` is starting: a tenth of the period
    (:data:`~exuclear.timescales.STEPS_PER_CONTACT_PERIOD`); inf where nothing is counted (an
    explicit solver: its error control, or the joint's rate criterion at fixed steps, resolves
    separations; an unknown period).  A contact that ends in a longer step of an implicit
    method rings and leaves the wall without a physical cause (a resting pendulum at steps of
    1e-3 s, 2.9 of its contact periods, leaves the wall 68 times in 2 s where DOPRI5 and
    physics give one contact): the joint counts such separations and its notes say so
    (:func:`exuclear.engine.diagnostics.chatter_note`)."""
    try:
        explicit = explicit_solver(mbs.sys["dynamicSolver"])
    except Exception:  # no SolveDynamic run: nothing to count against
        return math.inf
    if static_run(mbs):  # load steps, not time
        return math.inf
    return period / STEPS_PER_CONTACT_PERIOD if period > 0.0 and not explicit else math.inf


def _end_time(mbs: exu.MainSystem) -> float:
    """The end time [s] of the dynamic run ``mbs.SolveDynamic`` is starting; inf for a static
    solve (load steps, not time) or a run without ``SolveDynamic``'s settings."""
    try:
        end = float(mbs.sys["simulationSettings"].timeIntegration.endTime)
    except Exception:  # no SolveDynamic run: never told
        return math.inf
    return math.inf if static_run(mbs) else end


def static_run(mbs: exu.MainSystem) -> bool:
    """Whether the run starting is ``mbs.SolveStatic``'s, where an earlier ``SolveDynamic`` left
    its solver in ``mbs.sys`` too: each solver object is new per run, and the one starting has
    the lower step index (1 at its first step; a finished run's is its steps plus one)."""
    try:
        static, dynamic = mbs.sys["staticSolver"], mbs.sys.get("dynamicSolver")
        return dynamic is None or static.it.currentStepIndex < dynamic.it.currentStepIndex
    except Exception:  # no SolveStatic run
        return False


class _RunStart:
    """The kernel's run-start callback: returns the joint's
    :class:`~exuclear.engine.layout.RunStart` record for the run the solver is starting
    (whether the solver can shorten steps, its minimum step, the joint's label, how many
    clearance joints the system has, the factor on its ``rate_limit`` for the run,
    :func:`joint_refinement`, the longest step its free flight may
    grow to, :data:`GROWTH_CONTACT_PERIODS`, the longest step a held contact may take,
    :data:`HELD_CONTACT_PERIODS`, the step above which it asks for a Jacobian per
    step, :func:`steer_newton`, where finite it asks at the run's
    first step, the step above which a contact's end counts as unresolved,
    :func:`separation_step`, and the effective mass of its impacts, the reduced mass of its
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
            try:
                mass = joint_mass(mbs, handle)
                period = joint_contact_period(mbs, handle)
            except Exception:  # a body whose mass is not read: no Jacobian per step, no cap on growth
                period = math.nan
            if handle.steer_newton:
                handle.newton_changes, jacobian_step = steer_newton(mbs, period, self._token)
        growth_cap = GROWTH_CONTACT_PERIODS * period if period > 0.0 else math.inf
        # a convergence check's tighter run refines the joints' own steps with the solver's
        rate_scale = 1.0 / joint_refinement(mbs)
        separation = separation_step(mbs, period)
        # only in an implicit dynamic run (a static solve's load steps are no time; an explicit
        # solver's error control sets its step): where separations are counted
        contact_cap = HELD_CONTACT_PERIODS * period * rate_scale if separation < math.inf else math.inf
        # a journal outside its bearing: the kernel stops the run at its start, with this message
        refusal = outside_bearing(mbs, handle) if handle is not None else ""
        return RunStart(can_shorten, min_step, label(handle) if handle is not None else "", rate, len(joints_of(mbs)),
                        rate_scale, growth_cap, contact_cap, jacobian_step, separation, mass, refusal,
                        _end_time(mbs))

    def finished(self) -> None:
        """The run reached its end time (the kernel's ``tell_end``): the handle warns of what the
        whole run left unresolved, its chatter among it, at the end of the run rather than at
        the first read of its results."""
        mbs = self._mbs()
        handle = self._handle(mbs) if mbs is not None else None
        if handle is not None:
            handle._report()

    def jacobian_per_step(self, wanted: bool) -> None:
        """The joint asks for a Jacobian per step (``wanted``) or no longer (its kernel's
        ``steer_jacobian``, where its ask changes): :func:`~exuclear.engine.steering.vote_jacobian`."""
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
        return handle_of(mbs, self._token)

    def note(self) -> None:
        """The kernel's first unresolved step of a kind in this run: warn now (the run may
        still be stopped by Exudyn, after which nobody might ask the joint)."""
        mbs = self._mbs()
        handle = self._handle(mbs) if mbs is not None else None
        if handle is not None:
            handle._report(running=True)
