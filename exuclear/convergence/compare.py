"""What the convergence check compares between a run and its tighter run, and the rules by which they agree."""
from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..contact import V_MIN_DEFAULT
from ..history import ImpactRecord
from ..spectrum import amplitude_spectrum
from .records import JointRecord

#: Default path bound: 1 % of the clearance, the accuracy the defaults of the scenes are
#: chosen for (models/slider_crank.py, validation/cost/work_precision.py).
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


def _eccentricity(outputs: Mapping[str, Any]) -> list[str]:
    """The eccentricity's output columns: x and y, and z where the joint has it (a ball)."""
    return [k for k in ("ecc_x", "ecc_y", "ecc_z") if k in outputs]


def _interp(t: np.ndarray, ta: np.ndarray, ya: np.ndarray) -> np.ndarray:
    """``ya`` (times, or times x pairs of a translational joint) at the times ``t``."""
    if ya.ndim == 1:
        return np.interp(t, ta, ya)
    return np.column_stack([np.interp(t, ta, ya[:, k]) for k in range(ya.shape[1])])


def _path_signal(outputs: Mapping[str, Any]) -> np.ndarray:
    """The joint's path as one signal: ``|e|`` of a journal, a ball or a pin; a translational
    joint's slider centre across the guide (the mean of its corner-wall pairs' ``ecc_y``: the
    corners' offsets from the centre cancel; the spatial joint's, whose far and near walls'
    pairs hold z there, the mean of the centre's y and z)."""
    components = [np.asarray(outputs[k]) for k in _eccentricity(outputs)]
    if components[0].ndim == 2:
        return outputs["ecc_y"].mean(axis=1)
    return _length(components)


def _length(components: list[np.ndarray]) -> np.ndarray:
    """The length of a vector given by its components' arrays (hypot, component by component)."""
    out = np.hypot(components[0], components[1])
    for more in components[2:]:
        out = np.hypot(out, more)
    return out


def _compare_joint(a: JointRecord, b: JointRecord, end: float, bound: float) -> JointComparison:
    c = b.clearance
    ta, tb = a.outputs["time"], b.outputs["time"]
    inside = _span(tb, end)
    t = tb[inside]
    de = _length([_interp(t, ta, a.outputs[k]) - b.outputs[k][inside] for k in _eccentricity(b.outputs)]) / c
    if de.ndim == 2:  # a translational joint: its corners' largest departure
        de = de.max(axis=1)
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
    stats.append(_spectrum("|e|/c", ta, _path_signal(a.outputs) / c, tb, _path_signal(b.outputs) / c, end))
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
