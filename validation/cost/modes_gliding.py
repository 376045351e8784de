"""The issue-52 scene of a spatial journal gliding on its slices with friction: free along
its axis, resting on its bearing's bottom, sliding along the axis at 0.2 m/s and spinning at
50 rad/s (``coulomb:0.2``), in both contact modes against the compliant contact at
``--factor`` times the steps.

Prints per run the steps and Newton iterations, the largest distance of the journal's centre
across the axis and its final axial position from the reference's (in clearances), the
largest differences of the axial velocity and the spin, and when the axial slide stops
(Coulomb's law: the slip ``(v_a, R w)`` slows along itself, both parts reaching 0 at once).

::

    python -m validation.cost modes_gliding [--end 0.2] [--step 1e-4] [--factor 4]
"""
from __future__ import annotations

import argparse

import numpy as np

from validation._tables import markdown_table
from validation.cost._joint_type_scenes import solve
from validation.cost._spatial_scenes import CLEARANCE, spatial_journal

#: An axial speed [m/s] below this is taken as the slide's stop.
STOPPED = 1e-3


def glide(mode: str, step: float, end: float) -> tuple[np.ndarray, int, int]:
    """The run's states (t, position, velocity, angular velocity), steps and Newton iterations."""
    mbs, _, states = spatial_journal((0.0, 0.0, 0.2), (0.0, 0.0, 50.0), (0.0, -CLEARANCE, 0.0), (0.0, -9.81, 0.0),
                                     contact_mode=mode, friction="coulomb:0.2")
    solve(mbs, step, end)
    it = mbs.sys["dynamicSolver"].it
    return np.array(states), int(it.currentStepIndex) - 1, int(it.newtonStepsCount)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost modes_gliding", description=__doc__.split("\n")[0])
    ap.add_argument("--end", type=float, default=0.2, help="the run's end [s] (default 0.2)")
    ap.add_argument("--step", type=float, default=1e-4, help="the runs' step [s] (default 1e-4)")
    ap.add_argument("--factor", type=float, default=4.0, help="the reference's steps per step (default 4)")
    args = ap.parse_args(argv)
    reference, *_ = glide("compliant", args.step / args.factor, args.end)
    rows = []
    for mode, step in (("compliant", args.step), ("impulse", args.step), ("impulse", args.step / args.factor)):
        s, steps, newton = glide(mode, step, args.end)
        r = np.array([np.interp(s[:, 0], reference[:, 0], reference[:, k]) for k in range(10)]).T
        stop = s[np.argmax(np.abs(s[:, 6]) < STOPPED), 0] if (np.abs(s[:, 6]) < STOPPED).any() else np.nan
        rows.append([f"{mode}, {step:g} s", f"{steps} / {newton}",
                     f"{np.linalg.norm(s[:, 1:3] - r[:, 1:3], axis=1).max() / CLEARANCE:.3g}",
                     f"{abs(s[-1, 3] - r[-1, 3]) / CLEARANCE:.3g}", f"{np.abs(s[:, 6] - r[:, 6]).max():.2g}",
                     f"{np.abs(s[:, 9] - r[:, 9]).max():.2g}", f"{stop:.4g}"])
    stop = reference[np.argmax(np.abs(reference[:, 6]) < STOPPED), 0]
    rows.append([f"compliant, {args.step / args.factor:g} s (reference)", "", "", "", "", "", f"{stop:.4g}"])
    print(markdown_table(["run", "steps / Newton", "centre across the axis off [c]", "axial position off at the end [c]",
                          "v_a off [m/s]", "w off [rad/s]", "slide stops [s]"], rows))
    return 0
