"""The paper's slider-crank after many crank cycles of wear at B (docs/physics.md section 11).

Source problem: the paper's slider-crank (docs/physics.md section 6.2: 500 rpm, c = 0.1 mm,
steel on steel, Wang-Liu law, cr 0.9, no friction) with the bearing at B wearing by
Archard's law.  One cycle is one crank revolution after a start-up revolution (the start
from the ideal mechanism's state puts 22 impacts into the first one): each run covers two
revolutions, and the wear of the second, read at its start and its end, is the cycle's.
:func:`exuclear.predict_wear` extrapolates it over ``--cycles`` revolutions.  Then the
mechanism runs again with the worn bearing, against the unworn one.

Qualitative: Flores (Mech. Mach. Theory 44 (2009) 1211-1222) found the wear of a
slider-crank's joint "not uniformly distributed" around the bearing, concentrated where the
joint force points during the cycle; no published profile of this mechanism is at hand to
check the numbers against.

Outputs, in ``results/wear/``: ``slider_crank_wear_map.png`` (the polar wear map of the
bearing at B after the updates), ``slider_crank_worn.png`` (joint force, journal orbit
and slider acceleration, unworn and worn), ``slider_crank_wear.md`` (the numbers and the
wall time).  Run from the repository root::

    python -m validation.wear.slider_crank [--cycles N] [--coefficient K_D] [--out DIR]
"""
from __future__ import annotations

import argparse
import math
import os
import time
from dataclasses import replace

import numpy as np

import exuclear
from exuclear.models import slider_crank as sc
from exuclear.models._slider_crank_run import columns
from exuclear.wear import WearProfile
from validation._tables import markdown_table

DEFAULT_OUT = os.path.join("results", "wear")
#: A wear coefficient of hardened steel on steel: k = 1e-4 over H = 5 GPa [1/Pa].
COEFFICIENT = 2e-14
CYCLES = 1e6


class _SteadyCycle:
    """What :func:`exuclear.predict_wear` reads of one run: the profiles the run started from,
    ``bearing`` and ``journal``, plus the wear of its second revolution (``end`` - ``mid``)."""

    def __init__(self, bearing: np.ndarray, journal: np.ndarray, mid: WearProfile, end: WearProfile) -> None:
        self.profile = WearProfile(end.theta, bearing + end.bearing - mid.bearing, journal + end.journal - mid.journal,
                                   end.slip - mid.slip, end.stability - mid.stability, end.journal_radius,
                                   end.bearing_radius, end.length)

    def wear_profile(self) -> WearProfile:
        return self.profile


def _params(coefficient: float, backend: str) -> sc.SliderCrankParams:
    return sc.SliderCrankParams.paper(revolutions=2.0, wear_coefficient=coefficient, backend=backend)


