"""
A parameter study with its progress bar
=======================================

:class:`exuclear.Study` wraps a function of one parameter set that returns a row of
results; :func:`exuclear.grid` makes the runs of a grid; :func:`exuclear.run_study` runs
them on local cores (or a Dask cluster), shows a progress bar (tqdm) and returns a pandas
table, which it also writes to a CSV file that a second call resumes.  Here: the paper's
journal impact (:func:`exuclear.models.journal_bearing.run`) over the coefficient of
restitution and the bearing material, on one worker.  The same study from the command
line: ``exuclear study journal-bearing --cr 0.3:0.9:0.1 --bearing steel,aluminium --out t.csv``.
"""

import contextlib
import io

import matplotlib.pyplot as plt

import exuclear
from exuclear.models.journal_bearing import JournalBearingParams, run


def impact(values):
    """One run: the parameters of the grid in, a row of results out."""
    summary, _ = run(
        JournalBearingParams.paper(cr=values["cr"], bearing_material=values["bearing"])
    )
    return {
        "departure_velocity": summary.departure_velocity,
        "peak_force": summary.max_force,
        "duration": summary.contact_duration,
    }


study = exuclear.Study(impact, name="journal impact")
runs = exuclear.grid(cr=[0.3, 0.5, 0.7, 0.9], bearing=["steel", "aluminium"])
# workers=1: in this process, no pool.  The progress bar goes to stderr; here it is caught
# to show its last state (a terminal shows it updating in place).
with contextlib.redirect_stderr(io.StringIO()) as bar:
    table = exuclear.run_study(study, runs, workers=1)
print(bar.getvalue().split("\r")[-1].strip())
print(
    table[["cr", "bearing", "departure_velocity", "peak_force", "duration", "success"]]
)

# %%
# The table is a pandas DataFrame: one row per run, the parameters first, then the results
# and the run's status.  The softer aluminium bearing gives a lower, longer impact at the
# same restitution.
fig, ax = plt.subplots(1, 2, figsize=(11, 4), layout="constrained")
for bearing, rows in table.groupby("bearing"):
    ax[0].plot(rows["cr"], rows["departure_velocity"], "o-", label=f"{bearing} bearing")
    ax[1].plot(rows["cr"], rows["peak_force"], "o-", label=f"{bearing} bearing")
ax[0].plot([0.3, 0.9], [0.3 * 0.3, 0.9 * 0.3], "k:", label="cr x 0.3 m/s")
ax[0].set(xlabel="coefficient of restitution cr [-]", ylabel="departure velocity [m/s]")
ax[1].set(xlabel="coefficient of restitution cr [-]", ylabel="peak contact force [N]")
for a in ax:
    a.legend()
    a.grid(alpha=0.3)
plt.show()
