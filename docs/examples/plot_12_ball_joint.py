"""
A spherical pendulum on a ball joint with play
==============================================

A steel bar (0.3 m x 20 mm x 20 mm) hangs from the ground by a ball joint and swings in 3D.
``exuclear.CreateSphericalClearanceJoint`` takes the ``itemNumbers`` and ``position`` of
``mbs.CreateSphericalJoint`` and the joint's own parameters: a ball of 9.9 mm in a socket of
10 mm (c = 0.1 mm), Hertz's ball-in-socket stiffness with Lankarani-Nikravesh damping.
The bar starts with its ball against the socket's lower wall, where its weight holds it; the
figure shows the ball's eccentricity in the socket and the contact force, and the bar's free
end beside the same pendulum on the ideal joint.
"""

import exudyn as exu
import exudyn.utilities as eu
import matplotlib.pyplot as plt
import numpy as np
from exudyn.itemInterface import SensorBody

import exuclear

DENSITY, LENGTH, WIDTH, C = 7850.0, 0.3, 0.02, 1e-4  # [kg/m^3, m, m, m]
SPIN = np.array([5.0, 0.0, 3.0])  # initial angular velocity [rad/s]


def build(clearance: bool):
    """The pendulum; returns (mbs, joint or None, sensor of the free end)."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    centre = np.array([0.0, -LENGTH / 2, 0.0])
    bar = mbs.CreateRigidBody(
        inertia=eu.InertiaCuboid(DENSITY, [WIDTH, LENGTH, WIDTH]),
        referencePosition=list(centre),
        initialDisplacement=[0.0, -C if clearance else 0.0, 0.0],
        initialVelocity=list(np.cross(SPIN, centre)),
        initialAngularVelocity=list(SPIN),
        gravity=[0, -9.81, 0],
    )
    joint = None
    if clearance:
        joint = exuclear.CreateSphericalClearanceJoint(
            mbs,
            itemNumbers=[ground, bar],
            position=[0, 0, 0],
            ball_radius=10e-3 - C,
            socket_radius=10e-3,
            law="hertz+lankarani-nikravesh",
            cr=0.9,
        )
    else:
        mbs.CreateSphericalJoint(itemNumbers=[ground, bar], position=[0, 0, 0])
    tip = mbs.AddSensor(
        SensorBody(
            bodyNumber=bar,
            localPosition=[0, -LENGTH / 2, 0],
            storeInternal=True,
            outputVariableType=exu.OutputVariableType.Position,
        )
    )
    mbs.Assemble()
    return mbs, joint, tip


settings = exuclear.SolverSettings(end_time=0.3, method="generalized-alpha", step="auto", output_step=1e-3)
paths = {}
for clearance in (False, True):
    mbs, joint, tip = build(clearance)
    result = exuclear.simulate(mbs, settings)
    paths[clearance] = np.asarray(mbs.GetSensorStoredData(tip))
    if joint is not None:
        out = joint.outputs()
        print(f"{result.steps} steps, {len(joint.impacts())} impacts, largest penetration "
              f"{out['penetration'].max() * 1e6:.2f} um")

fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
ecc = np.sqrt(out["ecc_x"] ** 2 + out["ecc_y"] ** 2 + out["ecc_z"] ** 2)
axes[0].plot(out["time"], ecc / C, label="|e| / c")
axes[0].plot(out["time"], out["normal_force"] / out["normal_force"].max(), label="F_N / max F_N", lw=0.8)
axes[0].set_xlabel("time [s]")
axes[0].legend()
axes[0].set_title("the ball in its socket")
for clearance, style in ((False, "-"), (True, "--")):
    p = paths[clearance]
    axes[1].plot(p[:, 1], p[:, 3], style, label="clearance joint" if clearance else "ideal joint")
axes[1].set_xlabel("x of the free end [m]")
axes[1].set_ylabel("z of the free end [m]")
axes[1].set_aspect("equal", "datalim")
axes[1].legend()
axes[1].set_title("the free end, seen from above")
fig.tight_layout()
plt.show()
