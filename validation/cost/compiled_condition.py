"""Whether Exudyn calls a compiled condition without Python: the route a compiled
contact-following mode would take (issue 34, docs/guide/contact_following.md, "Where the
time goes").

The following mode holds a contact by an ``ObjectConnectorCoordinateVector`` over the
coordinates of the joint's two bodies.  On the Python kernel its rows ``n^T dv/dq_t`` are
set from Python at every step (``exuclear/engine/follow_conditions.py``), the largest part of
the mode's cost per step.  The same connector takes a ``constraintUserFunction`` and a
``jacobianUserFunction``, which receive the markers' coordinates and velocities at Newton's
iterate.  This script builds a probe module (``compiled_condition_probe.cpp`` beside it,
with pybind11 and the machine's C++ compiler) whose two functions have exactly Exudyn's
signatures, and runs a mass point of 1 kg held on a circle of 1 m under gravity (the
condition of a journal's centre in a fixed bearing) for 1 s in 1000 generalized-alpha steps,
at position and at velocity level, with those functions as Python functions and as the
compiled ones; and, for scale, with Exudyn's own ``ObjectConnectorDistance``.

Printed per case: the median wall time of ``--repeats`` runs, the compiled functions' calls
and how many of them came through pybind11's Python dispatcher (0: Exudyn called the
function pointer), the largest ``| |p| - 1 |``, and the end position's difference from the
Python functions' run.  Needs pybind11 (``pip install "pybind11>=2.10,<3"``, the build
requirement of exuclear's own kernel) and a C++ compiler.  Run nothing else meanwhile::

    python -m validation.cost compiled_condition
"""
from __future__ import annotations

import argparse
import importlib.util
import os
import shlex
import statistics
import subprocess
import sys
import sysconfig
import tempfile
import time
from pathlib import Path

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadForceVector,
    MarkerNodeCoordinates,
    MarkerNodePosition,
    NodePoint2D,
    NodePointGround,
    ObjectConnectorCoordinateVector,
    ObjectConnectorDistance,
    ObjectMassPoint2D,
    SensorNode,
)

SOURCE = Path(__file__).with_name("compiled_condition_probe.cpp")
#: The run: end time [s] and steps.
END, STEPS = 1.0, 1000


def build_probe(directory: str):
    """Compiles the probe module into ``directory`` and imports it; says what is missing
    where it cannot."""
    try:
        import pybind11
    except ImportError:
        sys.exit('compiled_condition needs pybind11: pip install "pybind11>=2.10,<3"')
    target = Path(directory) / ("compiled_condition_probe" + sysconfig.get_config_var("EXT_SUFFIX"))
    kernel = Path(__file__).resolve().parents[2] / "exuclear" / "_kernel"  # layout.hpp: the MainSystem caster
    includes = [f"-I{pybind11.get_include()}", f"-I{sysconfig.get_paths()['include']}", f"-I{kernel}"]
    command = [*shlex.split(os.environ.get("CXX", "c++")), "-O2", "-shared", "-fPIC", "-std=c++17", *includes,
               str(SOURCE), "-o", str(target)]
    try:
        subprocess.run(command, check=True, capture_output=True, text=True)
    except (OSError, subprocess.CalledProcessError) as err:
        sys.exit(f"compiled_condition: the probe module did not build ({' '.join(command)}): "
                 f"{getattr(err, 'stderr', '') or err}")
    spec = importlib.util.spec_from_file_location("compiled_condition_probe", target)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def python_functions():
    """The probe's two functions in Python."""
    def constraint(mbs, t, item, q, q_t, velocity_level):
        r = np.hypot(q[0], q[1])
        return [(q[0] * q_t[0] + q[1] * q_t[1]) / r] if velocity_level else [r - 1.0]

    def jacobian(mbs, t, item, q, q_t, velocity_level):
        r = np.hypot(q[0], q[1])
        return np.array([[q[0] / r, q[1] / r]])

    return constraint, jacobian


def run(functions: tuple, velocity_level: bool) -> tuple[float, np.ndarray]:
    """One run of the mass point on its circle; its wall time [s] and positions."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    node = mbs.AddNode(NodePoint2D(referenceCoordinates=[0, 0], initialCoordinates=[1.0, 0.0]))
    mbs.AddObject(ObjectMassPoint2D(mass=1.0, nodeNumber=node))
    mbs.AddLoad(LoadForceVector(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)),
                                loadVector=[0.0, -9.81, 0.0]))
    if functions is None:  # Exudyn's own distance constraint, for scale
        markers = [mbs.AddMarker(MarkerNodePosition(nodeNumber=n)) for n in (ground, node)]
        mbs.AddObject(ObjectConnectorDistance(markerNumbers=markers, distance=1.0))
    else:
        markers = [mbs.AddMarker(MarkerNodeCoordinates(nodeNumber=n)) for n in (ground, node)]
        mbs.AddObject(ObjectConnectorCoordinateVector(
            markerNumbers=markers, scalingMarker0=np.zeros((1, 1)), velocityLevel=velocity_level,
            constraintUserFunction=functions[0], jacobianUserFunction=functions[1]))
    sensor = mbs.AddSensor(SensorNode(nodeNumber=node, storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = END, STEPS
    ss.timeIntegration.verboseMode, ss.solution.file.write = 0, False
    ss.solution.sensors.writePeriod = END / STEPS
    start = time.perf_counter()
    mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    return time.perf_counter() - start, np.asarray(mbs.GetSensorStoredData(sensor))[:, 1:3]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m validation.cost compiled_condition",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeats", type=int, default=5, help="runs per median (default 5)")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as directory:
        probe = build_probe(directory)
        compiled = (probe.constraint, probe.jacobian)
        print(f"| level | functions | wall [ms], median of {args.repeats} | calls (constraint, Jacobian) | "
              "through Python's dispatcher | largest ||p| - 1| | end off the Python run |")
        print("|---|---|---|---|---|---|---|")
        for velocity_level in (False, True):
            reference = None
            cases = [("Python", python_functions()), ("compiled", compiled)]
            if not velocity_level:
                cases.append(("Exudyn's ObjectConnectorDistance", None))
            for label, functions in cases:
                walls = []
                for _ in range(args.repeats):
                    before = probe.counts()
                    wall, path = run(functions, velocity_level)
                    walls.append(wall)
                    after = probe.counts()
                dispatch, constraint, jacobian = (a - b for a, b in zip(after, before))
                reference = path if reference is None else reference
                print(f"| {'velocity' if velocity_level else 'position'} | {label} | "
                      f"{1e3 * statistics.median(walls):.1f} | "
                      f"{constraint}, {jacobian} | {dispatch} | "
                      f"{np.abs(np.hypot(path[:, 0], path[:, 1]) - 1.0).max():.2e} | "
                      f"{np.abs(path[-1] - reference[-1]).max():.1e} |", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
