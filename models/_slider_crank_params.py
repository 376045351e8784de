"""The slider-crank's parameters: :class:`SliderCrankParams` (the paper's values in
:meth:`SliderCrankParams.paper`), its formulations and its output columns."""
from __future__ import annotations

import math
import warnings
from dataclasses import field, replace

import exuclear

from ._defaults import PAPER_CLEARANCE, PAPER_CRANK_SPEED
from ._joint_fields import joint_fields, scene_joint, scene_params
from ._params import boolean, check_fields, nonnegative, nonzero, one_of, param, positive

FORMULATIONS = ("redundant", "minimal", "spatial")

#: Inertia added to the crank in the minimal formulation [kg m^2] to hold its speed
#: (see :func:`build`): 2.5e10 times the paper crank's own inertia about O, so a 100 N m
#: moment changes the 52 rad/s speed by less than 1e-4 rad/s^2 * 0.24 s = 2.4e-5 rad/s.
FLYWHEEL_INERTIA = 1e6

#: Output columns of a run (SI units, angles in degrees), in CSV order.
COLUMNS = ("time", "crank_angle", "slider_x", "slider_v", "slider_a", "contact_force", "crank_moment",
           "ecc_x", "ecc_y", "penetration", "in_contact")

#: Output columns a run with a lubricated joint at B adds (after :data:`COLUMNS`): the
#: film force [N], eccentricity ratio, smallest film thickness [m] and regime (0 film alone,
#: 1 film near the wall, 2 metal contact) of docs/physics.md section 10.8, and the force the
#: joint carries, film and metal contact together [N] (``contact_force`` is the metal
#: contact's alone).
FILM_COLUMNS = ("film_force", "eccentricity_ratio", "min_film_thickness", "regime", "joint_force")

#: Crank speeds above this [rad/s] (1e5 rpm) are legal but far beyond any slider-crank:
#: a warning asks whether rpm were given where rad/s are expected, or the like.
CRANK_SPEED_WARN = 1e5 * 2.0 * math.pi / 60.0


