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
Exudyn differentiates the joint's connector numerically (an
``ObjectConnectorRigidBodySpringDamper`` with a user function offers no analytic Jacobian:
its ``GetAvailableJacobians`` lists ``ODE2_ODE2`` and ``ODE2_ODE2_t`` without the
``_function`` flags, so ``CSystem::JacobianODE2RHS`` perturbs each of its coordinates).  The
forward-difference increment is ``relativeEpsilon * max(minimumCoordinateSize, |q|)``:
with Exudyn's default ``relativeEpsilon = 1e-7`` that is 1e-7 m on a coordinate of 1 m,
the size of a resting journal's penetration (0.2 um on the zoo's double pendulum).  A
contact force ``K delta^n`` differenced over an increment ``h`` has the relative slope error
``(n - 1) h / (2 delta)``, 12 % there, and Newton converges only linearly: 8 iterations
per step in contact where Exudyn's step recovery (``adaptiveStepRecoveryIterations = 7``)
needs 7 at most, so a step cut at an impact never grows back.

For the run it starts (the solver's own copy of the settings; the user's
``SimulationSettings`` are not changed), the joint therefore sets

- ``relativeEpsilon`` to at most :data:`RELATIVE_EPSILON`: an increment of 1e-9 m per metre
  of coordinate, a slope error of 0.25 % on a 0.2 um penetration at 1 m, and well above
  the round-off of the difference quotient (relative error ~1e-16 / 1e-9 = 1e-7; at 1e-10
  the Newton iterates carry that round-off out of the joint's plane, and an aligned spatial
  journal's tilt, physics.md section 9.8, then grows from 7e-12 rad, not from 1e-17);
- ``modifiedNewtonJacUpdatePerStep`` to True while the step ``h`` is longer than
  :data:`JACOBIAN_PER_STEP_ABOVE` times the joint's contact period ``T_c``
  (:func:`exuclear.timescales.contact_period`, under the joint's weight), where the user
  runs Exudyn's modified Newton (its default) without a Jacobian per step and with a largest
  step above that.  Newton's matrix holds the mass term ``M / (beta h^2)`` and the contact
  stiffness ``k = M omega_c^2``; their ratio ``beta (omega_c h)^2 = beta (2 pi h / T_c)^2``
  is 2.5 at ``h = T_c / 2`` (``beta ~ 1/4``) and 10 at ``h = T_c``.  There a Jacobian of
  another contact state, or of free flight, is wrong by that much and the modified Newton
  stalls (contraction ~0.4 per iteration, 8 to 11 iterations per step, read from Exudyn's
  verbose log of the zoo's double pendulum at ``h = 2 T_c``); one Jacobian at the start of
  each step holds the present stiffness.  Below, stale Jacobians still converge (6
  iterations per step on the zoo's ANCF pendulum at ``h = 0.4 T_c``) and the extra
  Jacobians cost more than they save (7.1 s against 5.2 s there).  The joint's kernel
  switches it with the steps (:func:`vote_jacobian`; Exudyn reads the setting at the start
  of each step): on after a step it accepts longer than ``T_c / 2``, off after one at most
  that long, and on for the step after one in which a contact opened or closed (its
  stiffness came or went) and after one it redoes or lets grow (a step of another length,
  whose mass term an older Jacobian does not hold: without these asks, and without a
  Jacobian per step at the run's first step, the beam pendulum's steps stay at 1e-7 s after
  its impacts, 120831 steps instead of 27213).  A sliding contact that the
  joint's rate criterion holds at steps below ``T_c / 2`` (friction) then runs on the
  Jacobian it has.  Measured against the same rule held for the whole run
  (``python -m validation.cost jacobian_steps``, sums over the restitutions 0.89, 0.9 and 0.91, own
  settings / ``exuclear.simulate``): rigid-body tutorial with friction 0.69 / 0.71 of the
  wall time, double pendulum with friction 0.78 / 0.70, four-bar 0.88 / 0.85, the piston
  engine 0.91 / 1.19 (a chaotic model whose contact chatters numerically with either rule:
  its 4x refined run has some 100 to 150 impacts, its runs 151 to 975).  The results move
  within what these models' chaos moves them by: over seven restitutions 0.88 to 0.92 (its
  ``--convergence``), the distance of the rigid-body tutorial with friction's |e|/c spectrum
  to its 4x refined run's is 0.08 to 0.28 with the rule held for the whole run (median
  0.155) and 0.12 to 0.28 with it switched with the steps (median 0.158, smaller in 4 of
  the 7 pairs), the four-bar's 0.010 to 0.057 and 0.013 to 0.070 (all within the check's 0.1).
  With several joints, the Jacobian comes per step while any of them asks for it.

- ``modifiedNewtonContractivity`` to at most :data:`CONTRACTIVITY`: Exudyn's modified
  Newton keeps its Jacobian while each iteration reduces the residual by at least this
  factor (Exudyn's default 0.5).  In contact the force's slope depends strongly on the
  state (the damping term ``D delta_dot / v_min`` of a settled contact multiplies the
  stiffness, eq. (9)), so an iteration with a Jacobian a few iterates old contracts by
  only 0.2 to 0.35 (read from Exudyn's verbose log of the zoo's beam pendulum and double
  pendulum), and Exudyn iterates on until its limit of 8 before it takes a new one: 9 to
  11 iterations per step.  At 0.2 a fresh Jacobian comes after the third such iteration
  (measured over 1 s of each zoo model, wall time: beam pendulum -24 %, double pendulum
  with friction -32 %, ANCF pendulum -27 %, rigid-body tutorial with friction -16 %,
  four-bar -5 %, the others within 3 %; the piston engine, whose run Exudyn's Newton
  ended at 0.12 s, ran to its end).

- ``absoluteTolerance`` to :data:`ABSOLUTE_TOLERANCE` where the user left Exudyn's default
  (1e-10, :data:`EXUDYN_ABSOLUTE_TOLERANCE`): Exudyn's residual is one L2 norm over the
  force residuals [N] and the constraint equations, and in contact its floor is the
  contact's tangent stiffness times the round-off of the coordinates the penetration is
  computed from.  Under the joint's weight that stiffness is 1e7 to 1.5e9 N/m on the zoo's
  joints (reduced masses 5e-4 kg to 25 kg, ``exuclear.timescales.contact_stiffness``), times 2.2e-16 m
  (a metre-sized coordinate's last bit) 2e-9 to 3e-7 N: above 1e-10, so a resting contact
  can stall Newton where nothing is wrong (issue 15's pendulum, 1.9e8 N/m on coordinates
  of 0.15 m, 3e-17 m: 5e-9 N; it stops at 0.37 s with 1e-9 and runs with 1e-8).  The joint
  raises it to exuclear's own :data:`exuclear.settings.NEWTON_ATOL_DEFAULT`, which is no
  looser because constraints would then be left unmet by the size of a contact's
  penetration (its reasoning there).  An absolute tolerance the user set (any value other
  than Exudyn's default) is kept: the joint's note on a run Exudyn stops then names it
  (:func:`exuclear.engine.diagnostics.stopped_note`).  The relative tolerance is left as
  set: Exudyn's default (1e-8) is exuclear's too, and a tighter one the user chose (the
  zoo's slider-crank keeps its example's 1e-10) is the user's to loosen, which the same
  note says.

Measured on the zoo (``validation/exudyn_examples``, own settings, plain
``mbs.SolveDynamic``, see README).  ``joint.steer_newton = False`` leaves the solver as
the user set it.
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
#: its weight, exuclear.timescales): the contact that ends the flight starts from a step its
#: rate criterion cuts to the contact's resolution in one or two attempts (a tenth each),
#: where a longer one took more Newton solves at steps far too long.  Averages over three
#: restitutions (0.89 to 0.91), zoo models: exuclear.simulate's double pendulum, whose
#: largest step is 20 contact periods, 9964 -> 6162 steps; the own-settings runs, whose
#: steps are at most 8 periods (but the beam pendulum's, 59), within the scatter that any
#: change of a bounce gives these chaotic models (the piston engine: 4694 and 10472 steps
#: at restitutions 0.90 and 0.91).
GROWTH_CONTACT_PERIODS = 10.0
#: A step through which a contact is held (in contact at both its ends) lasts at most this
#: many of the joint's contact periods (under its weight; divided like ``rate_limit`` in a
#: convergence check's tighter run): the joint's step control redoes a longer one at this
#: length.  At a step of many contact periods generalized-alpha neither resolves the held
#: contact's stiff mode nor damps it much (a tenth per step at spectral radius 0.9), and the
#: load's change between the step's ends sets it ringing.  Measured on the zoo's beam
#: pendulum (its example's step is 59 contact periods; the joint's rate rule let held steps
#: grow back to 15 periods and more) against its run at 64 times the steps, over its 5 s
#: (``python -m validation.held_contact``): without a cap 519 c off, at 8, 6, 4, 3 and 2
#: periods 23, 13, 5.7, 3.2 and 1.3 c, in about the same wall time (Newton's iterations per
#: step fall from 7.8 to 6.2 at 3 periods as the steps grow shorter).  Below 3 periods the
#: cap reaches the steps of the examples that rest on the wall at 2 contact periods (the
#: zoo's 2D double pendulum: 14377 steps instead of 11069 at 2, ``python -m
#: validation.held_contact --models double_pendulum_2d --caps inf,3,2 --reference 1``).  The piston engine (steps of
#: 7.8 periods) is chaotic (a 1e-9 m/s kick moves its run at 64 times the steps by 4.6 c,
#: ``python -m validation.contact_follow_long --models piston_engine``): its peak normal
#: force, 37.2 N at 64 times the steps and 36.7 N kicked, is 35.5 N at 3 periods and 23.2 N
#: without a cap, with 4737 steps against 3966.
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
        return RunStart(can_shorten, min_step, label(handle) if handle is not None else "", rate, len(joints_of(mbs)),
                        rate_scale, growth_cap, contact_cap, jacobian_step, separation, mass)

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
