"""Slider-crank with a revolute clearance joint: the paper's example 2 (docs/physics.md section 6.2).

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

Three formulations, all assembled from Exudyn items by the library:

- ``"redundant"``: ``ObjectRigidBody2D`` bodies with ideal ``JointRevolute2D`` (O, A)
  and ``JointPrismatic2D`` (slider) constraints; the crank speed is a velocity-level
  ``CoordinateConstraint`` on the crank angle, whose Lagrange multiplier is the
  driving moment.  Needs an implicit solver.
- ``"minimal"``: an ``ObjectKinematicTree`` with coordinates (crank angle, rod angle
  relative to the crank, slider x), so that explicit adaptive solvers (DOPRI5) apply.
  See :func:`build` for how the crank speed is held there.
- ``"spatial"``: the same mechanism built as an Exudyn user builds 3D models, six
  degrees of freedom per body (``mbs.CreateRigidBody``, ``mbs.CreateRevoluteJoint``,
  ``mbs.CreatePrismaticJoint``, ``exuclear.CreateClearanceJoint``); see
  :func:`_build_spatial`.  Needs an implicit solver.

Run ``python -m exuclear.models.slider_crank --help`` for the command line: one option per
:class:`SliderCrankParams` field (``--crank-length``, ...), the crank speed in rpm and the
solver settings.
"""
from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from dataclasses import dataclass, field, replace

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadMassProportional,
    MarkerBodyMass,
    MarkerBodyRigid,
    MarkerKinematicTreeRigid,
    MarkerNodeCoordinate,
    NodeGenericODE2,
    NodePointGround,
    NodeRigidBody2D,
    ObjectConnectorCoordinate,
    ObjectGround,
    ObjectJointPrismatic2D,
    ObjectJointRevolute2D,
    ObjectKinematicTree,
    ObjectRigidBody2D,
    SensorNode,
    SensorObject,
)
from exudyn.rigidBodyUtilities import RigidBodyInertia

import exuclear
from exuclear import SolverSettings
from exuclear import convergence as _convergence
from exuclear.columns import Column
from exuclear.contact import V_MIN_DEFAULT, law_and_restitution
from exuclear.engine import BACKENDS, DEFAULT_BACKEND, AccuracyWarning
from exuclear.engine.outputs import REGIME_CONTACT
from exuclear.materials import MATERIALS
from exuclear.settings import METHODS
from exuclear.timescales import reduced_mass

from . import _defaults
from ._cli import (
    OneLineParser,
    add_law_options,
    add_rpm_option,
    bad_input,
    check_output_dir,
    check_output_file,
    one_line_warnings,
)
from ._cli import write_csv as _write_columns
from ._defaults import PAPER_CLEARANCE, PAPER_CRANK_SPEED, PAPER_RPM
from ._lubricant import FILM_MODEL_DEFAULT, FILM_MODEL_NAMES, joint_force, lubrication
from ._params import (
    add_param_options,
    boolean,
    changes_from_args,
    check_fields,
    crank_speed_from_rpm,
    nonnegative,
    nonzero,
    one_of,
    optional,
    param,
    positive,
    study_columns,
)
from .scene import Scene

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
    bearing_radius: float = field(metadata=param("bearing radius R_B [m]", positive))
    clearance: float = field(metadata=param("radial clearance [m]", positive))
    bearing_length: float = field(metadata=param("bearing length [m]", option="length"))
    law: str = field(metadata=param("contact law", cli=False))  # --law, --stiffness, --damping (add_law_options)
    cr: float = field(metadata=param("coefficient of restitution", cli=False))
    journal_material: str = field(metadata=param(f"journal material: {', '.join(MATERIALS)}", option="journal"))
    bearing_material: str = field(metadata=param("bearing material", option="bearing"))
    friction: str = field(metadata=param("none | coulomb:MU | paper"))
    v_min: float = field(default=V_MIN_DEFAULT, metadata=param("floor of v0 in the damping term [m/s]"))
    ideal: bool = field(default=False, metadata=param("ideal revolute joints everywhere (the baseline)", boolean))
    formulation: str = field(default="minimal", metadata=param(
        "redundant, minimal or spatial", one_of(FORMULATIONS), cli=False))  # its own option: implied by others
    clearance_joints: tuple[str, ...] = field(default=("B",), metadata=param(
        "joints with clearance", cli=False))  # given as letters, --clearance-joints OAB
    backend: str = field(default=DEFAULT_BACKEND, metadata=param(
        "the joint's kernel: compiled (C++) or python", one_of(sorted(BACKENDS)), choices=BACKENDS))
    max_penetration: float | None = field(default=None, metadata=param(
        "penetration [m] beyond which the run stops (default: the larger of half the clearance and 0.1 % of the "
        "journal radius)", optional(positive)))
    viscosity: float | None = field(default=None, metadata=param(
        "dynamic viscosity of the oil in the clearance joint [Pa s] (default: none, a dry joint)", optional(positive)))
    film_model: str = field(default=FILM_MODEL_DEFAULT, metadata=param(
        "the oil film's model (docs/physics.md section 10), with --viscosity", one_of(FILM_MODEL_NAMES),
        choices=FILM_MODEL_NAMES))
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
        if self.clearance >= self.bearing_radius:
            raise ValueError(f"`clearance` must be smaller than `bearing_radius` (the journal radius is their "
                             f"difference), got clearance = {self.clearance}, bearing_radius = {self.bearing_radius}")
        joint = exuclear.make_joint(
            journal_radius=self.bearing_radius - self.clearance, bearing_radius=self.bearing_radius,
            length=self.bearing_length,
            law=self.law, cr=self.cr, journal_material=self.journal_material, bearing_material=self.bearing_material,
            friction=self.friction, v_min=self.v_min, lubrication=lubrication(self.viscosity, self.film_model))
        object.__setattr__(self, "_joint", joint)

    @property
    def joint(self) -> exuclear.ClearanceJoint:
        """The clearance joint at B (checked at construction)."""
        return self._joint

    @property
    def end_time(self) -> float:
        return 2.0 * math.pi * self.revolutions / abs(self.crank_speed)


def _initial_velocities(p: SliderCrankParams) -> tuple[float, float]:
    """Rod angular velocity and slider velocity of the ideal mechanism at crank angle 0."""
    return -p.crank_speed * p.crank_length / p.rod_length, 0.0


