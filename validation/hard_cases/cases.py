"""The case list and the study: every case and every floor through :func:`exuclear.study.run_study`."""
from __future__ import annotations

import json
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, fields
from typing import NamedTuple

import numpy as np

import exuclear
from exuclear import study as runner
from validation.hard_cases.common import (
    HIGH_RPM,
    LONG_REVOLUTIONS,
    LOW_CRS,
    MATERIAL_CR,
    POLYMER,
    QUICK_LONG_REVOLUTIONS,
    SETTLED_SHARE,
    STATIC_LIMIT,
    Case,
    Outcome,
)
from validation.hard_cases.crank import case_high_speed, case_stick_slip, case_three_joints, crank_case, stick_slip_params
from validation.hard_cases.floor import FLOORS, FloorRow, floor_row
from validation.hard_cases.journal import case_dropped, case_resting, case_slow_impact, low_restitution_case, low_restitution_laws


@dataclass
class Row:
    """A case after its run."""

    case: Case
    outcome: Outcome
    wall_time: float


@dataclass
class Study:
    """Everything a run of the study produced."""

    quick: bool
    rows: list[Row]
    floor: list[FloorRow]
    figures: dict[str, object] = field(default_factory=dict)
    runtime: float = 0.0

    def failures(self) -> list[Row]:
        return [r for r in self.rows if not r.outcome.passed]


# =======================================================================================
# the cases
# =======================================================================================

_LAWS, LAW_NOTES = low_restitution_laws()

#: Criterion shared by the slider-crank cases.
_AUDITS = ("energy audit of the minimal run within 1 % of the contact's gross work plus the flywheel's round-off, "
           "and of the same case in redundant coordinates within 1 %")
_CRANK = ("completes; all outputs finite; penetration below the joint's limit; " + _AUDITS + "; against the SciPy "
          "reference (library at rtol 1e-9, steps up to 0.03 deg of crank angle; first 20 ms, cut where a 1e-5 c "
          "perturbation of the reference exceeds 1e-3 c): max abs(de) <= 1 % of c, peak force within 1 %, same impacts")

CASES: tuple[Case, ...] = (
    Case("resting", "resting journal: set down on the bearing under gravity (Wang-Liu, cr 0.9)",
         f"settles to the analytic delta_s within {STATIC_LIMIT:g} (mean of the last 10 %); one contact onset, never "
         f"leaves the wall (no chatter); peak penetration <= the elastic step-load bound (no blow-up); finite; "
         f"audit within 1 % of gravity's work", case_resting),
    Case("dropped", "dropped journal: released at the bearing centre, falls c = 0.1 mm, bounces, comes to rest",
         f"completes; finite; no impact in the last {1 - SETTLED_SHARE:.0%} of the run (at rest); final penetration "
         f"within {STATIC_LIMIT:g} of delta_s; audit within 1 % of gravity's work", case_dropped),
    Case("slow_impact", "grazing impact at v0 = 1e-6 m/s (journal-bearing, Wang-Liu, cr 0.9)",
         "completes; the journal leaves the wall; finite; F_N >= 0; departure velocity within 1e-6 of the SciPy "
         "reference; effective restitution reported", case_slow_impact),
    *(Case(f"low_cr_{law}_{cr:g}", f"low restitution cr = {cr:g}, {law} (journal-bearing, 0.3 m/s)",
           "completes; leaves the wall; finite; F_N >= 0 at every step; departure velocity (1e-6), peak force, "
           "peak penetration and contact duration (1e-4) as the SciPy reference; effective restitution reported",
           low_restitution_case(law, cr)) for cr in LOW_CRS for law in _LAWS),
    Case("tiny_clearance", "slider-crank, clearance 1 um", _CRANK, crank_case({"clearance": 1e-6})),
    Case("large_clearance", "slider-crank, clearance 1 mm (warns: c > R_J / 10)", _CRANK,
         crank_case({"clearance": 1e-3})),
    Case("high_speed", f"slider-crank at {HIGH_RPM:g} rpm", _CRANK, case_high_speed),
    Case("long_run", f"slider-crank, {LONG_REVOLUTIONS:g} revolutions (paper case)",
         "completes; finite; penetration below the limit; " + _AUDITS + " (no reference: the motion is sensitive "
         "over long horizons)",
         crank_case({}, compare=False, revolutions=LONG_REVOLUTIONS, quick_revolutions=QUICK_LONG_REVOLUTIONS)),
    Case("long_run_friction", f"slider-crank, {LONG_REVOLUTIONS:g} revolutions with the paper's friction",
         "as the long run", crank_case({"friction": "paper"}, compare=False, revolutions=LONG_REVOLUTIONS,
                                       quick_revolutions=QUICK_LONG_REVOLUTIONS)),
    Case("aluminium", f"slider-crank, aluminium journal in a steel bearing (cr {MATERIAL_CR:g})", _CRANK,
         crank_case({"journal_material": "aluminium", "cr": MATERIAL_CR})),
    Case("polymer", f"slider-crank, polymer journal (E = 3 GPa, nu = 0.4) in a steel bearing (cr {MATERIAL_CR:g})",
         _CRANK, crank_case({"journal_material": POLYMER, "cr": MATERIAL_CR})),
    Case("stick_slip", "stick-slip: slider-crank with the modified Coulomb law (mu_s 0.3, mu_d 0.25)",
         "the slip velocity reverses in contact at least once per revolution; abs(F_T) <= mu_s F_N; " + _CRANK,
         case_stick_slip),
    Case("three_joints", "clearance at O, A and B (redundant coordinates, generalized-alpha at its default steps)",
         "completes; finite; penetrations below the limits; energy audit within 1 % of the contacts' gross work; slider "
         "within (1 + r / sqrt(l^2 - r^2)) * sum(c + max penetration) of the ideal mechanism (no reference covers "
         "three joints)", case_three_joints),
)

