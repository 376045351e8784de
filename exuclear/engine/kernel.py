"""The compiled kernel: loading it, and checking that Exudyn calls it without Python.

Exudyn converts a user function with pybind11's ``std::function`` caster.  For a
pybind11-bound C++ function that captures nothing and has exactly Exudyn's signature, it
keeps the raw function pointer and calls it with no Python in between; for anything else
it silently wraps the object and calls through Python.  So at import a tiny system (a
journal dropped into a fixed bearing) runs with the compiled functions, and the kernel's
counter of calls that came through pybind11's Python dispatcher must stay at zero.

Outcomes (:data:`STATUS`): ``"direct"`` (compiled, called without Python; the default
backend is then ``"compiled"``), ``"through-python"`` (it works but Exudyn calls it
through Python, e.g. a pybind11 or compiler mismatch: the default falls back to
``"python"``), ``"missing"`` (the extension was not built: no compiler at install time).
The last two warn once, saying why.
"""
from __future__ import annotations

import importlib
import warnings
from types import ModuleType

from ..exceptions import KernelWarning

STATUS_DIRECT, STATUS_THROUGH_PYTHON, STATUS_MISSING = "direct", "through-python", "missing"


def _load() -> tuple[ModuleType | None, str, str]:
    try:
        _ckernel = importlib.import_module("exuclear._ckernel")
    except ImportError as err:
        return None, STATUS_MISSING, (f"the compiled kernel exuclear._ckernel is not built ({err}); the clearance joint "
                                      "runs its Python kernel, 3 to 10 times slower. Reinstall with a C++ compiler "
                                      "and the Python headers present (pip install builds it)")
    try:
        before = _ckernel.dispatch_calls()
        calls = _self_test(_ckernel)
        through_python = _ckernel.dispatch_calls() - before
    except Exception as err:  # any failure here means: do not use it
        return None, STATUS_THROUGH_PYTHON, f"the compiled kernel failed its self-test ({type(err).__name__}: {err})"
    if calls == 0 or through_python > 0:
        return _ckernel, STATUS_THROUGH_PYTHON, (
            f"Exudyn calls the compiled kernel through Python ({through_python} of {calls} calls), so it brings no "
            "speed: the extension was built with another pybind11 or compiler ABI than Exudyn's (pybind11 must be "
            ">=2.10,<3). The clearance joint runs its Python kernel")
    return _ckernel, STATUS_DIRECT, ""


def _self_test(module: ModuleType) -> int:
    """Run 0.1 ms of a journal impact with the compiled functions; return the kernel's force calls."""
    import exudyn as exu
    from exudyn.itemInterface import (
        MarkerBodyRigid,
        NodeGenericData,
        NodeRigidBody2D,
        ObjectConnectorRigidBodySpringDamper,
        ObjectGround,
        ObjectRigidBody2D,
        VObjectConnectorRigidBodySpringDamper,
    )

    from ..joint import make_joint
    from .layout import DATA_COLUMNS, MAIN, parameters

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialVelocities=[0.3, 0, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.04, inertia=1e-6))
    joint = make_joint(journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, law="wang-liu", cr=0.9)
    joint_id = module.new_joint()
    data = mbs.AddNode(NodeGenericData(initialCoordinates=[0.0] * len(DATA_COLUMNS),
                                       numberOfDataCoordinates=len(DATA_COLUMNS)))
    mbs.AddObject(ObjectConnectorRigidBodySpringDamper(
        markerNumbers=[mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[-1e-4, 0, 0])),
                       mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[0, 0, 0]))],
        nodeNumber=data, stiffness=parameters(joint, joint_id, MAIN, 5e-5),
        springForceTorqueUserFunction=module.force_torque, postNewtonStepUserFunction=module.post_newton,
        visualization=VObjectConnectorRigidBodySpringDamper(show=False)))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = 1e-4
    ss.timeIntegration.numberOfSteps = 20
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.DOPRI5)
    calls = module.calls(joint_id)[0]
    module.release(joint_id)  # its slot is free for the first real joint
    return calls


COMPILED, STATUS, REASON = _load()
if STATUS != STATUS_DIRECT:
    # one line, with no source line under it (the cause is the install, not a line of code)
    warnings.warn_explicit(REASON, KernelWarning, filename="exuclear", lineno=0, module="exuclear.engine.kernel")


def default_backend() -> str:
    """``"compiled"`` where the self-test passed, else ``"python"``."""
    return "compiled" if STATUS == STATUS_DIRECT else "python"
