"""Convergence check of a user's model: run it again at tighter settings and say what agrees.

Clearance-joint motion can be chaotic: two runs at different steps follow the same path
for a while, then different impact sequences.  :func:`check_convergence` reruns a model
at a tighter step or tolerance (:func:`refined_settings`), takes the tighter run as the
reference, and reports

- the **path**: the time until which ``max |e - e_ref| / c`` stays under a bound
  (default 1 % of the clearance), per joint, and for named signals the time until which
  they stay within the bound times their range;
- the **impacts one by one** up to that horizon: impacts matched in time, their onset
  shifts, onset velocities and peak forces; and how long the impact sequence matches;
- the **peak forces** over the whole run and within the horizon;
- what can **only agree statistically** once the paths have parted: impact counts, the
  distributions of peak force and onset velocity (two-sample Kolmogorov-Smirnov test),
  and the spectra of the eccentricity and of the signals (Welch).  (The fraction of
  time in contact is left out: where the journal slides on the wall, its penetration
  hovers about zero and the in-contact flag flips with nanometres.)

The difference from the tighter run is taken as the error of the user's run: with a
method of order ``p``, the tighter run's own error is about ``factor**p`` times smaller.
A horizon shorter than the run is not by itself a fault of the settings: where the
motion is chaotic, any tighter run parts from a coarser one at some time, and only the
statistics can be trusted after it.

The model is given as a callable ``run(settings) -> RunRecord``, so that any Exudyn
model with clearance joints can be checked, on either path a model is run by:

- :func:`exuclear.simulate` with a :class:`~exuclear.SolverSettings`:
  ``RunRecord.from_handles(result, joints)`` builds the record from the result and the
  joints' handles; ``step="auto"`` is refined from the step the run chose (``result.step``);
- a plain ``mbs.SolveDynamic`` with an ``exu.SimulationSettings``: ``run`` takes one and
  returns ``RunRecord.from_mbs(mbs, joints)``; the tighter settings are a copy with
  ``timeIntegration.numberOfSteps`` multiplied and ``minimumStepSize`` (and, with
  ``automaticStepSize``, the tolerances and ``initialStepSize``) divided by the factor.

This module never imports exudyn itself and never plots.
"""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from .checks import check_positive
from .contact import V_MIN_DEFAULT
from .history import ImpactRecord
from .settings import SolverSettings
from .spectrum import amplitude_spectrum

#: Default refinement factor: steps (and tolerances of adaptive methods) divided by 4.  A
#: second-order method's error then drops 16-fold, so the difference to the tighter run
#: is the user's error to within about 7 %; a factor of 2 (4-fold, within 33 %) would
#: blur that, and 10 would cost 10 times the user's run.
DEFAULT_FACTOR = 4.0

#: Default path bound: 1 % of the clearance, the accuracy the defaults of the scenes are
#: chosen for (models/slider_crank.py, validation/work_precision.py).
DEFAULT_BOUND = 0.01

#: Impacts match one by one when their onsets are mutual nearest neighbours in time, lie
#: apart by less than the reference contact's duration or than the time in which the
#: approach speed ``|v0|`` covers the path bound (``bound c / |v0|``: paths that agree
#: to the bound may reach the wall that much apart), and their onset velocities and
#: peak forces agree within this relative tolerance: ten times the largest peak-force
#: difference of a converged default run in the cross-check (0.42 %, README), and well
#: below the scatter of impacts in a chaotic sequence.
IMPACT_RTOL = 0.1

#: Absolute floor of the onset-velocity tolerance [m/s]: the default ``v_min`` of the
#: damping term (docs/physics.md eq. 17), below which ``v0`` does not change the force.
IMPACT_V0_FLOOR = V_MIN_DEFAULT

#: Absolute floor of the peak-force tolerance, as a fraction of the reference run's
#: largest peak force: a grazing contact of a few newtons is not compared relatively.
IMPACT_FORCE_FLOOR = 0.01

#: Impact counts agree statistically when they differ by at most this many standard
#: deviations of a Poisson count with the reference's mean, ``2 sqrt(n_ref)``: a
#: yardstick (a chaotic impact sequence is not a Poisson process), not a theorem.
COUNT_SPREAD = 2.0

#: Significance level of the two-sample Kolmogorov-Smirnov tests: distributions agree
#: statistically when the test cannot tell them apart at 5 %.
KS_ALPHA = 0.05

#: Fewer impacts than this in either run: no distribution is compared (the test has no power).
KS_MIN_SAMPLES = 5

#: Spectra agree when the relative L2 distance of the amplitude spectra (Welch,
#: :func:`exuclear.spectrum.amplitude_spectrum`) is below this and the dominant lines coincide within one
#: frequency bin: a tenth of the spectrum is the level at which a spectral plot visibly differs.
SPECTRUM_TOL = 0.1

