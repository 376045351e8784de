"""Convergence check of a user's model: run it again at tighter settings and say what agrees.

Clearance-joint motion can be chaotic: two runs at different steps follow the same path
for a while, then different impact sequences.  :func:`check_convergence` reruns a model
at a tighter step or tolerance (:func:`refined_settings`), takes the tighter run as the
reference, and reports

- the **path**: the time until which ``max |e - e_ref| / c`` stays under a bound
  (default 1 % of the clearance), per joint, and for named signals the time until which
  they stay within the bound times their range;
- the **impacts one by one** up to that horizon: impacts matched in time, their onset
  shifts, onset velocities and peak forces; and how long the impact sequence matches;
- the **peak forces** over the whole run and within the horizon;
- what can **only agree statistically** once the paths have parted: impact counts, the
  distributions of peak force and onset velocity (two-sample Kolmogorov-Smirnov test),
  and the spectra of the eccentricity and of the signals (Welch).  (The fraction of
  time in contact is left out: where the journal slides on the wall, its penetration
  hovers about zero and the in-contact flag flips with nanometres.)

The difference from the tighter run is taken as the error of the user's run: with a
method of order ``p``, the tighter run's own error is about ``factor**p`` times smaller.
A horizon shorter than the run is not by itself a fault of the settings: where the
motion is chaotic, any tighter run parts from a coarser one at some time, and only the
statistics can be trusted after it.

The model is given as a callable ``run(settings) -> RunRecord``, so that any Exudyn
model with clearance joints can be checked, on either path a model is run by:

- :func:`exuclear.simulate` with a :class:`~exuclear.SolverSettings`:
  ``RunRecord.from_handles(result, joints)`` builds the record from the result and the
  joints' handles; ``step="auto"`` is refined from the step the run chose (``result.step``);
- a plain ``mbs.SolveDynamic`` with an ``exu.SimulationSettings``: ``run`` takes one and
  returns ``RunRecord.from_mbs(mbs, joints)``; the tighter settings are a copy with
  ``timeIntegration.numberOfSteps`` multiplied and ``minimumStepSize`` (and, with
  ``automaticStepSize``, the tolerances and ``initialStepSize``) divided by the factor.

This package never imports exudyn itself (its tighter Exudyn settings come from
:mod:`exuclear.engine.steering`, imported where a user hands Exudyn settings) and never plots.
"""
from .check import ConvergenceResult, check_convergence
from .compare import (
    COUNT_SPREAD,
    DEFAULT_BOUND,
    IMPACT_FORCE_FLOOR,
    IMPACT_RTOL,
    IMPACT_V0_FLOOR,
    KS_ALPHA,
    KS_MIN_SAMPLES,
    SPECTRUM_TOL,
    WELCH_SEGMENTS,
    JointComparison,
    SignalComparison,
    Statistic,
)
from .records import JointRecord, RunRecord
from .refine import DEFAULT_FACTOR, refined_settings

__all__ = ["COUNT_SPREAD", "DEFAULT_BOUND", "DEFAULT_FACTOR", "IMPACT_FORCE_FLOOR", "IMPACT_RTOL", "IMPACT_V0_FLOOR",
           "KS_ALPHA", "KS_MIN_SAMPLES", "SPECTRUM_TOL", "WELCH_SEGMENTS", "ConvergenceResult", "JointComparison",
           "JointRecord", "RunRecord", "SignalComparison", "Statistic", "check_convergence", "refined_settings"]
