"""Tables of the slider-crank report: one row per case (CSV and Markdown)."""
from __future__ import annotations

import math
from collections.abc import Sequence

from exuclear.models.slider_crank import SliderCrankParams
from validation._tables import markdown_table
from validation.slider_crank.cases import MATERIAL_CR, STARTUP, Sweep
from validation.slider_crank.diagnostics import Diagnostics, SweepRows
from validation.slider_crank.metrics import CaseMetrics, HistoryStats

# -- tables -------------------------------------------------------------------------



def _fmt(x: float, spec: str) -> str:
    return "-" if x is None or (isinstance(x, float) and math.isnan(x)) else format(x, spec)


def _case_record(column: str, value: str, m: CaseMetrics, failed: bool) -> dict[str, object]:
    """One table row of a sweep (SI units, micrometres for the position), in CSV order."""
    return {
        column: f"{value} (FAILED)" if failed else value,
        "peak contact force [N]": m.peak_force,
        "peak |a - ideal| [m/s2]": m.peak_da,
        "RMS a - ideal [m/s2]": m.rms_da,
        "impacts": m.impacts,
        "free flight": m.flight_fraction,
        "contact": m.contact_fraction,
        "band 150-350 Hz [m/s2]": m.band,
        "max |x - ideal| [um]": m.max_dx * 1e6,
        "max |v - ideal| [m/s]": m.max_dv,
        "RMS a - ideal, dead points [m/s2]": m.dead_rms,
        "RMS a - ideal, elsewhere [m/s2]": m.other_rms,
        "onsets after start-up": m.late_onsets,
        "last onset [deg]": m.last_onset,
        "contact after start-up": m.late_contact_fraction,
        "band, start-up replaced by ideal [m/s2]": m.band_late,
        "band, start-up only [m/s2]": m.band_startup,
        "band of a - ideal after start-up [m/s2]": m.band_dev,
        "peak of a - ideal spectrum [Hz]": m.mode_frequency,
        "max |v - ideal| after start-up [m/s]": m.late_max_dv,
        "dead-point ratio a": m.dead_ratio,
        "dead-point ratio force": m.force_ratio,
        "dead-point ratio moment": m.moment_ratio,
        "ratio a per dead point": " / ".join(f"{p:g}: {x:.2f}" for p, x in m.dead_each),
    }


#: Markdown formats of the sweep-table columns after the parameter column, and where
#: the first table (the key numbers) ends and the second (after the start-up) begins.
_CASE_FORMATS = (".0f", ".0f", ".1f", "d", ".3f", ".3f", ".2f", ".1f", ".3f", ".1f", ".1f",
                 "d", ".1f", ".3f", ".2f", ".2f", ".2f", ".0f", ".4f", ".2f", ".2f", ".2f", "s")
_FIRST_TABLE = 11


def _records(sweep: Sweep, rows: SweepRows) -> list[dict[str, object]]:
    return [_case_record(sweep.column, v.value, m, not r.success) for v, _, r, m in rows]


def sweep_table_md(sweep: Sweep, rows: SweepRows) -> str:
    """Markdown tables of one sweep's metrics: the key numbers, then those after the start-up."""
    records = _records(sweep, rows)
    header = list(records[0])
    cells = []
    for rec in records:
        values = list(rec.values())
        cells.append([values[0]] + [_fmt(x, f) for x, f in zip(values[1:], _CASE_FORMATS, strict=True)])
    cut = _FIRST_TABLE + 1
    first = markdown_table(header[:cut], [row[:cut] for row in cells])
    second = markdown_table(header[:1] + header[cut:], [row[:1] + row[cut:] for row in cells])
    return f"{first}\n\nAfter the start-up ({STARTUP:g}°) and dead-point ratios:\n\n{second}"




