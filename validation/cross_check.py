"""Cross-check of the Exudyn path against the independent SciPy reference solver.

Source problems: examples 1 and 2 of X. Wang, G. Liu, S. Ma, R. Tong, "Effects of
restitution coefficient and material characteristics on dynamic response of planar
multi-body systems with revolute clearance joint", J. Mech. Sci. Technol. 31(2) (2017)
587-597, restated in ``docs/physics.md`` sections 6.1 (journal-bearing impact) and
5.2 (slider-crank with a clearance joint between rod and slider).

The library (:mod:`exuclear.models.journal_bearing`, :mod:`exuclear.models.slider_crank`, through the
Exudyn element) and the reference (:mod:`validation.reference`, which shares only the
contact and friction laws) run the same cases:

- journal-bearing: every law of :data:`exuclear.contact.CONTACT_LAWS` over cr = 0.3, 0.5, 0.7,
  0.9, 1.0 (a law that rejects a cr, such as the elastic Hertz law below 1, is skipped
  and listed); departure velocity, peak force, peak penetration, contact duration;
- slider-crank, two crank revolutions: cr 0.3 and 0.9, steel and aluminium journals in a
  steel bearing, friction "none" and "paper", each in both formulations at their default
  settings and at converged settings; eccentricity, peak contact force, slider
  acceleration, impact count and onset times, wall times.

Before comparing, the reference is checked twice: its convergence (the paper case at a
100 times tighter tolerance) and the sensitivity of each case to a 1e-9 m perturbation,
which limits point-by-point comparison to the horizon where the motion is not sensitive.
Every pass/fail criterion is listed with its reason in the report.

Run from the repository root::

    python -m validation.cross_check [--out DIR] [--quick] [--workers N]

Every run (library or reference) is a run of the study runner
(:func:`exuclear.study.run_study`), on all cores by default; the comparisons follow in
this process.

``--quick`` runs two laws and the first 0.03 s of two slider-crank cases (which holds
every impact of the paper's case).  Exit status 0 if every journal-bearing case, every
slider-crank case at converged settings, the reference's convergence and the library's
onset bookkeeping passed, 1 otherwise; the rows at default settings are reported
(FAILING where they fail) but do not set the status.
"""
from __future__ import annotations

import argparse
import functools
import json
import math
import os
import re
import string
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field, replace
from typing import NamedTuple

import numpy as np

import exuclear
from exuclear.models import journal_bearing as jb_model
from exuclear.models import slider_crank as sc_model
from exuclear.models.journal_bearing import JournalBearingParams
from exuclear.models.slider_crank import SliderCrankParams
from exuclear.study import run_id, run_study
from validation._cli import add_workers_option
from validation._tables import markdown_table, template_blocks, template_path, write_csv
from validation.reference import journal_bearing as jb_reference
from validation.reference import slider_crank as sc_reference

DEFAULT_OUT = os.path.join("results", "cross_check")

# -- cases ----------------------------------------------------------------------------

#: Restitution coefficients of the journal-bearing sweep (the paper's Figs. 4 and 5).
CR_SWEEP = (0.3, 0.5, 0.7, 0.9, 1.0)
#: Laws of the quick run.
QUICK_LAWS = ("wang-liu", "lankarani-nikravesh")
#: Slider-crank cases: restitution, journal material (bearing steel), friction.
SC_CRS = (0.3, 0.9)
SC_JOURNALS = ("steel", "aluminium")
SC_FRICTIONS = ("none", "paper")
SC_BEARING = "steel"
#: Crank revolutions of the full slider-crank runs (docs/physics.md section 6.2: at least two).
REVOLUTIONS = 2.0
#: Horizon of the quick slider-crank runs [s]: the paper case's impacts all begin before
#: 0.024 s (measured by the reference); after that the journal stays in contact.
QUICK_HORIZON = 0.03
#: The two slider-crank cases of the quick run: (cr, journal, friction).
QUICK_SC_CASES = ((0.9, "steel", "none"), (0.3, "aluminium", "paper"))

# -- reference settings ---------------------------------------------------------------

#: Reference integrator and tolerances: DOP853 at rtol 1e-10; atol 1e-13 meets
#: penetrations of ~1e-6 m with seven digits.
REF_METHOD, REF_RTOL, REF_ATOL = "DOP853", 1e-10, 1e-13
#: Tolerances of the reference's convergence check: 100 times tighter.
REF_TIGHT_RTOL, REF_TIGHT_ATOL = 1e-12, 1e-15
#: Case of the convergence check: the paper's own (cr 0.9, steel, no friction), a long
#: sequence of bounces.
CONVERGENCE_CASE = (0.9, "steel", "none")
#: Output interval of the reference [s]: the library's paths are compared at the library's
#: own accepted steps (up to 1e-4 s apart, too far apart to interpolate a free-flight
#: parabola between them), with the reference interpolated linearly between its samples;
#: over 2e-6 s that misses by at most (2e-6)^2 / 8 * 7e3 m/s^2 (a 2 kN impact on
#: 0.3 kg) = 3.5e-9 m = 3.5e-5 c.
GRID_STEP = 2e-6
#: Output interval on which the reference's peak force is read [s]: 1/400 of a ~40 us
#: impact (docs/physics.md section 8), so sampling lowers a sine-like peak by < (pi / 400)^2 / 2 = 3e-5.
PEAK_STEP = 1e-7
#: Perturbation of the sensitivity check [m]: the clearance is enlarged by this (the
#: journal radius shrinks by it), which shifts the journal's free path to every wall by
#: 1e-9 m = 1e-5 c; the reference has no argument for its initial state.
PERTURBATION = 1e-9

# -- library settings -----------------------------------------------------------------

#: Output interval of the library's slider-crank runs [s].  Exudyn records at the first
#: accepted step at or after each output instant, so this records every accepted step
#: longer than 1e-7 s: peaks and onsets are those of the solver's own steps, not of a
#: 1e-5 s sampling.
EXUDYN_OUTPUT_STEP = 1e-7


class Variant(NamedTuple):
    """Solver settings of one slider-crank row: changes to the formulation's default."""

    formulation: str
    kind: str                       # "default" or "converged"
    changes: tuple[tuple[str, float], ...]