#: The cases by key.
_BY_KEY = {case.key: case for case in CASES}


class Trace(NamedTuple):
    """What the figures need of a journal run: its outputs and the static penetration."""

    out: dict[str, np.ndarray]
    delta_s: float


def run_part(values: dict[str, object]) -> dict[str, object]:
    """Study function of one part of the study at ``quick``: a case (``case``: its key;
    a case that raises is a failing case, shown as such) or the floor study at ``v_min``.
    Returns the outcome, or the floor's row, and the outputs the figures draw."""
    quick = bool(values["quick"])
    if "case" in values:
        try:
            outcome = _BY_KEY[values["case"]].run(quick)
        except Exception as err:
            outcome = Outcome(f"FAILED with {type(err).__name__}: {err}", False, {})
        summary: dict[str, object] = {"measured": outcome.measured, "passed": outcome.passed,
                                      "values": json.dumps(outcome.values)}
        if "stick_slip" in outcome.figures:
            _, out, _ = outcome.figures["stick_slip"]
            summary.update({f"stick_slip.{k}": np.asarray(v) for k, v in out.items()})
        return summary
    row, resting, dropped = floor_row(float(values["v_min"]), quick)
    summary = {f.name: getattr(row, f.name) for f in fields(FloorRow) if f.name not in ("v_min", "restitution")}
    summary.update(speeds=np.array(list(row.restitution)), restitution=np.array(list(row.restitution.values())))
    for name, run in (("resting", resting), ("dropped", dropped)):
        summary.update({f"{name}.time": run.out["time"], f"{name}.penetration": run.out["penetration"],
                        f"{name}.delta_s": run.delta_s})
    return summary


def _trace(rec: dict[str, object], name: str) -> Trace:
    return Trace({"time": rec[f"{name}.time"], "penetration": rec[f"{name}.penetration"]}, rec[f"{name}.delta_s"])


def _floor_row(v_min: float, rec: dict[str, object]) -> FloorRow:
    restitution = dict(zip(rec["speeds"].tolist(), rec["restitution"].tolist()))
    kept = {f.name: int(rec[f.name]) if f.type == "int" else float(rec[f.name]) for f in fields(FloorRow)
            if f.name not in ("v_min", "restitution")}
    return FloorRow(v_min=v_min, restitution=restitution, **kept)


def _print(line: str) -> None:
    print(line, flush=True)


def run_study(quick: bool = False, progress: Callable[[str], None] = _print,
              keys: Sequence[str] | None = None, workers: int | None = None) -> Study:
    """Run every case (or those in ``keys``) and the floor study through the study runner,
    on ``workers`` local processes (None: all cores; 1: in this process)."""
    start = time.perf_counter()
    cases = [c for c in CASES if keys is None or c.key in keys]
    parts = [{"case": c.key, "quick": quick} for c in cases]
    parts += [{"v_min": v, "quick": quick} for v in FLOORS] if keys is None else []
    progress(f"{len(cases)} cases{'' if keys else f' and {len(FLOORS)} floors'} ...")
    table = runner.run_study(run_part, parts, workers=workers, progress=False, keep_arrays=True)
    rows, floor, figures = [], [], {}
    for k, (part, rec) in enumerate(zip(parts, table.to_dict("records"), strict=True), 1):
        if "case" not in part:
            if not rec["success"]:
                raise RuntimeError(f"floor v_min = {part['v_min']:g} m/s failed: {rec['message']}")
            floor.append(_floor_row(part["v_min"], rec))
            figures.setdefault("resting", []).append((part["v_min"], _trace(rec, "resting")))
            if part["v_min"] == exuclear.contact.V_MIN_DEFAULT:
                figures["dropped"] = _trace(rec, "dropped")
            progress(f"floor v_min = {part['v_min']:g} m/s: done ({floor[-1].wall:.1f} s)")
            continue
        case = _BY_KEY[part["case"]]
        if rec["success"]:
            outcome = Outcome(rec["measured"], rec["passed"] is True or rec["passed"] == "True",
                              json.loads(rec["values"]))
        else:
            outcome = Outcome(f"FAILED with {rec['message']}", False, {})
        stick = {name[len("stick_slip."):]: v for name, v in rec.items()
                 if name.startswith("stick_slip.") and isinstance(v, np.ndarray)}
        if stick:
            params = stick_slip_params(quick)
            figures["stick_slip"] = (params, stick, params.joint.friction)
        rows.append(Row(case, outcome, float(rec["wall_time"])))
        progress(f"case {k}/{len(cases)}: {case.title}: {'pass' if outcome.passed else 'FAILING'} "
                 f"({rows[-1].wall_time:.1f} s)")
    return Study(quick, rows, floor, figures, time.perf_counter() - start)
