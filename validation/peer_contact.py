"""exuclear's clearance joint against Exudyn's own contact element, on the journal impact.

Source problem: the paper's journal-bearing impact (X. Wang, G. Liu, S. Ma, R. Tong, J.
Mech. Sci. Technol. 31(2) (2017) 587-597, example 1; docs/physics.md section 6.1), the
scene of :mod:`exuclear.models.journal_bearing`: a steel journal touching the wall of its
steel bearing at t = 0 and moving into it at 0.3 m/s; no gravity, no friction.

Compared, on the same scene with the same contact law (Hertz, ``F = K delta^1.5`` with
exuclear's ``K`` for this geometry and material, and the Carvalho-Martins/Gonthier
damping of restitution 0.9):

- ours: exuclear's joint, ``law="hertz+carvalho-martins"``, ``cr = 0.9``;
- the peer: Exudyn's C++ element ``ObjectContactSphereSphere`` with ``isHollowSphere1=True``
  (the journal a sphere of radius R_J in a hollow sphere of radius R_B: in the plane of the
  motion, the joint's circle in a circle), ``impactModel=2``, ``restitutionCoefficient = 0.9``.

Each runs under DOPRI5 (adaptive), RK44 and generalized-alpha (fixed steps), with the same
``exu.SimulationSettings`` for both elements, through a plain ``mbs.SolveDynamic``.  One
Markdown table: departure velocity (the paper's 0.269 m/s at cr 0.9; this law gives
0.9 x 0.3 = 0.270), peak contact force, steps, and the wall time of the solver call (median
of ``--repeats`` runs, ours and the peer's alternated, so that a load on the machine falls
on both alike) with the median ratio ours / peer.  Run nothing else meanwhile::

    python -m validation.peer_contact [--repeats N] [--parts]
"""
from __future__ import annotations

import argparse
import functools
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, replace

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    MarkerBodyRigid,
    NodeGenericData,
    NodeRigidBody2D,
    ObjectContactSphereSphere,
    ObjectGround,
    ObjectRigidBody2D,
    SensorObject,
)

import exuclear
from exuclear.models import journal_bearing as jb_model
from exuclear.settings import DEFAULT_STEP, METHODS
from validation._tables import markdown_table

#: The paper's scene with the one contact law both elements have: Hertz stiffness,
#: Carvalho-Martins damping (exact restitution cr for a free mass).
PARAMS = jb_model.JournalBearingParams.paper(law="hertz+carvalho-martins")
#: The paper's departure velocity at cr = 0.9 [m/s] (its section 5.1; docs/physics.md 6.1).
PAPER_DEPARTURE = 0.269

#: Fixed step of RK44 and generalized-alpha [s]: 80 steps per impact (~40 us); the departure
#: velocities of both elements were then within 2e-5 m/s of their value at 1e-7 s.
FIXED_STEP = 5e-7
#: DOPRI5: exuclear's default largest step (the paper's), and tolerances that resolve the
#: micrometre penetration (atol 1e-12 m against ~4.5 um); the error control shortens the
#: steps in contact to about 1 us.
DOPRI5_MAX_STEP, DOPRI5_RTOL, DOPRI5_ATOL = DEFAULT_STEP, 1e-8, 1e-12
#: Sensor interval [s]: shorter than every step taken, so that each accepted step is
#: recorded and the peak force is read at step ends, alike for both elements.
OUTPUT_STEP = 1e-7

SOLVERS = (
    ("DOPRI5", exuclear.SolverSettings(end_time=PARAMS.end_time, method="dopri5", step=DOPRI5_MAX_STEP,
                                       rtol=DOPRI5_RTOL, atol=DOPRI5_ATOL, output_step=OUTPUT_STEP)),
    ("RK44", exuclear.SolverSettings(end_time=PARAMS.end_time, method="rk44", step=FIXED_STEP,
                                     output_step=OUTPUT_STEP)),
    ("generalized-alpha", exuclear.SolverSettings(end_time=PARAMS.end_time, method="generalized-alpha",
                                                  step=FIXED_STEP, output_step=OUTPUT_STEP)),
)

#: The peer's contact switch: ObjectContactSphereSphere applies its force during a step only
#: where the gap it stored at the last accepted step (its data coordinate 0) is negative.
#: The journal starts touching the wall (gap 0), which counts as open: the first step would
#: fly into the wall without force (under DOPRI5's first step of 10 us, 3 um deep: the
#: journal then left at 0.335 m/s, restitution 1.12).  The smallest negative gap switches the
#: contact on from t = 0, as exuclear's joint does for a contact beginning at an accepted state.
PEER_START_GAP = -sys.float_info.min


@dataclass(frozen=True)
class Run:
    """One solver call: ``ok`` False with ``message`` where Exudyn stopped it."""

    ok: bool
    message: str
    departure: float  # [m/s], the journal's speed away from the wall at the end
    peak_force: float  # [N], largest recorded |contact force|
    steps: int  # accepted steps
    wall: float  # [s], the SolveDynamic call alone