#: The four rows per slider-crank case.  Converged settings: DOPRI5 at rtol 1e-9 (1000
#: times tighter than the default) and generalized-alpha at 1e-6 s (its error shrinks as
#: h^2: 1/100 of the default step's).
VARIANTS = (
    Variant("minimal", "default", ()),
    Variant("minimal", "converged", (("rtol", 1e-9), ("atol", 1e-12))),
    Variant("redundant", "default", ()),
    Variant("redundant", "converged", (("step", 1e-6), ("impact_step", None))),
)

# -- pass/fail criteria -----------------------------------------------------------------


class Criterion(NamedTuple):
    """A pass/fail bound: ``|value| <= limit``, with the reason for the limit."""

    key: str
    label: str
    limit: float
    reason: str


JB_CRITERIA = (
    Criterion("departure", "departure velocity, relative", 1e-6,
              "read in free flight, where it is constant: only integration error enters; DOPRI5 at rtol 1e-9 over "
              "~400 steps against DOP853 at rtol 1e-11 leaves ~1e-8, so 1e-6 has a wide margin"),
    Criterion("peak_force", "peak force, relative", 1e-4,
              "the library records at its accepted steps (at most 1e-7 s apart, output every 1e-8 s); a sine-like "
              "pulse of ~40 us sampled 1e-7 s off its peak is low by (pi 1e-7 / 40e-6)^2 / 2 = 3e-5; the reference "
              "refines its peak on the dense output; 1e-4 is three times the sampling bound"),
    Criterion("peak_penetration", "peak penetration, relative", 1e-4,
              "as the peak force (same sampling; penetration is flatter at its peak)"),
    Criterion("duration", "contact duration, relative", 1e-4,
              "the release instant is interpolated linearly between samples at most 1e-7 s apart on a ~40 us "
              "contact; curvature of the penetration there moves it by far less than 1e-4"),
)

#: Bound of the eccentricity difference, in units of the clearance c (reason below).
ECC_LIMIT = 0.01

SC_CRITERIA = (
    Criterion("ecc", "max abs(delta e) / c", ECC_LIMIT,
              "1 % of the clearance (1 um here): an orbit drawn in the clearance circle does not change visibly; "
              "the reference's own error is checked to stay below 1/100 of it"),
    Criterion("peak_force", "peak contact force, relative", 0.01,
              "1 %: the level at which the paper's force plots can be read; with F ~ v0^1.2 (Hertz scaling) it is "
              "0.8 % of the impact speed. Library: largest value at its accepted steps (recorded every step); "
              "reference: dense output sampled every 1e-7 s up to its peak, so sampling adds < 3e-5 there"),
    Criterion("onset_shift", "max onset shift [s]", 1e-5,
              "1e-5 s, the paper's largest step and output interval (0.03 deg of crank angle): an onset that moves "
              "less stays in the same output interval. Onsets of the library: its `onset_times`, interpolated "
              "linearly between accepted steps (checked against its recorded penetration, see onset bookkeeping)"),
)

#: Not a pass/fail criterion, reported only: the relative RMS of the slider-acceleration
#: difference (why: the report's ``acc_note``, :data:`REPORT_TEMPLATE`).

#: Onset bookkeeping: :attr:`SliderCrankResult.onset_times` must agree with the zero
#: crossings of the recorded penetration, which interpolate between the same accepted
#: states in the same way, to 1 % of the step across the crossing (round-off and
#: recording gaps below 1e-7 s stay far below that; a wrong time stamp shows as a whole step).
ONSET_BOOKKEEPING_LIMIT = 0.01

#: Convergence of the reference: its own eccentricity error must be 1/100 of the
#: library's bound, so that the comparison measures the library.
REF_CONVERGENCE_LIMIT = ECC_LIMIT / 100.0
#: Sensitivity: point-by-point comparison ends where the perturbed reference departs by
#: more than 1/10 of the eccentricity bound (it starts 1e-5 c apart).
SENSITIVITY_LIMIT = ECC_LIMIT / 10.0

# =======================================================================================
# journal-bearing
# =======================================================================================


@dataclass
class ImpactRow:
    """Library against reference on one journal-bearing impact."""

    law: str
    cr: float
    library: dict[str, float]
    reference: dict[str, float]
    errors: dict[str, float]
    wall_library: float
    wall_reference: float
    success: bool
    message: str

    @property
    def failed(self) -> list[str]:
        """Criteria (keys of :data:`JB_CRITERIA`) that the row misses."""
        return [c.key for c in JB_CRITERIA if not abs(self.errors[c.key]) <= c.limit]

    @property
    def passed(self) -> bool:
        return self.success and not self.failed


def impact_cases(laws: Sequence[str]) -> tuple[list[tuple[str, float]], list[str]]:
    """(law, cr) pairs of the sweep that each law accepts, and notes on those it rejects."""
    cases, skipped = [], []
    for law in laws:
        for cr in CR_SWEEP:
            try:
                JournalBearingParams.paper(law=law, cr=cr).joint()
            except ValueError as err:
                skipped.append(f"{law}, cr = {cr:g}: {err}")
                continue
            cases.append((law, cr))
    return cases, skipped


def _relative(a: float, b: float) -> float:
    return (a - b) / b


def compare_impact(law: str, cr: float) -> ImpactRow:
    """Run one impact in the library (its own settings) and in the reference (defaults)."""
    params = JournalBearingParams.paper(law=law, cr=cr)
    lib, _ = jb_model.run(params)
    ref = jb_reference.simulate(params)
    library = {"departure": lib.departure_velocity, "peak_force": lib.max_force,
               "peak_penetration": lib.max_penetration, "duration": lib.contact_duration}
    reference = {"departure": ref["departure_velocity"], "peak_force": ref["max_force"],
                 "peak_penetration": ref["max_penetration"], "duration": ref["contact_duration"]}
    errors = {k: _relative(library[k], reference[k]) for k in library}
    message = "; ".join(m for ok, m in ((lib.success, f"library: {lib.message}"),
                                        (ref["success"], f"reference: {ref['message']}")) if not ok)
    return ImpactRow(law, cr, library, reference, errors, lib.wall_time, ref["wall_time"],
                     lib.success and ref["success"], message)


