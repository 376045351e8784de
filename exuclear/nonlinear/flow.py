"""Runs of a periodically driven model that record its Poincare section and, with a
second copy, its largest Lyapunov exponent: :class:`Driven` (what a model must say about
itself), :func:`run_sections` (one run) and :func:`lyapunov`.

Two copies, one system.  The exponent is measured on the model's own flow (Benettin et
al., Meccanica 15 (1980) 9-20): a second copy of the model starts ``perturbation`` away
from the first, and once per period their distance ``d`` is measured, ``log(d / d0)``
summed and the second copy set back to distance ``d0`` along the same direction.  Both
copies sit in ONE Exudyn system, so the solver advances them with the same steps: on
separate adaptive step sequences the two step-size histories differ by more than the
perturbation and the distance grows from the integration error, which gave a positive
exponent for a periodic impacting orbit (shared/research: +0.12 against -0.128 1/s).
"""
from __future__ import annotations

import inspect
import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..checks import check_positive
from ..engine import simulate
from ..engine import state as _state
from ..settings import SolverSettings

#: Seed of the perturbation's direction: the same model gives the same exponent.
DIRECTION_SEED = 0
#: Relative round-off of a section time: a step that ends within it of a section ends on it
#: (the last section is the run's end time, which the solver reaches up to round-off).
TIME_ROUND_OFF = 1e-12


@dataclass(frozen=True)
class Driven:
    """A model driven with a period, as the nonlinear tools need it.

    Attributes
    ----------
    build : callable
        ``build(mbs)`` adds one copy of the model to the system ``mbs`` (not assembled)
        and returns what ``observe`` needs (anything: handles, item numbers).  A
        ``build(mbs, copy)`` receives the copy's index, 0 or 1: Exudyn refuses an item
        name twice, so a model that names its items needs it for :func:`lyapunov`.
    settings : SolverSettings
        Method, steps and tolerances; ``end_time`` is replaced by the periods of a run.
    period : float
        The driving period [s] (a crank at ``omega``: ``2 pi / omega``).
    observe : callable, optional
        ``observe(mbs, built) -> dict`` of floats: what the section records, read from
        the system's current state (``built``: what ``build`` returned for copy 0).
        Default: every clearance joint of the copy, its eccentricity ratios ``e_x/c``,
        ``e_y/c`` in the joint frame and their rates over ``c`` [1/s] (names
        ``B.ex``, ``B.ey``, ``B.vx``, ``B.vy`` for a joint named B); a model without one,
        its ODE2 coordinates and velocities (``q0``, ``v0``, ...).
    params : mapping
        The parameters it was made from (for :attr:`carry` and messages).
    carry : callable, optional
        ``carry(q, v, previous) -> (q, v)``: the state a run of this model starts from,
        given the final coordinates and velocities of a run of the ``previous``
        :class:`Driven` (a sweep carrying the state over).  Default: the state as it is.
    drive : tuple of int
        Coordinates of the copy (indices into its ODE2 coordinates, in the system's order)
        that carry the drive rather than the driven motion: a crank held at its speed by a
        flywheel.  The exponent leaves them out of the perturbation and the distance and
        gives the second copy the first one's values at every renormalisation: a
        perturbed drive speed would drift the phase without bound, a neutral direction
        whose exponent is 0 whatever the mechanism does.
    """

    build: Callable[..., Any]
    settings: SolverSettings
    period: float
    observe: Callable[[Any, Any], Mapping[str, float]] | None = None
    params: Mapping[str, Any] = field(default_factory=dict)
    carry: Callable[[np.ndarray, np.ndarray, Driven], tuple[np.ndarray, np.ndarray]] | None = None
    drive: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        if not callable(self.build):
            raise ValueError(f"`build` must be a function build(mbs), got {self.build!r}")
        if not isinstance(self.settings, SolverSettings):
            raise ValueError(f"`settings` must be an exuclear.SolverSettings, got {type(self.settings).__name__}")
        check_positive("period", self.period)


