"""Report of the hard cases: Markdown tables, the floor's conclusion, CSV records."""
from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import replace

import exuclear
from exuclear.models import slider_crank as sc_model
from exuclear.models.journal_bearing import JournalBearingParams
from exuclear.models.slider_crank import SliderCrankParams
from validation import cross_check as cc
from validation._tables import markdown_table, write_csv
from validation.hard_cases.cases import LAW_NOTES, Row, Study
from validation.hard_cases.common import DROPPED_TIME, GRAVITY
from validation.hard_cases.floor import FLOOR_CR, FLOORS, LOADED_GRAVITY, FloorRow
from validation.hard_cases.plots import plot_resting, plot_stick_slip

# =======================================================================================
# report
# =======================================================================================




def cases_md(rows: Sequence[Row]) -> str:
    """The main table: case, criterion, measured value, pass/fail, wall time."""
    body = [(r.case.title, r.case.criterion, r.outcome.measured, "pass" if r.outcome.passed else "**FAILING**",
             f"{r.wall_time:.1f}") for r in rows]
    return markdown_table(("case", "criterion (fixed before the run)", "measured", "status", "wall [s]"), body)


def floor_md(rows: Sequence[FloorRow]) -> str:
    """The floor study table."""
    speeds = list(rows[0].restitution)
    header = ("v_min [m/s]", *(f"cr_eff at {v:g} m/s" for v in speeds), "resting: settled to 1 % / steps",
              "loaded resting (100 N): steps / settled to 1 %", "dropped: impacts / last [ms] / final error",
              "slider-crank: steps / impacts / peak force [N]", "wall [s]")
    body = []
    for r in rows:
        body.append((f"{r.v_min:g}", *(f"{r.restitution[v]:.4f}" for v in speeds),
                     f"{_ms(r.resting_settle)} / {r.resting_steps}",
                     f"{r.loaded_steps} / {_ms(r.loaded_settle)}",
                     f"{r.dropped_impacts} / {r.dropped_last * 1e3:.1f} / {r.dropped_error:+.1e}",
                     f"{r.crank_steps} / {r.crank_impacts} / {r.crank_peak:.0f}", f"{r.wall:.1f}"))
    return markdown_table(header, body)


