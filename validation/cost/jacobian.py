"""What one Newton Jacobian costs with a clearance joint, and what an analytic one could save (issue 20).

Source problem: the zoo's planar double pendulum (validation/exudyn_examples/double_pendulum_2d.py,
after Exudyn's doublePendulum2D.py), whose elbow is an ideal revolute joint or exuclear's
clearance joint.  An implicit run spends most of its time in Jacobians there (Exudyn's
``displayComputationTime``: jacobianODE2 60 % of the clearance model's run, 3.5 Jacobians per
step).  Exudyn differentiates the joint's ``ObjectConnectorRigidBodySpringDamper`` numerically:
its ``GetAvailableJacobians`` names no analytic Jacobian for a connector with a user function,
so each Jacobian evaluates the connector once per coordinate and velocity of its two markers
(2 x 6 + 1 times for two 2D bodies).  The one user function Exudyn takes an analytic Jacobian
from is ``ObjectGenericODE2.jacobianUserFunction``, an object on *nodes*, not markers.

Printed: the time of one ``ComputeJacobianODE2RHS`` of the whole model [us], median of 5 x 2000
calls at the initial state, for

- the ideal elbow (``ObjectJointRevolute2D``, Exudyn's analytic constraint Jacobian);
- the clearance joint (the compiled kernel; its probe and torque connectors are off here, as
  for every planar joint without friction or film);
- an ``ObjectGenericODE2`` on the elbow's two nodes with a Python force function (numerical
  Jacobian, as the connector's) and with a Python ``jacobianUserFunction`` too (the elbow's ideal
  joint switched off; both return zeros: the cost of the route, not of the physics).

Run nothing else meanwhile::

    python -m validation.cost jacobian
"""
from __future__ import annotations

import argparse
import statistics
import time
import warnings

import exudyn as exu
import numpy as np
from exudyn.itemInterface import ObjectGenericODE2

from validation.exudyn_examples import double_pendulum_2d

#: Jacobians per timing and timings per case (the median is printed).
CALLS, REPEATS = 2000, 5


def jacobian_time(mbs: exu.MainSystem) -> float:
    """Median time [us] of one ODE2 Jacobian (positions and velocities) of the assembled ``mbs``."""
    solver = exu.MainSolverImplicitSecondOrder()
    ss = exu.SimulationSettings()
    ss.solution.file.write = False
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = 1e-3, 1
    solver.InitializeSolver(mbs, ss)
    solver.ComputeJacobianODE2RHS(mbs, 1.0, 1.0)  # the first call sizes the matrices
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        for _ in range(CALLS):
            solver.ComputeJacobianODE2RHS(mbs, 1.0, 1.0)
        times.append((time.perf_counter() - start) / CALLS)
    solver.FinalizeSolver(mbs, ss)
    return statistics.median(times) * 1e6


def generic_elbow(with_jacobian: bool) -> exu.MainSystem:
    """The ideal double pendulum with its elbow joint switched off and an ObjectGenericODE2 on
    the elbow's two nodes in its place (zero force; with or without a Jacobian function)."""
    model = double_pendulum_2d.build(False, 0.01)
    mbs = model.mbs
    revolute = [i for i in range(mbs.systemData.NumberOfObjects())
                if mbs.GetObject(i)["objectType"] == "JointRevolute2D"]
    mbs.SetObjectParameter(revolute[1], "activeConnector", False)  # the elbow (the shoulder is first)
    nodes = sorted({int(mbs.GetObject(i)["nodeNumber"]) for i in range(mbs.systemData.NumberOfObjects())
                    if mbs.GetObject(i)["objectType"] == "RigidBody2D"})
    n = 3 * len(nodes)
    zero_force, zero_jacobian = np.zeros(n), np.zeros((n, n))
    item = {"nodeNumbers": nodes, "massMatrix": np.zeros((n, n)),
            "forceUserFunction": lambda mbs, t, i, q, q_t: zero_force}
    if with_jacobian:
        item["jacobianUserFunction"] = lambda mbs, t, i, q, q_t, f, f_t: zero_jacobian
    mbs.AddObject(ObjectGenericODE2(**item))
    mbs.Assemble()
    return mbs


def main(argv: list[str] | None = None) -> int:
    argparse.ArgumentParser(prog="python -m validation.cost jacobian", description=__doc__.split("\n")[0]).parse_args(argv)
    warnings.simplefilter("ignore")  # the builders' unit notes are not the subject here
    rows = [
        ("ideal elbow (ObjectJointRevolute2D)", double_pendulum_2d.build(False, 0.01).mbs),
        ("clearance joint (connector, compiled kernel, numerical Jacobian)", double_pendulum_2d.build(True, 0.01).mbs),
        ("ObjectGenericODE2 on the two nodes, Python force, numerical Jacobian", generic_elbow(False)),
        ("ObjectGenericODE2 on the two nodes, Python force and jacobianUserFunction", generic_elbow(True)),
    ]
    print(f"one ODE2 Jacobian of the planar double pendulum [us], median of {REPEATS} x {CALLS} calls\n")
    print("| elbow | Jacobian [us] |")
    print("|---|---|")
    for label, mbs in rows:
        print(f"| {label} | {jacobian_time(mbs):.2f} |")
    return 0
