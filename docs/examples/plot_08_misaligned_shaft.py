"""
The spatial joint under misalignment
====================================

A steel shaft (R_J = 9.9 mm) spinning at 50 rad/s in two bearings of the paper's geometry
(R_B = 10 mm, L = 15 mm), 0.1 m apart, with bearing B 0.3 mm higher than A: three
clearances of misalignment, so the shaft tilts in both bearings and bears on their edges.
Each bearing is a spatial clearance joint (:func:`exuclear.AddClearanceJoint` with
``slices=20``): the journal is cut into slices along the axis, each with its own contact,
so the joint sees tilt, edge loading and the force distribution along the bearing.  The
scene is :mod:`exuclear.models.misaligned_shaft` (``ShaftParams.default``); 50 ms here.
"""

import matplotlib.pyplot as plt
import numpy as np

from exuclear.models.misaligned_shaft import ShaftParams, run, summary

params = ShaftParams.default()
result, out = run(params)
print(result.message or f"finished at t = {params.end_time} s")
for key, value in summary(params, out).items():
    print(f"{key:28s} {value:.4g}")

# %%
# Tilt and force along the bearings
# ---------------------------------
# Left: the shaft's tilt in each bearing settles above ``2 c / L``, the tilt at which both
# edges of a bearing touch: the shaft bears on one edge of each.  Right: the normal force
# per unit length along each bearing (the slices' forces over their width, mean of the
# second half of the run) piles up at the edges.
width = params.length / params.slices  # width of a slice [m]
c = params.bearing_radius - params.journal_radius
fig, ax = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
for name in ("A", "B"):
    o = out[name]
    ax[0].plot(
        o["time"] * 1e3,
        np.hypot(o["tilt_x"], o["tilt_y"]) * 1e3,
        label=f"bearing {name}",
    )
    late = o["time"] >= 0.5 * o["time"][-1]
    ax[1].plot(
        out["z"] * 1e3,
        o["normal_force"][late].mean(axis=0) / width / 1e3,
        "o-",
        label=f"bearing {name}",
    )
ax[0].axhline(2 * c / params.length * 1e3, color="grey", ls=":", label="2c / L")
ax[0].set(
    xlabel="time [ms]", ylabel="tilt of the shaft in the bearing [mrad]", title="tilt"
)
ax[1].set(
    xlabel="axial position in the bearing z [mm]",
    ylabel="normal force per length [N/mm]",
    title="force along the bearing",
)
for a in ax:
    a.legend()
plt.show()
