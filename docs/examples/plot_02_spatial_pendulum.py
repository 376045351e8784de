"""
Swapping a revolute joint for a clearance joint in a 3D model
=============================================================

A double pendulum of two steel bars (0.3 m x 20 mm x 20 mm) made by Exudyn's
``mbs.CreateRigidBody``, released from rest along the x axis.  The shoulder stays a
``mbs.CreateRevoluteJoint``; the elbow is the joint to replace.  The only change is the
function called at the elbow: ``exuclear.CreateClearanceJoint`` takes the same
``itemNumbers``, ``position`` and ``axis`` as ``mbs.CreateRevoluteJoint``, plus the
joint's own parameters.  ``constrainAxial=True`` keeps what the replaced joint held along
its axis (axial translation and tilt), so the contact acts in the plane of motion.
"""

import exudyn as exu
import exudyn.utilities as eu
import matplotlib.pyplot as plt
import numpy as np
from exudyn.itemInterface import SensorBody, SensorObject

import exuclear

DENSITY, LENGTH, WIDTH = 7850.0, 0.3, 0.02  # steel bar [kg/m^3, m, m]


def build(clearance: bool):
    """The double pendulum; returns (mbs, elbow joint or None, tip sensor, elbow force sensor)."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    inertia = eu.InertiaCuboid(DENSITY, [LENGTH, WIDTH, WIDTH])
    bars = [
        mbs.CreateRigidBody(
            inertia=inertia,
            referencePosition=[(k + 0.5) * LENGTH, 0, 0],
            gravity=[0, -9.81, 0],
        )
        for k in range(2)
    ]
    mbs.CreateRevoluteJoint(
        itemNumbers=[ground, bars[0]], position=[0, 0, 0], axis=[0, 0, 1]
    )
    elbow = [LENGTH, 0, 0]
    joint = None
    if clearance:
        joint = exuclear.CreateClearanceJoint(
            mbs,
            itemNumbers=bars,
            position=elbow,
            axis=[0, 0, 1],
            journal_radius=9.9e-3,
            bearing_radius=10e-3,
            length=20e-3,
            law="wang-liu",
            cr=0.7,
            journal_material="steel",
            bearing_material="steel",
            friction="none",
            constrainAxial=True,
        )
        connector = joint.objectNumber
    else:
        connector = mbs.CreateRevoluteJoint(
            itemNumbers=bars, position=elbow, axis=[0, 0, 1]
        )
    # the same sensors on either joint: ForceLocal is in the revolute joint's frame
    tip = mbs.AddSensor(
        SensorBody(
            bodyNumber=bars[1],
            localPosition=[LENGTH / 2, 0, 0],
            storeInternal=True,
            outputVariableType=exu.OutputVariableType.Position,
        )
    )
    force = mbs.AddSensor(
        SensorObject(
            objectNumber=connector,
            storeInternal=True,
            outputVariableType=exu.OutputVariableType.ForceLocal,
        )
    )
    mbs.Assemble()
    return mbs, joint, tip, force


# %%
# Both models with a plain ``mbs.SolveDynamic`` and the same settings: Exudyn's
# generalized-alpha at a fixed step of 2.5e-5 s, for 0.5 s.
def solve(mbs):
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = 0.5
    ss.timeIntegration.numberOfSteps = 20000
    ss.solution.sensors.writePeriod = 1e-4
    ss.timeIntegration.verboseMode = 0
    mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)


runs = {}
for clearance in (False, True):
    mbs, joint, tip, force = build(clearance)
    solve(mbs)
    runs[clearance] = (
        mbs.GetSensorStoredData(tip),
        mbs.GetSensorStoredData(force),
        joint,
    )
    print(f"clearance={clearance}: tip at t = 0.5 s: {runs[clearance][0][-1, 1:3]} m")

# %%
# The tip's path and the elbow's load
# -----------------------------------
# The paths part slowly; the elbow force of the clearance joint has the spikes of the
# impacts where the load turns, on top of the ideal joint's reaction.
(tip0, f0, _), (tip1, f1, joint) = runs[False], runs[True]
print(f"{len(joint.impacts())} impacts, notes: {joint.notes or 'none'}")

fig, ax = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
ax[0].plot(tip0[:, 1], tip0[:, 2], label="ideal elbow")
ax[0].plot(tip1[:, 1], tip1[:, 2], "--", label="clearance elbow, c = 0.1 mm")
ax[0].set(xlabel="x [m]", ylabel="y [m]", title="path of the free end", aspect="equal")
ax[0].legend()
ax[1].plot(f0[:, 0], np.hypot(f0[:, 1], f0[:, 2]), label="ideal elbow")
ax[1].plot(f1[:, 0], np.hypot(f1[:, 1], f1[:, 2]), lw=0.8, label="clearance elbow")
ax[1].set(
    xlabel="time [s]",
    ylabel="elbow force |F| [N]",
    title="load on the elbow",
    yscale="log",
)
ax[1].legend()
plt.show()