def _build_redundant(p: SliderCrankParams, mbs: exu.MainSystem) -> tuple[dict, dict]:
    r, l, w = p.crank_length, p.rod_length, p.crank_speed
    rod_rate, _ = _initial_velocities(p)
    g = [0.0, -p.gravity, 0.0]
    ground = mbs.AddObject(ObjectGround())
    # bodies: nodes at the centres of mass, all links along +X at t = 0
    n_crank = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[r / 2, 0, 0], initialVelocities=[0, w * r / 2, w]))
    n_rod = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[r + l / 2, 0, 0],
                                        initialVelocities=[0, w * r + rod_rate * l / 2, rod_rate]))
    n_slider = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[r + l, 0, 0]))
    crank = mbs.AddObject(ObjectRigidBody2D(nodeNumber=n_crank, mass=p.crank_mass, inertia=p.crank_inertia))
    rod = mbs.AddObject(ObjectRigidBody2D(nodeNumber=n_rod, mass=p.rod_mass, inertia=p.rod_inertia))
    # the slider does not rotate (its guide holds it): its inertia never enters the motion
    slider = mbs.AddObject(ObjectRigidBody2D(nodeNumber=n_slider, mass=p.slider_mass, inertia=p.slider_mass * 1e-4))
    if p.gravity > 0.0:
        for body in (crank, rod, slider):
            mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=body)),
                                             loadVector=g))

    def rigid(body, x):
        return mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[x, 0, 0]))

    # revolute joints: (name, journal body and point, bearing body and point); the pin
    # (journal) sits on the crank at O and A and on the rod at B (the paper's choice)
    revolutes = (("O", crank, -r / 2, ground, 0.0), ("A", crank, r / 2, rod, -l / 2), ("B", rod, l / 2, slider, 0.0))
    joints = {}
    for name, journal, x_journal, bearing, x_bearing in revolutes:
        if name in p.clearance_joints and not p.ideal:
            joints[name] = exuclear.AddClearanceJoint(
                mbs, [rigid(bearing, x_bearing), rigid(journal, x_journal)], joint=p.joint, name=name,
                backend=p.backend, maxPenetration=p.max_penetration,
                bearingRotates=bearing != slider)  # the guide holds the slider's rotation
        else:
            mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[rigid(bearing, x_bearing), rigid(journal, x_journal)]))
    mbs.AddObject(ObjectJointPrismatic2D(markerNumbers=[rigid(ground, r + l), rigid(slider, 0.0)],
                                         axisMarker0=[1, 0, 0], normalMarker1=[0, 1, 0], constrainRotation=True))
    # drive: crank angle rate = omega, a velocity-level coordinate constraint to ground;
    # its Lagrange multiplier is (minus) the driving moment
    n_ground = mbs.AddNode(NodePointGround())
    drive = mbs.AddObject(ObjectConnectorCoordinate(
        markerNumbers=[mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_ground, coordinate=0)),
                       mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_crank, coordinate=2))],
        velocityLevel=True, offset=w))
    store = dict(storeInternal=True, writeToFile=False)
    sensors = {
        "crank": mbs.AddSensor(SensorNode(nodeNumber=n_crank, outputVariableType=exu.OutputVariableType.Coordinates,
                                          **store)),
        "slider_x": mbs.AddSensor(SensorNode(nodeNumber=n_slider, outputVariableType=exu.OutputVariableType.Position,
                                             **store)),
        "slider_v": mbs.AddSensor(SensorNode(nodeNumber=n_slider, outputVariableType=exu.OutputVariableType.Velocity,
                                             **store)),
        "slider_a": mbs.AddSensor(SensorNode(nodeNumber=n_slider,
                                             outputVariableType=exu.OutputVariableType.Acceleration, **store)),
        "moment": mbs.AddSensor(SensorObject(objectNumber=drive, outputVariableType=exu.OutputVariableType.Force,
                                             **store)),
    }
    return joints, sensors


def _build_minimal(p: SliderCrankParams, mbs: exu.MainSystem) -> tuple[dict, dict]:
    r, l, w = p.crank_length, p.rod_length, p.crank_speed
    rod_rate, slider_rate = _initial_velocities(p)
    # coordinates: crank angle, rod angle relative to the crank, slider x (reference r + l)
    node = mbs.AddNode(NodeGenericODE2(referenceCoordinates=[0.0, 0.0, r + l], initialCoordinates=[0.0, 0.0, 0.0],
                                       initialCoordinates_t=[w, rod_rate - w, slider_rate], numberOfODE2Coordinates=3))

    def inertia(izz: float) -> np.ndarray:
        return np.diag([0.0, 0.0, izz])

    tree = mbs.AddObject(ObjectKinematicTree(
        nodeNumber=node, linkParents=[-1, 0, -1],
        jointTypes=[exu.JointType.RevoluteZ, exu.JointType.RevoluteZ, exu.JointType.PrismaticX],
        jointTransformations=exu.Matrix3DList([np.eye(3)] * 3),
        jointOffsets=exu.Vector3DList([[0.0, 0.0, 0.0], [r, 0.0, 0.0], [0.0, 0.0, 0.0]]),
        linkInertiasCOM=exu.Matrix3DList([inertia(p.crank_inertia + FLYWHEEL_INERTIA), inertia(p.rod_inertia),
                                          inertia(0.0)]),
        linkCOMs=exu.Vector3DList([[r / 2, 0.0, 0.0], [l / 2, 0.0, 0.0], [0.0, 0.0, 0.0]]),
        linkMasses=[p.crank_mass, p.rod_mass, p.slider_mass], gravity=[0.0, -p.gravity, 0.0]))
    # B: the bearing on the slider (link 2) at its origin, the journal on the rod (link 1) at its end
    markers = [mbs.AddMarker(MarkerKinematicTreeRigid(objectNumber=tree, linkNumber=link, localPosition=[x, 0.0, 0.0]))
               for link, x in ((2, 0.0), (1, l))]
    handle = exuclear.AddClearanceJoint(mbs, markers, joint=p.joint, name="B", backend=p.backend,
                                        maxPenetration=p.max_penetration)
    store = dict(storeInternal=True, writeToFile=False)
    sensors = {key: mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=kind, **store))
               for key, kind in (("q", exu.OutputVariableType.Coordinates),
                                 ("q_t", exu.OutputVariableType.Coordinates_t),
                                 ("q_tt", exu.OutputVariableType.Coordinates_tt))}
    return {"B": handle}, sensors


#: Rotation node of the spatial formulation's bodies, see :func:`_build_spatial`.
SPATIAL_NODE_TYPE = exu.NodeType.RotationRxyz

#: Index of the rotation about z among an Rxyz node's coordinates ``[x, y, z, rx, ry, rz]``.
_RXYZ_ANGLE_Z = 5


