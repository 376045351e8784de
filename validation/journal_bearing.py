"""Journal-bearing impact: the paper's Figs. 4-7 and their tables.

Source problem: example 1 of X. Wang, G. Liu, S. Ma, R. Tong, "Effects of restitution
coefficient and material characteristics on dynamic response of planar multi-body
systems with revolute clearance joint", J. Mech. Sci. Technol. 31(2) (2017) 587-597,
restated in ``docs/physics.md`` section 6.1: a 0.04 kg journal starts touching a
fixed bearing (R_B = 10 mm, R_J = 9.9 mm) and moves into it at 0.3 m/s.

Every run goes through :func:`exuclear.models.journal_bearing.run`, as a run of the study runner
(:func:`exuclear.study.run_study`); this script only chooses the cases, draws the curves
and writes the tables:

- Fig. 4: cr sweep, Wang-Liu law; Fig. 5: the same with Lankarani-Nikravesh;
- Fig. 6: bearing length sweep at cr = 0.9 (Wang-Liu);
- Fig. 7: steel-steel against a copper journal in a steel bearing (Wang-Liu, cr = 0.9);
- the effective restitution (departure / impact speed) of every law in
  :data:`exuclear.contact.CONTACT_LAWS` for cr = 0.1, 0.2, ..., 1.0.

Run from the repository root::

    python -m validation.journal_bearing [--out DIR] [--workers N]

Exit status 0 if every run succeeded, 1 otherwise (the failed runs are listed).
"""
from __future__ import annotations

import argparse
import json
import os
import sys
import time
import warnings
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field

import numpy as np

import exuclear
from exuclear.models.figures import impact_curves
from exuclear.models.journal_bearing import ImpactResult, JournalBearingParams, run
from exuclear.study import run_study
from validation._cli import add_workers_option
from validation._tables import write_csv

DEFAULT_OUT = os.path.join("results", "journal_bearing")
#: Worker processes of the study runner by default: 1, the runner's serial path in this
#: process.  The 45 runs take about 0.05 s each (about 2 s in all), and a worker process
#: must start and import Exudyn, NumPy and SciPy before its first run: on 2 idle cores,
#: 2 workers took 2.5 s for the whole script against 2.7 s in this process, a gain that
#: a busy machine turns into a loss; in this process the README's first command also
#: needs no process start-up nor pickling of this module's functions.
DEFAULT_WORKERS = 1

#: Restitution coefficients of the paper's Figs. 4 and 5.
CR_SWEEP = (0.3, 0.5, 0.7, 0.9, 1.0)
#: Bearing lengths of the paper's Fig. 6 [m].
LENGTH_SWEEP = (10e-3, 15e-3, 30e-3, 40e-3)
#: Restitution coefficient of the paper's Figs. 6 and 7.
CR_FIGS_6_7 = 0.9
#: Grid of the effective-restitution table: cr = 0.1, 0.2, ..., 1.0 (rounded so that
#: the values equal the literals 0.3, 0.5, ... and the cached runs are shared).
CR_GRID = tuple(round(0.1 * k, 1) for k in range(1, 11))

#: Published departure velocities [m/s] of the Wang-Liu law, keyed by cr.
#: Source: the paper, section 5.1 (restated in docs/physics.md section 6.1).
PAPER_WANG_LIU_DEPARTURE = {0.3: 0.098, 0.5: 0.145, 0.9: 0.269}

M_TO_UM = 1e6  # penetrations are shown in micrometres, as in the paper's figures
S_TO_US = 1e6  # contact durations in microseconds


@dataclass(frozen=True)
class Variant:
    """One run of a case: the shown parameter value, a legend label, the changes
    to :meth:`JournalBearingParams.paper`."""

    value: str
    label: str
    changes: dict[str, object] = field(hash=False)


@dataclass(frozen=True)
class Case:
    """One figure of the paper: runs that differ in one parameter.

    Parameters
    ----------
    stem : str
        File-name stem of the figures and the CSV table.
    title : str
        Figure and table title.
    column : str
        Header of the case-parameter column.
    variants : tuple of Variant
        The runs, in legend order.
    """

    stem: str
    title: str
    column: str
    variants: tuple[Variant, ...]


