"""
A journal resting on its wall: the contact-following mode (prototype)
=====================================================================

The pendulum of the first example, frictionless: after its first impacts the pin rides on
the bottom of its bearing for the rest of the swing.  At the step a user picks for the
pendulum (1 ms, generalized-alpha), that contact is far stiffer than the step resolves, and
Newton needs many iterations per step to hold the pin on the wall.

``contact_mode="follow"`` (an opt-in prototype, issue 34) hands such a sustained contact to
a condition that holds the pin at the contact law's own penetration under the present load,
with the condition's multiplier as the normal force; it hands it back to the compliant
contact where the multiplier turns tensile.  Both runs here are a plain ``mbs.SolveDynamic``
with the user's settings; a compliant run at 16 times the steps is the reference.  Both run
on the compiled kernel (the following mode's covers a joint between rigid
bodies; :doc:`/guide/contact_following` says which): the table below gives the steps, the
Newton iterations per step and the wall time of each.
"""

import time
import warnings

import exudyn as exu
import matplotlib.pyplot as plt
import numpy as np
from exudyn.itemInterface import (
    Force,
    MarkerBodyRigid,
    MarkerNodePosition,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
    RevoluteJoint2D,
    SensorNode,
    SensorObject,
)

import exuclear

L, m = 0.3, 1.0  # link length [m] and mass [kg]
J = m * L**2 / 12  # inertia about its centre [kg m^2]
phi0 = np.radians(60.0)  # release angle from the downward vertical [rad]
c = 1e-4  # radial clearance [m]
step, end = 1e-3, 2.0  # the user's step and end time [s]


