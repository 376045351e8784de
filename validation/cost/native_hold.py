"""The impulse mode's native hold (exuclear.engine.impulse_hold) on a journal that slides
along its wall: its reaction against the ideal joint's, the step-to-step alternation of its
multiplier and of its normal rate (index 3 under the trapezoidal rule, settled by
exuclear.engine.settling), and the energy it keeps.

The scene: a 1 m steel bar of 1 kg on a frictionless pin with 50 um clearance (R_B 10 mm),
released horizontal (the test scene of tests/test_impulse_mode.py): the journal drops onto
the wall, comes to rest, and while the bar swings its load turns, so that the held contact
slides along the wall.  The ideal revolute joint's reaction at the run's own state is
``m a_cm - m g``, with ``a_cm`` from the bar's angle and spin, ``alpha = (r x m g) / (m L^2 / 3)``.
Rows: from ``--window`` s on (the bounces over), the largest relative difference of the
reported reaction (the multiplier's three-step mean) and of the raw multiplier from the
ideal joint's, the multiplier's largest alternation ``|F_n - (F_(n-1) + F_(n+1)) / 2|`` over
the load, the normal rate's largest ``|v_n|`` (the hold's own output), the energy's largest
change [J], and the contact's releases (onsets after the first rest).

::

    python -m validation.cost native_hold [--steps 1e-4,2.5e-5] [--end 1.0] [--window 0.1]
"""
from __future__ import annotations

import argparse
import math
import warnings

import exudyn as exu
import numpy as np
from exudyn.itemInterface import Force, MarkerNodePosition, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from validation._tables import markdown_table

G = 9.81
LENGTH, MASS, CLEARANCE = 1.0, 1.0, 50e-6  # m, kg, m


def swinging_bar(step: float, end: float) -> tuple[np.ndarray, list, np.ndarray]:
    """The scene's run: per accepted step (t, ideal reaction, energy, raw multiplier, normal
    rate), the joint's impacts, and its outputs' reaction column."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.5 * LENGTH, 0, 0]))
    bar = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=MASS, inertia=MASS * LENGTH**2 / 12))
    mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)), loadVector=[0, -MASS * G, 0]))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the clearance ratio's note: chosen here
        joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, bar], position=[0, 0, 0],
                                              bearing_radius=10e-3, journal_radius=10e-3 - CLEARANCE,
                                              length=10e-3, cr=0.9, contact_mode="impulse")
    mbs.Assemble()
    ov, rows = exu.OutputVariableType, []

    def record(mbs: exu.MainSystem, t: float) -> bool:
        phi = mbs.GetNodeOutput(node, ov.Rotation)[2]
        w = mbs.GetNodeOutput(node, ov.AngularVelocity)[2]
        v = mbs.GetNodeOutput(node, ov.Velocity)
        r = 0.5 * LENGTH * np.array([math.cos(phi), math.sin(phi)])
        alpha = -r[0] * MASS * G / (MASS * LENGTH**2 / 3)
        ideal = MASS * (-w * w * r + alpha * np.array([-r[1], r[0]])) + np.array([0.0, MASS * G])
        energy = MASS * G * mbs.GetNodeOutput(node, ov.Position)[1] + 0.5 * MASS * (v @ v) + \
            0.5 * MASS * LENGTH**2 / 12 * w * w
        hold = joint.holdNumber
        force = float(np.ravel(mbs.GetObjectOutput(hold, ov.Force))[0])
        d, u = mbs.GetObjectOutput(hold, ov.Displacement), mbs.GetObjectOutput(hold, ov.Velocity)
        length = float(np.linalg.norm(d))  # 0 at the start: the journal at the bearing's centre
        rows.append((t, np.linalg.norm(ideal), energy, force, float(d @ u) / length if length else 0.0))
        return True

    mbs.SetPostStepUserFunction(record)
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = end, int(round(end / step))
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0
    ss.timeIntegration.verboseMode = 0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mbs.SolveDynamic(ss)
    return np.array(rows), joint.impacts(), joint.outputs()["normal_force"]


def row(step: float, end: float, window: float) -> list[str]:
    data, impacts, reported = swinging_bar(step, end)
    t, ideal, energy, force, rate = data[-len(reported):].T  # (the post-step function also runs at the start)
    held = t >= window
    alternation = np.abs(force[1:-1] - 0.5 * (force[:-2] + force[2:]))[held[1:-1]]
    rests = [i for i in impacts if i.restitution == 0.0]
    releases = len([i for i in rests if i.onset_time > rests[0].onset_time]) if rests else 0
    return [f"{step:g}", f"{t[-1]:.3g}",
            f"{np.abs(reported[held] / ideal[held] - 1).max():.2e}",
            f"{np.abs(force[held] / ideal[held] - 1).max():.2e}",
            f"{alternation.max() / (MASS * G):.2e}", f"{np.abs(rate[held]).max():.2e}",
            f"{np.abs(energy[held] - energy[held][0]).max():.2e}", str(releases)]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost native_hold", description=__doc__.split("\n")[0])
    ap.add_argument("--steps", default="1e-4,2.5e-5", help="the steps [s], comma-separated")
    ap.add_argument("--end", type=float, default=1.0, help="the run's end [s]")
    ap.add_argument("--window", type=float, default=0.1, help="the rows' window starts here [s]")
    args = ap.parse_args(argv)
    header = ["step [s]", "ran to [s]", "reaction off ideal", "raw multiplier off ideal", "alternation / m g",
              "max |v_n| [m/s]", "energy change [J]", "releases"]
    print(markdown_table(header, [row(float(h), args.end, args.window) for h in args.steps.split(",")]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