def run_worn(params: sc.SliderCrankParams, wear: exuclear.Wear):
    """Build the slider-crank with ``wear`` at B (its profiles where it starts), run it with
    the scene's default settings; the model, the run and the profiles after one revolution."""
    model = sc.build(params)
    model.joint.joint = replace(model.joint.joint, wear=wear)
    period = 2.0 * math.pi / abs(params.crank_speed)
    mid: list[WearProfile] = []

    def snapshot(mbs, t):  # the profiles at the end of the start-up revolution
        if not mid and t >= period:
            mid.append(model.joint.wear_profile())
        return True

    model.mbs.SetPreStepUserFunction(snapshot)
    sim = exuclear.simulate(model.mbs, sc.default_settings(params))
    if not sim.success:
        raise RuntimeError(f"the slider-crank stopped: {sim.message}")
    return model, sim, mid[0] if mid else None


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.wear.slider_crank", description=__doc__.split("\n\n")[0])
    ap.add_argument("--cycles", type=float, default=CYCLES, help="crank revolutions to predict (default %(default)g)")
    ap.add_argument("--coefficient", type=float, default=COEFFICIENT, help="k_D [1/Pa] (default %(default)g)")
    ap.add_argument("--backend", default="compiled", choices=("compiled", "python"), help="the joint's kernel")
    ap.add_argument("--out", default=DEFAULT_OUT, help="output directory (default %(default)s)")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    params = _params(args.coefficient, args.backend)
    wear = params.joint.wear
    runs = [0]

    def one_cycle(current: exuclear.Wear) -> _SteadyCycle:
        model, _sim, mid = run_worn(params, current)
        runs[0] += 1
        start = [np.array(p) if p is not None else np.zeros(wear.nodes) for p in (current.bearing, current.journal)]
        return _SteadyCycle(*start, mid, model.joint.wear_profile())

    t0 = time.perf_counter()
    prediction = exuclear.predict_wear(one_cycle, wear, args.cycles)
    wall = time.perf_counter() - t0
    final = prediction.final
    depth, angle = final.deepest()
    print(f"{args.cycles:g} revolutions predicted in {wall:.1f} s ({runs[0]} runs of two revolutions, "
          f"{len(prediction.steps)} updates): largest depth {depth * 1e6:.3f} um at {math.degrees(angle):.1f} deg, "
          f"worn volume {final.volume['bearing'] * 1e9:.4g} mm^3")

    # the wear map after some of the updates
    ax = plt.figure(figsize=(5.5, 5.5), layout="constrained").add_subplot(projection="polar")
    picks = sorted({0, len(prediction.cycles) // 4, len(prediction.cycles) // 2, len(prediction.cycles) - 1})
    for k in picks:
        prediction.profiles[k].plot(ax, label=f"{prediction.cycles[k]:.3g} revolutions")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.06), ncol=2, fontsize="small")
    ax.set_title("bearing wear depth at B [um] (joint frame)", fontsize=10, pad=14)
    map_png = os.path.join(args.out, "slider_crank_wear_map.png")
    plt.savefig(map_png, dpi=130)

    # the mechanism unworn and worn
    unworn_model, _, _ = run_worn(params, wear.starting_from(None, None))
    worn_model, _, _ = run_worn(params, wear.starting_from(final.bearing, None))
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2), layout="constrained")
    rows = []
    c = params.clearance
    for label, model in (("unworn", unworn_model), (f"worn, {args.cycles:.3g} revolutions", worn_model)):
        cols = columns(model)
        second = cols["time"] >= 2.0 * math.pi / abs(params.crank_speed)
        crank = cols["crank_angle"][second] - 360.0
        axes[0].plot(crank, cols["contact_force"][second], lw=0.8, label=label)
        axes[1].plot(cols["ecc_x"][second] / c, cols["ecc_y"][second] / c, lw=0.8, label=label)
        axes[2].plot(crank, cols["slider_a"][second], lw=0.8, label=label)
        impacts = len(model.joint.history.onset_times)
        rows.append([label, f"{cols['contact_force'].max():.1f}", f"{cols['contact_force'][second].max():.1f}",
                     str(impacts), f"{np.hypot(cols['ecc_x'], cols['ecc_y'])[second].max() / c:.3f}"])
    phi = np.linspace(0, 2 * np.pi, 200)
    axes[1].plot(np.cos(phi), np.sin(phi), "k", lw=0.6)
    axes[0].set(xlabel="crank angle [deg]", ylabel="contact force at B [N]", title="joint force, second revolution")
    axes[1].set(xlabel="e_x / c", ylabel="e_y / c", aspect="equal", title="journal orbit, second revolution")
    axes[2].set(xlabel="crank angle [deg]", ylabel="slider acceleration [m/s^2]",
                title="slider acceleration, second revolution")
    for a in axes:
        a.legend(fontsize="small")
        a.grid(alpha=0.3)
    worn_png = os.path.join(args.out, "slider_crank_worn.png")
    fig.savefig(worn_png, dpi=130)

    header = ["mechanism", "peak contact force [N]", "peak, second revolution [N]", "impacts", "largest |e|/c, second"]
    updates = [[f"{n:.4g}", f"{s:.4g}", f"{b:.4g}", f"{p.deepest()[0] * 1e9:.4g}"]
               for n, s, b, p in zip(prediction.cycles, prediction.steps, prediction.bounds, prediction.profiles)]
    md = os.path.join(args.out, "slider_crank_wear.md")
    with open(md, "w") as f:
        f.write(f"# The paper's slider-crank after {args.cycles:g} revolutions of wear at B\n\n"
                f"k_D = {args.coefficient:g} 1/Pa, {args.backend} kernel; predicted in {wall:.1f} s on this machine "
                f"({runs[0]} runs of two revolutions, {len(prediction.steps)} updates).  Largest depth "
                f"{depth * 1e6:.4g} um at {math.degrees(angle):.1f} deg of the joint frame; worn volume "
                f"{final.volume['bearing'] * 1e9:.4g} mm^3.  Qualitative (Flores 2009: the wear is not uniformly "
                "distributed).\n\n" + markdown_table(header, rows) + "\n\n## The updates\n\n"
                + markdown_table(["revolutions", "dN", "bound", "largest depth [nm]"], updates) + "\n")
    print(markdown_table(header, rows))
    print(f"wrote {map_png}\nwrote {worn_png}\nwrote {md}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
