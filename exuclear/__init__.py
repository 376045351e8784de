"""exuclear: revolute clearance joints for the Exudyn multibody engine.

Physics (pure Python, no exudyn): :mod:`~exuclear.contact`, :mod:`~exuclear.friction`,
:mod:`~exuclear.materials`, :mod:`~exuclear.geometry`, :mod:`~exuclear.joint`.
Engine glue: :mod:`~exuclear.engine`.  See ``docs/physics.md`` for the
equations.
"""
from ._checks import UnitWarning
from .contact import (
    ALIASES,
    CONTACT_LAWS,
    DAMPING_MODELS,
    DEFAULT_LAW,
    STIFFNESS_MODELS,
    V_MIN_DEFAULT,
    ContactLaw,
    Flores,
    Hertz,
    HuntCrossley,
    LankaraniNikravesh,
    ValidityWarning,
    WangLiu,
    compose_law,
    contact_law,
    damping_model,
    restitution_of_damping,
    stiffness_model,
)
from .convergence import ConvergenceResult, JointRecord, RunRecord, check_convergence, refined_settings
from .engine import (
    BACKENDS,
    DATA_COLUMNS,
    DEFAULT_BACKEND,
    OUTPUT_COLUMNS,
    AccuracyWarning,
    AddClearanceJoint,
    ClearanceJointHandle,
    CreateClearanceJoint,
    KernelWarning,
    SimulationResult,
    add_clearance_joint,
    simulate,
    simulation_settings,
)
from .friction import (
    FRICTION_NAMES,
    NO_FRICTION,
    Coulomb,
    FrictionLaw,
    ModifiedCoulomb,
    NoFriction,
    friction_law,
    smooth_step,
)
from .geometry import BearingGeometry, ContactKinematics, JointLoads, contact_kinematics, joint_loads
from .history import ContactState, ImpactRecord
from .joint import ClearanceJoint, JointResponse, make_joint
from .materials import MATERIALS, Material, composite_modulus, material
from .settings import METHODS, SolverSettings
from .study import Study, grid, run_study, sample

__version__ = "0.1.0"

__all__ = [
    "ALIASES", "DAMPING_MODELS", "STIFFNESS_MODELS", "ValidityWarning", "compose_law", "damping_model",
    "restitution_of_damping", "stiffness_model",
    "CONTACT_LAWS", "DEFAULT_LAW", "V_MIN_DEFAULT", "ContactLaw", "Flores", "Hertz", "HuntCrossley",
    "LankaraniNikravesh", "WangLiu", "contact_law",
    "BACKENDS", "DATA_COLUMNS", "DEFAULT_BACKEND", "OUTPUT_COLUMNS", "AddClearanceJoint", "ClearanceJointHandle", "CreateClearanceJoint",
    "KernelWarning", "AccuracyWarning", "SimulationResult", "add_clearance_joint", "simulate", "simulation_settings",
    "ContactState", "ImpactRecord",
    "FRICTION_NAMES", "NO_FRICTION", "Coulomb", "FrictionLaw", "ModifiedCoulomb", "NoFriction",
    "friction_law", "smooth_step",
    "BearingGeometry", "ContactKinematics", "JointLoads", "contact_kinematics", "joint_loads",
    "ClearanceJoint", "JointResponse", "make_joint",
    "MATERIALS", "Material", "composite_modulus", "material",
    "METHODS", "SolverSettings", "Study", "grid", "run_study", "sample", "UnitWarning",
    "ConvergenceResult", "JointRecord", "RunRecord", "check_convergence", "refined_settings",
]