#: A finished case: each variant with its summary and the joint's recorded outputs.
CaseRows = list[tuple[Variant, ImpactResult, dict[str, np.ndarray]]]


def _cr_sweep(law: str) -> tuple[Variant, ...]:
    return tuple(Variant(f"{cr:g}", f"cr = {cr:g}", {"law": law, "cr": cr}) for cr in CR_SWEEP)


def _length_sweep() -> tuple[Variant, ...]:
    return tuple(Variant(f"{L * 1e3:g}", f"L = {L * 1e3:g} mm", {"length": L, "cr": CR_FIGS_6_7})
                 for L in LENGTH_SWEEP)


def _material_pair() -> tuple[Variant, ...]:
    # Fig. 7's "steel-copper": the journal is copper and the bearing steel, as in the
    # paper's slider-crank material sweep (docs/physics.md section 6.2), where the bearing stays steel.
    return tuple(Variant(f"{j} / {b}", f"{j} journal, {b} bearing",
                         {"journal_material": j, "bearing_material": b, "cr": CR_FIGS_6_7})
                 for j, b in (("steel", "steel"), ("copper", "steel")))


def paper_cases() -> tuple[Case, ...]:
    """The four cases of the paper's Figs. 4-7 (docs/physics.md section 6.1)."""
    return (
        Case("fig4_wang_liu_cr", "Fig. 4: cr sweep, Wang-Liu law (L = 15 mm, steel-steel)", "cr",
             _cr_sweep("wang-liu")),
        Case("fig5_lankarani_nikravesh_cr", "Fig. 5: cr sweep, Lankarani-Nikravesh law (L = 15 mm, steel-steel)",
             "cr", _cr_sweep("lankarani-nikravesh")),
        Case("fig6_length", f"Fig. 6: bearing length, Wang-Liu law (cr = {CR_FIGS_6_7:g}, steel-steel)",
             "L [mm]", _length_sweep()),
        Case("fig7_material", f"Fig. 7: materials, Wang-Liu law (cr = {CR_FIGS_6_7:g}, L = 15 mm)",
             "journal / bearing", _material_pair()),
    )


def impact(values: dict[str, object]) -> dict[str, object]:
    """Study function of one impact: ``values`` holds the fields of a
    :class:`JournalBearingParams`.  Returns the summary (as JSON text, so that it comes
    back exactly) and the joint's recorded outputs (``out.<name>``, arrays)."""
    result, out = run(JournalBearingParams(**values))
    return {"result": json.dumps(asdict(result)), **{f"out.{name}": v for name, v in out.items()}}


class ImpactRunner:
    """Runs impacts through :func:`exuclear.study.run_study` and keeps every run.

    The cases share runs (Wang-Liu at cr = 0.9, L = 15 mm, steel-steel appears in
    Figs. 4, 6 and 7 and in the restitution table), so each parameter set runs once.
    :meth:`run` runs a list of parameter sets on ``workers`` local processes (None: all
    cores; 1: in this process); calling the runner returns a run, running it first if
    it is not there yet; :meth:`failures` lists the runs that did not succeed.
    """

    def __init__(self, workers: int | None = DEFAULT_WORKERS) -> None:
        self.workers = workers
        self.runs: dict[JournalBearingParams, tuple[ImpactResult, dict[str, np.ndarray]]] = {}

    def run(self, cases: Sequence[JournalBearingParams]) -> None:
        """Run the parameter sets of ``cases`` not run yet."""
        todo = [p for p in dict.fromkeys(cases) if p not in self.runs]
        if not todo:
            return
        table = run_study(impact, [asdict(p) for p in todo], workers=self.workers, progress=False,
                          keep_arrays=True)
        for params, rec in zip(todo, table.to_dict("records"), strict=True):
            if not rec["success"]:  # run() raised: not a failed impact but a broken case
                raise RuntimeError(f"run {describe(params)} raised {rec['message']}")
            out = {name[len("out."):]: v for name, v in rec.items()
                   if name.startswith("out.") and isinstance(v, np.ndarray)}
            self.runs[params] = (ImpactResult(**json.loads(rec["result"])), out)

    def __call__(self, params: JournalBearingParams) -> tuple[ImpactResult, dict[str, np.ndarray]]:
        self.run([params])
        return self.runs[params]

    def failures(self) -> list[tuple[str, ImpactResult]]:
        """``(description, result)`` of every run with ``success`` False."""
        return [(describe(params), result) for params, (result, _) in self.runs.items() if not result.success]