def _build_spatial(p: SliderCrankParams, mbs: exu.MainSystem) -> tuple[dict, dict]:
    """The slider-crank from 3D rigid bodies, as an Exudyn user builds it.

    Bodies: crank, rod and slider from ``mbs.CreateRigidBody`` with six degrees of
    freedom each, nodes at the centres of mass, gravity along -Y.  Their inertia about
    x and y never enters the motion (the angular velocities stay along z, a principal
    axis, and the joints hold the tilt), so each body gets its planar moment of inertia
    about all three axes; the slider's, which its guide keeps from turning, is that of
    the redundant formulation.

    Rotation node: ``NodeRigidBodyRxyz`` (:data:`SPATIAL_NODE_TYPE`), chosen over
    ``CreateRigidBody``'s default Euler parameters and the rotation vector:

    - its third angle ``rz`` is, while the tilts ``rx = ry = 0``, the rotation about z
      itself and its rate the angular velocity about z (``omega = e_x rx' + Rx e_y ry'
      + Rx Ry e_z rz'``), unbounded as the crank turns; so the crank speed is held as in
      the redundant formulation, by a velocity-level ``CreateCoordinateConstraint`` on
      ``rz`` (``rz' = omega``), and its multiplier is the moment about z (the virtual
      work ``M . Rx Ry e_z drz`` at zero tilt).  Euler parameters have no coordinate
      whose rate is the angular velocity about z; the rotation-vector node is made for
      Exudyn's explicit Lie-group integrators, and as plain coordinates for an implicit
      solver its rotation vector meets the ``2 pi`` singularity in every crank turn;
    - the Rxyz singularity lies at ``ry = +-90 deg``; the joints hold ``ry`` at zero;
    - three rotation coordinates and no Euler-parameter normalisation constraint.  (The
      joints need an implicit solver anyway: Exudyn's explicit solvers drop constraints,
      and they refuse Euler-parameter nodes.)

    Joints: ``mbs.CreateRevoluteJoint`` at O (ground-crank) and A (rod-crank), the slider
    guide ``mbs.CreatePrismaticJoint`` along X, and ``exuclear.CreateClearanceJoint`` at
    B with the bearing in the slider and the journal on the rod (``itemNumbers`` is
    [bearing body, journal body] throughout, as in the redundant formulation).

    Out-of-plane motion, counted: 3 bodies x 6 = 18 coordinates; a revolute joint holds
    5 (all but the rotation about its axis), the prismatic guide 5 (all but the slide
    along X), the drive 1, the clearance joint at B none (``constrainAxial=False``): 18 -
    16 = 2 degrees of freedom, the journal's in-plane motion in its bearing, as in the
    2D formulations.  The crank's out-of-plane motion (z, tilt) is held by O, the rod's
    by A alone (relative to the crank), the slider's by its guide; a joint at B holding
    the axial motion too would make 3 constraints redundant (a singular Jacobian, as
    for every planar loop of spatial revolute joints).  So the other cases keep that
    split:

    - ideal joint at B (``ideal``, or clearance at O or A only): a pin holding the two
      in-plane translations only, ``mbs.CreateGenericJoint`` with constrained axes
      x, y;
    - clearance at O or A: it replaces the only joint that holds the crank's or the
      rod's out-of-plane motion, so a ``mbs.CreateGenericJoint`` holds axial
      translation and tilt there (constrained axes z, rx, ry; what
      ``constrainAxial=True`` of the clearance joint is meant to add).

    No load acts out of the plane, so the out-of-plane displacements stay zero to
    round-off (:func:`out_of_plane`).
    """
    r, l, w = p.crank_length, p.rod_length, p.crank_speed
    rod_rate, _ = _initial_velocities(p)
    ground = mbs.AddObject(ObjectGround())

    def rigid_body(name: str, x: float, mass: float, inertia: float, v_y: float, omega: float) -> dict:
        return mbs.CreateRigidBody(
            name=name, referencePosition=[x, 0.0, 0.0], initialVelocity=[0.0, v_y, 0.0],
            initialAngularVelocity=[0.0, 0.0, omega], gravity=[0.0, -p.gravity, 0.0], nodeType=SPATIAL_NODE_TYPE,
            inertia=RigidBodyInertia(mass=mass, inertiaTensor=inertia * np.eye(3), inertiaTensorAtCOM=True),
            returnDict=True)

    # all links along +X at t = 0, velocities of the ideal mechanism at crank angle 0
    crank = rigid_body("crank", r / 2, p.crank_mass, p.crank_inertia, w * r / 2, w)
    rod = rigid_body("rod", r + l / 2, p.rod_mass, p.rod_inertia, w * r + rod_rate * l / 2, rod_rate)
    slider = rigid_body("slider", r + l, p.slider_mass, p.slider_mass * 1e-4, 0.0, 0.0)
    crank_body, rod_body, slider_body = crank["bodyNumber"], rod["bodyNumber"], slider["bodyNumber"]

    # revolute joints: (name, bearing body, journal body, centre); O holds the crank's
    # out-of-plane motion, A the rod's, the guide the slider's; B none (docstring)
    revolutes = (("O", ground, crank_body, [0.0, 0.0, 0.0]), ("A", rod_body, crank_body, [r, 0.0, 0.0]),
                 ("B", slider_body, rod_body, [r + l, 0.0, 0.0]))
    drawn = dict(axisRadius=p.bearing_radius, axisLength=p.bearing_length)  # Exudyn's defaults are 0.1 m, 0.4 m
    in_plane, out_of_plane_axes = [1, 1, 0, 0, 0, 0], [0, 0, 1, 1, 1, 0]  # constrainedAxes of a generic joint
    joints = {}
    for name, bearing, journal, centre in revolutes:
        pair = dict(itemNumbers=[bearing, journal], position=centre)
        if name in p.clearance_joints and not p.ideal:
            joints[name] = exuclear.CreateClearanceJoint(mbs, name=name, axis=[0.0, 0.0, 1.0], joint=p.joint,
                                                         backend=p.backend, maxPenetration=p.max_penetration,
                                                         bearingRotates=bearing != slider_body,  # the guide holds it
                                                         **pair)
            if name != "B":
                mbs.CreateGenericJoint(name=f"{name}:axial", constrainedAxes=out_of_plane_axes, show=False, **pair)
        elif name == "B":
            mbs.CreateGenericJoint(name=name, constrainedAxes=in_plane, show=False, **pair)
        else:
            mbs.CreateRevoluteJoint(name=name, axis=[0.0, 0.0, 1.0], **drawn, **pair)
    mbs.CreatePrismaticJoint(name="guide", itemNumbers=[ground, slider_body], position=[r + l, 0.0, 0.0],
                             axis=[1.0, 0.0, 0.0], **drawn)
    # drive: rz' = omega on the crank, a velocity-level coordinate constraint to ground;
    # its Lagrange multiplier is (minus) the driving moment
    drive = mbs.CreateCoordinateConstraint(name="drive", itemNumbers=[None, crank_body],
                                           coordinates=[None, _RXYZ_ANGLE_Z], velocityLevel=True, offset=w,
                                           show=False)
    store = dict(storeInternal=True, writeToFile=False)
    nodes = {"crank": crank["nodeNumber"], "rod": rod["nodeNumber"], "slider": slider["nodeNumber"]}
    coordinates = exu.OutputVariableType.Coordinates
    sensors = {key: mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=coordinates, **store))
               for key, node in nodes.items()}  # the crank's last column is rz, its angle (see columns)
    for key, kind in (("slider_x", exu.OutputVariableType.Position), ("slider_v", exu.OutputVariableType.Velocity),
                      ("slider_a", exu.OutputVariableType.Acceleration)):
        sensors[key] = mbs.AddSensor(SensorNode(nodeNumber=nodes["slider"], outputVariableType=kind, **store))
    sensors["moment"] = mbs.AddSensor(SensorObject(objectNumber=drive, outputVariableType=exu.OutputVariableType.Force,
                                                   **store))
    return joints, sensors


def out_of_plane(model: Scene) -> dict[str, float]:
    """Largest out-of-plane motion of a spatial run, per body: ``{body}_z``, the largest
    ``|z|`` of its centre of mass [m], and ``{body}_tilt``, the largest ``|rx|``,
    ``|ry|`` of its Rxyz angles [rad], for ``body`` in crank, rod, slider."""
    if model.params.formulation != "spatial":
        raise ValueError(f"out_of_plane needs the spatial formulation, got {model.params.formulation!r}")
    found = {}
    for body in ("crank", "rod", "slider"):
        q = np.asarray(model.mbs.GetSensorStoredData(model.sensors[body]))  # time, x, y, z, rx, ry, rz
        found[f"{body}_z"] = float(np.abs(q[:, 3]).max())
        found[f"{body}_tilt"] = float(np.abs(q[:, 4:6]).max())
    return found