@dataclass
class SectionRun:
    """What :func:`run_sections` returns.

    Attributes
    ----------
    times : ndarray, shape (k,)
        Section times [s]: the ends of the sampled periods.
    samples : dict of str to ndarray, shape (k,)
        The observables there (:attr:`Driven.observe`), interpolated to the section
        times (cubic Hermite on positions and velocities between the accepted steps).
    success, message : bool, str
        The run's (:func:`exuclear.simulate`).
    steps : int
        Accepted steps.
    wall_time : float
        The solver's wall time [s].
    final : tuple of ndarray
        Copy 0's coordinates and velocities at the end (for a sweep).
    log_stretch : ndarray
        With two copies: ``log(d / d0)`` per period, transient included.
    stretch_times : ndarray
        The instants of the renormalisations [s] (the first accepted step at or after
        each period's end).
    """

    times: np.ndarray
    samples: dict[str, np.ndarray]
    success: bool
    message: str
    steps: int
    wall_time: float
    final: tuple[np.ndarray, np.ndarray]
    log_stretch: np.ndarray = field(default_factory=lambda: np.zeros(0))
    stretch_times: np.ndarray = field(default_factory=lambda: np.zeros(0))


def _call_build(build: Callable[..., Any], mbs: Any, copy: int) -> Any:
    try:
        kinds = [p.kind for p in inspect.signature(build).parameters.values()]
    except (TypeError, ValueError):  # a builtin or a callable without a signature
        kinds = []
    positional = (inspect.Parameter.POSITIONAL_ONLY, inspect.Parameter.POSITIONAL_OR_KEYWORD)
    takes_copy = sum(k in positional for k in kinds) >= 2 or inspect.Parameter.VAR_POSITIONAL in kinds
    return build(mbs, copy) if takes_copy else build(mbs)


def _default_observe(mbs: Any, objects: range, coordinates: np.ndarray) -> Callable[[Any, Any], dict]:
    joints = _state.joints_among(mbs, objects)
    if joints:
        labels = _state.names(joints)

        def observe_joints(mbs: Any, built: Any) -> dict:
            out = {}
            for name, handle in zip(labels, joints):
                c = handle.joint.geometry.clearance
                e, e_t = _state.eccentricity(mbs, handle)
                out.update({f"{name}.ex": e[0] / c, f"{name}.ey": e[1] / c, f"{name}.vx": e_t[0] / c,
                            f"{name}.vy": e_t[1] / c})
            return out

        return observe_joints

    def observe_coordinates(mbs: Any, built: Any) -> dict:
        q, v = _state.current(mbs)
        return {**{f"q{i}": float(x) for i, x in enumerate(q[coordinates])},
                **{f"v{i}": float(x) for i, x in enumerate(v[coordinates])}}

    return observe_coordinates


def _hermite(t0: float, t1: float, y0: np.ndarray, y1: np.ndarray, d0: np.ndarray, d1: np.ndarray,
             t: float) -> np.ndarray:
    """The cubic Hermite interpolant of ``y`` with slopes ``d`` at ``t`` in ``[t0, t1]``."""
    h = t1 - t0
    s = (t - t0) / h
    return ((2 * s**3 - 3 * s**2 + 1) * y0 + (s**3 - 2 * s**2 + s) * h * d0
            + (-2 * s**3 + 3 * s**2) * y1 + (s**3 - s**2) * h * d1)


