"""The whole cross-check: every run of the library and the reference through the study
runner (:func:`exuclear.study.run_study`), then the comparisons in the order of the report."""
from __future__ import annotations

import json
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass

import numpy as np

import exuclear
from exuclear.models import slider_crank as sc_model
from exuclear.study import run_id, run_study
from validation.cross_check.common import CONVERGENCE_CASE, QUICK_HORIZON, QUICK_LAWS, REF_TIGHT_RTOL, VARIANTS, CrankCase, crank_cases
from validation.cross_check.crank import CrankRow, compare_crank, library_run
from validation.cross_check.journal import ImpactRow, compare_impact, impact_cases
from validation.cross_check.reference import (
    Convergence,
    ReferenceCase,
    assemble_reference,
    perturbed_params,
    reference_convergence,
    reference_peak_force,
    reference_run,
    tight_reference_run,
)
from validation.reference import slider_crank as sc_reference


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
