"""The Exudyn adapter: the only package of exuclear that imports exudyn or reads engine state.

- :mod:`~exuclear.engine.connector`: the clearance joint as Exudyn items
  (``CreateClearanceJoint``, ``AddClearanceJoint``, the helper connectors);
- :mod:`~exuclear.engine.handle`: the handle they return, and its backends
  (:mod:`~exuclear.engine.backends`: compiled and Python, the same methods);
- :mod:`~exuclear.engine.outputs`, :mod:`~exuclear.engine.drawing`,
  :mod:`~exuclear.engine.checks`: the handle's outputs, the joint's drawing, the
  builders' argument checks;
- :mod:`~exuclear.engine.kernel`: the compiled kernel and its import self-test;
- :mod:`~exuclear.engine._python_kernel`: the same user functions in Python;
- :mod:`~exuclear.engine.layout`: where parameters and outputs sit in the items (one
  named table, shared with the compiled kernel);
- :mod:`~exuclear.engine.solver`: ``simulate``, a convenience around ``SolveDynamic``.
"""
from ._diagnostics import OutOfPlaneWarning, unheld_motion
from .checks import default_penetration_limit
from .connector import BACKENDS, DEFAULT_BACKEND, AddClearanceJoint, CreateClearanceJoint, add_clearance_joint
from .handle import ClearanceJointHandle
from .kernel import KernelWarning
from .layout import DATA_COLUMNS
from .outputs import OUTPUT_COLUMNS
from .solver import AccuracyWarning, SimulationResult, simulate, simulation_settings

__all__ = ["BACKENDS", "DEFAULT_BACKEND", "OUTPUT_COLUMNS", "DATA_COLUMNS", "AddClearanceJoint", "ClearanceJointHandle",
           "CreateClearanceJoint", "add_clearance_joint", "default_penetration_limit", "KernelWarning",
           "AccuracyWarning", "SimulationResult", "simulate", "simulation_settings", "OutOfPlaneWarning",
           "unheld_motion"]
