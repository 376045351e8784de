"""exuclear: clearance joints (revolute, spherical, translational, pin-in-slot) for the Exudyn multibody engine.

The public API is the names of ``__all__`` below, by role:

- **joints**: :func:`CreateClearanceJoint`, :func:`AddClearanceJoint` (the revolute joint)
  :func:`CreateSphericalClearanceJoint` (a ball in a socket),
  :func:`CreatePrismaticClearanceJoint` (a slider in a guide) and
  :func:`CreatePinSlotClearanceJoint` (a pin in a slot), Exudyn items; they
  return a :class:`ClearanceJointHandle`; and the physics of one joint,
  :class:`ClearanceJoint` with its :class:`BearingGeometry`, built by :func:`make_joint`;
  :class:`Lubrication` (viscosity, film model) makes a joint lubricated (``lubrication=``),
  :class:`Wear` (Archard's law) makes its surfaces wear (``wear=``), and
  :func:`predict_wear` extrapolates one cycle's wear over many;
- **contact laws**: :func:`contact_law` is the one way to build a :class:`ContactLaw`,
  by the name of a named law (``"wang-liu"``) or of a stiffness model and a damping
  model (``"pereira+gonthier"``);
- **friction**: :func:`friction_law` (``"none"``, ``"coulomb:MU"``, ``"paper"``);
- **materials**: :class:`Material`, :data:`MATERIALS`, :func:`composite_modulus`;
- **settings and runs**: :class:`SolverSettings`, :func:`simulate` and its
  :class:`SimulationResult`;
- **convergence check**: :func:`check_convergence`, :class:`RunRecord`,
  :class:`ConvergenceResult`;
- **studies**: :class:`Study`, :func:`grid`, :func:`sample`, :func:`run_study`;
- **warnings**: :class:`UnitWarning`, :class:`ValidityWarning`, :class:`AccuracyWarning`.

Everything else stays importable from its module: the models behind the laws
(:mod:`exuclear.contact`: ``WangLiu``, ``STIFFNESS_MODELS``, ``DAMPING_MODELS``, the
laws' velocity floor ``V_MIN_DEFAULT``, ...), the solver methods (:mod:`exuclear.settings`:
``METHODS``), the friction classes (:mod:`exuclear.friction`), the contact kinematics
(:mod:`exuclear.geometry`), the contact history (:mod:`exuclear.history`) and the engine
glue (:mod:`exuclear.engine`: the kernel backends ``BACKENDS`` and ``DEFAULT_BACKEND``,
the joint outputs ``OUTPUT_COLUMNS``, ``DATA_COLUMNS``, ``simulation_settings``,
``KernelWarning``, ``unheld_motion`` and its ``OutOfPlaneWarning``, ...).  Physics
without exudyn: :mod:`~exuclear.contact`,
:mod:`~exuclear.friction`, :mod:`~exuclear.materials`, :mod:`~exuclear.geometry`,
:mod:`~exuclear.joint`; see ``docs/physics.md`` for the equations.

Of the third-party packages, ``import exuclear`` imports numpy and exudyn only;
matplotlib, pandas, tqdm, scipy and dask are imported where a function needs them
(``tests/test_api.py``).
"""
from .contact import ContactLaw, contact_law
from .convergence import ConvergenceResult, RunRecord, check_convergence
from .engine import (
    AddClearanceJoint,
    ClearanceJointHandle,
    CreateClearanceJoint,
    CreatePinSlotClearanceJoint,
    CreatePrismaticClearanceJoint,
    CreateSphericalClearanceJoint,
    SimulationResult,
    simulate,
)
from .exceptions import AccuracyWarning, UnitWarning, ValidityWarning
from .film import Lubrication
from .friction import friction_law
from .geometry import BearingGeometry
from .joint import ClearanceJoint, make_joint
from .materials import MATERIALS, Material, composite_modulus
from .settings import SolverSettings
from .wear import Wear, predict_wear

# The study names are imported on first use (PEP 562), not here: the study runner brings
# pandas and tqdm along when it runs, and ``import exuclear`` stays light.  ``python -m
# exuclear.study`` runs the package's ``__main__``, which nothing imports before runpy runs
# it, so runpy's double-import warning cannot arise, in the parent or in a worker.
_LAZY = {"Study": "study", "grid": "study", "sample": "study", "run_study": "study"}


def __getattr__(name: str):
    if name in _LAZY:
        import importlib

        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value  # found directly from now on
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_LAZY})


__version__ = "0.1.0"

__all__ = [
    # joints
    "CreateClearanceJoint", "AddClearanceJoint", "CreateSphericalClearanceJoint", "CreatePrismaticClearanceJoint",
    "CreatePinSlotClearanceJoint", "ClearanceJointHandle", "ClearanceJoint", "BearingGeometry",
    "make_joint", "Lubrication", "Wear", "predict_wear",
    # contact laws
    "contact_law", "ContactLaw",
    # friction
    "friction_law",
    # materials
    "Material", "MATERIALS", "composite_modulus",
    # settings and runs
    "SolverSettings", "simulate", "SimulationResult",
    # convergence check
    "check_convergence", "RunRecord", "ConvergenceResult",
    # studies
    "Study", "grid", "sample", "run_study",
    # warnings
    "UnitWarning", "ValidityWarning", "AccuracyWarning",
]
