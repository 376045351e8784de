"""Slider-crank with a revolute clearance joint: the paper's Figs. 10-20 and its claims.

Source problem: example 2 of X. Wang, G. Liu, S. Ma, R. Tong, "Effects of restitution
coefficient and material characteristics on dynamic response of planar multi-body
systems with revolute clearance joint", J. Mech. Sci. Technol. 31(2) (2017) 587-597,
restated in ``docs/physics.md`` section 6.2: a crank turning at 500 rpm drives a
slider through a connecting rod; the rod-slider joint has a radial clearance of 0.1 mm.

Every run goes through :mod:`exuclear.models.slider_crank`; this script chooses the cases,
measures them against the ideal mechanism, draws the figures and writes the report:

- restitution sweep: cr = 0.3, 0.5, 0.7, 0.9, steel journal and bearing (Wang-Liu law);
- material sweep at cr = 0.3: steel bearing, journal of steel, ductile iron, copper,
  aluminium;
- each sweep without friction and with the paper's friction law (eq. 11, Table 1);
- the ideal mechanism (redundant formulation, ideal revolute joint) as the baseline.

The report takes the paper's qualitative claims one by one and explains every
disagreement with diagnostic runs, without changing the library's model: a solver
tolerance ladder, the contact history at every accepted step (``v0``, impact
durations, what outputs every 1e-5 s can show), the ideal joint force at B in closed
form, and a run with ``v0`` floored at the first impact's speed.

The modules, by role: :mod:`.cases` (the sweeps, their settings, and the runs, each a
row of :func:`exuclear.study.run_study`), :mod:`.metrics` (measures against the ideal
mechanism), :mod:`.diagnostics` (which runs each part of the report needs),
:mod:`.tables`, :mod:`.claims` and :mod:`.report` (the Markdown), :mod:`.files` (figures
and CSV tables), :mod:`.cli`.

Run from the repository root::

    python -m validation.slider_crank [--out DIR] [--revolutions N] [--workers N]

The runs go to local worker processes, on all cores unless ``--workers`` says otherwise
(1: in this process); the numbers do not depend on it.

Exit status 0 if every run succeeded, 1 otherwise (the failed runs are named), 2 on
bad options.
"""
from validation.slider_crank.cli import main

__all__ = ["main"]
