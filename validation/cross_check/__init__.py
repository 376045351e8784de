"""Cross-check of the Exudyn path against the independent SciPy reference solver.

Source problems: examples 1 and 2 of X. Wang, G. Liu, S. Ma, R. Tong, "Effects of
restitution coefficient and material characteristics on dynamic response of planar
multi-body systems with revolute clearance joint", J. Mech. Sci. Technol. 31(2) (2017)
587-597, restated in ``docs/physics.md`` sections 6.1 (journal-bearing impact) and
6.2 (slider-crank with a clearance joint between rod and slider).

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

The modules, by role: :mod:`.common` (cases, settings and criteria, each with its
reason, and the shared metrics), :mod:`.journal` (the journal-bearing rows),
:mod:`.reference` (the slider-crank reference, its sensitivity and convergence),
:mod:`.crank` (the slider-crank rows and the onset bookkeeping), :mod:`.runs` (every run
through the study runner, then the comparisons), :mod:`.report` (the Markdown report
from ``report_template.md`` and the CSV tables), :mod:`.cli`.

``--quick`` runs two laws and the first 0.03 s of two slider-crank cases (which holds
every impact of the paper's case).  Exit status 0 if every journal-bearing case, every
slider-crank case at converged settings, the reference's convergence and the library's
onset bookkeeping passed, 1 otherwise; the rows at default settings are reported
(FAILING where they fail) but do not set the status.
"""
from validation.cross_check.cli import main
from validation.cross_check.common import (
    GRID_STEP,
    JB_CRITERIA,
    ONSET_BOOKKEEPING_LIMIT,
    QUICK_HORIZON,
    QUICK_LAWS,
    QUICK_SC_CASES,
    REF_RTOL,
    SC_CRITERIA,
    SENSITIVITY_LIMIT,
    VARIANTS,
    CrankCase,
    Variant,
    crank_cases,
    eccentricity_difference,
)
from validation.cross_check.crank import CrankRow, compare_crank, describe_settings, library_settings
from validation.cross_check.journal import compare_impact, impact_cases
from validation.cross_check.reference import reference_case, reference_peak_force, reference_run
from validation.cross_check.report import write_outputs
from validation.cross_check.runs import cross_check

__all__ = ["GRID_STEP", "JB_CRITERIA", "ONSET_BOOKKEEPING_LIMIT", "QUICK_HORIZON", "QUICK_LAWS", "QUICK_SC_CASES",
           "REF_RTOL", "SC_CRITERIA", "SENSITIVITY_LIMIT", "VARIANTS", "CrankCase", "CrankRow", "Variant",
           "compare_crank", "compare_impact", "crank_cases", "cross_check", "describe_settings",
           "eccentricity_difference", "impact_cases", "library_settings", "main", "reference_case",
           "reference_peak_force", "reference_run", "write_outputs"]