#: Welch segments: the signal is cut into this many (50 % overlap, so about twice as many
#: averages), trading frequency resolution for a smoother estimate.
WELCH_SEGMENTS = 4


# =======================================================================================
# what a run gives the check
# =======================================================================================

@dataclass(frozen=True)
class JointRecord:
    """One clearance joint's results of a run (copies, SI units).

    ``outputs``: ``time`` and :data:`exuclear.OUTPUT_COLUMNS` as recorded; ``impacts``:
    the contacts of the run in order, the last one still open at the end if
    ``last_open`` (its duration then runs to the end of the run); ``clearance`` [m].
    """

    clearance: float
    outputs: dict[str, np.ndarray]
    impacts: tuple[ImpactRecord, ...]
    last_open: bool = False

    @property
    def onset_times(self) -> np.ndarray:
        return np.array([r.onset_time for r in self.impacts])

    @classmethod
    def from_handle(cls, handle: Any) -> JointRecord:
        """The record of a :class:`exuclear.ClearanceJointHandle` after a run."""
        out = {k: np.array(v, dtype=float) for k, v in handle.outputs().items()}
        impacts = list(handle.impacts())
        state = handle.state()
        if state.in_contact:  # the contact going on at the end, so far
            impacts.append(ImpactRecord(state.onset_time, state.v0, state.peak_force,
                                        state.time - state.onset_time, state.max_penetration))
        return cls(handle.joint.geometry.clearance, out, tuple(impacts), bool(state.in_contact))


@dataclass(frozen=True)
class RunRecord:
    """What :func:`check_convergence` compares of one run.

    Parameters
    ----------
    joints : dict of str to JointRecord
        The clearance joints by name.
    signals : dict of str to (ndarray, ndarray)
        Named signals as ``(time, values)``, shapes (n,) and (n,), any units.
    success, message : bool, str
        Whether the run reached its end time, and why not.
    time_reached : float
        Simulated time reached [s].
    wall_time : float
        Wall time of the solver [s] (reported, not compared).
    step : float
        The step the run was given [s] (the largest for adaptive methods), as
        ``result.step`` says; NaN where unknown.  With ``SolverSettings(step="auto")``
        the check refines this step.
    """

    joints: dict[str, JointRecord]
    signals: dict[str, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)
    success: bool = True
    message: str = ""
    time_reached: float = math.inf
    wall_time: float = math.nan
    step: float = math.nan

    @classmethod
    def from_handles(cls, result: Any, joints: Mapping[str, Any],
                     signals: Mapping[str, tuple[np.ndarray, np.ndarray]] | None = None) -> RunRecord:
        """The record of a finished run: ``result`` from :func:`exuclear.simulate`,
        ``joints`` the clearance-joint handles by name, ``signals`` named ``(time, values)``."""
        return cls(*_recorded(joints, signals), success=bool(result.success), message=str(result.message),
                   time_reached=float(result.time_reached), wall_time=float(result.wall_time),
                   step=float(getattr(result, "step", math.nan)))

    @classmethod
    def from_mbs(cls, mbs: Any, joints: Mapping[str, Any],
                 signals: Mapping[str, tuple[np.ndarray, np.ndarray]] | None = None, *, success: bool = True,
                 message: str = "") -> RunRecord:
        """The record of a run made by a plain ``mbs.SolveDynamic``: ``joints`` the
        clearance-joint handles by name, ``signals`` named ``(time, values)``;
        ``success`` what ``SolveDynamic`` returned.  The time reached is the system's
        time after the run."""
        return cls(*_recorded(joints, signals), success=bool(success), message=str(message),
                   time_reached=float(mbs.systemData.GetTime()))


def _recorded(joints: Mapping[str, Any], signals: Mapping[str, tuple[np.ndarray, np.ndarray]] | None
              ) -> tuple[dict[str, JointRecord], dict[str, tuple[np.ndarray, np.ndarray]]]:
    """The joints' records and the signals as float arrays, checked."""
    if not isinstance(joints, Mapping):
        raise ValueError(f"`joints` must map names to clearance-joint handles, got {joints!r}")
    if not joints and not signals:
        raise ValueError("nothing to compare: give clearance-joint handles (`joints`) or `signals`")
    sig = {}
    for name, pair in (signals or {}).items():
        t, y = (np.array(v, dtype=float).reshape(-1) for v in pair)
        if t.shape != y.shape:
            raise ValueError(f"signal {name!r}: time and values differ in length ({t.size} and {y.size})")
        sig[str(name)] = (t, y)
    return {str(k): JointRecord.from_handle(h) for k, h in joints.items()}, sig


# =======================================================================================
# the refinement rule
# =======================================================================================

