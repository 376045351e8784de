"""
Is the run converged? The convergence check
===========================================

Impacts make a clearance joint's motion sensitive to the step: a run can look right and
still follow another path than a finer one.  :func:`exuclear.check_convergence` runs the
model a second time at a tighter step (a quarter by default) and says what agrees between
the two runs, and until when: the journal's path within 1 % of the clearance, the impacts
one by one, the peak forces.  It needs a function that builds and runs the model for given
settings and returns a :class:`exuclear.RunRecord`; here the paper's slider-crank
(:mod:`exuclear.models.slider_crank`) for a quarter of a crank revolution.
"""

import matplotlib.pyplot as plt

import exuclear
from exuclear.models import slider_crank as sc

params = sc.SliderCrankParams.paper(revolutions=0.25)


def model(settings):
    """Build the scene, run it with ``settings``, return what the check compares."""
    scene = sc.build(params)
    result = exuclear.simulate(scene.mbs, settings)
    return exuclear.RunRecord.from_handles(result, {"B": scene.joint})


settings = sc.default_settings(params)
check = exuclear.check_convergence(model, settings)
print(check.report())

# %%
# The difference between the two paths
# -------------------------------------
# The distance between the journal centres of the run and of the tighter run, over the
# clearance, against time; the check's bound (1 % of c) and the horizon up to which the
# paths agree.
j = check.joints["B"]
fig, ax = plt.subplots(figsize=(8, 4), layout="constrained")
ax.semilogy(j.time * 1e3, j.de / j.clearance, label="|e - e_tighter| / c")
ax.axhline(0.01, color="grey", ls=":", label="bound: 1 % of c")
ax.axvline(
    j.horizon * 1e3,
    color="C3",
    ls="--",
    label=f"paths agree until {j.horizon * 1e3:.1f} ms",
)
ax.set(
    xlabel="time [ms]",
    ylabel="path difference / clearance [-]",
    title=f"slider-crank, step {settings.step:.2g} s against {check.reference_settings.step:.2g} s",
)
ax.legend()
plt.show()