# =======================================================================================
# slider-crank
# =======================================================================================


class CrankCase(NamedTuple):
    """One slider-crank case: restitution, journal material, friction law."""

    cr: float
    journal: str
    friction: str

    @property
    def label(self) -> str:
        return f"cr {self.cr:g}, {self.journal}, friction {self.friction}"

    def params(self, horizon: float | None, formulation: str = "minimal") -> SliderCrankParams:
        """The paper's slider-crank with this case; ``horizon`` [s] or :data:`REVOLUTIONS`."""
        p = SliderCrankParams.paper(cr=self.cr, journal_material=self.journal, bearing_material=SC_BEARING,
                                    friction=self.friction, formulation=formulation, revolutions=REVOLUTIONS)
        if horizon is None:
            return p
        return replace(p, revolutions=horizon * p.crank_speed / (2.0 * math.pi))


def crank_cases(quick: bool) -> list[CrankCase]:
    """The slider-crank cases of a full or quick run."""
    if quick:
        return [CrankCase(*c) for c in QUICK_SC_CASES]
    return [CrankCase(cr, j, f) for cr in SC_CRS for j in SC_JOURNALS for f in SC_FRICTIONS]


def reference_run(params: SliderCrankParams, rtol: float = REF_RTOL, atol: float = REF_ATOL) -> sc_reference.Result:
    """The reference on the comparison grid (:data:`GRID_STEP`)."""
    return sc_reference.simulate(params, method=REF_METHOD, rtol=rtol, atol=atol, output_step=GRID_STEP)


def reference_peak_force(params: SliderCrankParams, coarse: sc_reference.Result) -> float:
    """Peak contact force of the reference, read every :data:`PEAK_STEP` s.

    The reference is run again up to one grid interval past the peak of its
    :data:`GRID_STEP` output; the fine sampling thus covers every contact up to that peak.
    """
    cols = coarse.columns
    t_peak = float(cols["time"][int(np.argmax(cols["contact_force"]))])
    t_end = min(t_peak + GRID_STEP, params.end_time)
    fine = sc_reference.simulate(params, t_end=t_end, method=REF_METHOD, rtol=REF_RTOL, atol=REF_ATOL,
                                 output_step=PEAK_STEP)
    return max(float(fine.columns["contact_force"].max()), float(cols["contact_force"].max()))


def eccentricity_difference(a: dict[str, np.ndarray], b: dict[str, np.ndarray]) -> np.ndarray:
    """``|e_a - e_b|`` on ``b``'s times, ``a`` interpolated linearly onto them [m]."""
    t = b["time"]
    dx = np.interp(t, a["time"], a["ecc_x"]) - b["ecc_x"]
    dy = np.interp(t, a["time"], a["ecc_y"]) - b["ecc_y"]
    return np.hypot(dx, dy)


@dataclass
class Sensitivity:
    """The reference against itself with the clearance enlarged by :data:`PERTURBATION`.

    ``max_divergence`` is the largest ``|delta e| / c`` on the grid over the run;
    ``horizon`` [s] the last grid time before ``|delta e| / c`` first exceeds
    :data:`SENSITIVITY_LIMIT` (the run's end if never); ``impacts`` the onset counts of
    the base and the perturbed run.
    """

    case: CrankCase
    max_divergence: float
    horizon: float
    end_time: float
    impacts: tuple[int, int]

    @property
    def sensitive(self) -> bool:
        return self.horizon < self.end_time


def perturbed_params(params: SliderCrankParams) -> SliderCrankParams:
    """``params`` with the clearance enlarged by :data:`PERTURBATION`."""
    return replace(params, clearance=params.clearance + PERTURBATION)


def sensitivity(case: CrankCase, params: SliderCrankParams, base: sc_reference.Result,
                perturbed: sc_reference.Result) -> Sensitivity:
    """The horizon of point-by-point comparison, from the reference of ``params`` and
    that of :func:`perturbed_params`."""
    divergence = eccentricity_difference(perturbed.columns, base.columns) / params.clearance
    t = base.columns["time"]
    # a perturbed run that stopped early says nothing beyond its end: count that as divergence
    beyond = np.flatnonzero((divergence > SENSITIVITY_LIMIT) | (t > perturbed.columns["time"][-1]))
    horizon = float(t[beyond[0] - 1]) if len(beyond) else float(t[-1])
    return Sensitivity(case, float(divergence.max()), max(horizon, 0.0), float(t[-1]),
                       (base.n_impacts, perturbed.n_impacts))


@dataclass
class ReferenceCase:
    """Everything the rows of one case compare against."""

    case: CrankCase
    params: SliderCrankParams
    result: sc_reference.Result
    peak_force: float
    ideal_acc_rms: float
    sensitivity: Sensitivity | None

    @property
    def horizon(self) -> float:
        """End of the point-by-point comparison [s]."""
        s = self.sensitivity
        return s.horizon if s is not None else self.params.end_time


def reference_case(case: CrankCase, horizon: float | None, check_sensitivity: bool = True) -> ReferenceCase:
    """Run the reference of ``case`` (and, optionally, its perturbed twin)."""
    params = case.params(horizon)
    result = reference_run(params)
    twin = reference_run(perturbed_params(params)) if check_sensitivity else None
    return assemble_reference(case, params, result, reference_peak_force(params, result), twin)


def assemble_reference(case: CrankCase, params: SliderCrankParams, result: sc_reference.Result, peak_force: float,
                       twin: sc_reference.Result | None) -> ReferenceCase:
    """The :class:`ReferenceCase` of finished runs: the reference of ``params``, its peak
    force (:func:`reference_peak_force`) and its perturbed twin (None: no sensitivity)."""
    ideal = sc_reference.ideal_kinematics(params, result.columns["time"])
    sens = sensitivity(case, params, result, twin) if twin is not None else None
    return ReferenceCase(case, params, result, peak_force, float(np.sqrt(np.mean(ideal["slider_a"] ** 2))), sens)


def library_settings(params: SliderCrankParams, variant: Variant) -> exuclear.SolverSettings:
    """The formulation's default settings with the variant's changes, outputs every step."""
    return replace(sc_model.default_settings(params), output_step=EXUDYN_OUTPUT_STEP, **dict(variant.changes))


