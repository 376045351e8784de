"""The cross-check's report and CSV tables: ``cross_check.md`` (the template
``report_template.md`` filled in), ``journal_bearing.csv`` and ``slider_crank.csv``."""
from __future__ import annotations

import functools
import math
import os
import re
import string
from collections.abc import Sequence

from validation._tables import markdown_table, template_blocks, template_path, write_csv
from validation.cross_check.common import (
    EXUDYN_OUTPUT_STEP,
    GRID_STEP,
    JB_CRITERIA,
    ONSET_BOOKKEEPING_LIMIT,
    PEAK_STEP,
    PERTURBATION,
    QUICK_HORIZON,
    REF_ATOL,
    REF_CONVERGENCE_LIMIT,
    REF_METHOD,
    REF_RTOL,
    REF_TIGHT_ATOL,
    REF_TIGHT_RTOL,
    REVOLUTIONS,
    SC_CRITERIA,
    SENSITIVITY_LIMIT,
    VARIANTS,
)
from validation.cross_check.crank import CrankRow
from validation.cross_check.journal import ImpactRow
from validation.cross_check.reference import Convergence, ReferenceCase
from validation.cross_check.runs import CrossCheck

#: The report's prose: a Markdown template next to this module, with the sentences the
#: results pick (:func:`validation._tables.template_blocks`).
REPORT_TEMPLATE = template_path(__file__, "report_template.md")


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
