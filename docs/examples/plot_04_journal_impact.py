"""
The paper's journal-bearing impact
==================================

The first example of Wang, Liu, Ma and Tong, *J. Mech. Sci. Technol.* 31(2) (2017)
587-597: a steel journal of 40 g (R_J = 9.9 mm) touches the wall of a steel bearing
(R_B = 10 mm, L = 15 mm) and moves into it at 0.3 m/s; no gravity, no friction.  The scene
is :mod:`exuclear.models.journal_bearing`: :meth:`JournalBearingParams.paper` gives the
paper's values, :func:`run` simulates one impact and summarises it.  The paper gives a
departure velocity of 0.269 m/s at ``cr = 0.9``.
"""

import matplotlib.pyplot as plt

from exuclear.models.journal_bearing import JournalBearingParams, run

results = {}
for cr in (0.5, 0.7, 0.9):
    summary, out = run(JournalBearingParams.paper(cr=cr))
    results[cr] = out
    print(
        f"cr = {cr}: departure velocity {summary.departure_velocity:.4f} m/s "
        f"(cr v = {summary.newton_departure_velocity:.3f}), peak force {summary.max_force:.0f} N, "
        f"max penetration {summary.max_penetration * 1e6:.2f} um, contact {summary.contact_duration * 1e6:.1f} us"
    )

# %%
# Force against penetration and time
# -----------------------------------
# The loop of each impact, as in the paper's Figs. 4-7: loading on the upper branch,
# unloading on the lower one; the area between them is the energy the damping takes.
fig, ax = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
for cr, out in results.items():
    inside = out["penetration"] > 0
    ax[0].plot(
        out["penetration"][inside] * 1e6,
        out["normal_force"][inside],
        label=f"cr = {cr}",
    )
    ax[1].plot(out["time"] * 1e6, out["normal_force"], label=f"cr = {cr}")
ax[0].set(
    xlabel="penetration [um]",
    ylabel="normal contact force [N]",
    title="force-penetration loop",
)
ax[1].set(
    xlabel="time [us]", ylabel="normal contact force [N]", title="contact force history"
)
for a in ax:
    a.legend()
    a.grid(alpha=0.3)
plt.show()