def describe_settings(s: exuclear.SolverSettings) -> str:
    """Short description of solver settings."""
    if s.adaptive:
        return f"{s.method} rtol {s.rtol:g}, atol {s.atol:g}, step <= {s.step:g} s"
    if s.impact_step is not None:
        return f"{s.method}, step {s.step:g} s, {s.impact_step:g} s from each contact onset"
    return f"{s.method}, fixed step {s.step:g} s"


def onset_shift(library: np.ndarray, reference: np.ndarray, horizon: float) -> tuple[float, str]:
    """Largest shift of paired onsets (in order) up to ``horizon`` [s], and a note.

    The note says when the counts differ; the shift then covers the first pairs only.
    """
    a, b = np.sort(library[library <= horizon]), np.sort(reference[reference <= horizon])
    n = min(len(a), len(b))
    shift = float(np.abs(a[:n] - b[:n]).max()) if n else (0.0 if len(a) == len(b) else math.nan)
    note = "" if len(a) == len(b) else f"onset counts differ ({len(a)} vs {len(b)}); shift over the first {n} pairs"
    return shift, note


class Crossings(NamedTuple):
    """Upward zero crossings of a recorded penetration: their times, interpolated linearly
    between the two records around each [s], and the intervals of those records [s]."""

    times: np.ndarray
    steps: np.ndarray


def recorded_onsets(cols: dict[str, np.ndarray]) -> Crossings:
    """The :class:`Crossings` of ``cols["penetration"]`` on ``cols["time"]``.

    With a record at every accepted step this is the onset rule of
    :class:`exuclear.history.ContactState`, on the recorded times.
    """
    t, d = cols["time"], cols["penetration"]
    k = np.flatnonzero((d[:-1] <= 0.0) & (d[1:] > 0.0))
    step = t[k + 1] - t[k]
    return Crossings(t[k] + step * (-d[k]) / (d[k + 1] - d[k]), step)


@dataclass
class OnsetBookkeeping:
    """``onset_times`` of a library run against the crossings of its recorded penetration.

    ``lag``: largest ``|onset_times - crossing|`` [s]; ``lag_steps``: the largest of those
    in steps across the crossings; NaN where the counts differ.
    """

    lag: float
    lag_steps: float
    counts: tuple[int, int]     # onset_times, crossings

    @property
    def passed(self) -> bool:
        return self.counts[0] == self.counts[1] and not self.lag_steps > ONSET_BOOKKEEPING_LIMIT


def onset_bookkeeping(reported: np.ndarray, crossings: Crossings) -> OnsetBookkeeping:
    """Compare the library's reported onsets with the recorded crossings."""
    counts = (len(reported), len(crossings.times))
    if counts[0] != counts[1]:
        return OnsetBookkeeping(math.nan, math.nan, counts)
    if not counts[0]:
        return OnsetBookkeeping(0.0, 0.0, counts)
    lag = np.abs(reported - crossings.times)
    return OnsetBookkeeping(float(lag.max()), float((lag / crossings.steps).max()), counts)


@dataclass
class CrankRow:
    """Library against reference on one slider-crank case at one setting.

    ``values`` holds the judged metrics (keys of :data:`SC_CRITERIA`) and ``acc``,
    reported only (see :data:`ACC_NOTE`).
    """

    case: CrankCase
    variant: Variant
    settings: str
    values: dict[str, float]
    impacts: tuple[int, int]        # library, reference
    peaks: tuple[float, float]      # library, reference [N]
    walls: tuple[float, float]      # library, reference [s]
    horizon: float
    bookkeeping: OnsetBookkeeping
    success: bool
    notes: list[str] = field(default_factory=list)

    @property
    def failed(self) -> list[str]:
        """Missed criteria: keys of :data:`SC_CRITERIA`, and ``"impacts"``."""
        missed = [c.key for c in SC_CRITERIA if not abs(self.values[c.key]) <= c.limit]
        return missed + (["impacts"] if self.impacts[0] != self.impacts[1] else [])

    @property
    def passed(self) -> bool:
        return self.success and not self.failed


def _point_metrics(lib: dict[str, np.ndarray], ref: ReferenceCase) -> tuple[float, float]:
    """max |delta e| / c at the library's output instants (the reference interpolated
    onto them) and the relative RMS of the slider-acceleration difference on the
    reference's grid, both up to the comparison horizon."""
    cols = ref.result.columns
    ecc = eccentricity_difference(cols, lib)[lib["time"] <= ref.horizon].max() / ref.params.clearance
    keep = (cols["time"] <= min(ref.horizon, float(lib["time"][-1])))
    d_acc = np.interp(cols["time"], lib["time"], lib["slider_a"]) - cols["slider_a"]
    return float(ecc), float(np.sqrt(np.mean(d_acc[keep] ** 2)) / ref.ideal_acc_rms)


def _run_notes(lib: sc_model.SliderCrankResult, ref: sc_reference.Result, *notes: str) -> list[str]:
    out = [n for n in notes if n]
    if not lib.success:
        out.append(f"library run failed: {lib.message}")
    if not ref.success:
        out.append(f"reference run failed: {ref.message}")
    return out


def library_run(params: SliderCrankParams, variant: Variant) -> sc_model.SliderCrankResult:
    """The library on ``params`` in ``variant``'s formulation, at its settings."""
    params = replace(params, formulation=variant.formulation)
    return sc_model.run(params, library_settings(params, variant))


def compare_crank(ref: ReferenceCase, variant: Variant, lib: sc_model.SliderCrankResult | None = None) -> CrankRow:
    """Compare the library on ``ref``'s case with ``variant``'s settings (``lib``, its
    :func:`library_run`; run here if not given) with the reference."""
    params = replace(ref.params, formulation=variant.formulation)
    settings = library_settings(params, variant)
    lib = lib if lib is not None else library_run(ref.params, variant)
    ecc, acc = _point_metrics(lib.columns, ref)
    shift, note = onset_shift(np.asarray(lib.onset_times), ref.result.onsets, ref.horizon)
    values = {"ecc": ecc, "peak_force": _relative(lib.peak_force, ref.peak_force), "onset_shift": shift, "acc": acc}
    return CrankRow(ref.case, variant, describe_settings(settings), values, (lib.impacts, ref.result.n_impacts),
                    (lib.peak_force, ref.peak_force), (lib.wall_time, ref.result.wall_time), ref.horizon,
                    onset_bookkeeping(np.asarray(lib.onset_times), recorded_onsets(lib.columns)),
                    lib.success and ref.result.success, _run_notes(lib, ref.result, note))