def describe(params: JournalBearingParams) -> str:
    """One-line description of a run's parameters."""
    return (f"{params.law}, cr = {params.cr:g}, L = {params.length * 1e3:g} mm, "
            f"{params.journal_material} journal / {params.bearing_material} bearing")


def case_rows(runner: ImpactRunner, case: Case, index: int, total: int) -> CaseRows:
    """The runs of every variant of ``case`` (run first if missing), printing one line per run."""
    print(f"case {index}/{total}: {case.title}", flush=True)
    rows = []
    for variant in case.variants:
        result, out = runner(JournalBearingParams.paper(**variant.changes))
        status = "" if result.success else f"  FAILED: {result.message}"
        print(f"  {variant.label}: departure {result.departure_velocity:.4f} m/s{status}", flush=True)
        rows.append((variant, result, out))
    return rows


def _case_record(case: Case, variant: Variant, result: ImpactResult) -> dict[str, object]:
    """One table row of a case, in the units of the paper's figures."""
    return {
        case.column: variant.value if result.success else f"{variant.value} (FAILED, see below)",
        "departure velocity [m/s]": result.departure_velocity,
        "peak force [N]": result.max_force,
        "peak penetration [um]": result.max_penetration * M_TO_UM,
        "contact duration [us]": result.contact_duration * S_TO_US,
        "Newton cr*v0 [m/s]": result.newton_departure_velocity,
    }


#: Markdown number formats of the case-table columns (after the parameter column).
_CASE_FORMATS = (".4f", ".1f", ".3f", ".2f", ".4f")


def case_table_md(case: Case, rows: CaseRows) -> str:
    """Markdown table of one case."""
    records = [_case_record(case, v, r) for v, r, _ in rows]
    header = list(records[0])
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for rec in records:
        values = list(rec.values())
        cells = [str(values[0])] + [format(x, f) for x, f in zip(values[1:], _CASE_FORMATS, strict=True)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)




def write_case_files(case: Case, rows: CaseRows, directory: str) -> list[str]:
    """The two figures and the CSV table of one case; returns the paths."""
    curves = [(v.label, out) for v, _, out in rows]
    paths = impact_curves(curves, directory, case.stem, title=case.title)
    records = [_case_record(case, v, r) for v, r, _ in rows]
    paths.append(write_csv(os.path.join(directory, f"{case.stem}.csv"), records))
    return paths


# -- effective restitution of every law ---------------------------------------------

@dataclass(frozen=True)
class RestitutionRow:
    """Effective restitution of one law over :data:`CR_GRID`; ``None`` where the law
    rejects that cr (``note`` says why); ``outside``: the cr at which the law leaves the
    range its source established it for (``outside_note`` says which range)."""

    law: str
    values: tuple[float | None, ...]
    note: str = ""
    outside: tuple[float, ...] = ()
    outside_note: str = ""


