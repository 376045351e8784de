"""
The paper's slider-crank against the ideal mechanism
====================================================

The second example of Wang et al. (2017): a slider-crank (crank 0.05 m, rod 0.3 m) driven
at 500 rpm with a clearance of 0.1 mm in the joint between rod and slider (B).  The scene
is :mod:`exuclear.models.slider_crank`; :meth:`SliderCrankParams.paper` gives the paper's
values and :func:`run` returns the time series of the slider and of the joint.  One crank
revolution here (0.12 s); the paper shows two.
"""

import matplotlib.pyplot as plt
import numpy as np

from exuclear.models.slider_crank import (
    SliderCrankParams,
    ideal_slider_acceleration,
    run,
)

params = SliderCrankParams.paper(revolutions=1.0)
clear = run(params)
# the ideal mechanism is a closed loop: the redundant formulation (2D bodies and joints)
ideal = run(
    SliderCrankParams.paper(revolutions=1.0, ideal=True, formulation="redundant")
)
print(
    f"clearance joint: {clear.impacts} impacts, peak force {clear.peak_force:.0f} N, {clear.message or 'finished'}"
)
print(f"ideal joint: peak force {ideal.peak_force:.1f} N")

# %%
# Slider acceleration
# -------------------
# The impacts in the joint put spikes on the slider's acceleration, around the smooth
# curve of the ideal mechanism (here also its closed form), until the journal settles on
# the wall.  The spikes reach several thousand m/s^2: the axis is cut at four times the
# ideal mechanism's largest acceleration, as the paper's figures cut them.
a, b = clear.columns, ideal.columns
theta = np.radians(b["crank_angle"])
ideal_a = ideal_slider_acceleration(
    theta, params.crank_speed, params.crank_length, params.rod_length
)
fig, ax = plt.subplots(figsize=(8, 4), layout="constrained")
ax.plot(
    a["crank_angle"], a["slider_a"], lw=0.8, label="clearance joint at B, c = 0.1 mm"
)
ax.plot(b["crank_angle"], b["slider_a"], "k", label="ideal joints")
ax.plot(b["crank_angle"], ideal_a, "C3:", label="ideal, closed form")
limit = 4 * np.abs(ideal_a).max()
ax.set(
    xlabel="crank angle [deg]",
    ylabel="slider acceleration [m/s^2]",
    xlim=(0, 360),
    ylim=(-limit, limit),
)
ax.legend()
plt.show()

# %%
# The journal's orbit and the joint force
# ---------------------------------------
# The journal centre relative to the bearing centre, over the clearance: 1 is the wall.
# It flies free, hits and rebounds where the load on the joint turns; the contact force
# spikes above the ideal joint's force.
fig, ax = plt.subplots(1, 2, figsize=(11, 4.5), layout="constrained")
phi = np.linspace(0, 2 * np.pi, 200)
ax[0].plot(np.cos(phi), np.sin(phi), "k", lw=0.8, label="clearance circle")
ax[0].plot(
    a["ecc_x"] / params.clearance,
    a["ecc_y"] / params.clearance,
    lw=0.8,
    label="journal centre",
)
ax[0].set(
    xlabel="e_x / c [-]", ylabel="e_y / c [-]", aspect="equal", title="journal orbit"
)
ax[0].legend(loc="upper right", fontsize="small")
ax[1].plot(a["crank_angle"], a["contact_force"], lw=0.8, label="clearance joint")
ax[1].plot(b["crank_angle"], b["contact_force"], "k", label="ideal joint")
ax[1].set(
    xlabel="crank angle [deg]",
    ylabel="joint force at B [N]",
    yscale="log",
    xlim=(0, 360),
    title="joint force",
)
ax[1].legend()
plt.show()