def refined_settings(settings: SolverSettings, factor: float = DEFAULT_FACTOR) -> SolverSettings:
    """The tighter settings of the check.

    Explicit adaptive methods (DOPRI5, ODE23): ``rtol``, ``atol`` and the largest step
    divided by ``factor`` (an error-controlled method at a tighter tolerance, its step
    limit with it).  Explicit fixed-step (RK44): the step divided.  Implicit methods
    (generalized-alpha, trapezoidal): the step and, with impact-aware steps, the
    ``impact_step`` divided; with steps the joints control (``joint_steps``), their
    ``rate_limit`` divided.  The output interval and everything else are kept.

    ``step="auto"`` has no number to divide until the model is built: give the settings
    with the step the run chose (``result.step``); :func:`check_convergence` does so.

    An ``exu.SimulationSettings`` (for a plain ``mbs.SolveDynamic``, which is given the
    solver type separately) is refined as a copy: ``timeIntegration.numberOfSteps``
    times ``factor`` (the step, and the largest step of adaptive solvers, divided),
    ``minimumStepSize`` divided, and with ``automaticStepSize`` (explicit adaptive
    solvers; implicit ones ignore these) ``relativeTolerance``, ``absoluteTolerance`` and
    a given ``initialStepSize`` divided.  The copy is an
    :class:`exuclear.engine.steering.RefinedSimulationSettings`, which also carries
    ``factor`` to the clearance joints' own step control: each joint of a run given these
    settings divides its ``rate_limit`` by it for that run.
    """
    if check_positive("factor", factor) <= 1.0:
        raise ValueError(f"`factor` must exceed 1 (the reference must be tighter), got {factor}")
    if _exudyn_settings(settings):
        return _refined_exudyn_settings(settings, factor)
    if not isinstance(settings, SolverSettings):
        raise ValueError(f"`settings` must be a SolverSettings or an exu.SimulationSettings, got "
                         f"{type(settings).__name__}")
    if settings.automatic:
        raise ValueError("`step` is 'auto', which is chosen from the model: refine the settings with the step the "
                         "run chose, dataclasses.replace(settings, step=result.step)")
    step = settings.step / factor
    changes: dict[str, Any] = {"step": step, "min_step": min(settings.min_step, step)}
    if settings.explicit and settings.adaptive:
        changes.update(rtol=settings.rtol / factor, atol=settings.atol / factor)
    elif not settings.explicit and settings.impact_step is not None:
        changes["impact_step"] = settings.impact_step / factor
    elif settings.steered:  # the joints' step control is the accuracy of these steps
        changes["rate_limit"] = settings.rate_limit / factor
    return replace(settings, **changes)


def _exudyn_settings(settings: object) -> bool:
    """Whether ``settings`` is an ``exu.SimulationSettings`` (told by its shape: this
    module does not import exudyn)."""
    return hasattr(getattr(settings, "timeIntegration", None), "numberOfSteps")


def _refined_exudyn_settings(settings: Any, factor: float) -> Any:
    """A copy of the ``exu.SimulationSettings`` ``settings``, refined (:func:`refined_settings`)."""
    from .engine.steering import RefinedSimulationSettings  # exudyn is imported where its settings are given

    # a copy (the user's settings stay as they are) whose joints divide their rate_limit by factor
    tighter = RefinedSimulationSettings(settings, getattr(settings, "joint_refinement", 1.0) * factor)
    ti = tighter.timeIntegration
    ti.numberOfSteps = math.ceil(settings.timeIntegration.numberOfSteps * factor - 1e-9)
    ti.minimumStepSize = settings.timeIntegration.minimumStepSize / factor
    if ti.automaticStepSize:
        ti.relativeTolerance = settings.timeIntegration.relativeTolerance / factor
        ti.absoluteTolerance = settings.timeIntegration.absoluteTolerance / factor
        ti.initialStepSize = settings.timeIntegration.initialStepSize / factor  # 0: the solver's own choice
    return tighter


def _end_time(settings: Any) -> float:
    return float(settings.timeIntegration.endTime) if _exudyn_settings(settings) else settings.end_time


def _rule(settings: Any, factor: float) -> str:
    if _exudyn_settings(settings):
        tolerances = "rtol, atol, " if settings.timeIntegration.automaticStepSize else ""
        return f"{tolerances}step and minimum step / {factor:g}"
    if settings.explicit and settings.adaptive:
        return f"rtol, atol and largest step / {factor:g}"
    if settings.explicit:
        return f"step / {factor:g}"
    if settings.steered:
        return f"largest step / {factor:g} (the joints' step control unchanged)"
    return f"step{' and impact step' if settings.impact_step is not None else ''} / {factor:g}"


