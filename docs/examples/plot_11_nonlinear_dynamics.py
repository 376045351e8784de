"""
Periodic or chaotic: phase portrait, Poincare map and orbit diagram
===================================================================

:mod:`exuclear.nonlinear` answers the question the papers on clearance joints ask again
and again: does the mechanism settle on a periodic motion, or is it chaotic?  Here:

1. the phase portrait of the slider-crank's journal in its clearance circle
   (``e_x / c`` against ``e_y / c``) with its Poincare points once per crank turn
   (:func:`~exuclear.nonlinear.stroboscopic`);
2. the Poincare map of the driven damped pendulum of Baker and Gollub in its chaotic
   window, and its verdict (:func:`~exuclear.nonlinear.classify`: the 0-1 test and the
   largest Lyapunov exponent of two copies of the model in one Exudyn system);
3. the pendulum's orbit diagram over its forcing amplitude
   (:func:`~exuclear.nonlinear.orbit_diagram`, here in this process; on all cores or a
   Dask cluster with ``workers=`` or ``scheduler=``), with the exponent of each value.

The same diagram from the command line:
``exuclear bifurcation exuclear.models.driven_pendulum --parameter forcing
--values 1.0:1.5:0.04 --periods 30 --transient 60 --exponent --out pendulum.csv``.
"""

import contextlib
import io

import matplotlib.pyplot as plt
import numpy as np

from exuclear.models import driven_pendulum, slider_crank
from exuclear.nonlinear import classify, exponent_of, orbit_diagram, run_sections, stroboscopic
from exuclear.nonlinear.plot import bifurcation, exponent_plot, phase_portrait, poincare_map

# %%
# The slider-crank with the paper's modified Coulomb friction at joint B: after the first
# turn's impacts the journal stays on the wall (``|e| / c`` just above 1) and rides round it
# once per crank turn, so the Poincare points after the start (the centre) pile up on one
# spot.
params = slider_crank.SliderCrankParams.paper(friction="paper", revolutions=4)
result = slider_crank.run(params)
c, cols = params.clearance, result.columns
period = 2.0 * np.pi / params.crank_speed
_, sections = stroboscopic(cols["time"], np.column_stack([cols["ecc_x"], cols["ecc_y"]]) / c, period)
phase_portrait(cols["ecc_x"] / c, cols["ecc_y"] / c, sections=sections[1:].T, ax=plt.subplots(figsize=(5, 5))[1])
plt.show()

# %%
# The pendulum at ``g = 1.5``: its Poincare map is the strange attractor of Baker and
# Gollub's figure 3.5.  Two copies of the model run side by side, the second kept 1e-6 away
# and set back once per period: the largest exponent comes out positive.
with contextlib.redirect_stdout(io.StringIO()):  # Exudyn's note on the Python force function
    run = run_sections(driven_pendulum.driven({"forcing": 1.5}), periods=400, transient_periods=20,
                       perturbation=1e-6)
theta = np.arctan2(run.samples["sin"], run.samples["cos"])
exponent = exponent_of(run, 20)[0]
verdict = classify(np.column_stack(list(run.samples.values())), exponent=exponent)
print(verdict)
poincare_map(theta, run.samples["omega"], xlabel="theta [rad]", ylabel="d theta / dt", title=f"g = 1.5: {verdict.kind}",
             ax=plt.subplots(figsize=(5, 4.5))[1])
plt.show()

# %%
# The orbit diagram over the forcing amplitude: periodic responses of several periods,
# chaos (a positive exponent) from about 1.15, and periodic windows within it.  Each value
# starts from rest, so where two attractors coexist it lands on one of them; 30 periods
# after 60 are sampled (too few for the 0-1 test: the exponent decides).
with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
    table = orbit_diagram("exuclear.models.driven_pendulum", "forcing", np.round(np.arange(1.0, 1.51, 0.04), 2),
                          periods=30, transient_periods=60, exponent=True, workers=1)
print(table[["forcing", "verdict"]].to_string(index=False))
fig, ax = plt.subplots(2, 1, figsize=(7, 6), sharex=True, layout="constrained")
bifurcation(table, "forcing", "omega", ax=ax[0])
exponent_plot(table, "forcing", ax=ax[1])
plt.show()
