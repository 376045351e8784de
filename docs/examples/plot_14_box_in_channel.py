"""
A box with play in a rectangular channel
========================================

``slider_width`` makes ``exuclear.CreatePrismaticClearanceJoint`` spatial: the slider is a box
(here 0.10 m x 0.05 m x 0.04 m, 76 g) in a channel with 1 mm of play per side in both
directions, its eight corners paired with the four walls (32 pairs, each with its own law and
history). The box starts at the channel's centre, thrown along the axis and spinning about all
three axes, under gravity, with Coulomb friction 0.1: it strikes the walls with its corners,
tumbles and settles onto the lower wall while it slides. The figure shows the box's centre
across the channel (in clearances) and the wall each contact was on.
"""

import exudyn as exu
import matplotlib.pyplot as plt
import numpy as np
from exudyn.utilities import InertiaCuboid

import exuclear

mbs = exu.SystemContainer().AddSystem()
ground = mbs.CreateGround()
box = mbs.CreateRigidBody(inertia=InertiaCuboid(380.0, sideLengths=[0.10, 0.05, 0.04]),
                          nodeType=exu.NodeType.RotationRxyz, referencePosition=[0, 0, 0],
                          initialVelocity=[0.5, 0.05, 0.03], initialAngularVelocity=[0.4, 0.3, 0.6],
                          gravity=[0, -9.81, 0], returnDict=True)
joint = exuclear.CreatePrismaticClearanceJoint(
    mbs, itemNumbers=[ground, box["bodyNumber"]], position=[0, 0, 0], axis=[1, 0, 0],
    slider_length=0.10, slider_height=0.05, slider_width=0.04, clearance=1e-3,
    stiffness=1e8, exponent=1.5, damping="carvalho-martins", cr=0.5, friction="coulomb:0.1")
mbs.Assemble()
result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=0.15, method="dopri5", step=1e-5, rtol=1e-7,
                                                        atol=1e-10, output_step=1e-4))
impacts = joint.impacts()
print(f"{result.steps} steps, {len(impacts)} corner contacts")

out = joint.outputs()
lower_upper = slice(0, 16)  # the pairs with the lower and upper walls: ecc_y is the corner's y
far_near = slice(16, 32)    # with the far and near walls: ecc_y is the corner's z
centre_y = out["ecc_y"][:, lower_upper].mean(axis=1)  # the corners' offsets cancel
centre_z = out["ecc_y"][:, far_near].mean(axis=1)
fig, ax = plt.subplots(2, 1, figsize=(7, 6))
ax[0].plot(out["time"] * 1e3, centre_y / 1e-3, lw=0.8, label="y / c")
ax[0].plot(out["time"] * 1e3, centre_z / 1e-3, lw=0.8, label="z / c")
ax[0].set(xlabel="t [ms]", ylabel="the box's centre [c]", title="across the channel: -+1 with a face on a wall")
ax[0].legend(fontsize=8)
walls = sorted({r.pair.split(" / ")[1] for r in impacts})
for k, wall in enumerate(walls):
    times = [r.onset_time * 1e3 for r in impacts if r.pair.endswith(wall)]
    ax[1].plot(times, np.full(len(times), k), "|", ms=12)
ax[1].set(xlabel="t [ms]", yticks=range(len(walls)), yticklabels=walls, title="contact onsets by wall")
fig.tight_layout()
plt.show()
