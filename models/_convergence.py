"""The convergence check (:func:`exuclear.check_convergence`) for the slider-crank scene.

The four-bar carries its own (:func:`exuclear.models.four_bar.check_convergence`); the slider-crank
module is edited by others, so its adapter lives here and ``exuclear.models.slider_crank`` only
calls it for ``--check-convergence``.
"""
from __future__ import annotations

import exuclear
from exuclear import SolverSettings

#: Slider-crank columns handed to the check as named signals (the time histories a user
#: of the scene reads: slider motion and the driving moment).
SLIDER_CRANK_SIGNALS = ("slider_x", "slider_v", "crank_moment")


def slider_crank_record(params, settings: SolverSettings) -> exuclear.RunRecord:
    """Build and run the slider-crank (``exuclear.models.slider_crank``) and return what the check compares:
    every clearance joint by its name (O, A, B) and :data:`SLIDER_CRANK_SIGNALS`."""
    from .slider_crank import _columns, build

    model = build(params)
    sim = exuclear.simulate(model.mbs, settings)
    cols = _columns(model)
    return exuclear.RunRecord.from_handles(sim, model.joints, {k: (cols["time"], cols[k]) for k in SLIDER_CRANK_SIGNALS})


def check_slider_crank(params, settings: SolverSettings, **options) -> exuclear.ConvergenceResult:
    """:func:`exuclear.check_convergence` of the slider-crank at ``settings``; ``options``
    (``factor``, ``bound``) go to it."""
    return exuclear.check_convergence(lambda s: slider_crank_record(params, s), settings, **options)