class _Recorder:
    """The post-step function of a run: the section samples of copy 0 and, with a second
    copy, the renormalisation of its distance once per period."""

    def __init__(self, mbs: Any, driven: Driven, built: Any, observe: Callable, first: int, count: int,
                 copies: tuple[np.ndarray, np.ndarray, np.ndarray] | None, perturbation: float,
                 h_max: float) -> None:
        self.mbs, self.built, self.observe = mbs, built, observe
        self.period = driven.period
        self.next_sample = first * driven.period
        self.last_sample = (first + count - 1) * driven.period
        self.copies, self.d0 = copies, perturbation
        self.next_renorm = driven.period
        self.h_max = h_max
        self.previous: tuple | None = None  # (t, q, v, a) of the last step before a section
        self.times: list[float] = []
        self.rows: list[dict] = []
        self.log_stretch: list[float] = []
        self.stretch_times: list[float] = []
        self.error: Exception | None = None

    def start(self) -> None:
        q, v = _state.initial(self.mbs)
        self.previous = (0.0, q, v, None)

    def __call__(self, mbs: Any, t: float) -> bool:
        try:
            self._step(mbs, t)
        except Exception as err:  # Exudyn would turn it into a failed run: kept and raised after it
            self.error = err
            return False
        return True

    def _pending(self) -> bool:
        """Whether a section is still to be sampled."""
        return self.next_sample <= self.last_sample * (1.0 + TIME_ROUND_OFF)

    def _step(self, mbs: Any, t: float) -> None:
        # the state is read within one largest step of a section (for the interpolation
        # across it) and at the renormalisations, not at every step
        near = self._pending() and t >= self.next_sample - self.h_max
        renormalise = self.copies is not None and t >= self.next_renorm
        if near or renormalise:
            q, v, a = _state.current(mbs, accelerations=True)
            if near:
                while self._pending() and t >= self.next_sample * (1.0 - TIME_ROUND_OFF):
                    self._sample(t, q, v, a)
                self.previous = (t, q, v, a)
            if renormalise:
                self._renormalise(t, q, v)

    def _sample(self, t: float, q: np.ndarray, v: np.ndarray, a: np.ndarray) -> None:
        t_k = self.next_sample
        t0, q0, v0, a0 = self.previous
        if t <= t_k or t0 >= t:  # the step ends on the section
            q_k, v_k = q, v
        else:
            q_k = _hermite(t0, t, q0, q, v0, v, t_k)
            v_k = _hermite(t0, t, v0, v, a0, a, t_k) if a0 is not None else v0 + (v - v0) * (t_k - t0) / (t - t0)
        if q_k is not q:  # observe at the section's state, then give the solver its own back
            _state.set_state(self.mbs, q_k, v_k)
            row = dict(self.observe(self.mbs, self.built))
            _state.set_state(self.mbs, q, v)
        else:
            row = dict(self.observe(self.mbs, self.built))
        self.rows.append(row)
        self.times.append(t_k)
        self.next_sample += self.period

    def _renormalise(self, t: float, q: np.ndarray, v: np.ndarray) -> None:
        one, two, drive = self.copies
        free = np.setdiff1d(np.arange(one.size), drive)
        dx = np.concatenate([q[two[free]] - q[one[free]], v[two[free]] - v[one[free]]])
        d = float(np.linalg.norm(dx))
        self.log_stretch.append(math.log(d / self.d0) if d > 0.0 else -math.inf)
        self.stretch_times.append(t)
        q, v = q.copy(), v.copy()
        if d > 0.0:
            dx *= self.d0 / d
            q[two[free]] = q[one[free]] + dx[:free.size]
            v[two[free]] = v[one[free]] + dx[free.size:]
        q[two[drive]], v[two[drive]] = q[one[drive]], v[one[drive]]
        _state.set_state(self.mbs, q, v)
        while self.next_renorm <= t:
            self.next_renorm += self.period


