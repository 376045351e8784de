"""
A slider-crank whose slider has play in its guide
=================================================

The benchmark of Flores, Leine and Glocker (2010): an undriven crank starts at 150 rad/s, and
the slider (0.10 m x 0.05 m, 1 mm of play per side) strikes the guide's walls with its
corners. ``exuclear.CreatePrismaticClearanceJoint`` pairs each of the slider's four corners
with both walls, each pair with its own law (``K delta^1.5`` with Carvalho-Martins damping,
restitution 0.4) and friction (0.01). The scene is ``exuclear.models.guided_slider_crank``;
this short run covers the first 30 ms (the benchmark runs 0.15 s, two crank turns). The
figure shows the slider's centre in the guide (``y / c`` = 1: against the upper wall), the
crank's speed (the undriven mechanism trades it with the slider's motion; each strike puts a
kink in it), and the contact force of every corner-wall pair that touches.
"""

import matplotlib.pyplot as plt

from exuclear.models import guided_slider_crank as scene
from exuclear.prismatic import pair_name

params = scene.GuidedSliderCrankParams.benchmark()
result = scene.run(params, scene.default_settings(params, end_time=0.03))
print(f"{len(result.impacts)} corner contacts, crank speed {result.crank_speed[-1]:.1f} rad/s at 30 ms")

fig, ax = plt.subplots(3, 1, figsize=(7, 8), sharex=False)
ax[0].plot(result.slider[:, 0] / params.crank_length, result.slider[:, 1] / params.clearance, lw=0.8)
ax[0].set(xlabel="x / l1", ylabel="y / c", title="the slider's centre in the guide")
ax[1].plot(result.time * 1e3, result.crank_speed, lw=0.8)
ax[1].set(xlabel="t [ms]", ylabel="crank speed [rad/s]")
for k in range(result.normal_force.shape[1]):
    if result.normal_force[:, k].max() > 0.0:
        ax[2].plot(result.time * 1e3, result.normal_force[:, k], lw=0.8, label=pair_name(k))
ax[2].set(xlabel="t [ms]", ylabel="corner force [N]")
ax[2].legend(fontsize=8)
fig.tight_layout()
plt.show()
