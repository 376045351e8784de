"""
A dry joint against a lubricated one
====================================

The paper's slider-crank (:mod:`exuclear.models.slider_crank`, 500 rpm, c = 0.1 mm) once
dry and once with oil in the clearance joint: ``viscosity`` (a
:class:`exuclear.Lubrication` on the joint) adds the hydrodynamic force of the film, here
the short-bearing model (``film_model="short"``) with an oil of 0.04 Pa s.  The command
line does the same with ``exuclear slider-crank --viscosity 0.04``.
"""

import matplotlib.pyplot as plt
import numpy as np

from exuclear.models.slider_crank import SliderCrankParams, run

dry = run(SliderCrankParams.paper(revolutions=1.0))
wet = run(SliderCrankParams.paper(revolutions=1.0, viscosity=0.04, film_model="short"))
for name, r in (("dry", dry), ("lubricated", wet)):
    print(
        f"{name:10s}: {r.impacts:2d} metal contacts, peak joint force "
        f"{np.max(r.columns.get('joint_force', r.columns['contact_force'])):.0f} N"
    )

# %%
# The film keeps journal and bearing apart: no metal contact, and the joint force (film
# and contact together) follows the load of the mechanism without the impact spikes.  The
# journal settles on an orbit inside the clearance (eccentricity ratio below 1).
c = 1e-4  # the paper's clearance [m]
a, b = dry.columns, wet.columns
fig, ax = plt.subplots(1, 2, figsize=(11, 4.5), layout="constrained")
ax[0].plot(a["crank_angle"], a["contact_force"], lw=0.8, label="dry: contact force")
ax[0].plot(b["crank_angle"], b["joint_force"], label="lubricated: film + contact force")
ax[0].set(
    xlabel="crank angle [deg]",
    ylabel="force in the joint at B [N]",
    yscale="log",
    xlim=(0, 360),
)
ax[0].legend()
phi = np.linspace(0, 2 * np.pi, 200)
ax[1].plot(np.cos(phi), np.sin(phi), "k", lw=0.8, label="clearance circle")
ax[1].plot(a["ecc_x"] / c, a["ecc_y"] / c, lw=0.8, label="dry")
ax[1].plot(b["ecc_x"] / c, b["ecc_y"] / c, label="lubricated")
ax[1].set(
    xlabel="e_x / c [-]", ylabel="e_y / c [-]", aspect="equal", title="journal orbit"
)
ax[1].legend(loc="upper right", fontsize="small")
plt.show()