def _law_checks(params: JournalBearingParams) -> tuple[str, str]:
    """Why a law does not accept these parameters, and where they leave the range its
    source established it for (the text of its ``ValidityWarning``); ``''`` for neither.
    The table chose these values itself: it reports the range in its notes, not as a
    warning."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", exuclear.ValidityWarning)
        try:
            params.joint()
        except ValueError as err:
            return str(err), ""
    return "", "; ".join(str(w.message) for w in caught if issubclass(w.category, exuclear.ValidityWarning))


def restitution_row(runner: ImpactRunner, law: str) -> RestitutionRow:
    """Effective restitution of ``law`` on the paper's scene for every cr of the grid."""
    values, rejected, reasons, outside, ranges = [], [], [], [], []
    for cr in CR_GRID:
        params = JournalBearingParams.paper(law=law, cr=cr)
        reason, out_of_range = _law_checks(params)
        if reason:
            values.append(None)
            rejected.append(f"{cr:g}")
            reasons.append(reason)
            continue
        if out_of_range:
            outside.append(cr)
            ranges.append(out_of_range)
        values.append(runner(params)[0].effective_restitution)
    note = f"rejects cr = {', '.join(rejected)} (first message: {reasons[0]})" if rejected else ""
    return RestitutionRow(law, tuple(values), note, tuple(outside), ranges[0] if ranges else "")


def restitution_params() -> list[JournalBearingParams]:
    """The runs of the restitution table: every law at every cr of the grid it accepts."""
    grid = [JournalBearingParams.paper(law=law, cr=cr) for law in exuclear.contact.CONTACT_LAWS for cr in CR_GRID]
    return [params for params in grid if not _law_checks(params)[0]]


def restitution_sweep(runner: ImpactRunner) -> list[RestitutionRow]:
    """:func:`restitution_row` for every law of :data:`exuclear.contact.CONTACT_LAWS`."""
    rows = []
    for k, law in enumerate(exuclear.contact.CONTACT_LAWS, start=1):
        print(f"restitution {k}/{len(exuclear.contact.CONTACT_LAWS)}: {law}, cr = {CR_GRID[0]:g} ... {CR_GRID[-1]:g}",
              flush=True)
        rows.append(restitution_row(runner, law))
    return rows


def restitution_md(rows: list[RestitutionRow]) -> str:
    """Markdown table of the effective restitution, with notes for rejected cr and for cr
    outside the range a law's source established (cells marked ``*``)."""
    header = ["law"] + [f"cr = {cr:g}" for cr in CR_GRID]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    notes = []
    for row in rows:
        marks = ""
        if row.note:
            notes.append(f"[{len(notes) + 1}] {row.law} {row.note}; only the cr it accepts is run.")
            marks += f" [{len(notes)}]"
        if row.outside:
            notes.append(f"[{len(notes) + 1}] {row.law} at cr = {', '.join(f'{cr:g}' for cr in row.outside)} (marked "
                         f"*): outside its source's range ({row.outside_note}).")
            marks += f" [{len(notes)}]"
        cells = [row.law + marks] + ["-" if e is None else f"{e:.4f}{'*' if cr in row.outside else ''}"
                                     for cr, e in zip(CR_GRID, row.values, strict=True)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines + [""] + notes)


def restitution_records(rows: list[RestitutionRow]) -> list[dict[str, object]]:
    """CSV records of the effective restitution (empty cells where a law rejects cr)."""
    records = []
    for row in rows:
        cells = {f"cr={cr:g}": ("" if e is None else e) for cr, e in zip(CR_GRID, row.values, strict=True)}
        records.append({"law": row.law, **cells})
    return records


# -- report ---------------------------------------------------------------------------

def paper_comparison_md(runner: ImpactRunner) -> str:
    """Our Wang-Liu departure velocities beside the paper's published ones."""
    lines = ["| cr | paper [m/s] | exuclear [m/s] | relative difference |", "|---|---|---|---|"]
    for cr, published in PAPER_WANG_LIU_DEPARTURE.items():
        ours = runner(JournalBearingParams.paper(law="wang-liu", cr=cr))[0].departure_velocity
        lines.append(f"| {cr:g} | {published:.3f} | {ours:.4f} | {100.0 * (ours - published) / published:+.2f} % |")
    return "\n".join(lines)


