"""The slider-crank reference: its runs on the comparison grid, its peak force, its
sensitivity to a perturbation of the clearance (the horizon of point-by-point
comparison) and its convergence against itself at tighter tolerances."""
from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from exuclear.models.slider_crank import SliderCrankParams
from validation.cross_check.common import (
    GRID_STEP,
    PEAK_STEP,
    PERTURBATION,
    REF_ATOL,
    REF_CONVERGENCE_LIMIT,
    REF_METHOD,
    REF_RTOL,
    REF_TIGHT_ATOL,
    REF_TIGHT_RTOL,
    SENSITIVITY_LIMIT,
    CrankCase,
    eccentricity_difference,
    onset_shift,
)
from validation.reference import slider_crank as sc_reference


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
