"""Independent SciPy reference solver for the clearance-joint scenes of docs/physics.md section 6.

What it shares with exuclear is the physics of the laws only: :func:`exuclear.make_joint`
builds the normal and friction laws and the reference calls ``ContactLaw.normal_force``
and ``FrictionLaw.coefficient``.  The contact geometry (docs/physics.md section 1), the loads
(section 4), the kinematics, the equations of motion (Lagrange, minimal coordinates) and
the integration (:func:`scipy.integrate.solve_ivp` with event-located contact phases) are
written here again, so that a disagreement with the Exudyn path points at assembly or
integration, not at the laws.

Modules
-------
journal_bearing
    The one-body impact of docs/physics.md section 6.1.
slider_crank
    The slider-crank of docs/physics.md section 6.2 (clearance joint at the rod-slider joint) and its
    ideal closed form.
guided_slider_crank
    The slider-crank of Flores, Leine, Glocker (2010) with a translational clearance joint:
    the slider's four corners against the guide's two walls, compliant.
reynolds
    A finite-difference solver of Reynolds' equation, the reference of the film laws
    (docs/physics.md section 10.6); it shares nothing with exuclear, not even the laws.
"""
from . import guided_slider_crank, journal_bearing, reynolds, slider_crank

__all__ = ["guided_slider_crank", "journal_bearing", "reynolds", "slider_crank"]