def _intro_md(runner: ImpactRunner) -> str:
    p = JournalBearingParams.paper()
    return (
        "# Journal-bearing impact: the paper's Figs. 4-7\n\n"
        "Source problem: example 1 of Wang, Liu, Ma, Tong, J. Mech. Sci. Technol. 31(2) (2017) "
        "587-597 (docs/physics.md section 6.1). A journal of mass "
        f"{p.mass:g} kg starts touching a fixed bearing (R_B = {p.bearing_radius * 1e3:g} mm, "
        f"R_J = {p.journal_radius * 1e3:g} mm, c = {(p.bearing_radius - p.journal_radius) * 1e3:.1f} mm) "
        f"and moves into it at v0 = {p.impact_velocity:g} m/s; no gravity, friction or rotation. "
        "The paper publishes the departure velocities of its Wang-Liu law; ours, from the "
        "same formulas, are beside them:\n\n" + paper_comparison_md(runner) + "\n\n"
        "In Fig. 7, \"steel-copper\" is a copper journal in a steel bearing (the bearing stays "
        "steel, as in the paper's slider-crank material sweep). Penetrations are in micrometres, "
        "durations in microseconds; the contact duration runs from the onset to the instant the "
        "penetration returns to zero.\n"
    )


def _case_section_md(case: Case, rows: CaseRows) -> str:
    figures = "\n".join(f"![{case.title}: {kind}]({case.stem}_{kind}.png)" for kind in ("force", "rate"))
    return f"## {case.title}\n\n{case_table_md(case, rows)}\n\n{figures}\n"


def _failures_md(failures: list[tuple[str, ImpactResult]]) -> str:
    if not failures:
        return ""
    return "## Failed runs\n\n" + "\n".join(f"- {name}: {r.message}" for name, r in failures) + "\n"


def write_report(path: str, runner: ImpactRunner, cases: list[tuple[Case, CaseRows]],
                 restitution: list[RestitutionRow]) -> str:
    """Write the Markdown report; returns ``path``."""
    parts = [_intro_md(runner)]
    parts += [_case_section_md(case, rows) for case, rows in cases]
    parts.append("## Effective restitution (departure speed / impact speed) of every law\n\n"
                 "Scene of docs/physics.md section 6.1 (L = 15 mm, steel-steel, v0 = "
                 f"{JournalBearingParams.paper().impact_velocity:g} m/s); CSV: `effective_restitution.csv`.\n\n"
                 + restitution_md(restitution) + "\n")
    parts.append(_failures_md(runner.failures()))
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(p for p in parts if p))
    return path


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m validation.journal_bearing", description=__doc__.split("\n")[0])
    ap.add_argument("--out", metavar="DIR", default=DEFAULT_OUT,
                    help="directory of the figures and tables (default %(default)s)")
    add_workers_option(ap, DEFAULT_WORKERS, "default %(default)s: in this process; these short runs gain little "
                                            "from starting workers")
    return ap


def main(argv: list[str] | None = None) -> int:
    """Run all cases, write figures, CSV tables and the report; 1 if any run failed."""
    ap = _parser()
    args = ap.parse_args(argv)
    start = time.perf_counter()
    os.makedirs(args.out, exist_ok=True)
    runner = ImpactRunner(args.workers)
    cases = paper_cases()
    runs = [JournalBearingParams.paper(**v.changes) for case in cases for v in case.variants] + restitution_params()
    print(f"running {len(set(runs))} impacts (the cases of Figs. 4-7 and the restitution table) "
          f"on {args.workers} worker{'s' if args.workers > 1 else ''}", flush=True)
    runner.run(runs)
    done, paths = [], []
    for k, case in enumerate(cases, start=1):
        rows = case_rows(runner, case, k, len(cases))
        paths += write_case_files(case, rows, args.out)
        done.append((case, rows))
    restitution = restitution_sweep(runner)
    paths.append(write_csv(os.path.join(args.out, "effective_restitution.csv"), restitution_records(restitution)))
    paths.append(write_report(os.path.join(args.out, "journal_bearing.md"), runner, done, restitution))
    for path in paths:
        print(f"wrote {path}")
    print(f"{len(runner.runs)} runs, wall time {time.perf_counter() - start:.1f} s")
    failures = runner.failures()
    for name, result in failures:
        print(f"error: run failed: {name}: {result.message}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