def build(params: SliderCrankParams) -> Scene:
    """Assemble the slider-crank in Exudyn: its clearance joints by name (``"O"``, ``"A"``,
    ``"B"``; ``Scene.joint`` is B, the paper's, or None) and its sensors.

    Crank speed: in the redundant formulation a velocity-level coordinate constraint
    holds it exactly and its multiplier is the driving moment.  Exudyn's explicit
    solvers cannot hold a coordinate at a prescribed rate (they drop constraints, and
    eliminate only fixed ones), so the minimal formulation gives the crank a flywheel
    of :data:`FLYWHEEL_INERTIA`: its speed then changes by less than 1e-6 of 500 rpm
    over the run, and the driving moment is the flywheel's reaction
    ``-FLYWHEEL_INERTIA * crank_angle_tt``, which equals the moment an exact drive
    would need up to that relative error.  The spatial formulation holds it as the
    redundant one does, on the crank's rotation coordinate about z (:func:`_build_spatial`).
    """
    if params.ideal and params.formulation == "minimal":
        raise ValueError("the ideal mechanism is a closed loop, which a kinematic tree cannot hold: "
                         "use formulation 'redundant' with `ideal`")
    if params.formulation == "minimal" and tuple(params.clearance_joints) != ("B",):
        raise ValueError("the minimal formulation has a clearance joint at B only (O and A are tree joints): "
                         f"use formulation 'redundant' for clearance_joints {params.clearance_joints}")
    start = time.perf_counter()
    mbs = exu.SystemContainer().AddSystem()
    builder = {"minimal": _build_minimal, "redundant": _build_redundant, "spatial": _build_spatial}[params.formulation]
    joints, sensors = builder(params, mbs)
    mbs.Assemble()
    return Scene(params, mbs, joints, sensors, build_time=time.perf_counter() - start, main_joint="B")


#: Default settings, chosen by ``validation/work_precision.py`` as the cheapest of each
#: formulation that holds the eccentricity error below 1 % of the clearance on the
#: paper's cases (cr 0.9 and 0.3) over two revolutions.  Minimal: DOPRI5 with steps of
#: at most 1e-4 s (longer free-flight steps would be interpolated linearly between the
#: 1e-5 s outputs) at rtol 1e-7; the paper's 1e-5 s maximum step costs 2.5 times as much
#: for the same error.  Redundant: generalized-alpha with impact-aware steps, 2e-5 s in
#: free flight and steady contact, 1e-6 s from each contact onset on; a fixed 1e-5 s
#: step errs by 12 % of c on the cr 0.9 case.
MINIMAL_DEFAULTS = {"method": "dopri5", "step": 1e-4, "rtol": 1e-7, "atol": 1e-10}
#: Redundant: generalized-alpha with impact-aware steps (2e-5 s, 1e-6 s from each contact
#: onset, grown in free flight by the joint), and a Jacobian wherever a modified-Newton
#: iteration reduces the residual by less than 100x (``newton_contractivity``).  The mechanism
#: turns its Jacobian fast (the crank at 500 rpm) and the matrix is small: at the joint's
#: contractivity 0.2 Newton takes 6.0 iterations per step on 32 Jacobians over two
#: revolutions, at 0.01 3.7 on 467, in 0.70 of the wall time and on the same path
#: (python -m validation.benchmark prints both).  Tried and dropped (measured against the
#: converged reference, cr 0.9, and python -m validation.scaled_defaults): the
#: steps the joint controls (``joint_steps``, KAPPA 0.02, 2.5e-5 s): 0.21 s at 6.4e-3 c on
#: the paper's case but 4.5e-2 c at 2000 rpm and 2.8e-2 c at c = 0.5 mm; 2.2e-5 s steps:
#: 0.27 s at 4.5e-3 c, but the tolerances of the ideal mechanism's and the spatial
#: formulation's checks were set at 2e-5 s.
REDUNDANT_DEFAULTS = {"method": "generalized-alpha", "step": 2e-5, "impact_step": 1e-6, "newton_contractivity": 0.01}
#: Spatial: the redundant formulation's steps; with the same integrator and steps the two
#: agree to ~2e-7 c.  Measured against the minimal formulation converged to 2e-5 c (DOPRI5,
#: rtol 1e-11, steps <= 2e-6 s) over two revolutions: 0.49 % of c (cr 0.9) and 0.16 % (cr
#: 0.3); 4e-5 s steps reach 0.99 % (cr 0.9), too close to the 1 % target.
SPATIAL_DEFAULTS = REDUNDANT_DEFAULTS
_DEFAULTS = {"minimal": MINIMAL_DEFAULTS, "redundant": REDUNDANT_DEFAULTS, "spatial": SPATIAL_DEFAULTS}


def default_settings(params: SliderCrankParams) -> SolverSettings:
    """Solver settings of a formulation (:data:`MINIMAL_DEFAULTS`,
    :data:`REDUNDANT_DEFAULTS`, :data:`SPATIAL_DEFAULTS`, measured at 500 rpm and
    c = 0.1 mm) carried to the model's crank speed and clearance by
    :func:`exuclear.models._defaults.scaled`; outputs every 1e-5 s."""
    return SolverSettings(end_time=params.end_time, **_scaled_defaults(params, _DEFAULTS[params.formulation]))


def _scaled_defaults(params: SliderCrankParams, base: dict) -> dict:
    theta = np.linspace(0.0, 2.0 * math.pi, 361)
    force = float(np.max(np.hypot(*ideal_joint_force(params, theta))))  # the load at B of the ideal mechanism
    mass = reduced_mass(params.rod_mass, params.slider_mass)
    return _defaults.scaled(base, params.crank_speed, params.clearance, params.joint, mass, force)


def accuracy_notes(params: SliderCrankParams, settings: SolverSettings) -> list[str]:
    """Why a run of ``params`` at its default settings may not be converged (issue 16)."""
    if params.ideal:
        return []
    return _defaults.accuracy_notes(params.crank_speed, params.clearance, len(params.clearance_joints),
                                    not settings.explicit)


@dataclass
class SliderCrankResult:
    """Outputs of a run: :data:`COLUMNS` as arrays, and the run's summary."""

    columns: dict[str, np.ndarray]
    success: bool
    message: str
    wall_time: float
    build_time: float
    steps: int
    rejected: int
    onset_times: np.ndarray  # contact onsets [s], found at accepted steps (none is missed by output sampling)
    #: Why the path may not be converged: the defaults' limits (:func:`accuracy_notes`) and
    #: the run's own findings (:attr:`exuclear.SimulationResult.notes`).
    notes: tuple[str, ...] = ()

    @property
    def impacts(self) -> int:
        return len(self.onset_times)

    @property
    def peak_force(self) -> float:
        return float(self.columns["contact_force"].max())