@dataclass
class Convergence:
    """The reference at :data:`REF_RTOL` against itself at :data:`REF_TIGHT_RTOL`."""

    case: CrankCase
    end_time: float
    ecc: float              # max |delta e| / c over the run
    onset_shift: float      # [s]
    impacts: tuple[int, int]
    walls: tuple[float, float]

    @property
    def passed(self) -> bool:
        return self.ecc <= REF_CONVERGENCE_LIMIT and self.impacts[0] == self.impacts[1]


def tight_reference_run(params: SliderCrankParams) -> sc_reference.Result:
    """The reference of ``params`` at the tolerances of the convergence check."""
    return reference_run(params, REF_TIGHT_RTOL, REF_TIGHT_ATOL)


def reference_convergence(ref: ReferenceCase, tight: sc_reference.Result | None = None) -> Convergence:
    """Measure the difference of ``ref``'s case at the tight tolerances (``tight``, its
    :func:`tight_reference_run`; run here if not given)."""
    tight = tight if tight is not None else tight_reference_run(ref.params)
    base = ref.result
    ecc = float(eccentricity_difference(tight.columns, base.columns).max() / ref.params.clearance)
    shift, _ = onset_shift(base.onsets, tight.onsets, ref.params.end_time)
    return Convergence(ref.case, ref.params.end_time, ecc, shift, (base.n_impacts, tight.n_impacts),
                       (base.wall_time, tight.wall_time))


# =======================================================================================
# the whole cross-check
# =======================================================================================


@dataclass
class CrossCheck:
    """All results of a run of the cross-check."""

    quick: bool
    impacts: list[ImpactRow]
    skipped: list[str]
    cranks: list[CrankRow]
    references: list[ReferenceCase]
    convergence: Convergence | None
    runtime: float = 0.0

    def failures(self) -> list[str]:
        """What failed among the checks that set the exit status: journal-bearing rows,
        slider-crank rows at converged settings, the reference's convergence and the
        library's onset bookkeeping (rows at default settings are reported only)."""
        out = [f"journal-bearing {r.law}, cr = {r.cr:g}: {', '.join(r.failed) or r.message}"
               for r in self.impacts if not r.passed]
        out += [f"slider-crank {r.case.label}, {r.variant.formulation} converged: "
                f"{', '.join(r.failed) or '; '.join(r.notes)}"
                for r in self.cranks if r.variant.kind == "converged" and not r.passed]
        if self.convergence is not None and not self.convergence.passed:
            out.append(f"reference not converged: max |delta e| / c = {self.convergence.ecc:.2e}")
        late = [r for r in self.cranks if not r.bookkeeping.passed]
        if late:
            out.append(f"onset bookkeeping: the library's onset_times miss the crossings of its recorded "
                       f"penetration in {len(late)} of {len(self.cranks)} slider-crank rows")
        return out


Progress = Callable[[str], None]


def _print(line: str) -> None:
    print(line, flush=True)


# =======================================================================================
# the runs, through the study runner
# =======================================================================================


def _crank_values(case: CrankCase, horizon: float | None) -> dict[str, object]:
    return {"cr": case.cr, "journal": case.journal, "friction": case.friction, "horizon": horizon}


def study_runs(jb_cases: Sequence[tuple[str, float]], cases: Sequence[CrankCase],
               horizon: float | None) -> list[dict[str, object]]:
    """The parameter sets of :func:`run_part` for a cross-check: the slider-crank runs
    first, the short journal-bearing comparisons last, so that no long run starts late."""
    runs: list[dict[str, object]] = []
    for case in cases:
        crank = _crank_values(case, horizon)
        runs += [{"part": "reference", **crank}, {"part": "twin", **crank}]
        if case == CrankCase(*CONVERGENCE_CASE):
            runs.append({"part": "tight", **crank})
    runs += [{"part": "library", **_crank_values(case, horizon), "variant": k}
             for case in cases for k in range(len(VARIANTS))]
    runs += [{"part": "impact", "law": law, "cr": cr} for law, cr in jb_cases]
    return runs


def _json(**values: object) -> str:
    """Scalars as JSON text, which reads back to the same floats (numpy scalars as Python's)."""
    return json.dumps(values, default=lambda v: v.item())


def _arrays(rec: dict[str, object], prefix: str) -> dict[str, np.ndarray]:
    return {k[len(prefix):]: v for k, v in rec.items() if k.startswith(prefix) and isinstance(v, np.ndarray)}


def _reference_summary(result: sc_reference.Result, **extra: float) -> dict[str, object]:
    scalars = _json(n_impacts=result.n_impacts, wall_time=result.wall_time, n_rhs=result.n_rhs,
                    success=result.success, message=result.message, **extra)
    return {"scalars": scalars, "onsets": np.asarray(result.onsets),
            **{f"columns.{k}": v for k, v in result.columns.items()},
            **{f"energy.{k}": v for k, v in result.energy.items()}}


def _reference_result(rec: dict[str, object]) -> sc_reference.Result:
    s = json.loads(rec["scalars"])
    return sc_reference.Result(columns=_arrays(rec, "columns."), onsets=rec["onsets"], n_impacts=s["n_impacts"],
                               wall_time=s["wall_time"], n_rhs=s["n_rhs"], success=s["success"],
                               message=s["message"], energy=_arrays(rec, "energy."))


def _library_summary(lib: sc_model.SliderCrankResult) -> dict[str, object]:
    scalars = _json(success=lib.success, message=lib.message, wall_time=lib.wall_time, build_time=lib.build_time,
                    steps=lib.steps, rejected=lib.rejected, notes=list(lib.notes))
    return {"scalars": scalars, "onset_times": np.asarray(lib.onset_times),
            **{f"columns.{k}": v for k, v in lib.columns.items()}}


