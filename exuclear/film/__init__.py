"""Film (lubrication) laws of the lubricated joint: the hydrodynamic force of an oil film.

A journal of radius ``R`` turns in a bearing with radial clearance ``c`` and width
(axial length) ``B = L``; the film between them carries a load when the surfaces drag oil
into a converging gap (wedge) or when the journal moves towards the wall (squeeze).
docs/physics.md section 10 states the physics; this module is its code.  Pure physics:
no exudyn, no state.

Notation (docs/physics.md section 1 and section 10): ``e`` is the eccentricity vector (journal
centre minus bearing centre), ``eps = |e| / c``, ``n = e / |e|``, ``phi`` the angle of ``e``;
the film thickness is ``h(theta) = c (1 + eps cos(theta))`` with ``theta`` measured, in the
sense of positive spin (counter-clockwise about ``+z``), from the line of the largest gap
(the direction ``-n``).  ``omega_J``, ``omega_B`` are the spins of journal and bearing
about ``+z``; the wedge acts with the effective angular velocity

    omega_eff = omega_J + omega_B - 2 dphi/dt           (physics.md eq. (56))

so that a journal whirling at half the mean spin carries no wedge load.  Forces are on
the journal [N] (the bearing gets the opposite), torques about ``+z`` [N m].  Units SI;
viscosity in Pa s.

Models (``Lubrication(model=...)``):

``"short"``
    Ocvirk's short bearing, dynamic form (Pinkus and Sternlicht 1961; as used by Flores
    et al., Mech. Mach. Theory 41 (2006) 247), half-Sommerfeld (Guembel) cavitation:
    the full-film pressure's positive part.  physics.md eqs. (58)-(60).
``"long"``
    Sommerfeld's long bearing with the same cavitation condition; the pressure level is
    that of a bearing open to ambient pressure at its ends.  physics.md eqs. (61)-(63).
``"finite"``
    Butenschoen's approximation (H. J. Butenschoen, Das hydrodynamische, zylindrische
    Gleitlager endlicher Breite unter instationaerer Belastung, Diss. Karlsruhe 1976; the
    rotation part is the one of DIN 31652-2): fits of the Sommerfeld number and the
    attitude angle for rotation, and of the squeeze Sommerfeld number, for
    ``1/8 <= B/D <= 1``.  physics.md eqs. (64)-(67).
"""
from .laws import (
    FILM_MODELS,
    FINITE_WIDTH_RANGE,
    SQUEEZE_TURN,
    VISCOSITY_WARN_ABOVE,
    FilmLaw,
    FiniteBearing,
    LongBearing,
    Lubrication,
    ShortBearing,
)
from .loads import (
    EPS_CAP_DEFAULT,
    EPS_FILM_DEFAULT,
    FilmKinematics,
    FilmLoad,
    attitude_angle,
    blend_eccentricity,
    eccentricity_ratio,
    film_kinematics,
    minimum_film_thickness,
    relative_clearance,
    sommerfeld_number,
)

__all__ = [
    # the lubricant and its models
    "Lubrication", "FilmLaw", "ShortBearing", "LongBearing", "FiniteBearing", "FILM_MODELS", "FINITE_WIDTH_RANGE",
    "SQUEEZE_TURN", "VISCOSITY_WARN_ABOVE",
    # kinematics, loads and the blend to metal contact
    "FilmLoad", "FilmKinematics", "film_kinematics", "blend_eccentricity", "EPS_FILM_DEFAULT", "EPS_CAP_DEFAULT",
    "eccentricity_ratio", "minimum_film_thickness", "relative_clearance", "sommerfeld_number", "attitude_angle",
]
