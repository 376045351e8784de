"""Settings and pass criteria of the hard cases (each with its reason), and the outcome of a case."""
from __future__ import annotations

import os
from collections.abc import Callable
from dataclasses import dataclass
from typing import NamedTuple

import exuclear
from exuclear.models import slider_crank as sc_model

DEFAULT_OUT = os.path.join("results", "hard_cases")

# -- scenes -----------------------------------------------------------------------------

#: Gravitational acceleration of the resting and dropped journal [m/s^2].
GRAVITY = 9.81
#: Restitution of the resting and dropped journal: the paper's slider-crank value and the
#: least damped of its sweep, so the slowest to settle.
RESTING_CR = 0.9
#: Simulated time of the resting journal [s]: its oscillation about delta_s (about
#: 4.8 kHz) decays as exp(-zeta omega t) with zeta ~ 0.03 at the default floor, by
#: 1e-7 in 20 ms.
RESTING_TIME = 0.02
#: Simulated time of the dropped journal [s]: 35 bounces, the last one at 80 ms (the
#: dropped journal's row of ``python -m validation.hard_cases`` reports them).
DROPPED_TIME = 0.12
#: Settings of the resting and dropped journal: DOPRI5 with steps up to 1e-5 s (20 per
#: period of the contact oscillation), rtol 1e-8; atol 1e-14 m is 6e-7 of delta_s.
RESTING_RTOL, RESTING_ATOL, RESTING_STEP = 1e-8, 1e-14, 1e-5
#: Outputs at every accepted step (Exudyn records at the first step at or after each
#: output instant), so the audits integrate over the solver's own steps.
EVERY_STEP = 1e-12
#: Impact speed of the grazing impact [m/s] (the issue) and its simulated time [s]: the
#: contact lasts about 0.5 ms (Hertz duration ~ v^-1/5: 40 us * (0.3 / 1e-6)^0.2).
SLOW_IMPACT_SPEED = 1e-6
SLOW_IMPACT_TIME = 1.5e-3
#: Library settings of the grazing impact: the peak penetration is only 0.15 nm, so the
#: absolute tolerance is 1e-17 m (1e-7 of it) and rtol 1e-13 (positions are ~c = 1e-4 m).
SLOW_RTOL, SLOW_ATOL, SLOW_STEP = 1e-13, 1e-17, 1e-6
#: Restitution coefficients of the low-restitution cases (the issue).
LOW_CRS = (0.05, 0.1)
#: Largest step of the low-restitution impacts [s].  The library reads its peak force
#: at accepted steps; at low cr the pulse is sharper than the sine-like one behind the
#: cross-check's 1e-4 bound (Flores at cr 0.05, D = 30: 2e-4 low at the 1e-7 s steps of
#: :func:`exuclear.models.journal_bearing.default_settings`), so the steps are 5 times shorter here,
#: which cuts the sampling error 25-fold.
LOW_CR_STEP = 2e-8
#: Polymer journal of the soft-material case (the issue): E = 3 GPa, nu = 0.4.
POLYMER = exuclear.Material(3e9, 0.4, "polymer")
#: Slider-crank cases run at the material sweep's restitution (docs/physics.md section 6.2: cr = 0.3).
MATERIAL_CR = 0.3
#: High crank speed [rpm] and the long run [revolutions] (the issue).
HIGH_RPM = 5000.0
LONG_REVOLUTIONS = 20.0
#: Revolutions of the slider-crank audit runs: docs/physics.md section 6.2 asks for at least two.
REVOLUTIONS = 2.0
#: Revolutions in the quick run.
QUICK_REVOLUTIONS = 0.5
QUICK_LONG_REVOLUTIONS = 3.0

# -- reference comparison -----------------------------------------------------------------

#: Horizon of the point-by-point comparison with the reference [s] (quick: half of it):
#: every case starts with its impacts there, and the perturbed reference shows whether
#: the motion is still insensitive (it is checked, not assumed).
COMPARE_TIME = 0.02
#: Relative perturbation of the clearance in the sensitivity check: 1e-5 c, as the
#: cross-check's 1e-9 m is for the paper's c = 0.1 mm, so the check scales with c.
PERTURBATION = 1e-5
#: Library settings of the comparison runs: the cross-check's converged DOPRI5 settings
#: (rtol 1e-9, atol 1e-12), with the largest step scaled to the crank speed: 1e-5 s at the
#: paper's 500 rpm (0.03 degrees of crank angle), 1e-6 s at 5000 rpm.  The contact-onset
#: velocity is interpolated within the step where contact begins, with an error of
#: order step^2 * acceleration (exuclear.history.ContactState), and accelerations grow as the
#: speed squared.  (At 5000 rpm over 20 ms a fixed 1e-5 s bound leaves max |de| = 2.7 % of
#: c, 1e-6 s 0.06 %: the 5000 rpm row of ``python -m validation.hard_cases`` reports the
#: former as ``ref_ecc_step_1e-5``.)
CONVERGED = (("rtol", 1e-9), ("atol", 1e-12))
CONVERGED_STEP_ANGLE = 1e-5 * sc_model.PAPER_CRANK_SPEED  # [rad]

# -- criteria -------------------------------------------------------------------------------

#: Energy audit bound, relative to the gross work of the contact forces,
#: ``int |F_N delta_dot + F_T v_T| dt`` (for the journal under gravity: the work of
#: gravity).  A force mapped wrongly (a lost moment arm, a sign) errs in proportion to
#: the work the contact forces do in and out, which the gross work measures; the part of
#: it that stays absorbed can be tiny (0.05 mJ at a 1 um clearance, against ~1e-6 of the
#: mechanism's 3 J of kinetic energy that the integrators' own energy errors reach).  The
#: dissipated part is a trapezoid rule over accepted steps, the only instants at which
#: Exudyn reports.
AUDIT_LIMIT = 0.01
#: Resting journal: relative error of the final penetration against delta_s.  Its
#: oscillation has decayed below 1e-7 and the tolerances allow ~6e-7 (see above); a load
#: or a stiffness off by 0.15 % moves delta_s by 0.1 %.
STATIC_LIMIT = 1e-3
#: Slack on the step-load bound of the largest penetration: the tolerance, 1e-14 m on
#: 30 nm, is far below it.
STEP_LOAD_SLACK = 1e-3
#: Share of the dropped journal's run at whose start it must have come to rest: the
#: last 20 % of the run without a new impact.
SETTLED_SHARE = 0.8
#: Friction coefficient bound: |F_T| <= mu_s F_N up to round-off.
MU_SLACK = 1e-9


class Outcome(NamedTuple):
    """Result of one case: the measured value (text), pass/fail, values for the CSV, and
    what a figure needs (``{name: data}``, see :func:`write_outputs`)."""

    measured: str
    passed: bool
    values: dict[str, float]
    figures: dict[str, object] = {}


@dataclass(frozen=True)
class Case:
    """A hard case: its title, its criterion (fixed before it runs) and how to run it."""

    key: str
    title: str
    criterion: str
    run: Callable[[bool], Outcome]