def _library_result(rec: dict[str, object]) -> sc_model.SliderCrankResult:
    s = json.loads(rec["scalars"])
    return sc_model.SliderCrankResult(columns=_arrays(rec, "columns."), success=s["success"], message=s["message"],
                                      wall_time=s["wall_time"], build_time=s["build_time"], steps=s["steps"],
                                      rejected=s["rejected"], onset_times=rec["onset_times"], notes=tuple(s["notes"]))


def run_part(values: dict[str, object]) -> dict[str, object]:
    """Study function of one run of the cross-check, by ``values["part"]``.

    ``impact``: the journal-bearing comparison of ``law`` at ``cr``
    (:func:`compare_impact`).  The others belong to the slider-crank case (``cr``,
    ``journal``, ``friction``) over ``horizon`` [s] (None: :data:`REVOLUTIONS`):
    ``reference`` (with its peak force), ``twin`` (:func:`perturbed_params`), ``tight``
    (:func:`tight_reference_run`) and ``library`` (:func:`library_run` of the
    :data:`VARIANTS` row ``variant``).  Scalars come back as JSON text, arrays whole.
    """
    part = values["part"]
    if part == "impact":
        return {"row": _json(**asdict(compare_impact(values["law"], values["cr"])))}
    case = CrankCase(values["cr"], values["journal"], values["friction"])
    params = case.params(values["horizon"])
    if part == "reference":
        result = reference_run(params)
        return _reference_summary(result, peak_force=reference_peak_force(params, result))
    if part == "twin":
        return _reference_summary(reference_run(perturbed_params(params)))
    if part == "tight":
        return _reference_summary(tight_reference_run(params))
    if part == "library":
        return _library_summary(library_run(params, VARIANTS[values["variant"]]))
    raise ValueError(f"unknown part {part!r} of the cross-check")


def cross_check(quick: bool = False, progress: Progress = _print, workers: int | None = None) -> CrossCheck:
    """Run every comparison of a full (or quick) cross-check; see the module docstring.

    The runs go through the study runner on ``workers`` local processes (None: all
    cores; 1: in this process); the comparisons follow here, in the order of the report.
    """
    start = time.perf_counter()
    laws = QUICK_LAWS if quick else tuple(exuclear.contact.CONTACT_LAWS)
    cases = crank_cases(quick)
    horizon = QUICK_HORIZON if quick else None
    jb_cases, skipped = impact_cases(laws)
    runs = study_runs(jb_cases, cases, horizon)
    progress(f"running {len(runs)} runs of the library and the reference through the study runner")
    table = run_study(run_part, runs, workers=workers, progress=False, keep_arrays=True)
    done = {}
    for values, rec in zip(runs, table.to_dict("records"), strict=True):
        if not rec["success"]:  # a comparison that raised: the script is broken, not the case
            raise RuntimeError(f"run {values} raised {rec['message']}")
        done[run_id(values)] = rec

    def record(**values: object) -> dict[str, object]:
        return done[run_id(values)]

    total = len(jb_cases) + len(cases) * len(VARIANTS)
    impacts = []
    for k, (law, cr) in enumerate(jb_cases, start=1):
        row = ImpactRow(**json.loads(record(part="impact", law=law, cr=cr)["row"]))
        progress(f"case {k}/{total}: journal-bearing {law}, cr = {cr:g}: {'pass' if row.passed else 'FAILING'}")
        impacts.append(row)
    refs, cranks = [], []
    for case in cases:
        crank = _crank_values(case, horizon)
        progress(f"reference: slider-crank {case.label} (and its perturbed twin)")
        base = record(part="reference", **crank)
        ref = assemble_reference(case, case.params(horizon), _reference_result(base),
                                 json.loads(base["scalars"])["peak_force"],
                                 _reference_result(record(part="twin", **crank)))
        refs.append(ref)
        for index, variant in enumerate(VARIANTS):
            row = compare_crank(ref, variant, _library_result(record(part="library", variant=index, **crank)))
            progress(f"case {len(impacts) + len(cranks) + 1}/{total}: slider-crank {case.label}, "
                     f"{variant.formulation} {variant.kind} ({row.settings}): {'pass' if row.passed else 'FAILING'}")
            cranks.append(row)
    conv_ref = next((r for r in refs if r.case == CrankCase(*CONVERGENCE_CASE)), None)
    convergence = None
    if conv_ref is not None:
        progress(f"reference convergence: {conv_ref.case.label} at rtol {REF_TIGHT_RTOL:g}")
        tight = _reference_result(record(part="tight", **_crank_values(conv_ref.case, horizon)))
        convergence = reference_convergence(conv_ref, tight)
    return CrossCheck(quick, impacts, skipped, cranks, refs, convergence, time.perf_counter() - start)


# =======================================================================================
# report
# =======================================================================================




#: The report's prose: a Markdown template next to this script, with the sentences the
#: results pick (:func:`validation._tables.template_blocks`).
REPORT_TEMPLATE = template_path(__file__, "cross_check_report.md")


@functools.cache
def _blocks() -> dict[str, string.Template]:
    return dict(template_blocks(REPORT_TEMPLATE))


def criteria_md() -> str:
    """The pass/fail criteria with their reasons."""
    rows = [("journal-bearing", c.label, f"{c.limit:g}", c.reason) for c in JB_CRITERIA]
    rows += [("slider-crank", c.label, f"{c.limit:g}", c.reason) for c in SC_CRITERIA]
    rows.append(("slider-crank", "impact count", "equal",
                 "an impact more or less is a qualitative difference of the motion"))
    rows.append(("slider-crank", "onset bookkeeping: abs(onset_times - recorded crossings) / step",
                 f"{ONSET_BOOKKEEPING_LIMIT:g}",
                 "both interpolate linearly between the same accepted states, so they agree to round-off when the "
                 "time stamps are right; a wrong stamp shows as a whole step"))
    rows.append(("reference", "max abs(delta e) / c against rtol 1e-12", f"{REF_CONVERGENCE_LIMIT:g}",
                 "1/100 of the library's eccentricity bound, so that a difference measures the library"))
    rows.append(("reference", "sensitivity: max abs(delta e) / c after a 1e-9 m perturbation", f"{SENSITIVITY_LIMIT:g}",
                 "1/10 of the eccentricity bound: beyond it the reference itself is uncertain at the scale of the "
                 "bound, and point-by-point comparison stops there"))
    table = markdown_table(("scene", "criterion", "bound", "reason"), rows)
    return table + "\n\n" + _blocks()["acc_note"].substitute()