def _describe(settings: Any) -> str:
    if _exudyn_settings(settings):
        ti = settings.timeIntegration
        s = (f"exu.SimulationSettings, {ti.numberOfSteps:.0f} steps of {(ti.endTime - ti.startTime) / ti.numberOfSteps:.3g} s, "
             f"minimum step {ti.minimumStepSize:.3g} s")
        if ti.automaticStepSize:
            s += f", rtol {ti.relativeTolerance:.3g}, atol {ti.absoluteTolerance:.3g}"
        return s
    s = f"{settings.method}, step {settings.step:.3g} s"
    if settings.explicit and settings.adaptive:
        s += f" (largest), rtol {settings.rtol:.3g}, atol {settings.atol:.3g}"
    if settings.impact_step is not None:
        s += f", impact step {settings.impact_step:.3g} s"
    if settings.steered:
        s += " (largest; the joints control the steps)"
    return s


# =======================================================================================
# comparisons
# =======================================================================================

@dataclass(frozen=True)
class Statistic:
    """A quantity compared between the run and the reference; ``agrees`` by ``rule``."""

    name: str
    value: float
    reference: float
    agrees: bool
    rule: str


@dataclass(frozen=True)
class JointComparison:
    """One joint, the run against the reference (SI units; ``*_rel`` relative to the reference).

    Attributes
    ----------
    clearance : float
    time, de : ndarray
        The reference's output times within the compared span and ``|e - e_ref| / c`` there.
    horizon : float
        Time [s] until which ``de`` stays under the bound (the compared end if it never leaves it).
    path_agrees : bool
        ``de`` stays under the bound over the whole compared span.
    max_de, max_de_in_horizon : float
        Largest ``de`` over the span, and before the horizon.
    peak_force, peak_force_ref, peak_force_rel : float
        Largest contact force (normal and tangential) over the span [N].
    peak_force_horizon, peak_force_horizon_ref, peak_force_horizon_rel : float
        The same within the horizon.
    impacts, impacts_ref : int
        Contact onsets in the compared span.
    impacts_in_horizon, impacts_in_horizon_ref : int
        Onsets before the horizon.
    matched_in_horizon : int
        Reference impacts before the horizon with a match in the run.
    onset_shift_max, onset_velocity_diff_max, peak_force_diff_max : float
        Over the matched impacts before the horizon: largest ``|t - t_ref|`` [s],
        ``|v0 - v0_ref| / |v0_ref|`` and ``|F - F_ref| / F_ref``.
    impact_horizon : float
        Onset time [s] of the first impact that has no match within the tolerances
        (:data:`IMPACT_RTOL`), in either run; the compared end if all match.
    statistics : list of Statistic
        Impact count, distributions of peak force and onset velocity, spectrum of ``|e|``.
    """

    clearance: float
    time: np.ndarray
    de: np.ndarray
    horizon: float
    path_agrees: bool
    max_de: float
    max_de_in_horizon: float
    peak_force: float
    peak_force_ref: float
    peak_force_rel: float
    peak_force_horizon: float
    peak_force_horizon_ref: float
    peak_force_horizon_rel: float
    impacts: int
    impacts_ref: int
    impacts_in_horizon: int
    impacts_in_horizon_ref: int
    matched_in_horizon: int
    onset_shift_max: float
    onset_velocity_diff_max: float
    peak_force_diff_max: float
    impact_horizon: float
    statistics: list[Statistic]


@dataclass(frozen=True)
class SignalComparison:
    """A named signal: ``horizon`` [s] until which ``|y - y_ref|`` stays under the bound
    times the reference's range ``scale``; ``max_diff_rel`` the largest difference over
    the span relative to ``scale``; ``spectrum`` the spectral :class:`Statistic`."""

    name: str
    scale: float
    horizon: float
    path_agrees: bool
    max_diff_rel: float
    spectrum: Statistic


def _rel(value: float, reference: float) -> float:
    return (value - reference) / abs(reference) if reference != 0.0 else (0.0 if value == 0.0 else math.inf)


def _horizon(t: np.ndarray, d: np.ndarray, bound: float, end: float) -> float:
    """Time at which ``d`` first exceeds ``bound`` (interpolated between samples), or ``end``."""
    over = np.flatnonzero(d > bound)
    if over.size == 0:
        return end
    k = int(over[0])
    if k == 0:
        return float(t[0])
    f = (bound - d[k - 1]) / (d[k] - d[k - 1])
    return float(t[k - 1] + f * (t[k] - t[k - 1]))


def _span(t: np.ndarray, end: float) -> np.ndarray:
    return t <= end * (1.0 + 1e-12)


