"""The impulse contact mode's Coulomb friction against the compliant contact's (issue 52).

Source problem: a 1 m steel bar of 1 kg swinging on a pin of 50 um clearance with friction,
released horizontal under gravity (the impulse mode's swinging pendulum of
tests/test_impulse_mode.py, with friction): the journal drops onto its wall, and while the
bar swings down and up the other side its held contact slides along the wall, sticks where
the bar turns, and slides back.  For each friction law (``coulomb:0.3``, and the paper's law
with its static 0.3 and dynamic 0.25) the script prints, at the run's end (1 s), the energy
the bar lost (the friction work at its pin, eq. (27)), its angle, and the accepted steps and
Newton iterations, for the compliant contact at ``--factor`` times the steps (the reference),
the compliant contact at the step, and the impulse mode at the step.  The zoo's models with
friction are rows of ``python -m validation.cost modes --models
double_pendulum_2d_friction,double_pendulum_3d_ep_friction,rigid_body_tutorial3_friction``.

::

    python -m validation.cost modes_friction [--step 1e-4] [--factor 4] [--end-time 1]
"""
from __future__ import annotations

import argparse
import math
from typing import Any

import exudyn as exu
import numpy as np
from exudyn.itemInterface import Force, MarkerNodePosition, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from validation._tables import markdown_table

#: Standard gravity [m/s^2].
G = 9.81
#: The bar: length [m], mass [kg]; the pin: bearing radius [m], clearance [m].
LENGTH, MASS, BEARING, CLEARANCE = 1.0, 1.0, 10e-3, 50e-6


def swinging_bar(friction: str, mode: str) -> tuple[exu.MainSystem, int, Any]:
    """The bar on its pin (module docstring), assembled: (mbs, the bar's node, the joint)."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.5 * LENGTH, 0, 0]))
    bar = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=MASS, inertia=MASS * LENGTH**2 / 12))
    mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)), loadVector=[0, -MASS * G, 0]))
    joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, bar], position=[0, 0, 0], bearing_radius=BEARING,
                                          journal_radius=BEARING - CLEARANCE, length=10e-3, cr=0.9, friction=friction,
                                          contact_mode=mode)
    mbs.Assemble()
    return mbs, node, joint


def bar_energy(mbs: exu.MainSystem, node: int) -> float:
    """The bar's mechanical energy [J] now (0 at rest with its centre at the pin's height)."""
    v = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity), dtype=float)
    w = float(mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity)[2])
    height = float(mbs.GetNodeOutput(node, exu.OutputVariableType.Position)[1])
    return MASS * G * height + 0.5 * MASS * float(v @ v) + 0.5 * MASS * LENGTH**2 / 12 * w * w


def run(friction: str, mode: str, step: float, end_time: float) -> dict[str, float]:
    """One run: the energy lost [J], the bar's angle [rad] at the end, steps and Newton
    iterations (the compliant contact under Exudyn's default spectral radius 0.9, the
    impulse mode under 1, which it needs)."""
    mbs, node, _ = swinging_bar(friction, mode)
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = end_time
    ss.timeIntegration.numberOfSteps = int(round(end_time / step))
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0 if mode == "impulse" else 0.9
    ss.timeIntegration.verboseMode = 0
    start = bar_energy(mbs, node)
    ok = mbs.SolveDynamic(ss)
    it = mbs.sys["dynamicSolver"].it
    return {"ok": float(ok), "lost": start - bar_energy(mbs, node),
            "angle": float(mbs.GetNodeOutput(node, exu.OutputVariableType.Rotation)[2]),
            "steps": float(it.currentStepIndex - 1), "newton": float(it.newtonStepsCount)}


def rows(step: float, factor: float, end_time: float) -> list[list[str]]:
    """Per friction law: the reference, the compliant and the impulse run (module docstring)."""
    out = []
    for friction in ("none", "coulomb:0.3", "paper"):
        reference = run(friction, "compliant", step / factor, end_time)
        for mode, result in (("compliant", run(friction, "compliant", step, end_time)),
                             ("impulse", run(friction, "impulse", step, end_time))):
            off = result["lost"] / reference["lost"] - 1.0
            turn = abs(math.remainder(result["angle"] - reference["angle"], 2.0 * math.pi))
            out.append([friction, mode, f"{result['steps']:.0f} / {result['newton']:.0f}",
                        f"{result['lost']:.6g} J ({off:+.2e})", f"{turn:.2e}" if result["ok"] else "failed"])
        out.append([friction, f"compliant, {factor:g}x the steps", f"{reference['steps']:.0f} / "
                    f"{reference['newton']:.0f}", f"{reference['lost']:.6g} J", "reference"])
    return out


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost modes_friction", description=__doc__.split("\n")[0])
    ap.add_argument("--step", type=float, default=1e-4, help="the step [s] (default %(default)s)")
    ap.add_argument("--factor", type=float, default=4.0, help="the reference's steps per step (default %(default)s)")
    ap.add_argument("--end-time", type=float, default=1.0, help="the run's end [s] (default %(default)s)")
    args = ap.parse_args(argv)
    if not args.step > 0.0 or not args.end_time > 0.0:
        ap.error(f"--step and --end-time must be positive, got {args.step}, {args.end_time}")
    if not args.factor > 1.0:
        ap.error(f"--factor must exceed 1, got {args.factor}")
    print(markdown_table(["friction", "contact", "steps / Newton", "energy lost (against the reference)",
                          "angle off the reference [rad]"], rows(args.step, args.factor, args.end_time)))
    return 0