def _status(passed: bool, failed: Sequence[str]) -> str:
    return "pass" if passed else "**FAILING**" + (f" ({', '.join(failed)})" if failed else "")


def impacts_md(rows: Sequence[ImpactRow]) -> str:
    """Journal-bearing table: relative differences library - reference."""
    body = [(r.law, f"{r.cr:g}", f"{r.reference['departure']:.5f}",
             *(f"{r.errors[c.key]:+.1e}" for c in JB_CRITERIA),
             f"{r.wall_library:.2f}", f"{r.wall_reference:.3f}", _status(r.passed, r.failed)) for r in rows]
    header = ("law", "cr", "reference departure [m/s]", *(c.label for c in JB_CRITERIA), "wall library [s]",
              "wall reference [s]", "status")
    return markdown_table(header, body)


def _fmt_shift(value: float) -> str:
    return "-" if math.isnan(value) else f"{value * 1e6:.2f}"


def cranks_md(rows: Sequence[CrankRow]) -> str:
    """Slider-crank table, one row per case and setting."""
    body = []
    for r in rows:
        v = r.values
        body.append((r.case.label, r.variant.formulation, f"{r.variant.kind}: {r.settings}", f"{v['ecc']:.2e}",
                     f"{v['peak_force']:+.2%}", f"{r.impacts[0]} / {r.impacts[1]}", _fmt_shift(v["onset_shift"]),
                     f"{v['acc']:.1%}", f"{r.walls[0]:.2f}", f"{r.walls[1]:.2f}", _status(r.passed, r.failed)))
    header = ("case", "formulation", "settings", "max abs(de)/c", "peak force", "impacts lib / ref",
              "max onset shift [us]", "RMS(da)/RMS(a_ideal) (reported only)", "wall lib [s]", "wall ref [s]",
              "status")
    return markdown_table(header, body)


def bookkeeping_md(rows: Sequence[CrankRow]) -> str:
    """The onset bookkeeping check, one row per case and setting."""
    body = [(r.case.label, f"{r.variant.formulation} {r.variant.kind}", _fmt_shift(r.bookkeeping.lag),
             f"{r.bookkeeping.lag_steps:.2e}", f"{r.bookkeeping.counts[0]} / {r.bookkeeping.counts[1]}",
             _status(r.bookkeeping.passed, [])) for r in rows]
    header = ("case", "settings", "max abs(onset_times - crossings) [us]", "max abs(onset_times - crossings) / step",
              "counts onset_times / crossings", "status")
    return markdown_table(header, body)


def sensitivity_md(refs: Sequence[ReferenceCase]) -> str:
    """Sensitivity of each case to the perturbation."""
    rows = []
    for r in refs:
        s = r.sensitivity
        if s is None:
            continue
        rows.append((s.case.label, f"{s.max_divergence:.2e}", f"{s.max_divergence * r.params.clearance / PERTURBATION:.2g}",
                     f"{s.impacts[0]} / {s.impacts[1]}",
                     f"{s.horizon:.4f}" + (" (sensitive)" if s.sensitive else " (whole run)")))
    return markdown_table(("case", "max abs(de)/c", "amplification (max abs(de) / perturbation)", "impacts base / perturbed",
                   "point-by-point horizon [s]"), rows)


def convergence_md(conv: Convergence | None) -> str:
    """Sentence on the reference's convergence."""
    blocks = _blocks()
    if conv is None:
        return blocks["no_convergence"].substitute()
    return blocks["convergence"].substitute(
        case=conv.case.label, end_time=f"{conv.end_time:.4g}", ref_rtol=f"{REF_RTOL:g}", ref_atol=f"{REF_ATOL:g}",
        tight_rtol=f"{REF_TIGHT_RTOL:g}", tight_atol=f"{REF_TIGHT_ATOL:g}", ecc=f"{conv.ecc:.2e}",
        impacts=f"{conv.impacts[0]} / {conv.impacts[1]}", onset_shift=_fmt_shift(conv.onset_shift),
        walls=f"{conv.walls[0]:.1f} s / {conv.walls[1]:.1f} s", limit=f"{REF_CONVERGENCE_LIMIT:g}",
        status="pass" if conv.passed else "**FAILING**")


def _sensitivity_sentence(refs: Sequence[ReferenceCase]) -> str:
    sens = [r.sensitivity for r in refs if r.sensitivity is not None]
    if not sens:
        return ""
    if any(s.sensitive for s in sens):
        return _blocks()["sensitive"].substitute()
    return _blocks()["not_sensitive"].substitute(limit=f"{SENSITIVITY_LIMIT:g}")


def _converged_step() -> str:
    """The changes of the redundant formulation's converged row, e.g. ``step 1e-06``."""
    rows = [v for v in VARIANTS if v.formulation == "redundant" and v.kind == "converged"]
    return "; ".join(f"{name} {value:g}" for variant in rows for name, value in variant.changes if value is not None)


#: Missed criteria of rows at default settings, in the order the report explains them.
_DEFAULT_MISSES = ("ecc", "peak_force", "onset_shift", "impacts")


def _default_explanations(rows: Sequence[CrankRow]) -> list[str]:
    """What the failures of rows at default settings mean, one paragraph per missed criterion."""
    blocks = _blocks()
    missed = {k for r in rows for k in r.failed}
    text = [blocks["defaults"].substitute()] if rows else []
    text += [blocks[f"default_{key}"].substitute(converged_step=_converged_step())
             for key in _DEFAULT_MISSES if key in missed]
    return text


