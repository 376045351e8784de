"""Solver settings: one typed object, mapped onto Exudyn in exactly one place.

The mapping lives in :func:`exuclear.engine.solver.simulation_settings`; this module
holds only the documented choices and their checks.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

from .checks import check_choice, check_positive, check_real

#: Default KAPPA of the clearance joints' own step control (``ClearanceJointHandle.rate_limit``,
#: :attr:`SolverSettings.rate_limit`): a step in contact may change the penetration rate by at
#: most this fraction of max(|v0|, v_min), v0 the contact's onset velocity.  An impact reverses
#: the rate, a change of (1 + e) v0, so 0.1 asks for about 20 steps per reversal, with neither
#: the bodies' masses nor the law's stiffness in the criterion.  Measured on the journal impact
#: (0.2 ms, generalized-alpha, 1 to 20 steps given): departure velocity 1.3 % to 2.4 % off the
#: paper's 0.269 m/s at 0.5, 1.3 % at 0.25, within 0.8 % at 0.1 (tests/test_step_control.py asks
#: 1 %).  A path to 1 % of c over many impacts asks for less: the paper's redundant slider-crank
#: (22 impacts in two revolutions, steps of at most 2e-5 s) 7.7e-2 c at 0.1, 1.6e-2 c at 0.03
#: (docs/guide/solver_path.md, "What the joint does to your steps").
RATE_LIMIT_DEFAULT = 0.1

#: Exudyn's default numerical damping of generalized-alpha at infinite frequency.
SPECTRAL_RADIUS_DEFAULT = 0.9

#: Newton tolerances of the implicit methods, on the residual of the equations of motion.
#: Exudyn's absolute 1e-10 is meant for smooth models: in contact the contact stiffness times
#: the coordinates' round-off leaves a residual floor above it, and Newton fails on a resting
#: pendulum; Exudyn stops when either tolerance is met, so an absolute tolerance above that
#: floor ends the iteration there.  It is no looser, because Exudyn's residual is one norm over
#: forces [N] and constraint equations [m, rad], and a looser one leaves constraints unmet by
#: a contact's penetration.  The relative tolerance stays at Exudyn's 1e-8: a looser one makes
#: a drive's multiplier inexact.  docs/validation/step_control.md has the measurements.
NEWTON_RTOL_DEFAULT = 1e-8
NEWTON_ATOL_DEFAULT = 1e-8

#: ``SolverSettings.linear_solver``: exuclear's name -> Exudyn's ``LinearSolverType`` member.
LINEAR_SOLVERS = {"dense": "EXUdense", "sparse": "EigenSparse"}

#: The default ``min_step`` [s]: the explicit adaptive methods' floor (their error control fails
#: below); the implicit methods' adaptive steps keep Exudyn's minimum step (1e-8 s) unless
#: another ``min_step`` is given.
MIN_STEP_DEFAULT = 1e-12

#: The step when none is given [s]: the paper's maximum step.
DEFAULT_STEP = 1e-5

#: The value of ``step`` that asks :func:`exuclear.simulate` to choose it from the model
#: (:func:`exuclear.engine.solver.automatic_step`).
AUTO = "auto"

#: The value of ``method`` that asks :func:`exuclear.simulate` to choose it from the model
#: (:func:`exuclear.engine.solver.automatic_method`).
AUTO_METHOD = "auto"

#: Method name -> (Exudyn DynamicSolverType name, explicit?, adaptive by default?).
METHODS: dict[str, tuple[str, bool, bool]] = {
    "dopri5": ("DOPRI5", True, True),
    "ode23": ("ODE23", True, True),
    "rk44": ("RK44", True, False),
    "generalized-alpha": ("GeneralizedAlpha", False, False),
    "trapezoidal": ("TrapezoidalIndex2", False, False),
}


@dataclass(frozen=True)
class SolverSettings:
    """Time integration settings.

    Parameters
    ----------
    end_time : float
        Simulated time [s], > 0.
    method : str
        ``"auto"`` (default): :func:`exuclear.simulate` chooses from the model
        (:func:`exuclear.engine.solver.automatic_method`): ``"generalized-alpha"`` where the
        model has constraints (joints, coordinate constraints: algebraic equations, which
        Exudyn's explicit solvers cannot take) or the settings give an option of the
        implicit methods (``impact_step``, ``joint_steps``, ``spectral_radius``, the Newton
        options), else ``"dopri5"``; ``result.method`` says which.  Or one of
        :data:`METHODS`: ``"dopri5"`` (adaptive Dormand-Prince 5(4), explicit: only for
        models without constraints), ``"ode23"``, ``"rk44"`` (fixed step),
        ``"generalized-alpha"`` or ``"trapezoidal"`` (implicit, any model).
    step : float or "auto"
        The step of fixed-step methods; the largest step of adaptive ones and of the
        implicit methods, whose steps the clearance joints shorten where their contacts
        need it (``joint_steps``), as under a plain ``mbs.SolveDynamic`` with Exudyn's
        defaults [s].  Default :data:`DEFAULT_STEP`, 1e-5 s, the paper's maximum step.

        ``"auto"``: :func:`exuclear.simulate` chooses the step from the model
        (:func:`exuclear.engine.solver.automatic_step`; ``result.step`` says which).
        Explicit adaptive methods (DOPRI5, ODE23) control their step by their error
        estimate and keep :data:`DEFAULT_STEP` as their largest step.  Implicit methods
        whose steps the joints control (``joint_steps``, their default) take the largest
        step ``end_time / 1000`` (:data:`exuclear.timescales.MIN_STEPS_PER_RUN`): the joints
        shorten the steps where their contacts begin, are held or end.  ``end_time / 1000``
        resolves a motion of a tenth of the run with 100 steps and knows nothing of the
        model's own frequencies (check such a run at half the step, or with
        :func:`exuclear.check_convergence`).  Fixed steps (RK44, or an implicit method with
        ``joint_steps=False``) take

            step = min(T_c / 10 over the clearance joints, end_time / 1000)

        (:func:`exuclear.timescales.step_from_contact_periods`).  ``T_c`` is a joint's
        contact period ``2 pi sqrt(m / k)`` [s]: ``m`` the reduced mass of its two
        bodies, ``k`` the tangent stiffness of its contact law under the weight of ``m``
        (the model's gravity; 9.81 m/s^2 where it has none).  This is the estimate by
        which the joints judge chatter (in any implicit run), so a run at the automatic
        step is never flagged for it.  Ten steps per period resolve a contact that opens
        (issue 15's pendulum: steps of 2.3 periods chatter, a quarter period does not).
        The force is a rough estimate, and need be no more: under a Hertz-like law
        ``T_c`` varies as ``F**(-1/6)``, so a load ten times the weight shortens it by
        a third, within the margin of the ten steps.  ``impact_step`` and ``min_step``
        must not exceed the chosen step.  :func:`exuclear.check_convergence` needs a
        number: give it the settings with ``step=result.step`` (and
        ``joint_steps=settings.steered``).
    rtol, atol : float
        Relative and absolute error tolerances of adaptive explicit methods.  Default
        rtol 1e-6 (the paper's tolerance) and atol 1e-9 m, i.e. 1e-5 of the paper's
        0.1 mm clearance, so eccentricity errors stay well below the clearance.
    min_step : float
        Smallest step an adaptive method may take [s]; it fails below.  Must not
        exceed ``step``.  Default :data:`MIN_STEP_DEFAULT` (1e-12 s), the explicit
        methods' floor; the implicit methods' adaptive steps (``joint_steps``) keep
        Exudyn's minimum step, 1e-8 s, unless another value is given (the joints shorten
        steps down to 10 times it: a smaller one lets them resolve a more abrupt contact).
    spectral_radius : float
        Numerical damping of the generalized-alpha method at infinite frequency, in
        [0, 1]; Exudyn's default 0.9.  Implicit methods only: another value with an
        explicit method raises ``ValueError``.
    output_step : float
        Interval of recorded outputs [s]; default 1e-5 s.
    impact_step : float, optional
        Implicit methods only: impact-aware steps.  ``step`` is then the largest step;
        whenever a clearance joint's contact begins within a step (or the run begins in
        an impact), the step is redone with ``impact_step`` [s], and the step doubles
        again after every ``recovery_steps`` accepted steps, up to ``step``; in free flight
        the joints let it grow faster, up to the time the journal needs to reach the wall
        (docs/guide/solver_path.md, "What the joint does to your steps").  Default None: no
        impact-aware steps.
    joint_steps : bool, optional
        Implicit methods only: adaptive steps controlled by the clearance joints
        (docs/guide/solver_path.md, "What the joint does to your steps"): ``step`` is the largest
        step; a joint rejects a step in which its contact cannot be resolved, and Exudyn
        redoes it (or a step whose Newton iteration failed) shorter, down to Exudyn's
        ``minimumStepSize``, 1e-8 s, then doubles it again after 10 accepted steps that
        converged in at most 7 Newton iterations (Exudyn's rule): what a plain
        ``mbs.SolveDynamic`` does with Exudyn's defaults.  Default None: True for the
        implicit methods without ``impact_step``.  False: fixed steps, and a step whose
        Newton iteration fails ends the run.  :attr:`steered` is the value in effect.
    rate_limit : float
        KAPPA of the clearance joints' own step control for this run (each joint's
        ``rate_limit``, restored after the run): a step in contact may change the
        penetration rate by at most this fraction of ``max(|v0|, v_min)``.  Default
        :data:`RATE_LIMIT_DEFAULT` (0.1).  It sets the accuracy of the steps the joints
        control (``joint_steps``); with fixed steps it sets what the joints report as
        unresolved.  Implicit methods only (explicit ones control their step by their error
        estimate); :func:`exuclear.check_convergence` divides it with the steps.
    recovery_steps : int
        Accepted steps between two doublings of the step after an impact (with
        ``impact_step``); default 100, i.e. 100 us at 1e-6 s, longer than one impact of
        the paper's scenes (~40 us, docs/physics.md section 8).
    newton_rtol, newton_atol : float
        Implicit methods only: Newton's relative tolerance (the residual's reduction from
        the step's first iterate) and absolute tolerance (one norm over the residuals of
        all equations, in their units: forces N, N m, and constraint equations m, rad).
        Defaults :data:`NEWTON_RTOL_DEFAULT`, :data:`NEWTON_ATOL_DEFAULT` (both 1e-8): an
        absolute tolerance looser than Exudyn's 1e-10, because stiff contact puts a
        round-off floor under the residual, and no looser, because constraints would then
        be left unmet by the size of a contact's penetration.
    newton_contractivity : float, optional
        Implicit methods only: Exudyn's ``newton.modifiedNewtonContractivity``, in (0, 1]:
        the modified Newton method computes a new Jacobian where an iteration reduces the
        residual by less than this factor.  Default None: the joints' choice (at most
        :data:`exuclear.engine.steering.CONTRACTIVITY`, 0.2).  Smaller values take more
        Jacobians and fewer iterations: worth it where Jacobians are cheap and the motion
        turns the Jacobian fast (the redundant slider-crank's defaults, measured there).
    linear_solver : str
        The linear solver of the implicit methods' Newton iterations: ``"dense"`` (Exudyn's
        default ``EXUdense``) or ``"sparse"`` (``EigenSparse``, Exudyn's choice for large
        models: beams, cables, many bodies).  Implicit methods only.
    verbose : int
        Exudyn's verbose mode: 0 silent; 1 prints progress (time reached, time to go)
        every few seconds of a long run.
    """

    end_time: float
    method: str = AUTO_METHOD
    step: float | Literal["auto"] = DEFAULT_STEP
    rtol: float = 1e-6
    atol: float = 1e-9
    min_step: float = MIN_STEP_DEFAULT
    spectral_radius: float = SPECTRAL_RADIUS_DEFAULT
    output_step: float = 1e-5
    impact_step: float | None = None
    joint_steps: bool | None = None
    rate_limit: float = RATE_LIMIT_DEFAULT
    recovery_steps: int = 100
    newton_rtol: float = NEWTON_RTOL_DEFAULT
    newton_atol: float = NEWTON_ATOL_DEFAULT
    newton_contractivity: float | None = None
    linear_solver: str = "dense"
    verbose: int = 0

    def __post_init__(self) -> None:
        check_positive("end_time", self.end_time)
        if self.method != AUTO_METHOD:
            check_choice("method", self.method, {**METHODS, AUTO_METHOD: None})
        if self.step is None or isinstance(self.step, str) and self.step != AUTO:
            raise ValueError(f"`step` must be a positive number [s] or {AUTO!r} (chosen from the model), got {self.step!r}")
        if not self.automatic:
            check_positive("step", self.step)
        check_positive("rtol", self.rtol)
        check_positive("atol", self.atol)
        if check_positive("min_step", self.min_step) > self._step_or(math.inf):
            raise ValueError(f"`min_step` must not exceed `step`, got min_step = {self.min_step}, step = {self.step}")
        rho = check_real("spectral_radius", self.spectral_radius)
        if not 0.0 <= rho <= 1.0:
            raise ValueError(f"`spectral_radius` must lie in [0, 1], got {rho}")
        if rho != SPECTRAL_RADIUS_DEFAULT and self.explicit:
            raise ValueError(f"`spectral_radius` applies to the implicit methods (generalized-alpha, trapezoidal); "
                             f"{self.method!r} is explicit and has no numerical damping to set, got {rho}")
        check_positive("output_step", self.output_step)
        for name in ("newton_rtol", "newton_atol"):
            value = check_positive(name, getattr(self, name))
            if value != (NEWTON_RTOL_DEFAULT if name == "newton_rtol" else NEWTON_ATOL_DEFAULT) and self.explicit:
                raise ValueError(f"`{name}` applies to the implicit methods (their Newton iteration); "
                                 f"{self.method!r} is explicit: use rtol, atol, got {value}")
        if self.newton_contractivity is not None:
            value = check_real("newton_contractivity", self.newton_contractivity)
            if not 0.0 < value <= 1.0:
                raise ValueError(f"`newton_contractivity` must lie in (0, 1] (Exudyn's modifiedNewtonContractivity), "
                                 f"got {value}")
            if self.explicit:
                raise ValueError(f"`newton_contractivity` applies to the implicit methods (their Newton iteration); "
                                 f"{self.method!r} is explicit, got {value}")
        check_choice("linear_solver", self.linear_solver, LINEAR_SOLVERS)
        if self.linear_solver != "dense" and self.explicit:
            raise ValueError(f"`linear_solver` applies to the implicit methods (their Newton iteration); "
                             f"{self.method!r} is explicit, got {self.linear_solver!r}")
        if isinstance(self.verbose, bool) or not isinstance(self.verbose, int) or self.verbose < 0:
            raise ValueError(f"`verbose` must be a non-negative integer (Exudyn's verbose mode), got {self.verbose!r}")
        if self.impact_step is not None:
            if self.explicit:
                raise ValueError(f"`impact_step` applies to the implicit methods; {self.method!r} controls its "
                                 "step by its error estimate (use rtol, atol)")
            if check_positive("impact_step", self.impact_step) > self._step_or(math.inf):
                raise ValueError(f"`impact_step` must not exceed `step`, got impact_step = {self.impact_step}, "
                                 f"step = {self.step}")
        if self.joint_steps is not None and not isinstance(self.joint_steps, bool):
            raise ValueError(f"`joint_steps` must be True, False or None (the default for the step), got "
                             f"{self.joint_steps!r}")
        if self.joint_steps:
            if self.explicit:
                raise ValueError(f"`joint_steps` applies to the implicit methods; {self.method!r} controls its step by "
                                 "its error estimate (use rtol, atol)")
            if self.impact_step is not None:
                raise ValueError("give `joint_steps` or `impact_step`, not both: with joint_steps the joints choose "
                                 f"the steps at a contact, got impact_step = {self.impact_step}")
        if check_real("rate_limit", self.rate_limit) < 0.0:
            raise ValueError(f"`rate_limit` must be non-negative (0 turns the joints' rate criterion off), got "
                             f"{self.rate_limit}")
        if self.rate_limit != RATE_LIMIT_DEFAULT and self.explicit:
            raise ValueError(f"`rate_limit` applies to the implicit methods; {self.method!r} controls its step by its "
                             f"error estimate (use rtol, atol), got {self.rate_limit}")
        if isinstance(self.recovery_steps, bool) or not isinstance(self.recovery_steps, int) or self.recovery_steps < 1:
            raise ValueError(f"`recovery_steps` must be a positive integer, got {self.recovery_steps!r}")
        if self._step_or(0.0) > self.end_time:
            raise ValueError(f"`step` must not exceed `end_time`, got step = {self.step}, end_time = {self.end_time}")

    @property
    def automatic(self) -> bool:
        """True if ``step`` is ``"auto"`` (chosen from the model by :func:`exuclear.simulate`)."""
        return self.step == AUTO

    def _step_or(self, default: float) -> float:
        """``step`` [s], or ``default`` where it is ``"auto"``."""
        return default if self.automatic else float(self.step)

    @property
    def steered(self) -> bool:
        """True if the clearance joints control the steps (``joint_steps``, or its default:
        an implicit method without ``impact_step``)."""
        if self.joint_steps is not None:
            return self.joint_steps
        return not self.explicit and self.impact_step is None

    @property
    def method_from_model(self) -> bool:
        """True if ``method`` is ``"auto"`` (chosen from the model by :func:`exuclear.simulate`)."""
        return self.method == AUTO_METHOD

    @property
    def implicit_options(self) -> list[str]:
        """The options given that only the implicit methods take (their names)."""
        defaults = {"spectral_radius": SPECTRAL_RADIUS_DEFAULT, "newton_rtol": NEWTON_RTOL_DEFAULT,
                    "newton_atol": NEWTON_ATOL_DEFAULT, "rate_limit": RATE_LIMIT_DEFAULT, "linear_solver": "dense",
                    "impact_step": None, "joint_steps": None, "newton_contractivity": None}
        return [name for name, default in defaults.items() if getattr(self, name) != default]

    @property
    def explicit(self) -> bool:
        """Whether the method is explicit; ``"auto"`` counts as implicit until it is chosen
        (the implicit methods' options are accepted with it)."""
        return False if self.method_from_model else METHODS[self.method][1]

    @property
    def adaptive(self) -> bool:
        return False if self.method_from_model else METHODS[self.method][2]
