"""Slider-crank with a revolute clearance joint: the paper's example 2 (MODEL.md 5.2).

::

        Y
        ^        A (ideal revolute)
        |       o.
        |  crank  '.   connecting rod
        |  r /      '.      l
        |   /  theta  '.         B (clearance joint: journal on the rod,
        O--o------------'o.__     bearing in the slider)
      ground pivot,      [slider]====> X   (ideal prismatic guide, y = 0)
      crank turns at a constant omega

Two formulations, both assembled from Exudyn items by the library:

- ``"redundant"``: ``ObjectRigidBody2D`` bodies with ideal ``JointRevolute2D`` (O, A)
  and ``JointPrismatic2D`` (slider) constraints; the crank speed is a velocity-level
  ``CoordinateConstraint`` on the crank angle, whose Lagrange multiplier is the
  driving moment.  Needs an implicit solver.
- ``"minimal"``: an ``ObjectKinematicTree`` with coordinates (crank angle, rod angle
  relative to the crank, slider x), so that explicit adaptive solvers (DOPRI5) apply.
  See :func:`build` for how the crank speed is held there.

Run ``python -m models.slider_crank --help`` for the command line.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import exuclear
from exuclear import SolverSettings

FORMULATIONS = ("redundant", "minimal")

#: 500 rpm in rad/s (the paper's crank speed).
PAPER_CRANK_SPEED = 500.0 * 2.0 * math.pi / 60.0


@dataclass(frozen=True)
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
        Constant crank angular speed [rad/s], counter-clockwise; crank angle 0 at t = 0.
    revolutions : float
        Simulated crank revolutions (end time ``2 pi revolutions / crank_speed``).
    gravity : float
        Gravitational acceleration along -Y [m/s^2].
    bearing_radius, clearance, bearing_length : float
        Bearing radius ``R_B``, radial clearance ``c = R_B - R_J`` and length ``L`` [m].
    law, cr, journal_material, bearing_material, friction, v_min
        The clearance joint's physics, as in :func:`exuclear.make_joint`.
    ideal : bool
        True: ideal revolute joint at B instead of the clearance joint (the baseline).
    formulation : str
        ``"redundant"`` or ``"minimal"``, see the module docstring.
    """

    crank_length: float
    rod_length: float
    crank_mass: float
    rod_mass: float
    slider_mass: float
    crank_inertia: float
    rod_inertia: float
    crank_speed: float
    revolutions: float
    gravity: float
    bearing_radius: float
    clearance: float
    bearing_length: float
    law: str
    cr: float
    journal_material: str
    bearing_material: str
    friction: str
    v_min: float = exuclear.V_MIN_DEFAULT
    ideal: bool = False
    formulation: str = "minimal"
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
                   revolutions=2.0, gravity=9.81, bearing_radius=10e-3, clearance=0.1e-3, bearing_length=15e-3,
                   law="wang-liu", cr=0.9, journal_material="steel", bearing_material="steel", friction="none")
        return replace(base, **changes)

    def __post_init__(self) -> None:
        check = exuclear._checks
        for name in ("crank_length", "rod_length", "crank_mass", "rod_mass", "slider_mass", "crank_inertia",
                     "rod_inertia", "crank_speed", "revolutions"):
            check.check_positive(name, getattr(self, name))
        check.check_nonnegative("gravity", self.gravity)
        if self.rod_length <= self.crank_length:
            raise ValueError(f"`rod_length` must exceed `crank_length` for a full-turning crank, "
                             f"got l = {self.rod_length}, r = {self.crank_length}")
        if self.formulation not in FORMULATIONS:
            raise ValueError(f"unknown `formulation` {self.formulation!r}; known: {', '.join(FORMULATIONS)}")
        geometry = exuclear.BearingGeometry.from_clearance(self.bearing_radius, self.clearance, self.bearing_length)
        joint = exuclear.make_joint(
            journal_radius=geometry.journal_radius, bearing_radius=geometry.bearing_radius, length=geometry.length,
            law=self.law, cr=self.cr, journal_material=self.journal_material, bearing_material=self.bearing_material,
            friction=self.friction, v_min=self.v_min)
        object.__setattr__(self, "_joint", joint)

    @property
    def joint(self) -> exuclear.ClearanceJoint:
        """The clearance joint at B (checked at construction)."""
        return self._joint

    @property
    def end_time(self) -> float:
        return 2.0 * math.pi * self.revolutions / self.crank_speed