def failing_md(x: CrossCheck) -> str:
    """The failing rows and what they mean."""
    bad = [r for r in x.cranks if not r.passed] + [r for r in x.impacts if not r.passed]
    if not bad:
        return _blocks()["no_failures"].substitute()
    lines = []
    for r in bad:
        if isinstance(r, ImpactRow):
            lines.append(f"- journal-bearing {r.law}, cr = {r.cr:g}: {', '.join(r.failed)} {r.message}")
            continue
        missed = ", ".join(f"{k} = {r.values[k]:.3g}" if k in r.values else f"{k} {r.impacts[0]} vs {r.impacts[1]}"
                           for k in r.failed)
        lines.append(f"- {r.case.label}, {r.variant.formulation} {r.variant.kind} ({r.settings}): {missed}"
                     + (f"; {'; '.join(r.notes)}" if r.notes else ""))
    explain = _default_explanations([r for r in bad if isinstance(r, CrankRow) and r.variant.kind == "default"])
    if any(isinstance(r, CrankRow) and r.variant.kind == "converged" for r in bad) or \
            any(isinstance(r, ImpactRow) for r in bad):
        explain.append(_blocks()["unexplained"].substitute())
    return "\n".join(lines) + "\n\n" + "\n\n".join(explain)


def bookkeeping_sentence(rows: Sequence[CrankRow]) -> str:
    """What the bookkeeping table shows."""
    late = [r for r in rows if not r.bookkeeping.passed]
    if not late:
        return _blocks()["bookkeeping_pass"].substitute()
    return _blocks()["bookkeeping_fail"].substitute(late=len(late), rows=len(rows))


def skipped_md(skipped: Sequence[str]) -> str:
    """The journal-bearing cases a law rejected, as a list ("" if none)."""
    if not skipped:
        return ""
    return _blocks()["skipped"].substitute(items="\n".join(f"- {s}" for s in skipped))


def report_md(x: CrossCheck) -> str:
    """The Markdown report: :data:`REPORT_TEMPLATE` filled in with the results of ``x``."""
    text = _blocks()["report"].substitute(
        quick_option=" --quick" if x.quick else "", quick_label="quick run: " if x.quick else "",
        horizon=f"the first {QUICK_HORIZON:g} s" if x.quick else f"{REVOLUTIONS:g} crank revolutions",
        runtime=f"{x.runtime:.0f}", cores=os.cpu_count() or "?", criteria=criteria_md(),
        ref_method=REF_METHOD, ref_rtol=f"{REF_RTOL:g}", ref_atol=f"{REF_ATOL:g}", grid_step=f"{GRID_STEP:g}",
        output_step=f"{EXUDYN_OUTPUT_STEP:g}", peak_step=f"{PEAK_STEP:g}", convergence=convergence_md(x.convergence),
        perturbation=f"{PERTURBATION:g}", perturbation_c=f"{PERTURBATION / 1e-4:g}",
        sensitivity_limit=f"{SENSITIVITY_LIMIT:g}", sensitivity_table=sensitivity_md(x.references),
        sensitivity_sentence=_sensitivity_sentence(x.references), impacts_table=impacts_md(x.impacts),
        skipped=skipped_md(x.skipped), cranks_table=cranks_md(x.cranks), bookkeeping_table=bookkeeping_md(x.cranks),
        bookkeeping_sentence=bookkeeping_sentence(x.cranks), failing=failing_md(x))
    return re.sub(r"\n{3,}", "\n\n", text).strip("\n") + "\n"  # an empty field leaves one blank line


def write_report(path: str, x: CrossCheck) -> str:
    """Write the Markdown report (:func:`report_md`); returns ``path``."""
    with open(path, "w", encoding="utf-8") as f:
        f.write(report_md(x))
    return path


def impact_records(rows: Sequence[ImpactRow]) -> list[dict[str, object]]:
    """CSV records of the journal-bearing rows (SI units)."""
    out = []
    for r in rows:
        rec: dict[str, object] = {"law": r.law, "cr": r.cr}
        for key in r.library:
            rec[f"{key}_library"], rec[f"{key}_reference"], rec[f"{key}_rel_error"] = (
                r.library[key], r.reference[key], r.errors[key])
        rec.update(wall_library_s=r.wall_library, wall_reference_s=r.wall_reference, passed=r.passed)
        out.append(rec)
    return out


def crank_records(rows: Sequence[CrankRow]) -> list[dict[str, object]]:
    """CSV records of the slider-crank rows (SI units)."""
    return [{"cr": r.case.cr, "journal": r.case.journal, "friction": r.case.friction,
             "formulation": r.variant.formulation, "kind": r.variant.kind, "settings": r.settings,
             "horizon_s": r.horizon, "max_decc_over_c": r.values["ecc"], "peak_force_library_N": r.peaks[0],
             "peak_force_reference_N": r.peaks[1], "peak_force_rel_error": r.values["peak_force"],
             "acc_rms_rel": r.values["acc"], "impacts_library": r.impacts[0], "impacts_reference": r.impacts[1],
             "max_onset_shift_s": r.values["onset_shift"],
             "onset_times_max_lag_s": r.bookkeeping.lag, "onset_times_max_lag_steps": r.bookkeeping.lag_steps,
             "wall_library_s": r.walls[0], "wall_reference_s": r.walls[1], "passed": r.passed,
             "onset_bookkeeping_passed": r.bookkeeping.passed, "notes": "; ".join(r.notes)} for r in rows]




def write_outputs(x: CrossCheck, directory: str) -> list[str]:
    """The report and the two CSV tables; returns the paths."""
    os.makedirs(directory, exist_ok=True)
    paths = []
    if x.impacts:
        paths.append(write_csv(os.path.join(directory, "journal_bearing.csv"), impact_records(x.impacts)))
    if x.cranks:
        paths.append(write_csv(os.path.join(directory, "slider_crank.csv"), crank_records(x.cranks)))
    paths.append(write_report(os.path.join(directory, "cross_check.md"), x))
    return paths


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m validation.cross_check", description=__doc__.split("\n")[0])
    ap.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="directory of the report and CSV tables "
                    "(default %(default)s)")
    ap.add_argument("--quick", action="store_true",
                    help=f"two laws and the first {QUICK_HORIZON:g} s of two slider-crank cases")
    add_workers_option(ap)
    return ap


def main(argv: list[str] | None = None) -> int:
    """Run the cross-check and write the report; 1 if a case that must pass failed."""
    ap = _parser()
    args = ap.parse_args(argv)
    x = cross_check(quick=args.quick, workers=args.workers)
    for path in write_outputs(x, args.out):
        print(f"wrote {path}")
    print(f"total runtime {x.runtime:.1f} s")
    failures = x.failures()
    for failure in failures:
        print(f"error: FAILING: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