def ideal_joint_force(params: SliderCrankParams, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Force of the rod on the slider at B in the ideal mechanism [N], as ``(fx, fy)``.

    Closed form at constant crank speed ``w`` (signed: clockwise cranks too): rod angle ``phi`` from
    ``r sin(theta) + l sin(phi) = 0``; the frictionless guide gives
    ``fx = m_slider * a_slider``; ``fy`` follows from the rod's moment balance about A,
    ``(B - A) x (-F) + (G - A) x m_rod g = I_G phi'' + (G - A) x m_rod a_G``.  This is
    the direction ``n`` the journal is pressed towards (force on the bearing ``F_N n``).
    Its magnitude is the ``contact_force`` column of an ideal run, the force the ideal
    joint at B carries (``docs/physics.md`` eqs. (30)-(32)).

    Parameters
    ----------
    params : SliderCrankParams
        Mechanism (the clearance fields are not used).
    theta : ndarray, shape (n,)
        Crank angles [rad].
    """
    r, l, w, g = params.crank_length, params.rod_length, params.crank_speed, params.gravity
    m, inertia = params.rod_mass, params.rod_inertia
    s, c = np.sin(theta), np.cos(theta)
    phi = np.arcsin(-r * s / l)
    sp, cp = np.sin(phi), np.cos(phi)
    phi_t = -r * w * c / (l * cp)
    phi_tt = (r * w**2 * s + l * sp * phi_t**2) / (l * cp)
    a_slider = -r * w**2 * c - l * cp * phi_t**2 - l * sp * phi_tt
    ag_x = -r * w**2 * c + 0.5 * l * (-sp * phi_tt - cp * phi_t**2)
    ag_y = -r * w**2 * s + 0.5 * l * (cp * phi_tt - sp * phi_t**2)
    fx = params.slider_mass * a_slider
    rhs = inertia * phi_tt + 0.5 * l * m * (cp * ag_y - sp * ag_x)
    fy = (l * sp * fx - 0.5 * l * cp * m * g - rhs) / (l * cp)
    return fx, fy


def columns(model: Scene) -> dict[str, np.ndarray]:
    """The recorded :data:`COLUMNS` of a finished run (SI units, angles in degrees)."""
    p, mbs, s = model.params, model.mbs, model.sensors

    def data(key: str) -> np.ndarray:
        return np.asarray(mbs.GetSensorStoredData(s[key]))

    if p.formulation == "minimal":
        q, q_t, q_tt = data("q"), data("q_t"), data("q_tt")
        t = q[:, 0]
        cols = {"time": t, "crank_angle": np.degrees(q[:, 1]), "slider_x": q[:, 3] + p.crank_length + p.rod_length,
                "slider_v": q_t[:, 3], "slider_a": q_tt[:, 3], "crank_moment": -FLYWHEEL_INERTIA * q_tt[:, 1]}
    else:
        crank = data("crank")
        t = crank[:, 0]
        # the crank angle is the node's last coordinate: phi of a 2D node, rz of an Rxyz node
        cols = {"time": t, "crank_angle": np.degrees(crank[:, -1]), "slider_x": data("slider_x")[:, 1],
                "slider_v": data("slider_v")[:, 1], "slider_a": data("slider_a")[:, 1],
                # the multiplier is the constraint's reaction on the crank: the drive is its negative
                "crank_moment": -data("moment")[:, 1]}
    if model.joint is None:
        zeros = np.zeros_like(t)
        # the ideal joint at B carries the reaction force; in the ideal mechanism it has a
        # closed form; with clearance at O or A only, B's force is not measured (NaN)
        force = np.hypot(*ideal_joint_force(p, np.radians(cols["crank_angle"]))) if p.ideal else np.full_like(t, np.nan)
        cols.update(contact_force=force, ecc_x=zeros, ecc_y=zeros, penetration=np.full_like(t, -p.clearance),
                    in_contact=zeros)
    else:
        out = model.joint.outputs()
        # the eccentricity in the global x, y (the spatial formulation's joint frame is that of
        # mbs.CreateRevoluteJoint, turned in the plane)
        ecc_x, ecc_y = model.joint.frame[:2, :2] @ np.array([out["ecc_x"], out["ecc_y"]])
        cols.update(contact_force=np.hypot(out["normal_force"], out["tangential_force"]), ecc_x=ecc_x,
                    ecc_y=ecc_y, penetration=out["penetration"], in_contact=out["in_contact"])
        if model.joint.joint.film is not None:
            cols.update({k: out[k] for k in FILM_COLUMNS[:-1]}, joint_force=joint_force(out))
            return {k: cols[k] for k in COLUMNS + FILM_COLUMNS}
    return {k: cols[k] for k in COLUMNS}


def run(params: SliderCrankParams, settings: SolverSettings | None = None) -> SliderCrankResult:
    """Build and simulate; returns the recorded :data:`COLUMNS` and the run's summary.

    With the default settings, where those are not shown to hold 1 % of c
    (:func:`accuracy_notes`), the run warns (:class:`exuclear.AccuracyWarning`) and the
    result's ``notes`` say why and what to do.
    """
    model = build(params)
    notes: tuple[str, ...] = ()
    if settings is None:
        settings = default_settings(params)
        notes = tuple(accuracy_notes(params, settings))
        for note in notes:
            warnings.warn(note, AccuracyWarning, stacklevel=2)
    sim = exuclear.simulate(model.mbs, settings)
    onsets = np.array(model.joint.history.onset_times if model.joint is not None else [])  # joint B
    return SliderCrankResult(columns(model), sim.success, sim.message, sim.wall_time, model.build_time,
                             sim.steps, sim.rejected, onsets, notes + sim.notes)


def write_csv(path: str, columns: dict[str, np.ndarray], incomplete: str = "", notes: tuple[str, ...] = ()) -> None:
    """Write :data:`COLUMNS` (and :data:`FILM_COLUMNS` where ``columns`` holds them: a
    lubricated joint) with a header line (SI units, angles in degrees).

    ``incomplete``: why the run stopped early; it then goes first, as a comment line
    ``# INCOMPLETE: ...`` before the header; ``notes`` follow as ``# NOTE: ...`` lines.
    """
    names = COLUMNS + FILM_COLUMNS if "film_force" in columns else COLUMNS
    _write_columns(path, columns, names, incomplete, notes)


#: The columns :func:`record` hands to :func:`exuclear.check_convergence` as named
#: signals (the time histories a user of the scene reads: slider motion and the driving moment).
SIGNALS = ("slider_x", "slider_v", "crank_moment")


def record(params: SliderCrankParams, settings: SolverSettings) -> _convergence.RunRecord:
    """Build and run the slider-crank and return what :func:`exuclear.check_convergence`
    compares: every clearance joint by its name (O, A, B) and :data:`SIGNALS`."""
    model = build(params)
    sim = exuclear.simulate(model.mbs, settings)
    cols = columns(model)
    return _convergence.RunRecord.from_handles(sim, model.joints, {k: (cols["time"], cols[k]) for k in SIGNALS})


def check_convergence(params: SliderCrankParams, settings: SolverSettings | None = None,
                      **options: object) -> _convergence.ConvergenceResult:
    """:func:`exuclear.check_convergence` of this scene at ``settings`` (default
    :func:`default_settings`); ``options`` go to it (``factor``, ``bound``, ...)."""
    return _convergence.check_convergence(lambda s: record(params, s), settings or default_settings(params), **options)


def _parser() -> argparse.ArgumentParser:
    """The command line: one option per :class:`SliderCrankParams` field
    (:func:`~exuclear.models._params.add_param_options`); defaults :meth:`SliderCrankParams.paper`."""
    p = SliderCrankParams.paper()
    ap = OneLineParser(prog="python -m exuclear.models.slider_crank", description=__doc__.split("\n")[0])
    add_law_options(ap, p.law, p.cr)
    add_param_options(ap, p)
    add_rpm_option(ap, p.crank_speed)
    ap.add_argument("--formulation", choices=FORMULATIONS, default=None,
                    help="minimal (kinematic tree, DOPRI5; default), redundant (2D bodies and joints, implicit "
                         "solver; the default for --ideal and for clearance at O or A, said so in the output) or "
                         "spatial (3D bodies and joints made by Exudyn's Create functions, implicit solver)")
    ap.add_argument("--clearance-joints", default="B",
                    help="joints with clearance, letters of OAB (crank-ground, crank-rod, rod-slider); "
                         "more than B needs --formulation redundant or spatial (default %(default)s)")
    ap.add_argument("--method", choices=list(METHODS),
                    help="solver (default: per formulation); an implicit method gets the implicit default steps "
                         f"({REDUNDANT_DEFAULTS['step']:g} s, {REDUNDANT_DEFAULTS['impact_step']:g} s from each "
                         "contact onset) in either formulation unless --step is given")
    ap.add_argument("--step", type=float, help="fixed step, or largest step of adaptive and impact-aware methods [s]")
    ap.add_argument("--rtol", type=float, help="relative tolerance of adaptive methods")
    ap.add_argument("--atol", type=float, help="absolute tolerance of adaptive methods")
    ap.add_argument("--dt-out", type=float, default=1e-5,
                    help="output interval [s]; outputs are taken at the first accepted step at or after each "
                         "interval, so where the adaptive steps are longer (up to --step) every step is recorded. "
                         "Impacts are counted at every accepted step whatever the interval, but the printed peak "
                         "force, the CSV and the plots see only the outputs: above 1e-5 s an impact (~40 us) is "
                         "sampled coarsely or missed (default %(default)s)")
    ap.add_argument("--csv", metavar="FILE", help="write the time series (columns: " + ", ".join(COLUMNS) + ")")
    ap.add_argument("--plot", metavar="DIR", help="write the plots, with the ideal mechanism as baseline, to DIR")
    ap.add_argument("--verbose", action="store_true", help="Exudyn's progress output during the run")
    ap.add_argument("--check-convergence", action="store_true",
                    help="run again at a tighter step or tolerance and print what agrees with it, and over which "
                         "horizon (exuclear.check_convergence)")
    return ap


def _settings(args: argparse.Namespace, params: SliderCrankParams) -> SolverSettings:
    method = args.method or default_settings(params).method
    # the defaults of the method's family, whatever the formulation: an implicit method at
    # the explicit default's 1e-4 s fixed step overshoots the impacts (peak force 2.4e7 N
    # on the paper's case instead of 2.1e3 N)
    family = MINIMAL_DEFAULTS if METHODS[method][1] else (
        SPATIAL_DEFAULTS if params.formulation == "spatial" else REDUNDANT_DEFAULTS)
    base = SolverSettings(end_time=params.end_time, **_scaled_defaults(params, {**family, "method": method}))
    changes = {k: v for k, v in (("step", args.step), ("rtol", args.rtol), ("atol", args.atol)) if v is not None}
    if base.impact_step is not None and args.step is not None and args.step <= base.impact_step:
        changes["impact_step"] = None  # a step at or below the impact step: plain fixed steps
    return replace(base, output_step=positive("--dt-out", args.dt_out),
                   verbose=int(args.verbose), **changes)


def _formulation(args: argparse.Namespace) -> tuple[str, str]:
    """The formulation asked for or implied by the options, and why, if it was implied."""
    if args.formulation:
        return args.formulation, ""
    if args.ideal:
        return "redundant", " (chosen for --ideal: a kinematic tree cannot close the loop)"
    if set(args.clearance_joints) - {"B"}:
        return "redundant", f" (chosen for --clearance-joints {args.clearance_joints}: the tree has O and A built in)"
    return "minimal", ""


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    one_line_warnings()
    try:
        law, cr = law_and_restitution(args.law, args.stiffness, args.damping, args.cr, args.paper_law,
                                       args.paper_cr)
        formulation, chosen = _formulation(args)
        params = SliderCrankParams.paper(
            **changes_from_args(args, SliderCrankParams), law=law, cr=cr, crank_speed=crank_speed_from_rpm("rpm", args.rpm),
            formulation=formulation, clearance_joints=tuple(args.clearance_joints))
        settings = _settings(args, params)
        if args.csv is not None:
            check_output_file("--csv", args.csv)
        if args.plot is not None:
            check_output_dir("--plot", args.plot)
        result = run(params, settings)
        defaults = args.step is None and args.rtol is None and args.atol is None
        notes = tuple(accuracy_notes(params, settings)) if defaults else ()
        for note in notes:  # after the run: a model that cannot be built is refused without them
            warnings.warn(note, AccuracyWarning, stacklevel=1)
    except ValueError as err:
        return bad_input(err)
    kind = "ideal joint at B" if params.ideal else (
        f"clearance {params.clearance * 1e3:g} mm, {params.law} cr = {params.cr}, {params.journal_material} journal, "
        f"{params.bearing_material} bearing, friction {params.friction}"
        + ("" if params.viscosity is None else f", oil {params.viscosity:g} Pa s ({params.film_model} film)"))
    print(f"slider-crank, {formulation} coordinates{chosen}, {settings.method}: {kind}")
    if result.success:
        print(f"  simulated {params.end_time:.4g} s ({params.revolutions:g} revolutions) in {result.steps} steps "
              f"({result.rejected} rejected)")
    else:
        reached = float(result.columns["time"][-1]) if len(result.columns["time"]) else 0.0
        print(f"  STOPPED EARLY: last output at t = {reached:.4g} s of {params.end_time:.4g} s "
              f"({reached / params.end_time * params.revolutions:.3g} of {params.revolutions:g} revolutions), "
              f"{result.steps} steps ({result.rejected} rejected); see the error below")
    sampled = f" (in the outputs every {settings.output_step:g} s)" if settings.output_step > 1e-5 else ""
    if params.ideal:
        print(f"  joint force at B {np.nanmin(result.columns['contact_force']):.1f} to "
              f"{np.nanmax(result.columns['contact_force']):.1f} N (closed form of the ideal mechanism)")
    else:
        print(f"  peak contact force {result.peak_force:.1f} N{sampled}, impacts {result.impacts}")
        if "film_force" in result.columns:
            cols, t = result.columns, result.columns["time"]
            contact = float(np.trapezoid((cols["regime"] == REGIME_CONTACT).astype(float), t)) / (t[-1] - t[0])
            print(f"  oil film: peak joint force (film and contact) {cols['joint_force'].max():.1f} N, largest "
                  f"eccentricity ratio {cols['eccentricity_ratio'].max():.4g}, smallest film thickness "
                  f"{max(cols['min_film_thickness'].min(), 0.0) * 1e6:.3g} um, metal contact {100.0 * contact:.3g} % "
                  "of the time")
    print(f"  wall time {result.wall_time:.2f} s (model building {result.build_time:.3f} s)")
    if args.check_convergence:
        print(check_convergence(params, settings).report())
    if args.csv is not None:
        write_csv(args.csv, result.columns, incomplete="" if result.success else result.message, notes=notes + result.notes)
        print(f"wrote {args.csv}")
    if args.plot is not None:
        from exuclear.models.figures import slider_crank_figures

        baseline = result if params.ideal else run(replace(params, ideal=True, formulation="redundant"))
        cases = [] if params.ideal else [(f"cr = {params.cr}", result.columns)]
        for path in slider_crank_figures(cases, baseline.columns, params.clearance, args.plot, "slider_crank",
                                         title=f"slider-crank: {kind}"):
            print(f"wrote {path}")
    if not result.success:
        written = f"; the outputs up to then were written to {args.csv} and are INCOMPLETE" if args.csv else ""
        print(f"error: {result.message}{written}", file=sys.stderr)
        return 1
    return 0


# =======================================================================================
# the slider-crank as a parameter study (exuclear.study)
# =======================================================================================

#: Parameters of :func:`study` and their defaults: the paper's case (:meth:`SliderCrankParams.paper`)
#: with the crank speed in rpm, ``startup`` revolutions left out of the steady metrics and
#: ``revolutions`` measured after them.  Every name but ``rpm`` and ``startup`` is a
#: :class:`SliderCrankParams` field.  ``viscosity`` None (or ``"none"`` on a command line:
#: ``--viscosity none,0.01,0.1`` sweeps dry and two oils) is a dry joint, whatever the
#: ``film_model`` of its row.
def _study_defaults() -> dict:
    paper = SliderCrankParams.paper()
    fields = ("law", "journal_material", "bearing_material", "friction", "bearing_length", "gravity", "v_min",
              "formulation", "backend", "viscosity", "film_model")
    return {"cr": paper.cr, "clearance": paper.clearance, "rpm": PAPER_RPM, "startup": 1.0,
            "revolutions": paper.revolutions, **{name: getattr(paper, name) for name in fields}}


STUDY_PARAMETERS = _study_defaults()

#: The metrics of :func:`study`: what each is, its unit (axis labels of study plots).
#: "Steady": after the ``startup`` revolutions.
STUDY_METRICS = {
    "peak_force": Column("peak contact force, whole run", "N"),
    "peak_force_steady": Column("peak contact force, steady", "N"),
    "peak_force_by_rev": Column("peak contact force per steady revolution", "N"),
    "impacts": Column("contact onsets, whole run"),
    "impacts_per_rev": Column("contact onsets per steady revolution"),
    "impacts_by_rev": Column("contact onsets in each steady revolution"),
    "max_ecc_over_c": Column("largest |e| / c, steady"),
    # the force the joint carries, oil film and metal contact together (joint_force): the
    # peak contact force of a dry joint
    "peak_joint_force": Column("peak joint force (film and contact), whole run", "N"),
    # c - |e| at its smallest, steady: negative where the journal penetrates the wall
    "min_film_thickness": Column("smallest film thickness c - |e|, steady", "m"),
    "metal_contact_fraction": Column("fraction of the steady time in metal contact"),
    # RMS over the steady revolutions of the slider acceleration minus the ideal
    # mechanism's (ideal_slider_acceleration), and that over the ideal RMS
    "slider_acc_rms_dev": Column("RMS deviation of the slider acceleration from the ideal", "m/s^2"),
    "slider_acc_rms_dev_rel": Column("RMS deviation of the slider acceleration / ideal RMS"),
    # the energy audit (_energy_audit; minimal formulation and a dry joint, NaN otherwise)
    "drive_work": Column("drive work", "J"),
    "contact_dissipated": Column("energy dissipated by the contact", "J"),
    "energy_residual": Column("energy residual", "J"),
    "energy_residual_rel": Column("energy residual / gross contact work"),
    "steps": Column("solver steps"),
    "sim_wall_time": Column("solver wall time", "s"),
}

#: Parameters (from the :class:`SliderCrankParams` fields: help, unit, the command line's
#: other spellings such as ``--length``) and metrics of the study, for
#: ``python -m exuclear.study`` and its plots.
STUDY_COLUMNS = {
    **study_columns(SliderCrankParams, STUDY_PARAMETERS, {
        "friction": "friction law", "formulation": "formulation",
        "revolutions": "crank revolutions after the start-up"}),
    "rpm": Column("crank speed", "rpm"),
    "startup": Column("start-up revolutions, left out of the steady metrics"),
    **STUDY_METRICS,
}

#: Output interval of a study run [s]: below any step, so that every accepted step is
#: recorded and the energy audit's trapezoid rule and the peak force see each impact.
STUDY_EVERY_STEP = 1e-12


def study_params(values: dict) -> SliderCrankParams:
    """The :class:`SliderCrankParams` of a study's parameter set (defaults
    :data:`STUDY_PARAMETERS`); ``ValueError`` for a value the model refuses."""
    v = {**STUDY_PARAMETERS, **values}
    if isinstance(v["viscosity"], str) and v["viscosity"].lower() == "none":
        v["viscosity"] = None  # a dry joint, as the command line spells it
    if v["viscosity"] is None:
        # the dry runs of a sweep over viscosity and film model (--viscosity none,0.01
        # --film-model finite): a dry joint has no film, so the film model does not apply
        v["film_model"] = FILM_MODEL_DEFAULT
    unknown = sorted(set(v) - set(STUDY_PARAMETERS))
    if unknown:
        raise ValueError(f"unknown study parameters {unknown}; known: {', '.join(STUDY_PARAMETERS)}")
    crank_speed = crank_speed_from_rpm("rpm", v["rpm"])
    nonnegative("startup", v["startup"])
    positive("revolutions", v["revolutions"])
    fields = {k: v[k] for k in STUDY_PARAMETERS if k not in ("rpm", "startup", "revolutions")}
    return SliderCrankParams.paper(**fields, crank_speed=crank_speed,
                                   revolutions=v["startup"] + v["revolutions"])


def check_study(values: dict) -> None:
    """Raise ``ValueError`` for a study parameter set the model refuses (before any run)."""
    study_params(values)


def ideal_slider_acceleration(theta: np.ndarray, omega: float, r: float, l: float) -> np.ndarray:
    """Slider acceleration of the ideal mechanism at constant crank speed [m/s^2].

    ``x = r cos(theta) + D``, ``D = sqrt(l^2 - r^2 sin^2 theta)``, differentiated twice
    at ``theta' = omega``::

        x'' = -r w^2 cos(theta) - r^2 w^2 [cos(2 theta) / D + r^2 sin^2 cos^2 / D^3]
    """
    s, c = np.sin(theta), np.cos(theta)
    d = np.sqrt(l**2 - (r * s) ** 2)
    return -r * omega**2 * c - r**2 * omega**2 * ((c**2 - s**2) / d + r**2 * s**2 * c**2 / d**3)


def _elastic_energy(law: exuclear.ContactLaw, delta: float) -> float:
    """``int_0^delta F_el`` [J], the energy a contact stores at penetration ``delta``."""
    from scipy.integrate import quad

    return 0.0 if delta <= 0.0 else quad(law.elastic_force, 0.0, delta, epsabs=0.0, epsrel=1e-12)[0]


def mechanical_energy(model: Scene) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Kinetic plus potential energy of crank (its own inertia, not the flywheel's), rod
    and slider of a minimal-formulation run [J], from the recorded tree coordinates (crank
    angle, rod angle relative to the crank, slider x); returns ``(time, energy, crank
    speed)`` at the recorded instants."""
    if model.params.formulation != "minimal":
        raise ValueError(f"the energy is written for the minimal formulation, got {model.params.formulation!r}")
    p, mbs = model.params, model.mbs
    r, l = p.crank_length, p.rod_length
    q = np.asarray(mbs.GetSensorStoredData(model.sensors["q"]))
    q_t = np.asarray(mbs.GetSensorStoredData(model.sensors["q_t"]))
    th, thd = q[:, 1], q_t[:, 1]
    phi, phid, xd = th + q[:, 2], thd + q_t[:, 2], q_t[:, 3]
    gx = -r * np.sin(th) * thd - l / 2 * np.sin(phi) * phid
    gy = r * np.cos(th) * thd + l / 2 * np.cos(phi) * phid
    kinetic = (0.5 * (p.crank_inertia + p.crank_mass * r**2 / 4) * thd**2 + 0.5 * p.rod_mass * (gx**2 + gy**2)
               + 0.5 * p.rod_inertia * phid**2 + 0.5 * p.slider_mass * xd**2)
    potential = p.gravity * (p.crank_mass * r / 2 * np.sin(th) + p.rod_mass * (r * np.sin(th) + l / 2 * np.sin(phi)))
    return q[:, 0], kinetic + potential, thd