def build_ours(removed: tuple[str, ...] = ()) -> tuple[exu.MainSystem, int, int]:
    """The scene with exuclear's joint: (system, journal node, force sensor); ``removed``
    switches parts off for :func:`parts` (``"sensors"``: the force sensor and the joint's own
    record, then neither stored nor written; a user-function name: that function)."""
    scene = jb_model.build(PARAMS)
    sensor = scene.mbs.AddSensor(SensorObject(objectNumber=scene.joint.objectNumber, storeInternal=True,
                                              outputVariableType=exu.OutputVariableType.ForceLocal))
    for item in removed:
        if item == "sensors":
            for number in (sensor, scene.joint.sensorNumber):
                scene.mbs.SetSensorParameter(number, "storeInternal", False)
        else:
            scene.mbs.SetObjectParameter(scene.joint.objectNumber, item, 0)
    scene.mbs.Assemble()
    return scene.mbs, scene.nodes["journal"], sensor


def build_peer() -> tuple[exu.MainSystem, int, int]:
    """The same scene with Exudyn's ObjectContactSphereSphere: (system, journal node, force sensor)."""
    law = PARAMS.joint().law  # the stiffness and the geometry exuclear derives from PARAMS
    geometry = law.geometry
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[geometry.clearance, 0.0, 0.0],
                                       initialVelocities=[PARAMS.impact_velocity, 0.0, 0.0]))
    journal = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=PARAMS.mass,
                                              inertia=0.5 * PARAMS.mass * geometry.journal_radius**2))
    # data: gap, tangential velocity, impact velocity (approach speed > 0), plastic overlap
    data = mbs.AddNode(NodeGenericData(initialCoordinates=[PEER_START_GAP, 0.0, PARAMS.impact_velocity, 0.0],
                                       numberOfDataCoordinates=4))
    contact = mbs.AddObject(ObjectContactSphereSphere(
        markerNumbers=[mbs.AddMarker(MarkerBodyRigid(bodyNumber=journal)),   # sphere 0: the journal
                       mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground))],   # sphere 1, hollow: the bearing
        nodeNumber=data, spheresRadii=[geometry.journal_radius, geometry.bearing_radius], isHollowSphere1=True,
        contactStiffness=law.stiffness_model.k0,  # PointContact: F_e = K delta^n (docs/physics.md eq. (13))
        contactStiffnessExponent=law.exponent, restitutionCoefficient=law.cr, impactModel=2,
        minimumImpactVelocity=law.v_min))  # exuclear's floor of v0 in the damping (docs/physics.md eq. (17))
    sensor = mbs.AddSensor(SensorObject(objectNumber=contact, storeInternal=True,
                                        outputVariableType=exu.OutputVariableType.Force))
    mbs.Assemble()
    return mbs, node, sensor


def simulation_settings(settings: exuclear.SolverSettings) -> exu.SimulationSettings:
    """exuclear's mapping of ``settings``, with the one change the peer needs, for both elements.

    ``discontinuous.useRecommendedStepSize = False`` (Exudyn's default is True).  With it on,
    the peer stops under generalized-alpha ("SolveDynamic terminated" at t = 39 us, where the
    contact opens; the same with ``adaptiveStep``): its post-Newton error at a change of
    contact state is ``contactStiffness * |gap|``, a force only for an exponent of 1; with
    K = 1.5e11 N/m^1.5 it asks for a gap below 7e-12 m, a step of 2.5e-11 s at 0.27 m/s,
    shortens the step to Exudyn's minimum (1e-8 s) and gives up.  Under RK44 it changes the
    peer's fixed steps (817 instead of 800), under DOPRI5 it adds steps (87 instead of 81;
    the same result here, but on an impact from free flight, the journal started at the
    centre, it left at 0.295 m/s instead of 0.270).  exuclear's joint takes the same steps
    to the same results either way: on fixed steps the solver cannot shorten them and the
    joint accepts them, and under DOPRI5 the error control takes over from the joint's step
    criteria (docs/guide/solver_path.md, "What the joint does to your steps").
    """
    ss = exuclear.engine.simulation_settings(settings)
    ss.timeIntegration.discontinuous.useRecommendedStepSize = False
    return ss


