"""The library (Exudyn element) against the independent SciPy reference.

Source problems: examples 1 and 2 of Wang, Liu, Ma, Tong, J. Mech. Sci. Technol. 31(2)
(2017) 587-597, restated in docs/physics.md sections 6.1 (journal-bearing impact) and 6.2 (slider-crank).
The comparisons and their tolerances are those of :mod:`validation.cross_check`; each
tolerance carries its reason there (``JB_CRITERIA``, ``SC_CRITERIA``).

Default run: every law on the journal-bearing impact, and the first impacts of two
slider-crank cases (the first 0.03 s) at converged settings.  Marked slow: the full
cross-check (two revolutions, 8 cases, both formulations).
"""
from __future__ import annotations

import pytest

import exuclear
from validation import cross_check as cc

JB_CASES, JB_SKIPPED = cc.impact_cases(tuple(exuclear.contact.CONTACT_LAWS))
CONVERGED = [v for v in cc.VARIANTS if v.kind == "converged"]
SC_CASES = [cc.CrankCase(*c) for c in cc.QUICK_SC_CASES]


def _silent(line: str) -> None:
    """Progress sink of the tests."""


# --------------------------------------------------------------------------------------
# journal-bearing impact, docs/physics.md section 6.1
# --------------------------------------------------------------------------------------
def test_every_law_is_run_over_the_sweep():
    # the sweep of the paper's Figs. 4-5; only the elastic Hertz law rejects cr < 1
    assert len(JB_CASES) == 5 * (len(exuclear.contact.CONTACT_LAWS) - 1) + 1
    assert ("hertz", 1.0) in JB_CASES
    assert all(note.startswith("hertz") for note in JB_SKIPPED)


@pytest.mark.parametrize("law, cr", JB_CASES)
def test_journal_bearing_agrees_with_reference(law, cr):
    row = cc.compare_impact(law, cr)
    assert row.success, row.message
    for c in cc.JB_CRITERIA:
        assert abs(row.errors[c.key]) <= c.limit, f"{c.label}: {row.errors[c.key]:.2e} beyond {c.limit:g}"


# --------------------------------------------------------------------------------------
# slider-crank first impacts, docs/physics.md section 6.2: t <= 0.03 s holds every impact of the paper
# case (cr 0.9, steel, no friction: 22 onsets, the last at 0.023 s)
# --------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def crank_rows() -> dict[tuple[cc.CrankCase, str], cc.CrankRow]:
    """Minimal (DOPRI5 rtol 1e-9) and redundant (h = 1e-6 s) rows of both quick cases."""
    rows = {}
    for case in SC_CASES:
        ref = cc.reference_case(case, cc.QUICK_HORIZON, check_sensitivity=False)
        for variant in CONVERGED:
            rows[case, variant.formulation] = cc.compare_crank(ref, variant)
    return rows


@pytest.mark.parametrize("formulation", [v.formulation for v in CONVERGED])
@pytest.mark.parametrize("case", SC_CASES, ids=[c.label for c in SC_CASES])
def test_slider_crank_first_impacts_agree_with_reference(crank_rows, case, formulation):
    row = crank_rows[case, formulation]
    assert row.success, row.notes
    assert row.impacts[0] == row.impacts[1] > 0
    limits = {c.key: c.limit for c in cc.SC_CRITERIA}
    assert row.values["ecc"] <= limits["ecc"]                      # 1 % of c
    assert abs(row.values["peak_force"]) <= limits["peak_force"]   # 1 %
    assert row.values["onset_shift"] <= limits["onset_shift"]      # 1e-5 s, the library's onset_times
    assert row.passed


@pytest.mark.parametrize("formulation", [v.formulation for v in CONVERGED])
@pytest.mark.parametrize("case", SC_CASES, ids=[c.label for c in SC_CASES])
def test_onset_times_match_recorded_crossings(crank_rows, case, formulation):
    # the reported onsets and the crossings of the recorded penetration interpolate
    # between the same accepted states: they agree to round-off if the time stamps are
    # right, and a stamp one step off shows as a whole step (bound: 1 % of the step)
    row = crank_rows[case, formulation]
    assert row.bookkeeping.counts[0] == row.bookkeeping.counts[1]
    assert row.bookkeeping.lag_steps <= cc.ONSET_BOOKKEEPING_LIMIT, f"lag {row.bookkeeping.lag_steps:.2f} steps"


# --------------------------------------------------------------------------------------
# the script
# --------------------------------------------------------------------------------------
def test_quick_run_writes_report_and_tables(tmp_path, capsys):
    status = cc.main(["--quick", "--out", str(tmp_path)])
    out, err = capsys.readouterr()
    n_cases = len(cc.impact_cases(cc.QUICK_LAWS)[0]) + len(cc.QUICK_SC_CASES) * len(cc.VARIANTS)
    assert f"case {n_cases}/{n_cases}:" in out
    assert status == (1 if "error: FAILING" in err else 0)
    report = (tmp_path / "cross_check.md").read_text(encoding="utf-8")
    for criterion in cc.JB_CRITERIA + cc.SC_CRITERIA:
        assert criterion.reason in report
    assert "noisy" in report and "sensitivity" in report
    jb_lines = (tmp_path / "journal_bearing.csv").read_text(encoding="utf-8").splitlines()
    sc_lines = (tmp_path / "slider_crank.csv").read_text(encoding="utf-8").splitlines()
    assert len(jb_lines) == 1 + len(cc.impact_cases(cc.QUICK_LAWS)[0])
    assert len(sc_lines) == 1 + len(cc.QUICK_SC_CASES) * len(cc.VARIANTS)


@pytest.mark.slow
def test_full_cross_check_converged_settings_pass(tmp_path):
    # every slider-crank case over two revolutions (about 10 minutes on 2 cores)
    x = cc.cross_check(quick=False, progress=_silent)
    cc.write_outputs(x, str(tmp_path))
    assert x.convergence is not None and x.convergence.passed
    assert [f"{r.law} {r.cr:g}" for r in x.impacts if not r.passed] == []
    converged = [r for r in x.cranks if r.variant.kind == "converged"]
    assert len(converged) == len(cc.crank_cases(quick=False)) * len(CONVERGED)
    assert [f"{r.case.label}, {r.variant.formulation}: {r.failed} {r.notes}" for r in converged if not r.passed] == []
