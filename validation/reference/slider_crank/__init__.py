"""SciPy reference for the slider-crank with a clearance joint (docs/physics.md section 6.2, the paper's example 2).

The crank angle is prescribed; the free coordinates are the rod's absolute angle and the
slider position, and the clearance joint at B (journal on the rod, bearing in the
slider) decouples rod and slider.  The equations of motion are written here from
Lagrange's equations, independently of the library; only the contact and friction laws
are shared (:mod:`validation.reference._contact`).

The modules, by role: :mod:`.mechanism` (the sketch, the mechanism's constants, its
equations of motion and the closed form of the ideal mechanism), :mod:`.phases` (the
piecewise integration: free flight and contact phases between located events),
:mod:`.outputs` (:class:`Result` and the sampling of the phases' dense output),
:mod:`.driver` (:func:`simulate`), :mod:`.cli`.

Run from the repository root::

    python -m validation.reference.slider_crank [--law L] [--cr CR] [--friction F] [--ideal] [--csv FILE] ...
"""
from validation.reference.slider_crank.cli import main
from validation.reference.slider_crank.driver import METHODS, simulate
from validation.reference.slider_crank.mechanism import _laws, _mechanism, ideal_kinematics
from validation.reference.slider_crank.outputs import COLUMNS, ENERGY_COLUMNS, Result
from validation.reference.slider_crank.phases import _gap, _integrate, _missed_onset

__all__ = ["COLUMNS", "ENERGY_COLUMNS", "METHODS", "Result", "_gap", "_integrate", "_laws", "_mechanism",
           "_missed_onset", "ideal_kinematics", "main", "simulate"]