def floor_conclusion(rows: Sequence[FloorRow]) -> str:
    """What the floor study shows, in numbers taken from ``rows``."""
    by = {r.v_min: r for r in rows}
    lo, mid, hi = by[FLOORS[0]], by[exuclear.contact.V_MIN_DEFAULT], by[FLOORS[-1]]
    slow = min(lo.restitution)
    lines = [
        f"- Impacts faster than the floor do not see it: at {max(lo.restitution):g} m/s the effective restitution is "
        f"{lo.restitution[max(lo.restitution)]:.4f} / {mid.restitution[max(mid.restitution)]:.4f} / "
        f"{hi.restitution[max(hi.restitution)]:.4f} for v_min = {lo.v_min:g} / {mid.v_min:g} / {hi.v_min:g} m/s.",
        f"- Impacts slower than the floor lose less energy than cr asks: at {slow:g} m/s the effective restitution is "
        f"{lo.restitution[slow]:.4f} / {mid.restitution[slow]:.4f} / {hi.restitution[slow]:.4f} (cr = {FLOOR_CR:g}): the "
        "damping term is scaled by v0 / v_min. Such impacts carry (v0 / 0.3 m/s)^2 of a paper impact's energy, "
        f"below {(mid.v_min / 0.3) ** 2:.2g} at the default floor.",
        f"- The dropped journal makes {lo.dropped_impacts} / {mid.dropped_impacts} / {hi.dropped_impacts} impacts, the "
        f"last at {lo.dropped_last * 1e3:.1f} / {mid.dropped_last * 1e3:.1f} / {hi.dropped_last * 1e3:.1f} ms of "
        f"{DROPPED_TIME * 1e3:.0f} ms; its final penetration is off delta_s by {lo.dropped_error:+.1e} / "
        f"{mid.dropped_error:+.1e} / {hi.dropped_error:+.1e}.",
        f"- The resting journal settles to 1 % of delta_s in {_ms(lo.resting_settle)} / "
        f"{_ms(mid.resting_settle)} / {_ms(hi.resting_settle)} ({lo.resting_steps} / "
        f"{mid.resting_steps} / {hi.resting_steps} steps).",
        f"- The loaded resting journal (100 N on 0.04 kg) needs {lo.loaded_steps} / {mid.loaded_steps} / "
        f"{hi.loaded_steps} DOPRI5 steps: the damping term of a contact begun at v0 < v_min has the rate "
        "D F / (v_min m), stiff for an explicit method once it exceeds ~3 / step (and, overdamped, it creeps to "
        f"delta_s: settled in {_ms(lo.loaded_settle)} / {_ms(mid.loaded_settle)} / {_ms(hi.loaded_settle)}).",
        f"- The paper's slider-crank does not depend on the floor: {lo.crank_steps} / {mid.crank_steps} / "
        f"{hi.crank_steps} steps, {lo.crank_impacts} / {mid.crank_impacts} / {hi.crank_impacts} impacts, peak force "
        f"{lo.crank_peak:.0f} / {mid.crank_peak:.0f} / {hi.crank_peak:.0f} N.",
    ]
    # the verdict as it was written from the numbers, and the facts it rests on: checked,
    # so that a change in the numbers does not leave a verdict standing that they no longer carry
    facts = {
        f"{hi.v_min:g} m/s keeps the dropped journal bouncing longer": hi.dropped_impacts > 1.5 * mid.dropped_impacts,
        f"{lo.v_min:g} m/s makes the loaded journal stiffer": lo.loaded_steps > 2 * mid.loaded_steps,
        f"{hi.v_min:g} m/s leaves the set-down journal ringing":
            math.isnan(hi.resting_settle) or hi.resting_settle > 5 * mid.resting_settle,
        "the paper's slider-crank does not depend on the floor":
            lo.crank_impacts == mid.crank_impacts and abs(lo.crank_peak / mid.crank_peak - 1) < 1e-3,
    }
    v = mid.v_min
    if all(facts.values()):
        lines += ["", (
            f"**The floor stays at {mid.v_min:g} m/s.** {hi.v_min:g} m/s is worse on every low-speed case: slow "
            f"impacts return almost all their energy (effective restitution {hi.restitution[v]:.4f} at {v:g} m/s, "
            f"cr = {FLOOR_CR:g}), the dropped journal is still bouncing late in the run ({hi.dropped_impacts} impacts, "
            f"the last at {hi.dropped_last * 1e3:.0f} ms), and the set-down journal rings for the whole run. "
            f"{lo.v_min:g} m/s damps slow impacts as cr asks down to {lo.v_min:g} m/s and settles the set-down "
            f"journal sooner, but a contact that begins below the floor then has a damping rate "
            f"{mid.v_min / lo.v_min:.0f} times higher: {lo.loaded_steps} instead of {mid.loaded_steps} DOPRI5 steps "
            f"for the loaded journal. Impacts slower than {mid.v_min:g} m/s carry less than {(v / 0.3) ** 2:.2g} of "
            "a paper impact's energy, so the better restitution there does not pay for that stiffness. No other "
            "treatment is proposed: none was shown to be better on these cases.")]
    else:
        lines += ["", "**Review the floor**: the verdict of this study (keep 1e-3 m/s) rested on facts that these "
                      "numbers no longer show: " + "; ".join(k for k, ok in facts.items() if not ok) + "."]
    return "\n".join(lines)


def _ms(seconds: float) -> str:
    return "not within the run" if math.isnan(seconds) else f"{seconds * 1e3:.2f} ms"


def case_records(rows: Sequence[Row]) -> list[dict[str, object]]:
    return [{"case": r.case.key, "title": r.case.title, "criterion": r.case.criterion, "measured": r.outcome.measured,
             "passed": r.outcome.passed, "wall_time_s": round(r.wall_time, 3)} for r in rows]


def floor_records(rows: Sequence[FloorRow]) -> list[dict[str, object]]:
    out = []
    for r in rows:
        rec: dict[str, object] = {"v_min": r.v_min}
        rec.update({f"cr_eff_at_{v:g}": e for v, e in r.restitution.items()})
        rec.update(resting_settle_s=r.resting_settle, resting_steps=r.resting_steps, loaded_steps=r.loaded_steps,
                   loaded_settle_s=r.loaded_settle, dropped_impacts=r.dropped_impacts, dropped_last_onset_s=r.dropped_last,
                   dropped_final_error=r.dropped_error, crank_steps=r.crank_steps, crank_impacts=r.crank_impacts,
                   crank_peak_force_N=r.crank_peak, wall_time_s=round(r.wall, 3))
        out.append(rec)
    return out


