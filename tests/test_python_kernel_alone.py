"""The library where the compiled kernel cannot be imported (an install without a compiler):
it warns once at import (``KernelWarning``), defaults to the Python kernel, and a joint
gives the compiled kernel's results.  Checked in a fresh interpreter in which an import
hook refuses ``exuclear._ckernel``, as a missing extension does."""
from __future__ import annotations

import json
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np

import exuclear
from exuclear.engine import KernelWarning, kernel
from validation import translational as val

TESTS = Path(__file__).resolve().parent
#: What the fresh interpreter runs: the import hook, the import of exuclear with its warnings
#: recorded, then :func:`turning_guide` on the default backend; one line of JSON.
CHILD = """
import importlib.abc, json, sys, warnings

class NoCompiledKernel(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name == "exuclear._ckernel":
            raise ImportError("refused by tests/test_python_kernel_alone.py")
        return None

sys.meta_path.insert(0, NoCompiledKernel())
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    from exuclear.engine import kernel
sys.path.insert(0, {tests!r})
from test_python_kernel_alone import turning_guide
print(json.dumps({{"status": kernel.STATUS, "backend": kernel.default_backend(),
                  "warnings": [(w.category.__name__, str(w.message)) for w in caught],
                  "run": turning_guide(None)}}))
"""
#: Output columns compared between the two runs.
COLUMNS = ("penetration", "penetration_rate", "normal_force", "tangential_force", "slip_velocity", "ecc_x", "ecc_y")


def turning_guide(backend: str | None) -> dict:
    """A slider rattling in a turning guide with Coulomb friction for 20 ms
    (:func:`validation.translational.slider_in_guide`: every term of the corners' kinematics
    and loads): the joint's outputs, the final coordinates and the impacts, as plain lists."""
    mbs, joint, _ = val.slider_in_guide(backend, velocity=(0.2, 0.3, 3.0), gravity=0.0, guide_spin=5.0,
                                        friction="coulomb:0.2")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=0.02, **val.SETTINGS))
    out = joint.outputs()
    return {"backend": joint.backend, "success": result.success, "time": out["time"].tolist(),
            **{c: out[c].tolist() for c in COLUMNS}, "q": mbs.systemData.GetODE2Coordinates().tolist(),
            "pairs": [r.pair for r in joint.impacts()], "impacts": [list(r[:-1]) for r in joint.impacts()]}


def test_without_the_compiled_kernel_the_python_kernel_warns_once_and_gives_the_same_run():
    child = subprocess.run([sys.executable, "-c", CHILD.format(tests=str(TESTS))], capture_output=True, text=True,
                           timeout=120, cwd=TESTS.parent)
    assert child.returncode == 0, child.stderr
    alone = json.loads(child.stdout.strip().splitlines()[-1])
    assert (alone["status"], alone["backend"], alone["run"]["backend"]) == (kernel.STATUS_MISSING, "python", "python")
    told = [text for category, text in alone["warnings"] if category == KernelWarning.__name__]
    assert len(told) == 1 and "the compiled kernel exuclear._ckernel is not built" in told[0], alone["warnings"]

    here = turning_guide(kernel.default_backend())  # the compiled kernel where this install has it
    assert alone["run"]["success"] and here["success"]
    assert alone["run"]["pairs"] == here["pairs"] and len(here["pairs"]) >= 4  # the same contacts, several corners
    for key in ("time", *COLUMNS, "q", "impacts"):
        # the same formulas in the same order, no fused multiply-add (setup.py): round-off only, the
        # bound tests/test_translational_joint.py holds the two kernels to on this scene
        np.testing.assert_allclose(alone["run"][key], here[key], rtol=1e-12, atol=1e-15, err_msg=key)