def _energy_audit(model: Scene) -> dict[str, float]:
    """Energy balance of a minimal-formulation run with outputs at every step [J].

    Drive work (what the flywheel gave up, ``-J_fly (w_end^2 - w_0^2) / 2``) = change of
    the links' kinetic and potential energy + energy the contact absorbed (elastic energy
    stored at the end, plus ``int (F_N - F_el) delta' + F_T v_T dt`` dissipated, trapezoid
    rule) + residual.  ``energy_residual_rel`` is the residual over the gross contact
    work ``int |F_N delta' + F_T v_T| dt``; it includes the round-off of the flywheel's
    energy (``validation/hard_cases.py`` bounds it).
    """
    t, energy, omega = mechanical_energy(model)
    change = float(energy[-1] - energy[0])
    work = float(-0.5 * FLYWHEEL_INERTIA * (omega[-1] - omega[0]) * (omega[-1] + omega[0]))
    out, law = model.joint.outputs(), model.joint.joint.law
    t, delta, f_n, rate = out["time"], out["penetration"], out["normal_force"], out["penetration_rate"]
    friction = out["tangential_force"] * out["slip_velocity"]
    elastic = np.array([law.elastic_force(d) if d > 0.0 else 0.0 for d in delta])
    stored = _elastic_energy(law, float(delta[-1])) - _elastic_energy(law, float(delta[0]))
    dissipated = float(np.trapezoid((f_n - elastic) * rate + friction, t))
    gross = float(np.trapezoid(np.abs(f_n * rate + friction), t))
    residual = work - change - stored - dissipated
    return {"drive_work": work, "contact_dissipated": dissipated, "energy_residual": residual,
            "energy_residual_rel": residual / gross if gross > 0.0 else math.nan}