def _spectrum(name: str, t: np.ndarray, y: np.ndarray, t_ref: np.ndarray, y_ref: np.ndarray,
              end: float) -> Statistic:
    """Welch amplitude spectra of both signals, resampled on the reference's median output step."""
    rule = f"relative L2 distance < {SPECTRUM_TOL:g} and dominant lines within one bin"
    inside = _span(t_ref, end)
    steps = np.diff(t_ref[inside])
    dt = float(np.median(steps)) if steps.size else 0.0
    n = int(end / dt) + 1 if dt > 0.0 else 0
    if n < 4 * WELCH_SEGMENTS:
        return Statistic(f"spectrum of {name}", math.nan, math.nan, False, "too few samples for a spectrum")
    grid = np.arange(n) * dt
    f, sa = amplitude_spectrum(t, y, dt, window="hann", segments=WELCH_SEGMENTS, grid=grid)
    _, sb = amplitude_spectrum(t_ref, y_ref, dt, window="hann", segments=WELCH_SEGMENTS, grid=grid)
    norm = float(np.linalg.norm(sb))
    distance = float(np.linalg.norm(sa - sb)) / norm if norm > 0.0 else (0.0 if not sa.any() else math.inf)
    fa, fb = float(f[1:][np.argmax(sa[1:])]), float(f[1:][np.argmax(sb[1:])])
    agrees = distance < SPECTRUM_TOL and abs(fa - fb) <= (f[1] - f[0]) * (1.0 + 1e-9)
    return Statistic(f"spectrum of {name} (dominant line {fa:.4g} Hz vs {fb:.4g} Hz; distance)", distance, 0.0,
                     agrees, rule)


def _distribution(name: str, a: np.ndarray, b: np.ndarray) -> Statistic:
    from scipy.stats import ks_2samp

    if a.size < KS_MIN_SAMPLES or b.size < KS_MIN_SAMPLES:
        return Statistic(f"distribution of {name}", math.nan, math.nan, a.size == b.size,
                         f"fewer than {KS_MIN_SAMPLES} impacts: not compared as a distribution")
    p = float(ks_2samp(a, b).pvalue)
    return Statistic(f"distribution of {name} (median)", float(np.median(a)), float(np.median(b)), p >= KS_ALPHA,
                     f"two-sample Kolmogorov-Smirnov p = {p:.2g} >= {KS_ALPHA:g}")


def _match(run: list[ImpactRecord], ref: list[ImpactRecord]) -> list[tuple[int, int]]:
    """Mutual nearest neighbours by onset time: pairs (run index, reference index)."""
    if not run or not ref:
        return []
    ta, tb = np.array([r.onset_time for r in run]), np.array([r.onset_time for r in ref])
    nearest_b = np.abs(ta[:, None] - tb[None, :]).argmin(axis=1)
    nearest_a = np.abs(tb[:, None] - ta[None, :]).argmin(axis=1)
    return [(i, int(j)) for i, j in enumerate(nearest_b) if nearest_a[j] == i]


def _compare_joint(a: JointRecord, b: JointRecord, end: float, bound: float) -> JointComparison:
    c = b.clearance
    ta, tb = a.outputs["time"], b.outputs["time"]
    inside = _span(tb, end)
    t = tb[inside]
    dx = np.interp(t, ta, a.outputs["ecc_x"]) - b.outputs["ecc_x"][inside]
    dy = np.interp(t, ta, a.outputs["ecc_y"]) - b.outputs["ecc_y"][inside]
    de = np.hypot(dx, dy) / c
    horizon = _horizon(t, de, bound, end)
    before = t <= horizon

    def force(rec: JointRecord, until: float) -> float:
        keep = _span(rec.outputs["time"], until)
        f = np.hypot(rec.outputs["normal_force"][keep], rec.outputs["tangential_force"][keep])
        return float(f.max()) if f.size else 0.0

    fa, fb, fha, fhb = force(a, end), force(b, end), force(a, horizon), force(b, horizon)
    ia = [r for r in a.impacts if r.onset_time <= end]
    ib = [r for r in b.impacts if r.onset_time <= end]
    pairs = _match(ia, ib)
    force_floor = IMPACT_FORCE_FLOOR * max((r.peak_force for r in ib), default=0.0)
    good_ref, good_run = set(), set()
    shifts, dv0, dforce = [], [], []
    for i, j in pairs:
        ra, rb = ia[i], ib[j]
        shift = abs(ra.onset_time - rb.onset_time)
        v_diff = abs(ra.onset_velocity - rb.onset_velocity)
        f_diff = abs(ra.peak_force - rb.peak_force)
        window = max(rb.duration, bound * c / max(abs(rb.onset_velocity), IMPACT_V0_FLOOR))
        if (shift <= window
                and v_diff <= IMPACT_RTOL * abs(rb.onset_velocity) + IMPACT_V0_FLOOR
                and f_diff <= IMPACT_RTOL * rb.peak_force + force_floor):
            good_ref.add(j)
            good_run.add(i)
        if rb.onset_time <= horizon:
            shifts.append(shift)
            dv0.append(v_diff / max(abs(rb.onset_velocity), IMPACT_V0_FLOOR))
            dforce.append(f_diff / max(rb.peak_force, force_floor) if rb.peak_force > 0.0 else 0.0)
    bad = [r.onset_time for k, r in enumerate(ib) if k not in good_ref]
    bad += [r.onset_time for k, r in enumerate(ia) if k not in good_run]
    impact_horizon = min(bad, default=end)
    matched = sum(1 for _, j in pairs if ib[j].onset_time <= horizon)

    stats = []
    n, n_ref = len(ia), len(ib)
    spread = COUNT_SPREAD * math.sqrt(max(n_ref, 1))
    stats.append(Statistic("impact count", n, n_ref, abs(n - n_ref) <= spread,
                           f"|difference| <= {COUNT_SPREAD:g} sqrt(n_ref) = {spread:.1f}"))
    stats.append(_distribution("peak force [N]", np.array([r.peak_force for r in ia]),
                               np.array([r.peak_force for r in ib])))
    stats.append(_distribution("onset velocity [m/s]", np.array([r.onset_velocity for r in ia]),
                               np.array([r.onset_velocity for r in ib])))
    stats.append(_spectrum("|e|/c", ta, np.hypot(a.outputs["ecc_x"], a.outputs["ecc_y"]) / c, tb,
                           np.hypot(b.outputs["ecc_x"], b.outputs["ecc_y"]) / c, end))
    return JointComparison(
        clearance=c, time=t, de=de, horizon=horizon, path_agrees=bool(de.max() <= bound) if de.size else True,
        max_de=float(de.max()) if de.size else 0.0,
        max_de_in_horizon=float(de[before].max()) if before.any() else 0.0,
        peak_force=fa, peak_force_ref=fb, peak_force_rel=_rel(fa, fb),
        peak_force_horizon=fha, peak_force_horizon_ref=fhb, peak_force_horizon_rel=_rel(fha, fhb),
        impacts=n, impacts_ref=n_ref, impacts_in_horizon=sum(1 for r in ia if r.onset_time <= horizon),
        impacts_in_horizon_ref=sum(1 for r in ib if r.onset_time <= horizon), matched_in_horizon=matched,
        onset_shift_max=max(shifts, default=0.0), onset_velocity_diff_max=max(dv0, default=0.0),
        peak_force_diff_max=max(dforce, default=0.0), impact_horizon=float(impact_horizon), statistics=stats)


