"""The guide's first model (docs/guide/first_model.md): a four-bar a user builds with Exudyn's
own items, one revolute joint replaced by a clearance joint, run with a plain
``mbs.SolveDynamic`` and compared with the ideal mechanism.

Source problem: a crank-rocker four-bar (crank 0.05 m, coupler 0.25 m, rocker 0.20 m, ground
0.30 m; steel bars 20 x 25 mm) driven at 300 rpm through a velocity-level
``CoordinateConstraint``, the clearance joint between coupler and rocker (R_B = 10 mm,
c = 0.1 mm, L = 15 mm, steel on steel, Wang-Liu with cr = 0.7, Coulomb friction 0.1), the
model of issue 48.  The reference is the same model with an ideal pin at B; the clearance
model's rocker stays within the bound the clearance allows (:func:`rocker_bound`).

``python -m validation.first_hour`` prints, for three steps of generalized-alpha, the plain
call and :func:`exuclear.simulate` side by side (reached time, impacts, wall time) and the
clearance model against the ideal one.  Wall times are timings: take them on a quiet machine.
"""
from __future__ import annotations

# [build]
import math

import exudyn as exu
import numpy as np
from exudyn.itemInterface import SensorBody
from exudyn.utilities import InertiaCuboid, RotationMatrixZ

import exuclear

CRANK, COUPLER, ROCKER, GROUND = 0.05, 0.25, 0.20, 0.30  # link lengths a, b, c, d [m]
OMEGA = 300 * math.pi / 30  # crank speed [rad/s], 300 rpm
BAR = [0.02, 0.025]  # bar cross-section [m], steel


def four_bar(clearance_joint: bool = True) -> tuple:
    """The four-bar at crank angle 0, moving as the ideal mechanism does: returns the
    system, the clearance joint (None for the ideal mechanism) and the sensors of the
    coupler's and the rocker's angles."""
    # where the pins are: O2 at the origin, A on the crank, B where coupler and rocker meet
    A, O4 = np.array([CRANK, 0.0]), np.array([GROUND, 0.0])
    along = (COUPLER**2 - ROCKER**2 + (GROUND - CRANK) ** 2) / (2 * (GROUND - CRANK))
    B = A + [along, math.sqrt(COUPLER**2 - along**2)]
    phi3, phi4 = (math.atan2(*(B - A)[::-1]), math.atan2(*(B - O4)[::-1]))
    # the links' rates from the loop closure: a w e2' + b w3 e3' = c w4 e4'
    w3, w4 = np.linalg.solve([[-COUPLER * math.sin(phi3), ROCKER * math.sin(phi4)],
                              [COUPLER * math.cos(phi3), -ROCKER * math.cos(phi4)]], [0.0, -CRANK * OMEGA])

    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()

    def link(start, end, w, v_start):
        """A steel bar from ``start`` to ``end`` turning at ``w``, ``start`` moving at ``v_start``."""
        mid, axis = (start + end) / 2, end - start
        v_mid = v_start + w * np.array([-(mid - start)[1], (mid - start)[0]])
        return mbs.CreateRigidBody(inertia=InertiaCuboid(7850, [np.linalg.norm(axis), *BAR]),
                                   referencePosition=[*mid, 0], referenceRotationMatrix=RotationMatrixZ(
                                       math.atan2(axis[1], axis[0])), initialVelocity=[*v_mid, 0],
                                   initialAngularVelocity=[0, 0, w], gravity=[0, -9.81, 0],
                                   nodeType=exu.NodeType.RotationRxyz)  # rotation z: coordinate 5

    crank = link(np.zeros(2), A, OMEGA, np.zeros(2))
    coupler = link(A, B, w3, OMEGA * np.array([-A[1], A[0]]))
    rocker = link(O4, B, w4, np.zeros(2))
    mbs.CreateRevoluteJoint(itemNumbers=[ground, crank], position=[0, 0, 0], axis=[0, 0, 1])
    mbs.CreateRevoluteJoint(itemNumbers=[crank, coupler], position=[*A, 0], axis=[0, 0, 1])
    mbs.CreateRevoluteJoint(itemNumbers=[ground, rocker], position=[*O4, 0], axis=[0, 0, 1])
    joint = None
    if clearance_joint:  # bearing in the rocker, journal on the coupler
        joint = exuclear.CreateClearanceJoint(
            mbs, name="B", itemNumbers=[rocker, coupler], position=[*B, 0], axis=[0, 0, 1],
            journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, law="wang-liu", cr=0.7,
            journal_material="steel", bearing_material="steel", friction="coulomb:0.1")
    else:  # the ideal pin: in-plane translations only (the other joints hold the rest)
        mbs.CreateGenericJoint(itemNumbers=[rocker, coupler], position=[*B, 0], constrainedAxes=[1, 1, 0, 0, 0, 0])
    # the crank turns at OMEGA: its rotation coordinate's rate held by a constraint
    mbs.CreateCoordinateConstraint(itemNumbers=[None, crank], coordinates=[None, 5], offset=OMEGA,
                                   velocityLevel=True)
    sensors = {name: mbs.AddSensor(SensorBody(bodyNumber=body, storeInternal=True,
                                                  outputVariableType=exu.OutputVariableType.Rotation))
               for name, body in (("coupler", coupler), ("rocker", rocker))}
    mbs.Assemble()
    return mbs, joint, sensors
