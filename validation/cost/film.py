"""Cost of the compiled film force per evaluation, against the dry contact's (issue 23, part 5).

The brief: the compiled film force per evaluation at most 3 times the dry contact's.  The
kernel's ``time_force`` evaluates the joint connector's force function (parameter decoding
included, as Exudyn's call does) many times at one state; this script times

- ``dry contact``: a dry joint in contact (penetration 1 um, closing, with Coulomb friction):
  the contact law's full path;
- ``film``: the same joint lubricated, the journal at eps 0.5 (the film alone), for each
  model;
- ``film + contact``: lubricated and in contact (the film blended near the wall, plus the
  dry law);

and a whole run: the steady-load scene of tests/test_lubricated_joint.py per step,
lubricated against dry (the dry journal resting on the wall).  Medians of repeated
trials, the cases of a trial timed one after the other; the machine (2 cores) is shared, so
single numbers vary by tens of per cent::

    python -m validation.cost film
"""
from __future__ import annotations

import argparse
import statistics
import time

import exudyn as exu
from exudyn.itemInterface import LoadForceVector, MarkerBodyPosition, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.engine import kernel
from exuclear.engine.layout import MAIN, parameters

R, C, L = 0.02, 40e-6, 0.01     # journal radius, clearance, length [m]: B/D = 1/4
ETA, OMEGA = 0.05, 100.0         # [Pa s], [rad/s]
EVALUATIONS = 200_000            # per trial: ~10-50 ms, long against the clock's resolution
TRIALS = 15


def joint(model: str | None) -> exuclear.ClearanceJoint:
    lube = None if model is None else exuclear.Lubrication(viscosity=ETA, model=model)
    return exuclear.make_joint(journal_radius=R, bearing_radius=R + C, length=L, cr=0.9, friction="coulomb:0.1",
                               lubrication=lube)


def per_evaluation(cases: list[tuple[str | None, float]]) -> list[tuple[float, float]]:
    """Per case ``(model, eps)`` (a joint at eccentricity ratio ``eps``, closing at 1 mm/s): the
    median seconds per force evaluation, and the median over trials of its ratio to the first
    case's.  The cases are timed side by side, one after the other in every trial, so that a
    load on the shared machine falls on all of them alike."""
    ck = kernel.COMPILED
    setups = []
    for model, eps in cases:
        joint_id = ck.new_joint()
        p = parameters(joint(model), joint_id, MAIN, 1e-3)
        d, v, w = [eps * C, 0.0, 0.0], [1e-3, 0.0, 0.0], [0.0, 0.0, OMEGA]
        ck.time_force(p, d, v, w, 1.0, 10)  # the run's initial state is taken here
        setups.append((joint_id, p, d, v, w))
    try:
        times = [[ck.time_force(p, d, v, w, 2.0, EVALUATIONS) for _, p, d, v, w in setups] for _ in range(TRIALS)]
    finally:
        for joint_id, *_ in setups:
            ck.release(joint_id)
    return [(statistics.median(trial[k] for trial in times), statistics.median(trial[k] / trial[0] for trial in times))
            for k in range(len(cases))]


def per_step(model: str | None, steps: int = 5000) -> float:
    """Median wall time per step [s] of the steady-load scene (B/D 1/4, load of eps 0.5)."""
    load = 0.25 ** 2 / 2 * 0.5 * (3.1416 ** 2 * 0.75 + 4.0) ** 0.5 / 0.75 ** 2 * (2 * R * 0.25 * 2 * R * ETA * OMEGA
                                                                                / (C / R) ** 2)
    times = []
    for _ in range(5):
        mbs = exu.SystemContainer().AddSystem()
        ground = mbs.AddObject(ObjectGround())
        node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[0, -0.3 * C, 0],
                                           initialVelocities=[0, 0, OMEGA]))
        pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=0.01 * load / (C * OMEGA ** 2), inertia=100.0))
        mbs.AddLoad(LoadForceVector(markerNumber=mbs.AddMarker(MarkerBodyPosition(bodyNumber=pin)),
                                    loadVector=[0, -load, 0]))
        lube = {} if model is None else {"lubrication": exuclear.Lubrication(viscosity=ETA, model=model)}
        exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, pin], position=[0, 0, 0], axis=[0, 0, 1],
                                      journal_radius=R, bearing_radius=R + C, length=2 * R * 0.25, cr=0.9,
                                      friction="coulomb:0.1", **lube)
        mbs.Assemble()
        ss = exu.SimulationSettings()
        ss.timeIntegration.endTime = steps * 1e-4
        ss.timeIntegration.numberOfSteps = steps
        ss.timeIntegration.verboseMode = 0
        ss.solution.file.write = False
        start = time.perf_counter()
        mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
        times.append((time.perf_counter() - start) / steps)
    return statistics.median(times)


def main(argv: list[str] | None = None) -> None:
    argparse.ArgumentParser(prog="python -m validation.cost film", description=__doc__.split("\n")[0]).parse_args(argv)
    if kernel.COMPILED is None:
        raise SystemExit(f"the compiled kernel is not available: {kernel.REASON}")
    contact = 1.0 + 1e-6 / C
    cases = [("dry contact (penetration 1 um)", None, contact)]
    for model in ("short", "long", "finite"):
        cases.append((f"{model} film, eps 0.5", model, 0.5))
        cases.append((f"{model} film + contact (penetration 1 um)", model, contact))
    results = per_evaluation([(model, eps) for _, model, eps in cases])
    print(f"compiled force function, medians of {TRIALS} trials x {EVALUATIONS} evaluations, the cases side by side "
          "in each trial (shared 2-core machine)")
    for (name, _, _), (seconds, ratio) in zip(cases, results):
        print(f"  {name:42s} {seconds * 1e9:7.1f} ns   {ratio:5.2f} x dry contact")
    dry_step = per_step(None)
    print("steady-load scene, generalized-alpha, 5000 steps, median of 5 runs")
    print(f"  {'dry (journal resting on the wall)':42s} {dry_step * 1e6:7.2f} us/step")
    for model in ("short", "long", "finite"):
        s = per_step(model)
        print(f"  {model + ' film':42s} {s * 1e6:7.2f} us/step   {s / dry_step:5.2f} x dry")
