"""The slider-crank rows: the library at one setting (:data:`.common.VARIANTS`) against
the reference of its case, and the library's onset bookkeeping against its own record."""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import NamedTuple

import numpy as np

import exuclear
from exuclear.models import slider_crank as sc_model
from exuclear.models.slider_crank import SliderCrankParams
from validation.cross_check.common import (
    EXUDYN_OUTPUT_STEP,
    ONSET_BOOKKEEPING_LIMIT,
    SC_CRITERIA,
    CrankCase,
    Variant,
    _relative,
    eccentricity_difference,
    onset_shift,
)
from validation.cross_check.reference import ReferenceCase
from validation.reference import slider_crank as sc_reference


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