@scene_params
class SliderCrankParams:
    """Parameters of the slider-crank (SI units); :meth:`paper` gives the paper's values.

    Parameters
    ----------
    crank_length, rod_length : float
        ``r`` and ``l`` [m]; centres of mass at the link midpoints.
    crank_mass, rod_mass, slider_mass : float
        Masses [kg].
    crank_inertia, rod_inertia : float
        Inertias about the centres of mass [kg m^2].
    crank_speed : float
        Constant crank angular speed [rad/s], non-zero: positive counter-clockwise (the
        paper's), negative clockwise; crank angle 0 at t = 0.
    revolutions : float
        Simulated crank revolutions (end time ``2 pi revolutions / |crank_speed|``).
    gravity : float
        Gravitational acceleration along -Y [m/s^2].
    bearing_radius, clearance, bearing_length : float
        Bearing radius ``R_B``, radial clearance ``c = R_B - R_J`` and length ``L`` [m].
    law, cr, journal_material, bearing_material, friction, v_min
        The clearance joint's physics, as in :func:`exuclear.make_joint`.
    ideal : bool
        True: ideal revolute joints everywhere (the baseline).
    clearance_joints : tuple of str
        Which revolute joints have clearance: any of ``"O"`` (crank-ground), ``"A"``
        (crank-rod), ``"B"`` (rod-slider, the paper's); all with the same geometry,
        law and materials.  Only ``("B",)`` in the minimal formulation.
    formulation : str
        ``"redundant"``, ``"minimal"`` or ``"spatial"``, see the module docstring.
    backend : str
        How the clearance joints' forces are evaluated, see
        :func:`exuclear.CreateClearanceJoint`: ``"compiled"`` (default where built) or ``"python"``.
    max_penetration : float, optional
        Penetration [m] beyond which a run stops, see :func:`exuclear.AddClearanceJoint`;
        default None, the library's default bound.
    viscosity : float, optional
        Dynamic viscosity [Pa s] of the oil in the clearance joints (:class:`exuclear.Lubrication`);
        default None, dry joints.
    film_model : str
        The oil film's model, ``"short"``, ``"long"`` or ``"finite"`` (docs/physics.md section
        10); only with a ``viscosity``.
    wear_coefficient : float, optional
        ``k_D = k / H`` [1/Pa] of the clearance joints' wear (:class:`exuclear.Wear`, docs/physics.md
        section 11); default None, no wear.  Not with the spatial formulation.
    wear_surface, wear_pressure : str
        Which surfaces wear and the pressure over the arc, as :class:`exuclear.Wear` takes them.
    """

    crank_length: float = field(metadata=param("crank length r [m]", positive))
    rod_length: float = field(metadata=param("rod length l [m]", positive))
    crank_mass: float = field(metadata=param("crank mass [kg]", positive))
    rod_mass: float = field(metadata=param("rod mass [kg]", positive))
    slider_mass: float = field(metadata=param("slider mass [kg]", positive))
    crank_inertia: float = field(metadata=param("crank inertia about its centre of mass [kg m^2]", positive))
    rod_inertia: float = field(metadata=param("rod inertia about its centre of mass [kg m^2]", positive))
    crank_speed: float = field(metadata=param(
        "crank speed [rad/s]", nonzero("positive counter-clockwise, negative clockwise"), cli=False))  # --rpm
    revolutions: float = field(metadata=param("crank revolutions", positive))
    gravity: float = field(metadata=param("gravity along -Y [m/s^2]", nonnegative))
    _joint_fields = joint_fields("bearing_radius", "clearance", "bearing_length", "law", "cr", "journal_material",
                                 "bearing_material", "friction", "v_min")
    ideal: bool = field(default=False, metadata=param("ideal revolute joints everywhere (the baseline)", boolean))
    formulation: str = field(default="minimal", metadata=param(
        "redundant, minimal or spatial", one_of(FORMULATIONS), cli=False))  # its own option: implied by others
    clearance_joints: tuple[str, ...] = field(default=("B",), metadata=param(
        "joints with clearance", cli=False))  # given as letters, --clearance-joints OAB
    _more_joint_fields = joint_fields("backend", "max_penetration", "viscosity", "film_model", "wear_coefficient",
                                      "wear_surface", "wear_pressure")
    _joint: exuclear.ClearanceJoint | None = field(default=None, init=False, repr=False, compare=False)

    @classmethod
    def paper(cls, **changes: object) -> SliderCrankParams:
        """The paper's example 2: crank 0.05 m / 0.194 kg, rod 0.30 m / 1.062 kg /
        0.034 kg m^2, slider 0.281 kg, 500 rpm, bearing R_B = 10 mm, c = 0.1 mm,
        L = 15 mm, steel on steel, Wang-Liu law with cr = 0.9, no friction, 2 revolutions.

        The crank inertia is not given by the paper: ``m r^2 / 12`` (a slender rod).
        """
        base = cls(crank_length=0.05, rod_length=0.30, crank_mass=0.194, rod_mass=1.062, slider_mass=0.281,
                   crank_inertia=0.194 * 0.05**2 / 12.0, rod_inertia=0.034, crank_speed=PAPER_CRANK_SPEED,
                   revolutions=2.0, gravity=9.81, bearing_radius=10e-3, clearance=PAPER_CLEARANCE,
                   bearing_length=15e-3,
                   law="wang-liu", cr=0.9, journal_material="steel", bearing_material="steel", friction="none")
        return replace(base, **changes)

    def __post_init__(self) -> None:
        check_fields(self)
        if abs(self.crank_speed) > CRANK_SPEED_WARN:
            warnings.warn(f"crank speed {self.crank_speed:.3g} rad/s is above 1e5 rpm; `crank_speed` is in rad/s",
                          exuclear.UnitWarning, stacklevel=3)  # at the caller of the class (or of replace())
        if self.rod_length <= self.crank_length:
            raise ValueError(f"`rod_length` must exceed `crank_length` for a full-turning crank, "
                             f"got l = {self.rod_length}, r = {self.crank_length}")
        if not self.clearance_joints or not set(self.clearance_joints) <= {"O", "A", "B"}:
            raise ValueError(f"`clearance_joints` must name some of O, A, B, got {self.clearance_joints!r}")
        if len(set(self.clearance_joints)) != len(self.clearance_joints):
            raise ValueError(f"`clearance_joints` must name each joint once, got {self.clearance_joints!r}")
        object.__setattr__(self, "_joint", scene_joint(self))

    @property
    def joint(self) -> exuclear.ClearanceJoint:
        """The clearance joint at B (checked at construction)."""
        return self._joint

    @property
    def end_time(self) -> float:
        return 2.0 * math.pi * self.revolutions / abs(self.crank_speed)