# [build end]


# [run]
def run_plain(mbs, step: float, end_time: float) -> bool:
    """A plain ``mbs.SolveDynamic``: generalized-alpha with ``step`` and Exudyn's defaults."""
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = end_time
    ss.timeIntegration.numberOfSteps = round(end_time / step)
    ss.solution.sensors.writePeriod = 1e-4
    ss.solution.file.write = False
    return mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
# [run end]


def rocker_bound(coupler: np.ndarray, rocker: np.ndarray, reach: float) -> float:
    """The largest rocker angle error [rad] that a pin displaced by ``reach`` [m] at B allows:
    the loop closure ``c dphi4 e4' - b dphi3 e3' = eps`` dotted with ``e3`` gives
    ``|dphi4| <= |eps| / (c |sin(phi3 - phi4)|)``, here at the smallest ``|sin|`` of the
    ideal run's coupler and rocker angles ``coupler``, ``rocker`` [rad] (the crank angle is
    the same in both runs: its rate is held)."""
    return reach / (ROCKER * float(np.min(np.abs(np.sin(coupler - rocker)))))


def against_ideal(step: float, end_time: float) -> dict[str, float]:
    """The clearance model and the ideal mechanism at ``step``: the largest rocker angle
    difference, its bound (:func:`rocker_bound`), the joint's largest ``|e| / c`` and its
    impacts."""
    angles, joint = {}, None
    for kind in ("ideal", "clearance"):
        mbs, handle, sensors = four_bar(clearance_joint=kind == "clearance")
        if not run_plain(mbs, step, end_time):
            raise RuntimeError(f"the {kind} four-bar did not reach {end_time} s")
        data = {name: np.asarray(mbs.GetSensorStoredData(n)) for name, n in sensors.items()}
        angles[kind] = {"time": data["rocker"][:, 0], **{name: np.unwrap(d[:, 3]) for name, d in data.items()}}
        joint = handle or joint
    out, c = joint.outputs(), joint.joint.geometry.clearance
    reach = c + max(0.0, float(np.max(out["penetration"])))
    ideal, clear = angles["ideal"], angles["clearance"]
    # the sensors write at the first accepted step after each write period: the runs' steps
    # differ where the joint shortens them, so the clearance run is read at the ideal run's times
    rocker = np.interp(ideal["time"], clear["time"], clear["rocker"])
    return {"difference": float(np.max(np.abs(rocker - ideal["rocker"]))),
            "bound": rocker_bound(ideal["coupler"], ideal["rocker"], reach),
            "max_eps": float(np.max(np.hypot(out["ecc_x"], out["ecc_y"]))) / c, "impacts": len(joint.impacts())}


def side_by_side(step: float, end_time: float) -> list[tuple]:
    """The plain call and :func:`exuclear.simulate` at ``step``: (path, reached time, impacts, wall time)."""
    import time

    rows = []
    mbs, joint, _ = four_bar()
    start = time.perf_counter()
    run_plain(mbs, step, end_time)
    rows.append(("mbs.SolveDynamic", mbs.systemData.GetTime(), len(joint.impacts()), time.perf_counter() - start))
    mbs, joint, _ = four_bar()
    result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=end_time, method="generalized-alpha", step=step))
    rows.append(("exuclear.simulate", result.time_reached, len(joint.impacts()), result.wall_time))
    return rows


def main(argv: list[str] | None = None) -> int:
    import argparse

    ap = argparse.ArgumentParser(prog="python -m validation.first_hour", description=__doc__.split("\n\n")[0])
    ap.add_argument("--end-time", type=float, default=1.0, help="simulated time [s] (default 1)")
    ap.add_argument("--steps", default="1e-4,5e-5,2.5e-5", help="steps of generalized-alpha [s], comma-separated")
    args = ap.parse_args(argv)
    steps = [float(s) for s in args.steps.split(",")]
    print(f"four-bar, generalized-alpha, end time {args.end_time:g} s (wall times: take them on a quiet machine)")
    print("| step [s] | path | reached [s] | impacts | wall time [s] |\n|---|---|---|---|---|")
    for step in steps:
        for path, reached, impacts, wall in side_by_side(step, args.end_time):
            print(f"| {step:g} | {path} | {reached:.4g} | {impacts} | {wall:.2f} |")
    print("\n| step [s] | max rocker angle difference to the ideal [rad] | its bound [rad] | max abs(e)/c | impacts |"
          "\n|---|---|---|---|---|")
    for step in steps:
        r = against_ideal(step, args.end_time)
        print(f"| {step:g} | {r['difference']:.3g} | {r['bound']:.3g} | {r['max_eps']:.4g} | {r['impacts']} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