def _describe_defaults() -> str:
    """The slider-crank's default settings of both formulations, in words."""
    p = SliderCrankParams.paper()
    return "; ".join(f"{f}: {cc.describe_settings(sc_model.default_settings(replace(p, formulation=f)))}"
                     for f in sc_model.FORMULATIONS)


def write_report(path: str, study: Study, figures: Sequence[str]) -> str:
    failing = study.failures()
    parts = [
        "# Hard cases: numerical stability of the clearance joint\n",
        "Source problem: the clearance joint of `docs/physics.md` (Wang, Liu, Ma, Tong, J. Mech. Sci. Technol. "
        "31(2) (2017) 587-597): the journal-bearing scene (5.1) and the slider-crank (5.2), at the edges of their "
        f"use. Command: `python -m validation.hard_cases{' --quick' if study.quick else ''}`"
        f"{' (quick run: shorter runs)' if study.quick else ''}; total runtime {study.runtime:.0f} s. Wall times are "
        "single runs on a shared 2-core machine: indicative only.\n",
        "Defaults unless a case says otherwise: Wang-Liu law, steel on steel, no friction, the paper's dimensions; "
        f"slider-crank in minimal coordinates at `slider_crank.default_settings` ({_describe_defaults()}), outputs at every "
        "accepted step; energy audit as in the module docstring (drive work from the flywheel, elastic energy "
        "exact, dissipation by the trapezoid rule over the steps).\n",
        "Static penetration of the resting journal: K_eff(delta_s) delta_s^1.5 = m g with K_eff(delta) = "
        "(pi E* L / 2) sqrt(1 / (2 (c + delta))), solved by Brent's method: "
        + (f"delta_s = {study.rows[0].outcome.values['delta_s_m'] * 1e9:.4f} nm for m = "
           f"{JournalBearingParams.paper().mass:g} kg, g = {GRAVITY:g} m/s^2.\n"
           if study.rows and "delta_s_m" in study.rows[0].outcome.values else "see the module docstring.\n"),
        "## Cases\n",
        cases_md(study.rows) + "\n",
    ]
    if LAW_NOTES:
        parts.append("Not run at low restitution (the law rejects it): " + "; ".join(LAW_NOTES) + ".\n")
    parts.append("## Failing cases\n")
    parts.append("\n".join(f"- {r.case.title}: {r.outcome.measured}" for r in failing) + "\n" if failing
                 else "No case fails.\n")
    if study.floor:
        parts += [
            "## The floor v_min of the onset velocity\n",
            "Grazing and permanent contact make the onset velocity v0 tiny; the damping term D delta_dot / v0 is "
            f"then evaluated with max(v0, v_min) (docs/physics.md eq. (17)). Floors compared: {', '.join(f'{v:g}' for v in FLOORS)} m/s. "
            f"Effective restitution: Wang-Liu law, cr = {FLOOR_CR:g}, the paper's journal-bearing scene at the impact "
            "speeds shown. Resting: the journal set down at rest under gravity (as in the case above); loaded "
            f"resting: the same under {LOADED_GRAVITY:g} m/s^2 (100 N); dropped: released at the centre; slider-crank: "
            "the paper case (cr 0.9).\n",
            floor_md(study.floor) + "\n",
            floor_conclusion(study.floor) + "\n",
        ]
    if figures:
        parts.append("## Figures\n")
        parts += [f"![{os.path.basename(f)}]({os.path.basename(f)})\n" for f in figures]
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(parts))
    return path


def write_outputs(study: Study, directory: str) -> list[str]:
    """Report, CSV tables and figures; returns the paths."""
    os.makedirs(directory, exist_ok=True)
    figures = []
    if "resting" in study.figures:
        figures.append(plot_resting(study.figures, directory))
    if "stick_slip" in study.figures:
        figures.append(plot_stick_slip(study.figures, directory))
    paths = [write_csv(os.path.join(directory, "hard_cases.csv"), case_records(study.rows))]
    if study.floor:
        paths.append(write_csv(os.path.join(directory, "v_min_floor.csv"), floor_records(study.floor)))
    paths.append(write_report(os.path.join(directory, "hard_cases.md"), study, figures))
    return paths + figures