def _compare_signal(name: str, a: tuple[np.ndarray, np.ndarray], b: tuple[np.ndarray, np.ndarray], end: float,
                    bound: float) -> SignalComparison:
    (ta, ya), (tb, yb) = a, b
    inside = _span(tb, end)
    t, y_ref = tb[inside], yb[inside]
    scale = float(y_ref.max() - y_ref.min()) if y_ref.size else 0.0
    diff = np.abs(np.interp(t, ta, ya) - y_ref)
    rel = diff / scale if scale > 0.0 else np.where(diff > 0.0, math.inf, 0.0)
    horizon = _horizon(t, rel, bound, end)
    return SignalComparison(name, scale, horizon, bool(rel.max() <= bound) if rel.size else True,
                            float(rel.max()) if rel.size else 0.0, _spectrum(name, ta, ya, tb, yb, end))


# =======================================================================================
# the check and its result
# =======================================================================================

@dataclass(frozen=True)
class ConvergenceResult:
    """Outcome of :func:`check_convergence`; :meth:`report` says it in words.

    Attributes
    ----------
    settings, reference_settings : SolverSettings or exu.SimulationSettings
        The user's settings (with the step the run chose where they said
        ``step="auto"``) and the tighter ones (the reference).
    factor, bound : float
        The refinement factor and the path bound (fraction of the clearance).
    run, reference : RunRecord
        Both runs' records.
    end : float
        End of the compared span [s]: where both runs have results.
    joints : dict of str to JointComparison
    signals : dict of str to SignalComparison
    horizon : float
        The earliest joint path horizon [s].
    path_agrees : bool
        Every joint's path stays within the bound over the whole run, and both runs completed.
    signals_agree : bool
        Every named signal stays within the bound over the whole run.
    """

    settings: Any
    reference_settings: Any
    factor: float
    bound: float
    run: RunRecord
    reference: RunRecord
    end: float
    joints: dict[str, JointComparison]
    signals: dict[str, SignalComparison]

    @property
    def horizon(self) -> float:
        return min((j.horizon for j in self.joints.values()), default=self.end)

    @property
    def complete(self) -> bool:
        """Both runs reached the end time."""
        return self.run.success and self.reference.success

    @property
    def path_agrees(self) -> bool:
        """Every joint's path agrees over the whole run, and both runs completed (signals aside)."""
        return self.complete and all(j.path_agrees for j in self.joints.values())

    @property
    def signals_agree(self) -> bool:
        """Every named signal agrees within the bound over the whole run."""
        return all(s.path_agrees for s in self.signals.values())

    def statistics_agree(self) -> bool:
        """Every statistical comparison of every joint and signal agrees."""
        return (all(s.agrees for j in self.joints.values() for s in j.statistics)
                and all(s.spectrum.agrees for s in self.signals.values()))

    def report(self) -> str:
        """The comparison in words: what agrees, over which horizon, and what only statistically."""
        pct = 100.0
        lines = [f"Convergence check: {_describe(self.settings)}",
                 f"  against a tighter run ({_rule(self.settings, self.factor)}): {_describe(self.reference_settings)};",
                 "  the tighter run is the reference, its difference the error of the run."]
        for label, rec in (("run", self.run), ("reference", self.reference)):
            if not rec.success:
                lines.append(f"  The {label} STOPPED EARLY at t = {rec.time_reached:.6g} s: {rec.message}")
        lines.append(f"  Compared over 0 .. {self.end:.6g} s{'' if self.complete else ' (where both have results)'}.")
        for name, j in self.joints.items():
            lines.append(f"Joint {name} (clearance {j.clearance * 1e3:.4g} mm):")
            if j.path_agrees:
                lines.append(f"  path: AGREES over the whole run: max |de|/c = {j.max_de:.2g} <= {self.bound:g}")
            else:
                lines.append(f"  path: agrees until t = {j.horizon:.6g} s ({j.horizon / self.end * pct:.0f} % of the "
                             f"run; max |de|/c {j.max_de_in_horizon:.2g} <= {self.bound:g} until then), then "
                             f"parts: max |de|/c = {j.max_de:.3g} over the run")
            lines.append(f"  impacts one by one up to t = {j.horizon:.6g} s: {j.matched_in_horizon} of "
                         f"{j.impacts_in_horizon_ref} reference impacts matched ({j.impacts_in_horizon} in the run); "
                         f"onset shift <= {j.onset_shift_max * 1e6:.3g} us, onset velocity within "
                         f"{j.onset_velocity_diff_max * pct:.2g} %, peak force within {j.peak_force_diff_max * pct:.2g} %")
            seq = ("over the whole run" if j.impact_horizon >= self.end
                   else f"until t = {j.impact_horizon:.6g} s ({j.impact_horizon / self.end * pct:.0f} % of the run)")
            lines.append(f"  impact sequence (onset, v0 and peak force within {IMPACT_RTOL * pct:g} %) matches {seq}")
            lines.append(f"  peak force: {j.peak_force:.5g} N vs {j.peak_force_ref:.5g} N "
                         f"({j.peak_force_rel * pct:+.2g} %) over the run; {j.peak_force_horizon:.5g} N vs "
                         f"{j.peak_force_horizon_ref:.5g} N ({j.peak_force_horizon_rel * pct:+.2g} %) within the horizon")
            lines.append("  statistics over the run (run vs reference):")
            lines += [f"    {_statistic_line(s)}" for s in j.statistics]
        if self.signals:
            lines.append("Signals (bound: the same fraction of each signal's range in the reference):")
            for s in self.signals.values():
                when = ("AGREES over the whole run" if s.path_agrees
                        else f"agrees until t = {s.horizon:.6g} s ({s.horizon / self.end * pct:.0f} % of the run)")
                lines.append(f"  {s.name}: {when}; max difference {s.max_diff_rel * pct:.2g} % of its range "
                             f"{s.scale:.4g}")
                lines.append(f"    {_statistic_line(s.spectrum)}")
        lines.append("Verdict:")
        parted = [s for s in self.signals.values() if not s.path_agrees]
        if not self.joints:
            lines.append("  no clearance joint was recorded: " + (
                "every signal agrees over the whole run at this bound." if not parted and self.complete else
                "signals part: " + ", ".join(f"{s.name} at t = {s.horizon:.6g} s" for s in parted) + "."))
        elif self.path_agrees:
            lines.append("  the joints' paths agree over the whole run at this bound: the settings are converged "
                         "for this model and run length.")
            if parted:
                lines.append("  but not every signal: " + ", ".join(f"{s.name} only until t = {s.horizon:.6g} s"
                                                                    for s in parted) + ".")
        else:
            lines.append(f"  trust the joints' paths up to t = {self.horizon:.6g} s only; after it the runs follow "
                         "different paths.")
            if parted:
                lines.append("  signals: " + ", ".join(f"{s.name} until t = {s.horizon:.6g} s" for s in parted) + ".")
            held = [s.name.split(" (")[0] for j in self.joints.values() for s in j.statistics if s.agrees]
            held += [s.spectrum.name.split(" (")[0] for s in self.signals.values() if s.spectrum.agrees]
            failed = [s.name.split(" (")[0] for j in self.joints.values() for s in j.statistics if not s.agrees]
            failed += [s.spectrum.name.split(" (")[0] for s in self.signals.values() if not s.spectrum.agrees]
            if held:
                lines.append(f"  agree only statistically: {', '.join(held)}.")
            if failed:
                lines.append(f"  do not agree even statistically: {', '.join(failed)}; tighten the settings "
                             "(or run longer for statistics) before using them.")
        return "\n".join(lines)