def run_sections(driven: Driven, *, periods: int, transient_periods: int = 0, perturbation: float | None = None,
                 start: tuple[np.ndarray, np.ndarray] | None = None) -> SectionRun:
    """Run ``driven`` for ``transient_periods + periods`` periods from t = 0 and record
    its observables at the end of each of the last ``periods`` periods.

    With ``perturbation`` (> 0), a second copy runs beside the first in the same system
    and is renormalised to that distance once per period (module docstring); the run's
    ``log_stretch`` then holds the logarithms of the stretches.  ``start``: coordinates
    and velocities of copy 0 to start from (a sweep), instead of the model's initial
    state.
    """
    periods = _count("periods", periods, 1)
    transient_periods = _count("transient_periods", transient_periods, 0)
    mbs = _state.new_system()
    first = _state.object_count(mbs)
    built = _call_build(driven.build, mbs, 0)
    middle = _state.object_count(mbs)
    if perturbation is not None:
        check_positive("perturbation", perturbation)
        _call_build(driven.build, mbs, 1)
    end = _state.object_count(mbs)
    mbs.Assemble()
    mine = _state.coordinates_of(mbs, range(first, middle))
    if mine.size == 0:
        raise ValueError("`build` added no object with coordinates to the system")
    copies = None
    q, v = _state.initial(mbs)
    if start is not None:
        q[mine], v[mine] = start
    if perturbation is not None:
        theirs = _second_copy(mbs, range(first, middle), range(middle, end), mine)
        drive = _drive(driven.drive, mine.size)
        direction = np.random.default_rng(DIRECTION_SEED).standard_normal((2, mine.size))
        direction[:, drive] = 0.0
        direction *= perturbation / np.linalg.norm(direction)
        q[theirs], v[theirs] = q[mine] + direction[0], v[mine] + direction[1]
        copies = (mine, theirs, drive)
    _state.set_state(mbs, q, v, at_start=True)
    observe = driven.observe or _default_observe(mbs, range(first, middle), mine)
    settings = replace(driven.settings, end_time=(transient_periods + periods) * driven.period)
    h_max = settings.step if isinstance(settings.step, float) else settings.end_time
    recorder = _Recorder(mbs, driven, built, observe, transient_periods + 1, periods, copies,
                         perturbation or 0.0, h_max)
    recorder.start()
    mbs.SetPostStepUserFunction(recorder)
    begin = time.perf_counter()
    result = simulate(mbs, settings)
    wall = time.perf_counter() - begin
    if recorder.error is not None:
        raise recorder.error
    q_end, v_end = _state.current(mbs)
    names = list(recorder.rows[0]) if recorder.rows else []
    samples = {name: np.array([row[name] for row in recorder.rows], dtype=float) for name in names}
    return SectionRun(np.asarray(recorder.times), samples, result.success, result.message, result.steps,
                      result.wall_time if math.isfinite(result.wall_time) else wall, (q_end[mine], v_end[mine]),
                      np.asarray(recorder.log_stretch), np.asarray(recorder.stretch_times))


def _drive(drive: object, size: int) -> np.ndarray:
    index = np.asarray(drive, dtype=int).reshape(-1)
    if index.size and (index.min() < 0 or index.max() >= size or np.unique(index).size != index.size):
        raise ValueError(f"`drive` must name distinct coordinates of the copy, 0 to {size - 1}, got {tuple(drive)}")
    if index.size == size:
        raise ValueError("`drive` names every coordinate: nothing is left to perturb")
    return index


def _count(name: str, value: object, low: int) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < low:
        raise ValueError(f"`{name}` must be an integer >= {low}, got {value!r}")
    return int(value)


def _second_copy(mbs: Any, one: range, two: range, mine: np.ndarray) -> np.ndarray:
    """The coordinate indices of the second copy; ``ValueError`` where it is not a copy of
    the first or the model has constraints or first-order coordinates."""
    theirs = _state.coordinates_of(mbs, two)
    q, v = _state.initial(mbs)
    if theirs.size != mine.size or not (np.array_equal(q[theirs], q[mine]) and np.array_equal(v[theirs], v[mine])):
        raise ValueError("`build` must add the same model each time it is called (the second copy differs from the "
                         "first in its coordinates or initial state)")
    constrained = _state.constraint_objects(mbs, range(one.start, two.stop))
    if constrained:
        # a perturbation of all coordinates violates the constraints (trap 3 of the docs):
        # only independent coordinates may be perturbed
        raise ValueError(f"the model has constraints (objects {constrained}); the exponent perturbs every coordinate, "
                         "which would violate them: build the model in minimal coordinates (a kinematic tree, "
                         "ObjectKinematicTree) for the exponent")
    if _state.ode1_size(mbs):
        raise ValueError("the model has first-order (ODE1) coordinates, which the exponent does not perturb")
    return theirs