def pendulum():
    """The link hanging from the ground at the origin, turned by phi0; returns
    (mbs, ground, link, node)."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(
        NodeRigidBody2D(
            referenceCoordinates=[L / 2 * np.sin(phi0), -L / 2 * np.cos(phi0), phi0]
        )
    )
    link = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=m, inertia=J))
    mbs.AddLoad(
        Force(
            markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)),
            loadVector=[0, -9.81 * m, 0],
        )
    )
    return mbs, ground, link, node


def settings(refine: int = 1):
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = end
    ss.timeIntegration.numberOfSteps = int(round(end / step)) * refine
    ss.timeIntegration.verboseMode = 0
    ss.solution.file.write = False
    ss.solution.sensors.writePeriod = step / refine
    return ss


def run(contact_mode: str, refine: int = 1):
    """The pendulum with its clearance joint, solved at ``step / refine``; returns the
    joint, the link's angle and Newton's iteration count at every step, and the wall time."""
    mbs, ground, link, node = pendulum()
    with warnings.catch_warnings():
        # the prototype says so when it is chosen (an AccuracyWarning): read once here
        warnings.simplefilter("ignore")
        joint = exuclear.CreateClearanceJoint(
            mbs,
            itemNumbers=[ground, link],
            position=[0, 0, 0],
            axis=[0, 0, 1],
            journal_radius=10e-3 - c,
            bearing_radius=10e-3,
            length=15e-3,
            law="wang-liu",
            cr=0.7,
            journal_material="steel",
            bearing_material="steel",
            friction="none",
            contact_mode=contact_mode,
        )
    angle = mbs.AddSensor(
        SensorNode(
            nodeNumber=node,
            storeInternal=True,
            outputVariableType=exu.OutputVariableType.Coordinates,
        )
    )
    newton = []  # Newton's iterations so far, after every accepted step

    def count(mbs, t):
        newton.append((t, mbs.sys["dynamicSolver"].it.newtonStepsCount))
        return True

    mbs.SetPostStepUserFunction(count)
    mbs.Assemble()
    start = time.perf_counter()
    mbs.SolveDynamic(settings(refine), solverType=exu.DynamicSolverType.GeneralizedAlpha)
    wall = time.perf_counter() - start
    data = np.asarray(mbs.GetSensorStoredData(angle))
    return joint, data[:, 0], data[:, 3], np.array(newton), wall


def ideal_load(refine: int = 16):
    """The pivot's reaction with an ideal revolute joint: the load the pin carries; returns
    time and its magnitude."""
    mbs, ground, link, _ = pendulum()
    pivot = mbs.AddObject(
        RevoluteJoint2D(
            markerNumbers=[
                mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground)),
                mbs.AddMarker(MarkerBodyRigid(bodyNumber=link, localPosition=[0, L / 2, 0])),
            ]
        )
    )
    force = mbs.AddSensor(
        SensorObject(objectNumber=pivot, storeInternal=True, outputVariableType=exu.OutputVariableType.Force)
    )
    mbs.Assemble()
    mbs.SolveDynamic(settings(refine), solverType=exu.DynamicSolverType.GeneralizedAlpha)
    data = np.asarray(mbs.GetSensorStoredData(force))
    return data[:, 0], np.hypot(data[:, 1], data[:, 2])


ref_joint, ref_t, ref_angle, _, _ = run("compliant", refine=16)
runs = {mode: run(mode) for mode in ("compliant", "follow")}

print(f"{'run':<22} {'steps':>6} {'Newton / step':>14} {'wall [s]':>9} {'angle off the reference [rad]':>30}")
for mode, (joint, t, angle, newton, wall) in runs.items():
    steps = len(newton)  # accepted steps
    off = np.abs(angle - np.interp(t, ref_t, ref_angle)).max()
    label = f"{mode} ({joint.backend})"  # the kernel each ran on
    print(f"{label:<22} {steps:>6} {newton[-1, 1] / steps:>14.2f} {wall:>9.3f} {off:>30.2e}")
print("following:", runs["follow"][0].follow_counts())

# %%
# What the condition carries: the load, not the contact's vibration
# ------------------------------------------------------------------
# The reference shows the pin vibrating on its wall, excited by the first impacts and
# still there a second later.  The compliant contact at the user's step keeps part of it;
# the condition holds the pin at the static penetration of the present load and keeps only
# the load, which the ideal joint's reaction gives.  Over the half second plotted below (the
# vibration: the force less its mean over 20 ms):
window_t = (1.0, 1.5)  # [s]
forces = {"compliant, 16x the steps": ref_joint.outputs()}
forces.update((mode, runs[mode][0].outputs()) for mode in runs)
ideal_time, ideal_force = ideal_load()
forces["ideal joint, 16x the steps"] = {"time": ideal_time, "normal_force": ideal_force}
grid = np.arange(*window_t, step / 16)
smooth = np.ones(int(round(0.02 / (step / 16))))
smooth /= smooth.size
print(f"{'run':<27} {'mean [N]':>9} {'vibration, RMS [N]':>19} {'its strongest frequency [Hz]':>29}")
for label, out in forces.items():
    f = np.interp(grid, out["time"], out["normal_force"])
    vibration = (f - np.convolve(f, smooth, mode="same"))[smooth.size:-smooth.size]
    spectrum = np.abs(np.fft.rfft(vibration))
    peak = np.fft.rfftfreq(vibration.size, step / 16)[np.argmax(spectrum)]
    print(f"{label:<27} {f.mean():>9.2f} {np.sqrt(np.mean(vibration**2)):>19.2f} {peak:>29.0f}")

# %%
# The normal force and Newton's work
# ----------------------------------
# Top: the pin's normal force over half a second of the sustained contact, the
# compliant contact's and, while followed, the condition's multiplier, against the
# reference run's and the ideal joint's reaction (the first impacts, before, reach some
# hundred newtons).  Bottom: Newton's iterations per
# step, the mean over 50 steps.  Once the condition holds the contact Newton converges in
# one or two iterations, where the compliant contact at the same step takes several.
fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), layout="constrained")
reference = forces["compliant, 16x the steps"]
top.plot(reference["time"], reference["normal_force"], color="grey", lw=3, alpha=0.5,
         label="compliant, 16x the steps")
top.plot(ideal_time, ideal_force, color="k", lw=0.8, label="ideal joint's reaction")
for mode, style, width in (("compliant", "-", 1.0), ("follow", "--", 2.0)):
    out = forces[mode]
    top.plot(out["time"], out["normal_force"], style, lw=width, label=mode)
top.set_xlim(*window_t)
top.set(xlabel="time [s]", ylabel="normal force [N]", ylim=(0, 40))
top.legend(loc="upper right")
for mode, style in (("compliant", "-"), ("follow", "--")):
    newton = runs[mode][3]
    per_step = np.diff(newton[:, 1])
    window = 50
    mean = np.convolve(per_step, np.ones(window) / window, mode="valid")
    bottom.plot(newton[window:, 0], mean, style, label=mode)
bottom.set(xlabel="time [s]", ylabel="Newton iterations / step", ylim=(0, None))
bottom.legend(loc="upper right")
plt.show()
