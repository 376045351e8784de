"""The Exudyn adapter: the only package of exuclear that imports exudyn or reads engine state.

Its modules in layers, each importing only from the layers below it
(``tests/test_structure.py`` holds the package to that: no import cycle):

1. **simulate** -- :mod:`~exuclear.engine.solver`: ``simulate``, a convenience around
   ``SolveDynamic``, with its settings mapping and its result;
2. **items and frames** -- :mod:`~exuclear.engine.connector`: the clearance joint as Exudyn
   items (``CreateClearanceJoint``, ``AddClearanceJoint``, the helper connectors), with the
   builders' argument checks (:mod:`~exuclear.engine.arguments`), the joint's drawing
   (:mod:`~exuclear.engine.drawing`) and the deprecated body-point builder
   ``add_clearance_joint`` (:mod:`~exuclear.engine.legacy`);
3. **the handle** -- :mod:`~exuclear.engine.handle`: the handle the builders return (item
   numbers, physics, results), its outputs (:mod:`~exuclear.engine.outputs`) and its
   backends (:mod:`~exuclear.engine.backends`: compiled and Python, the same methods);
4. **diagnostics** -- :mod:`~exuclear.engine.diagnostics`: the model checks before a run
   and the joint's notes after it (steps not resolved, chatter, a stopped run);
5. **steering** -- :mod:`~exuclear.engine.steering`: what the joint sets and asks of the
   solver's run (the run-start record, step growth, the Jacobian vote, Newton's settings);
6. **the model** -- :mod:`~exuclear.engine.bodies`: the masses and contact period of a
   joint's bodies; :mod:`~exuclear.engine.registry`: the joints of a system;
7. **the kernels** -- :mod:`~exuclear.engine.kernel`: the compiled kernel
   (``exuclear/_kernel/``) and its import self-test; :mod:`~exuclear.engine._python_kernel`:
   the same user functions in Python, in modules of the same names as the compiled
   kernel's files (layout, kinematics, laws, contacts, film, joint_state, step_control,
   bindings); :mod:`~exuclear.engine.layout`: where parameters and outputs sit in the items
   (one named table, shared with the compiled kernel).

The warnings are those of :mod:`exuclear.exceptions`.
"""
from ..exceptions import AccuracyWarning, KernelWarning, OutOfPlaneWarning
from .arguments import default_penetration_limit
from .connector import BACKENDS, DEFAULT_BACKEND, AddClearanceJoint, CreateClearanceJoint
from .diagnostics import unheld_motion
from .handle import ClearanceJointHandle
from .layout import DATA_COLUMNS
from .legacy import add_clearance_joint
from .outputs import OUTPUT_COLUMNS
from .prismatic import CreatePrismaticClearanceJoint
from .slot import CreatePinSlotClearanceJoint
from .solver import SimulationResult, simulate, simulation_settings
from .spherical import CreateSphericalClearanceJoint

__all__ = ["BACKENDS", "DEFAULT_BACKEND", "OUTPUT_COLUMNS", "DATA_COLUMNS", "AddClearanceJoint", "ClearanceJointHandle",
           "CreateClearanceJoint", "CreateSphericalClearanceJoint", "CreatePrismaticClearanceJoint", "CreatePinSlotClearanceJoint", "add_clearance_joint", "default_penetration_limit", "KernelWarning",
           "AccuracyWarning", "SimulationResult", "simulate", "simulation_settings", "OutOfPlaneWarning",
           "unheld_motion"]
