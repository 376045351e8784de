"""Hard cases: numerical stability of the clearance joint at the edges of its use.

Source problem: the revolute clearance joint of ``docs/physics.md`` (X. Wang, G. Liu,
S. Ma, R. Tong, J. Mech. Sci. Technol. 31(2) (2017) 587-597): its journal-bearing scene
(docs/physics.md section 6.1) and its slider-crank (docs/physics.md section 6.2), pushed to where integrators and
contact laws get into trouble (docs/physics.md section 8).  Every case states its pass criterion
before it runs (:data:`CASES`); the report is a table of case, criterion, measured
value, pass/fail and wall time, written to ``results/hard_cases/hard_cases.md`` with a
CSV copy and figures.

Cases:

- grazing and permanent contact: a journal resting on its bearing under gravity, one
  dropped onto it from the centre, and an impact at ``v0 = 1e-6 m/s``;
- low restitution: ``cr = 0.05`` and ``0.1`` with every law that accepts them;
- clearances of 1 micrometre and 1 mm; 5000 rpm; 20 crank revolutions;
- soft journals: aluminium, and a polymer with ``E = 3 GPa``, ``nu = 0.4``;
- stick-slip with the paper's modified Coulomb law (``mu_s = 0.3``, ``mu_d = 0.25``);
- clearance at all three revolute joints of the slider-crank (redundant coordinates,
  generalized-alpha).

Static penetration of the resting journal.  Under its weight ``W = m g`` the journal
settles where the elastic part of the law carries it (``delta_dot = 0``):

    K_eff(delta_s) * delta_s^1.5 = m g,   K_eff(delta) = (pi E* L / 2) sqrt(1 / (2 (c + delta)))

for the Wang-Liu law (docs/physics.md eqs. (9), (11)).  ``K_eff`` depends on ``delta``, so ``delta_s`` is
the root of ``F_el(delta) - m g`` on ``(0, c]`` (:func:`static_penetration`, Brent's
method; ``F_el`` rises monotonically there).  For the paper's journal (0.04 kg, steel,
L = 15 mm, c = 0.1 mm) it is 16.25 nm.  The largest penetration after the journal is set
down at ``delta = 0`` with no speed is bounded by the elastic step-load response,
``m g delta_max = E_el(delta_max)`` with ``E_el(delta) = int_0^delta F_el`` (damping only
lowers it): :func:`step_load_penetration`.

Energy audit.  Work put in (the drive, or gravity) = change of kinetic and potential
energy + energy absorbed by the contacts.  The absorbed energy is split into the
elastic energy stored at the end, a function of the state (exact), and the dissipated
energy ``int ((F_N - F_el) delta_dot + F_T v_T) dt``, integrated by the trapezoid rule
over every accepted step.  The drive work of the minimal slider-crank is the energy the
flywheel gives up, ``-J_fly (omega_end^2 - omega_0^2) / 2``, exact but blurred by the
round-off of the flywheel's 1.4e9 J (:func:`flywheel_roundoff`); each slider-crank case
is therefore audited again in redundant coordinates (no flywheel: the drive constraint's
multiplier), where the contact work is summed as generalized-alpha's own energy balance
does (:func:`_contact_energy`).  The residual is judged against the gross work of the
contact forces (:data:`AUDIT_LIMIT`).

The floor ``v_min`` of the onset velocity (docs/physics.md eq. (17)) is compared at 1e-4, 1e-3 (the
default) and 1e-2 m/s on the low-speed cases (:func:`floor_study`).

The modules, by role: :mod:`.common` (settings and criteria, each with its reason),
:mod:`.audit` (analytic values, energy audits), :mod:`.journal` and :mod:`.crank` (the
cases of each scene), :mod:`.floor` (the floor study), :mod:`.cases` (the case list; every
case and every floor is a run of :func:`exuclear.study.run_study`), :mod:`.report`,
:mod:`.plots`, :mod:`.cli`.

Run from the repository root::

    python -m validation.hard_cases [--out DIR] [--quick] [--workers N]

The cases run on local worker processes, on all cores unless ``--workers`` says
otherwise (1: in this process); the numbers do not depend on it.

``--quick`` shortens the runs (under a minute).  Exit status 0 if every case passes,
1 otherwise; failing cases are listed, never dropped.
"""
from validation import cross_check as cc
from validation.hard_cases.audit import flywheel_roundoff, static_penetration, step_load_penetration
from validation.hard_cases.cases import CASES, run_study
from validation.hard_cases.cli import main
from validation.hard_cases.common import (
    AUDIT_LIMIT,
    LOW_CR_STEP,
    MU_SLACK,
    SLOW_ATOL,
    SLOW_IMPACT_SPEED,
    SLOW_IMPACT_TIME,
    SLOW_RTOL,
    SLOW_STEP,
)
from validation.hard_cases.crank import run_crank, slip_statistics
from validation.hard_cases.journal import (
    JournalRun,
    compare_impact,
    final_error,
    low_restitution_laws,
    resting_params,
    run_journal,
)

__all__ = ["AUDIT_LIMIT", "CASES", "LOW_CR_STEP", "MU_SLACK", "SLOW_ATOL", "SLOW_IMPACT_SPEED", "SLOW_IMPACT_TIME",
           "SLOW_RTOL", "SLOW_STEP", "JournalRun", "cc", "compare_impact", "final_error", "flywheel_roundoff",
           "low_restitution_laws", "main", "resting_params", "run_crank", "run_journal", "run_study",
           "slip_statistics", "static_penetration", "step_load_penetration"]