def solve(build: Callable[[], tuple[exu.MainSystem, int, int]], settings: exuclear.SolverSettings) -> Run:
    """Build a fresh scene with ``build`` and integrate it once."""
    mbs, node, sensor = build()
    ss = simulation_settings(settings)
    solver = getattr(exu.DynamicSolverType, METHODS[settings.method][0])
    start = time.perf_counter()
    try:
        ok, message = bool(mbs.SolveDynamic(ss, solverType=solver)), ""
    except Exception as err:  # Exudyn raises its own error types on solver failure
        ok, message = False, f"{type(err).__name__}: {err}"
    wall = time.perf_counter() - start
    if not ok:
        message = f"failed at t = {mbs.systemData.GetTime():.3g} s ({message or 'solver reported failure'})"
    stored = mbs.GetSensor(sensor)["storeInternal"]  # not where parts() switched the sensors off
    force = np.linalg.norm(mbs.GetSensorStoredData(sensor)[:, 1:4], axis=1) if stored else np.zeros(0)
    return Run(ok, message, departure=-float(mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)[0]),
               peak_force=float(force.max()) if force.size else float("nan"),
               steps=int(mbs.sys["dynamicSolver"].it.currentStepIndex) - 1, wall=wall)


def compare(settings: exuclear.SolverSettings, repeats: int) -> tuple[Run, Run, float]:
    """Ours and the peer's run, ``repeats`` times alternated: the first runs (each with its
    median wall time) and the median of the per-pair wall-time ratios ours / peer."""
    pairs = [(solve(build_ours, settings), solve(build_peer, settings)) for _ in range(repeats)]
    ours, peer = pairs[0]
    ours = replace(ours, wall=statistics.median(o.wall for o, _ in pairs))
    peer = replace(peer, wall=statistics.median(p.wall for _, p in pairs))
    return ours, peer, statistics.median(o.wall / p.wall for o, p in pairs)


#: What ``--parts`` switches off in our run, one after another (RK44, the same 800 steps each).
PARTS = (("ours, as above", ()),
         ("its two sensors neither stored nor written", ("sensors",)),
         ("without the post-Newton function too", ("sensors", "postNewtonStepUserFunction")),
         ("a bare connector: no user function at all", ("sensors", "postNewtonStepUserFunction",
                                                        "springForceTorqueUserFunction")))


def parts(repeats: int) -> str:
    """Where our run's time goes under RK44 (800 steps, four stages each): the median wall time
    with the parts of :data:`PARTS` removed, against the peer's, as a Markdown table."""
    settings = dict(SOLVERS)["RK44"]
    peer = statistics.median(solve(build_peer, settings).wall for _ in range(repeats))
    rows = []
    for label, removed in PARTS:
        wall = statistics.median(solve(functools.partial(build_ours, removed), settings).wall for _ in range(repeats))
        rows.append([label, f"{wall * 1e3:.2f}", f"{wall / peer:.2f}"])
    rows.append(["the peer (its force sensor kept)", f"{peer * 1e3:.2f}", "1.00"])
    return markdown_table(["RK44, 5e-7 s, 800 steps", "wall [ms]", "/ peer"], rows)


def _values(run: Run) -> list[str]:
    """Departure, peak force, steps, wall time [ms] of one run; "failed" (its message below the table)."""
    if not run.ok:
        return ["failed"] * 4
    return [f"{run.departure:.5f}", f"{run.peak_force:.1f}", f"{run.steps}", f"{run.wall * 1e3:.2f}"]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.peer_contact", description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=5, help="runs per element and solver; the median is quoted "
                                                           "(default 5)")
    ap.add_argument("--parts", action="store_true", help="also time our run with its sensors, its post-Newton "
                                                          "function and its force function removed in turn (RK44)")
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error("--repeats must be at least 1")
    law = PARAMS.joint().law
    print(f"journal impact at {PARAMS.impact_velocity} m/s, {law.name}, cr = {law.cr}, K = {law.stiffness_model.k0:.4g} "
          f"N/m^{law.exponent:g}; paper (Wang-Liu law): departure {PAPER_DEPARTURE} m/s; compiled kernel: "
          f"{exuclear.engine.kernel.STATUS}; medians of {args.repeats}\n")
    header = ["solver (same settings for both)", "departure ours / peer [m/s]", "peak force ours / peer [N]",
              "steps ours / peer", "wall ours / peer [ms]", "wall ratio ours / peer"]
    rows, failures = [], []
    for name, settings in SOLVERS:
        setting = (f"rtol {settings.rtol:g}, atol {settings.atol:g} m, steps <= {settings.step:g} s"
                   if settings.adaptive else f"step {settings.step:g} s")
        ours, peer, ratio = compare(settings, args.repeats)
        pairs = [f"{a} / {b}" for a, b in zip(_values(ours), _values(peer))]
        rows.append([f"{name}, {setting}", *pairs, f"{ratio:.2f}" if ours.ok and peer.ok else "-"])
        failures += [f"{name}, {who}: {run.message}" for who, run in (("ours", ours), ("peer", peer)) if not run.ok]
    print(markdown_table(header, rows))
    for line in failures:
        print(line)
    if args.parts:
        print("\n" + parts(args.repeats))
    return 0


if __name__ == "__main__":
    sys.exit(main())