def study(values: dict) -> dict:
    """One run of a slider-crank study (:mod:`exuclear.study`); parameters
    :data:`STUDY_PARAMETERS`.  The run covers ``startup + revolutions`` crank
    revolutions; "steady" metrics use the last ``revolutions`` only.

    Returns
    -------
    dict
        The metrics of :data:`STUDY_METRICS` (meaning and unit there); ``success`` and
        ``message`` of the run.
    """
    p = study_params(values)
    model = build(p)
    settings = replace(default_settings(p), output_step=STUDY_EVERY_STEP)
    sim = exuclear.simulate(model.mbs, settings)
    cols = columns(model)
    t = cols["time"]
    startup = float({**STUDY_PARAMETERS, **values}["startup"])
    t_start = 2.0 * math.pi * startup / abs(p.crank_speed)
    steady = t >= t_start
    onsets = np.asarray(model.joint.history.onset_times)
    ecc = np.hypot(cols["ecc_x"], cols["ecc_y"]) / p.clearance
    ideal = ideal_slider_acceleration(np.radians(cols["crank_angle"]), p.crank_speed, p.crank_length, p.rod_length)

    def rms(x: np.ndarray) -> float:
        ts = t[steady]
        return math.sqrt(float(np.trapezoid(x[steady] ** 2, ts)) / (ts[-1] - ts[0])) if steady.sum() > 1 else math.nan

    dev = rms(cols["slider_a"] - ideal)
    in_contact = (cols["penetration"] > 0.0).astype(float)
    # the audit counts what the metal contact dissipates, not the oil film's viscous work:
    # with a film its residual would be that work, so a lubricated run has none
    audit = (_energy_audit(model) if p.formulation == "minimal" and p.viscosity is None else
             dict.fromkeys(("drive_work", "contact_dissipated", "energy_residual", "energy_residual_rel"), math.nan))
    steady_force = cols["contact_force"][steady]
    # each steady revolution on its own (the last one may be partial): the points of a
    # bifurcation diagram
    period = 2.0 * math.pi / abs(p.crank_speed)
    revolution = np.floor((t - t_start) / period * (1.0 + 1e-12)).astype(int)
    count = math.ceil(p.revolutions - startup - 1e-9)
    by_rev = [cols["contact_force"][revolution == k] for k in range(count)]
    return {
        "peak_force": float(cols["contact_force"].max()),
        "peak_force_steady": float(steady_force.max()) if steady_force.size else math.nan,
        "peak_force_by_rev": [float(f.max()) if f.size else math.nan for f in by_rev],
        "impacts": len(onsets),
        "impacts_per_rev": float(np.sum(onsets >= t_start)) / (p.revolutions - startup),
        "impacts_by_rev": np.bincount(np.floor((onsets[onsets >= t_start] - t_start) / period).astype(int),
                                      minlength=count)[:count].tolist(),
        "max_ecc_over_c": float(ecc[steady].max()) if steady.any() else math.nan,
        "peak_joint_force": float(cols.get("joint_force", cols["contact_force"]).max()),
        "min_film_thickness": p.clearance * (1.0 - float(ecc[steady].max())) if steady.any() else math.nan,
        "metal_contact_fraction": rms(in_contact) ** 2,  # the time average of a 0/1 signal
        "slider_acc_rms_dev": dev, "slider_acc_rms_dev_rel": dev / rms(ideal),
        **audit,
        "steps": sim.steps, "sim_wall_time": sim.wall_time,
        "success": sim.success, "message": sim.message,
    }


if __name__ == "__main__":
    sys.exit(main())