def _history_record(stem: str, value: str, h: HistoryStats) -> dict[str, object]:
    return {
        "sweep": stem, "case": value, "impacts": h.onsets, "v0 first [m/s]": h.v0_first,
        "v0 of the last contact [m/s]": h.v0_last, "last onset [deg]": h.last_onset,
        "D/v0 last over first": h.damping_gain, "zeta last contact (min)": h.zeta[0],
        "zeta last contact (max)": h.zeta[1], "normal vibration [Hz] (min)": h.normal_frequency[0],
        "normal vibration [Hz] (max)": h.normal_frequency[1], "true peak force [N]": h.true_peak,
        "true peak at [deg]": h.true_peak_angle, "first impact [us]": h.first_duration * 1e6,
        "shortest contact [us]": h.shortest * 1e6, "min F_N after start-up [N]": h.late_min_force,
        "at [deg]": h.late_min_angle, "min F_N near dead points [N]": h.dead_min_force,
        "contact near dead points": h.dead_contact, "stick fraction": h.stick_fraction,
        "stick near rod turning": h.stick_near_turning,
        "F_N vs ideal |F| (RMS rel.)": h.force_mismatch, "ecc - ideal F direction [deg]": h.angle_offset,
        "max abs(ecc - ideal F direction) [deg]": h.max_angle_offset,
    }


def _history_rows(diag: Diagnostics, sweeps: Sequence[Sweep]) -> list[tuple[str, str, HistoryStats]]:
    """``(case, friction, stats)`` of every recorded history, each parameter set once."""
    rows, seen = [], set()
    for sweep in sweeps:
        for variant in sweep.variants:
            h = diag.histories.get((sweep.stem, variant.value))
            params = SliderCrankParams.paper(**variant.changes)
            if h is None or params in seen:
                continue
            seen.add(params)
            name = variant.label if sweep.kind == "cr" else f"{variant.label}, cr = {MATERIAL_CR:g}"
            rows.append((name, sweep.friction, h))
    return rows


def history_table_md(diag: Diagnostics, sweeps: Sequence[Sweep]) -> str:
    """Markdown tables of the contact histories: onset speed and damping, then forces."""
    rows = _history_rows(diag, sweeps)
    damping = markdown_table(
        ["case", "friction", "impacts", "v0 first [m/s]", "v0 last contact [m/s]", "last onset [deg]",
         "D/v0: last / first", "zeta of last contact", "normal vibration [Hz]"],
        [[name, fr, h.onsets, f"{h.v0_first:.4f}", f"{h.v0_last:.2e}", f"{h.last_onset:.1f}", f"{h.damping_gain:.0f}",
          f"{h.zeta[0]:.2f}-{h.zeta[1]:.2f}", f"{h.normal_frequency[0]:.0f}-{h.normal_frequency[1]:.0f}"]
         for name, fr, h in rows])
    forces = markdown_table(
        ["case", "friction", "true peak force [N] at [deg]", "first impact [us]", "shortest contact [us]",
         "min F_N after start-up [N] at [deg]", "min F_N near dead points [N]", "contact near dead points",
         "stick fraction", "F_N vs ideal abs(F), RMS rel.", "ecc vs ideal F direction, mean / max [deg]"],
        [[name, fr, f"{h.true_peak:.0f} at {h.true_peak_angle:.3f}", f"{h.first_duration * 1e6:.0f}",
          f"{h.shortest * 1e6:.0f}", f"{h.late_min_force:.1f} at {h.late_min_angle:.0f}", f"{h.dead_min_force:.1f}",
          f"{h.dead_contact:.3f}", f"{h.stick_fraction:.3f}", f"{h.force_mismatch:.3f}",
          f"{h.angle_offset:+.1f} / {h.max_angle_offset:.1f}"] for name, fr, h in rows])
    return f"{damping}\n\n{forces}"


def _short_rows_md(rows: SweepRows, label: str) -> list[list[object]]:
    return [[label, v.label, m.impacts, m.late_onsets, f"{m.late_contact_fraction:.3f}", f"{m.peak_force:.0f}",
             f"{m.dead_rms:.1f}", f"{m.other_rms:.1f}", f"{m.dead_ratio:.2f}", f"{m.band:.2f}", f"{m.band_dev:.2f}",
             f"{m.mode_frequency:.0f}"] for v, _, _, m in rows]


_SHORT_HEADER = ["treatment", "case", "impacts", "onsets after start-up", "contact after start-up", "peak force [N]",
                 "RMS a - ideal, dead points", "elsewhere", "ratio", "band [m/s2]", "band of a - ideal", "peak [Hz]"]