@dataclass(frozen=True)
class LyapunovResult:
    """What :func:`lyapunov` returns.

    Attributes
    ----------
    exponent : float
        The largest Lyapunov exponent [1/s] over the sampled periods: the sum of
        ``log(d / d0)`` over them divided by the time they span.
    running : ndarray, shape (periods,)
        The estimate after each sampled period [1/s] (converged where it levels off).
    log_stretch : ndarray, shape (periods,)
        ``log(d / d0)`` per sampled period.
    times : ndarray, shape (periods,)
        Instants of the renormalisations [s].
    period : float
        The driving period [s]; ``exponent * period`` is the exponent per period.
    success, message : bool, str
        The run's.
    steps : int
        Accepted steps of the run (both copies together).
    """

    exponent: float
    running: np.ndarray = field(repr=False)
    log_stretch: np.ndarray = field(repr=False)
    times: np.ndarray = field(repr=False)
    period: float
    success: bool
    message: str
    steps: int


def exponent_of(run: SectionRun, transient_periods: int) -> tuple[float, np.ndarray, np.ndarray, np.ndarray]:
    """The exponent [1/s], its running estimate, the stretches and their instants after
    ``transient_periods`` renormalisations of a two-copy run."""
    logs, times = run.log_stretch[transient_periods:], run.stretch_times[transient_periods:]
    if logs.size == 0:  # no second copy, or the run stopped within the transient
        return math.nan, logs, logs, times
    t0 = run.stretch_times[transient_periods - 1] if transient_periods else 0.0
    running = np.cumsum(logs) / (times - t0)
    return float(running[-1]), running, logs, times


def lyapunov(build: Callable[..., Any], settings: SolverSettings, *, period: float, periods: int,
             transient_periods: int = 0, perturbation: float = 1e-6, drive: tuple[int, ...] = ()) -> LyapunovResult:
    """The largest Lyapunov exponent [1/s] of a periodically driven Exudyn model's own flow.

    Two copies of the model run in one system, advanced by the same steps; once per
    ``period`` the second is set back to the distance ``perturbation`` from the first
    (Benettin's method; :mod:`exuclear.nonlinear.flow`).  The distance is the Euclidean
    norm over the copy's ODE2 coordinates and velocities, in their own units.

    Parameters
    ----------
    build : callable
        ``build(mbs)`` adds one copy of the model to ``mbs``; ``build(mbs, copy)`` gets
        the copy's index, 0 or 1, to name its items apart (Exudyn refuses a name twice).
        Called twice; the two copies must be equal.  The model must have no constraints
        (the perturbation would violate them): minimal coordinates, e.g. a kinematic tree.
    settings : SolverSettings
        Method, steps and tolerances; the end time follows from the periods.  An
        explicit method is the one to use: it takes the next step from the state set
        between steps, while an implicit one keeps its own acceleration history.
    period : float
        The driving period [s].
    periods : int
        Periods over which the exponent is averaged.
    transient_periods : int
        Periods run first and left out (renormalised all the same: the perturbation
        turns towards the most stretched direction meanwhile).
    perturbation : float
        The distance ``d0`` kept between the copies, in the units of the coordinates
        (m, rad and their rates): well above the integration error (at 1e-8 the steps'
        error drove the distance in the research runs) and well below the scale of the
        motion (the clearance of a joint).
    drive : tuple of int
        Coordinates of the copy that carry the drive (:attr:`Driven.drive`), left out.

    The clearance joints of each copy keep their own contact history (onset time and
    velocity) in their own data nodes.  Setting the second copy back moves it by up to
    ``d`` without touching that history: a copy set back out of or into the wall
    ends or begins its contact at the next step, with the history of its own path.
    A speed-driven crank's periodic response has a NEGATIVE exponent, not zero: the drive
    is not a direction of the flow that neither grows nor shrinks, as the time is of an
    autonomous system.
    """
    driven = Driven(build, settings, period, drive=tuple(drive))
    run = run_sections(driven, periods=periods, transient_periods=transient_periods, perturbation=perturbation)
    exponent, running, logs, times = exponent_of(run, transient_periods)
    return LyapunovResult(exponent, running, logs, times, driven.period, run.success, run.message, run.steps)
