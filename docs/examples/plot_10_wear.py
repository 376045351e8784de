"""
Wear of a pin under a swinging load
===================================

A journal turns at a constant speed in a fixed bearing while the load on it swings by
+-60 degrees about -x, as the load on a crank pin swings with the crank.  The model is
built the usual Exudyn way; ``wear=exuclear.Wear(...)`` on the clearance joint makes the
bearing wear by Archard's law while it runs (docs/physics.md section 11), and
:func:`exuclear.predict_wear` extrapolates one swing over many.  The wear coefficient is an
accelerated one, so that a few swings show it.
"""

import math

import exudyn as exu
import matplotlib.pyplot as plt
from exudyn.itemInterface import (
    CoordinateConstraint,
    Force,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    NodePointGround,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
)

import exuclear

R, c, L = 10e-3, 0.1e-3, 15e-3  # bearing radius, clearance, length [m]
F, spin, swing = 500.0, 100.0, 1.0 / 0.1  # load [N], journal speed [rad/s], swings per second
period = 1.0 / swing  # one swing of the load: one cycle [s]


def one_cycle(wear):
    """Build the pin with ``wear`` on its joint and run one swing of the load; return the joint."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[-c, 0, 0], initialVelocities=[0, 0, spin]))
    pin = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=1.0, inertia=0.5 * (R - c) ** 2))
    m_pin = mbs.AddMarker(MarkerBodyRigid(bodyNumber=pin))

    def load(mbs, t, vector):  # the load swings by +-60 degrees about -x
        a = math.radians(60.0) * math.sin(2.0 * math.pi * t / period)
        return [-F * math.cos(a), F * math.sin(a), 0.0]

    mbs.AddLoad(Force(markerNumber=m_pin, loadVectorUserFunction=load))
    m_angle = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=2))
    m_fixed = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=mbs.AddNode(NodePointGround()), coordinate=0))
    mbs.AddObject(CoordinateConstraint(markerNumbers=[m_fixed, m_angle], offset=spin, velocityLevel=True))
    joint = exuclear.AddClearanceJoint(
        mbs, [mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground)), m_pin], journal_radius=R - c, bearing_radius=R,
        length=L, law="lankarani-nikravesh", cr=0.5, wear=wear, show=False)
    mbs.Assemble()
    settings = exu.SimulationSettings()
    settings.timeIntegration.endTime = period
    settings.timeIntegration.numberOfSteps = 1000
    settings.solution.file.write = False
    mbs.SolveDynamic(settings)
    return joint


wear = exuclear.Wear(coefficient=1e-12)
first = one_cycle(wear).wear_profile()
prediction = exuclear.predict_wear(one_cycle, wear, cycles=50, progress=False)
print(f"after one swing: {first.deepest()[0] * 1e6:.2f} um; after 50: {prediction.deepest()[-1] * 1e6:.1f} um "
      f"in {len(prediction.steps)} updates of {', '.join(f'{s:g}' for s in prediction.steps)} swings")

# %%
# The wear map: the bearing wears over the arc the load sweeps, deepest where the load
# dwells (its turning points at +-60 degrees about 180), and the imprint deepens and widens
# as it takes the journal's shape.
ax = plt.figure(figsize=(9, 4.5), layout="constrained").add_subplot(1, 2, 1, projection="polar")
for cycles, profile in zip(prediction.cycles, prediction.profiles):
    if cycles in (prediction.cycles[0], prediction.cycles[len(prediction.cycles) // 2], prediction.cycles[-1]):
        profile.plot(ax, label=f"{cycles:g} swings")
ax.legend(loc="upper left", bbox_to_anchor=(-0.25, 1.12), fontsize="small")
ax2 = plt.subplot(1, 2, 2)
ax2.plot([0, *prediction.cycles], [0, *(prediction.deepest() * 1e6)], "o-")
ax2.set(xlabel="swings", ylabel="largest bearing depth [um]", title="predict_wear's updates")
ax2.grid(alpha=0.3)
plt.show()
