"""
A clearance joint in a 2D model of your own
===========================================

A planar pendulum, a link of 0.3 m and 1 kg built from ``NodeRigidBody2D`` and
``ObjectRigidBody2D``, hangs from the ground by its pivot: once an ideal revolute joint
(``RevoluteJoint2D``), once a clearance joint (:func:`exuclear.CreateClearanceJoint`,
radial clearance 0.1 mm, friction coefficient 0.1).  Released at 60 degrees, the link
swings; the pin of the clearance joint rides on the bottom of its bearing, pressed there by
gravity and the centrifugal force.  Exudyn's sensors read both models the same way.
"""

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
)

import exuclear

L, m = 0.3, 1.0  # link length [m] and mass [kg]
J = m * L**2 / 12  # inertia about its centre [kg m^2]
phi0 = np.radians(60.0)  # release angle from the downward vertical [rad]
c = 1e-4  # radial clearance [m]


def build(clearance: bool):
    """The pendulum with its pivot at the origin; returns (mbs, joint or None, angle sensor)."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    # the link's centre, L/2 below the pivot turned by phi0; the pivot is at local (0, L/2)
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
    joint = None
    if clearance:
        # bearing (hole) on the ground, journal (pin) on the link: mbs.CreateRevoluteJoint's
        # keywords plus the joint's own
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
            friction="coulomb:0.1",
        )
    else:
        mbs.AddObject(
            RevoluteJoint2D(
                markerNumbers=[
                    mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground)),
                    mbs.AddMarker(
                        MarkerBodyRigid(bodyNumber=link, localPosition=[0, L / 2, 0])
                    ),
                ]
            )
        )
    angle = mbs.AddSensor(
        SensorNode(
            nodeNumber=node,
            storeInternal=True,
            outputVariableType=exu.OutputVariableType.Rotation,
        )
    )
    mbs.Assemble()
    return mbs, joint, angle


# %%
# Run both for one second with Exudyn's generalized-alpha solver (the ideal joint is a
# constraint: an implicit method).  :func:`exuclear.simulate` is ``mbs.SolveDynamic`` plus
# impact-aware steps; a plain ``mbs.SolveDynamic`` works too.
settings = exuclear.SolverSettings(
    end_time=1.0,
    method="generalized-alpha",
    step=5e-5,
    impact_step=2e-6,
    output_step=1e-4,
)
runs = {}
for clearance in (False, True):
    mbs, joint, angle = build(clearance)
    result = exuclear.simulate(mbs, settings)
    print(
        f"clearance={clearance}: {result.message or 'finished'} in {result.steps} steps"
    )
    runs[clearance] = (mbs.GetSensorStoredData(angle), joint)

# %%
# The swing and the pin in its bearing
# ------------------------------------
# The swings part slowly: the friction in the clearance joint takes energy, so the link
# comes back short of 60 degrees.  The pin's centre (eccentricity over clearance, 1 =
# touching the wall) falls from the centre onto the wall, bounces a few times (the force
# peaks at the start), then rides on the wall as the link swings, and the normal force
# follows the load of the pivot.
(ideal, _), (clear, joint) = runs[False], runs[True]
out = joint.outputs()

fig, ax = plt.subplots(1, 3, figsize=(12, 3.8), layout="constrained")
ax[0].plot(ideal[:, 0], np.degrees(ideal[:, -1]), label="ideal revolute joint")
ax[0].plot(
    clear[:, 0], np.degrees(clear[:, -1]), "--", label="clearance joint, c = 0.1 mm"
)
ax[0].set(xlabel="time [s]", ylabel="link angle [deg]", title="swing")
ax[0].legend(loc="lower right")

ax[1].plot(out["time"], out["normal_force"], color="C1")
ax[1].set(
    xlabel="time [s]", ylabel="normal contact force [N]", title="load on the pivot"
)

theta = np.linspace(0, 2 * np.pi, 200)
ax[2].plot(np.cos(theta), np.sin(theta), "k", lw=0.8, label="clearance circle")
ax[2].plot(out["ecc_x"] / c, out["ecc_y"] / c, color="C1", label="pin centre")
ax[2].set(
    xlabel="e_x / c [-]",
    ylabel="e_y / c [-]",
    title="pin in the bearing (joint frame)",
    aspect="equal",
)
ax[2].legend(loc="upper right", fontsize="small")
plt.show()