def _statistic_line(s: Statistic) -> str:
    verdict = "agrees" if s.agrees else "DIFFERS"
    if math.isnan(s.value):
        return f"{s.name}: {s.rule}"
    if s.name.startswith("spectrum"):
        return f"{s.name} {s.value:.3g}: {verdict} ({s.rule})"
    return f"{s.name}: {s.value:.4g} vs {s.reference:.4g}: {verdict} ({s.rule})"


def _end(rec: RunRecord) -> float:
    ends = [rec.time_reached] + [float(j.outputs["time"][-1]) for j in rec.joints.values() if j.outputs["time"].size]
    ends += [float(t[-1]) for t, _ in rec.signals.values() if t.size]
    return min(ends)


def check_convergence(run: Callable[[Any], RunRecord], settings: Any, *,
                      factor: float = DEFAULT_FACTOR, bound: float = DEFAULT_BOUND,
                      baseline: RunRecord | None = None) -> ConvergenceResult:
    """Rerun a model at tighter settings and compare (module docstring).

    Parameters
    ----------
    run : callable
        ``run(settings) -> RunRecord``: builds the model, runs it with the given
        settings and returns its record.  Called once with ``settings`` (unless
        ``baseline`` is given), then once with the tighter settings.  Joints and signals
        are matched by name.  Either path:

        - ``settings`` a :class:`SolverSettings`: ``run`` calls
          ``result = exuclear.simulate(mbs, settings)`` and returns
          ``RunRecord.from_handles(result, {"B": joint})``;
        - ``settings`` an ``exu.SimulationSettings``: ``run`` calls
          ``mbs.SolveDynamic(settings, solverType=...)`` and returns
          ``RunRecord.from_mbs(mbs, {"B": joint})``.
    settings : SolverSettings or exu.SimulationSettings
        The user's settings (:func:`refined_settings` makes the tighter ones).  With
        ``step="auto"`` the first run chooses the step (its record's ``step``, from
        ``result.step``), and that step is refined.
    factor : float
        Refinement factor (> 1), see :func:`refined_settings`; default :data:`DEFAULT_FACTOR`.
    bound : float
        Path bound as a fraction of each joint's clearance (and of each signal's range),
        in (0, 1]; default :data:`DEFAULT_BOUND` (1 %).
    baseline : RunRecord, optional
        The record of a run at ``settings`` already made (saves one run).

    Returns
    -------
    ConvergenceResult
    """
    if not callable(run):
        raise ValueError(f"`run` must be a callable run(settings) -> RunRecord, got {type(run).__name__}")
    automatic = isinstance(settings, SolverSettings) and settings.automatic
    if not automatic:
        refined_settings(settings, factor)  # bad settings or factor fail before any run
    elif check_positive("factor", factor) <= 1.0:
        raise ValueError(f"`factor` must exceed 1 (the reference must be tighter), got {factor}")
    if not 0.0 < check_positive("bound", bound) <= 1.0:
        raise ValueError(f"`bound` must lie in (0, 1] (a fraction of the clearance), got {bound}")
    first = baseline if baseline is not None else run(settings)
    label = "baseline" if baseline is not None else "run(settings)"
    if not isinstance(first, RunRecord):
        raise ValueError(f"{label} must return a RunRecord (RunRecord.from_handles or .from_mbs), got "
                         f"{type(first).__name__}")
    if automatic:  # the step the model chose is the one refined
        if not math.isfinite(first.step):
            raise ValueError(f"`step` is 'auto' but {label}'s record does not say which step the run chose: build it "
                             "with RunRecord.from_handles(result, ...), whose result.step it is")
        settings = replace(settings, step=first.step, joint_steps=settings.steered)
    reference_settings = refined_settings(settings, factor)
    # the joints' own steps are refined with the solver's: exuclear.simulate sets their rate_limit
    # from the refined SolverSettings, a plain mbs.SolveDynamic's joints read the factor from
    # the refined exu.SimulationSettings (RefinedSimulationSettings)
    second = run(reference_settings)
    if not isinstance(second, RunRecord):
        raise ValueError(f"run(tighter settings) must return a RunRecord (RunRecord.from_handles or .from_mbs), got "
                         f"{type(second).__name__}")
    if set(first.joints) != set(second.joints) or set(first.signals) != set(second.signals):
        raise ValueError(f"the two runs recorded different joints or signals: {sorted(first.joints)} "
                         f"{sorted(first.signals)} and {sorted(second.joints)} {sorted(second.signals)}")
    end = min(_end(first), _end(second), _end_time(settings))
    joints = {k: _compare_joint(first.joints[k], second.joints[k], end, bound) for k in second.joints}
    signals = {k: _compare_signal(k, first.signals[k], second.signals[k], end, bound) for k in second.signals}
    return ConvergenceResult(settings, reference_settings, float(factor), float(bound), first, second, end,
                             joints, signals)
