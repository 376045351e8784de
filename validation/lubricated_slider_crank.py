"""The paper's slider-crank with a lubricated joint at B, dry and lubricated side by side (issue 23).

Source problem: example 2 of X. Wang, G. Liu, S. Ma, R. Tong, J. Mech. Sci. Technol. 31(2)
(2017) 587-597 (docs/physics.md section 6.2): the slider-crank at 500 rpm with the clearance
joint at the rod-slider pin B (c = 0.1 mm, L = 15 mm, steel on steel, Wang-Liu law, cr = 0.9,
no friction), in the redundant formulation, two revolutions, the scene's default settings.
Three runs: the joint at B dry (the paper's), the same joint lubricated, and the ideal
mechanism.  The lubricated-joint literature (Ravn, Shivaswamy, Alshaer, Lankarani, J. Mech.
Des. 122 (2000) 484; Flores, Ambrosio, Claro, Lankarani, Mech. Mach. Theory 41 (2006) 247;
Flores et al., Nonlinear Dyn. 56 (2009) 277) finds that the oil film

(a) removes the impact peaks of the joint force,
(b) keeps the journal off the bearing wall,
(c) brings the slider acceleration close to the ideal mechanism's;

each is checked here with numbers: (a) the peak joint force (film and metal contact
together) against the dry joint's and the ideal joint's; (b) the largest eccentricity ratio,
the smallest film thickness ``c - |e|`` and the share of the time in metal contact; (c) the
RMS deviation of the slider acceleration from the ideal mechanism's closed form.

**The oil** (:data:`OIL_VISCOSITY`): an SAE 40 engine oil of the grades 15W-40, 20W-40,
25W-40 or 40 at the smallest viscosity its grade guarantees in a hot engine bearing: SAE J300
sets a high-temperature high-shear (HTHS) viscosity of at least 3.7 mPa s at 150 degC for
them (ASTM D4683, shear rate 1e6 1/s; SAE J300 as tabulated e.g. by Anton Paar,
https://wiki.anton-paar.com/za-en/sae-viscosity-grades/).  HTHS is the grade's viscosity
under the shear of an engine bearing, so this is the hot, thin end of what the joint meets;
a cooler oil is thicker, and :data:`SWEEP_VISCOSITIES` shows what that changes.  The film
model is the finite bearing (Butenschoen, docs/physics.md section 10.3): B/D = 15 / 19.8 =
0.76 lies inside its fits (1/8 ... 1), where the short model overestimates an approaching
journal's squeeze force by up to a factor 6.5 (section 10.6).

Also: the wall time of the lubricated run over the dry one's (medians of ``--repeats``
runs each, dry and lubricated alternately: the machine is shared) and the lubricated run's
accuracy by the scene's :func:`~exuclear.models.slider_crank.check_convergence` (a run at
steps four times smaller as the reference).

Run from the repository root::

    python -m validation.lubricated_slider_crank [--out DIR] [--repeats N] [--viscosity ETA]

Writes ``acceleration.png`` (slider acceleration dry, lubricated and ideal against the
crank angle), ``orbit.png`` (the journal centre inside the clearance circle),
``joint_force.png`` and ``report.md`` to ``results/lubricated_slider_crank/``.
"""
from __future__ import annotations

import argparse
import math
import os
import statistics
import sys
import warnings
from dataclasses import dataclass

import numpy as np

from exuclear.engine import AccuracyWarning
from exuclear.models import slider_crank as sc
from validation._tables import markdown_table

#: The oil's dynamic viscosity [Pa s]: SAE J300's smallest HTHS viscosity at 150 degC of the
#: SAE 40 grades 15W-40, 20W-40, 25W-40 and 40 (module docstring).
OIL_VISCOSITY = 3.7e-3
#: The film model: the finite bearing, B/D = 0.76 inside its fits (module docstring).
FILM_MODEL = "finite"
#: Viscosities of the sweep [Pa s]: the oil above up to a thick oil (0.1 Pa s is of the
#: order of an SAE 30 oil near 40 degC, exuclear.Lubrication's docstring), to see where the
#: journal stays off the wall.
SWEEP_VISCOSITIES = (3.7e-3, 1e-2, 2e-2, 5e-2, 1e-1)
#: Timed runs of each kind (dry, lubricated), alternately; the medians are compared.
DEFAULT_REPEATS = 5


@dataclass
class Case:
    """One run: its name, parameters and result."""

    name: str
    params: sc.SliderCrankParams
    result: sc.SliderCrankResult


def paper(viscosity: float | None = None, ideal: bool = False) -> sc.SliderCrankParams:
    """The paper's slider-crank in the redundant formulation; oil at B with ``viscosity``."""
    changes = {} if viscosity is None else {"viscosity": viscosity, "film_model": FILM_MODEL}
    return sc.SliderCrankParams.paper(formulation="redundant", ideal=ideal, **changes)


def run(params: sc.SliderCrankParams) -> sc.SliderCrankResult:
    """A run at the scene's default settings (their AccuracyWarning, if any, is in ``notes``)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", AccuracyWarning)
        result = sc.run(params, sc.default_settings(params))
    if not result.success:
        raise RuntimeError(f"the run {params} failed: {result.message}")
    return result


def rms_deviation(cols: dict[str, np.ndarray], params: sc.SliderCrankParams) -> float:
    """RMS over the run of the slider acceleration minus the ideal mechanism's closed form
    (:func:`~exuclear.models.slider_crank.ideal_slider_acceleration`) [m/s^2], trapezoid rule."""
    t = cols["time"]
    ideal = sc.ideal_slider_acceleration(np.radians(cols["crank_angle"]), params.crank_speed, params.crank_length,
                                         params.rod_length)
    return math.sqrt(float(np.trapezoid((cols["slider_a"] - ideal) ** 2, t)) / (t[-1] - t[0]))


def time_share(cols: dict[str, np.ndarray], flag: np.ndarray) -> float:
    """The share of the run's time where ``flag`` holds (trapezoid rule: the outputs are
    denser around contact onsets, where the steps are shorter, so a count would overweight them)."""
    t = cols["time"]
    return float(np.trapezoid(flag.astype(float), t)) / (t[-1] - t[0])


def summary(case: Case) -> dict[str, float]:
    """The numbers of claims (a)-(c) for one run."""
    cols, p = case.result.columns, case.params
    ecc = np.hypot(cols["ecc_x"], cols["ecc_y"]) / p.clearance
    lubricated = "joint_force" in cols
    return {
        "peak_joint_force": float(np.max(cols["joint_force"] if lubricated else cols["contact_force"])),
        "peak_contact_force": float(np.max(cols["contact_force"])) if not p.ideal else math.nan,
        "max_eccentricity_ratio": float(ecc.max()) if not p.ideal else math.nan,
        "min_film_thickness": float(p.clearance * (1.0 - ecc.max())) if not p.ideal else math.nan,
        "metal_contact_share": time_share(cols, cols["penetration"] > 0.0) if not p.ideal else math.nan,
        "impacts": case.result.impacts if not p.ideal else 0,
        "rms_dev": rms_deviation(cols, p),
        "wall_time": case.result.wall_time,
    }


def timing(repeats: int, viscosity: float) -> tuple[list[float], list[float]]:
    """Solver wall times [s] of ``repeats`` dry and lubricated runs, alternately."""
    dry, oiled = [], []
    for _ in range(repeats):
        dry.append(run(paper()).wall_time)
        oiled.append(run(paper(viscosity)).wall_time)
    return dry, oiled


def figures(cases: list[Case], directory: str) -> list[str]:
    """The literature's figures: slider acceleration and joint force against the crank angle
    (dry, lubricated, ideal), the journal centre's orbit inside the clearance circle."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    styles = {"dry": dict(color="tab:red", lw=0.7), "lubricated": dict(color="tab:blue", lw=0.9),
              "ideal": dict(color="k", ls="--", lw=1.0)}
    paths = []
    for key, label, log in (("slider_a", "slider acceleration [m/s²]", False),
                            ("force", "joint force at B (film and contact) [N]", True)):
        fig, ax = plt.subplots(figsize=(7.5, 3.8))
        for case in cases:
            cols = case.result.columns
            y = cols["slider_a"] if key == "slider_a" else cols.get("joint_force", cols["contact_force"])
            ax.plot(cols["crank_angle"], y, label=case.name, **styles[case.name])
        ax.set_xlabel("crank angle [°]")
        ax.set_ylabel(label)
        if log:
            ax.set_yscale("log")
            ax.set_ylim(bottom=1.0)
        ax.legend(fontsize=8)
        fig.tight_layout()
        paths.append(os.path.join(directory, "acceleration.png" if key == "slider_a" else "joint_force.png"))
        fig.savefig(paths[-1], dpi=130)
        plt.close(fig)
    fig, ax = plt.subplots(figsize=(5.0, 5.0))
    clearance = cases[0].params.clearance * 1e6
    angle = np.linspace(0.0, 2.0 * math.pi, 361)
    ax.plot(clearance * np.cos(angle), clearance * np.sin(angle), "k-", lw=0.8, label="clearance circle")
    for case in cases:
        if not case.params.ideal:
            cols = case.result.columns
            ax.plot(cols["ecc_x"] * 1e6, cols["ecc_y"] * 1e6, label=case.name, **styles[case.name])
    ax.set_aspect("equal")
    ax.set_xlabel("journal centre x - bearing centre x [µm]")
    ax.set_ylabel("y [µm]")
    ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    paths.append(os.path.join(directory, "orbit.png"))
    fig.savefig(paths[-1], dpi=130)
    plt.close(fig)
    return paths


def _row(name: str, s: dict[str, float]) -> list[str]:
    def g(x: float, fmt: str = ".4g") -> str:
        return "-" if isinstance(x, float) and math.isnan(x) else format(x, fmt)

    return [name, g(s["peak_joint_force"]), g(s["peak_contact_force"]), g(s["max_eccentricity_ratio"]),
            g(s["min_film_thickness"] * 1e6), g(100.0 * s["metal_contact_share"], ".3g"), str(s["impacts"]),
            g(s["rms_dev"]), g(s["wall_time"], ".3g")]


HEADER = ["run", "peak joint force [N]", "peak metal contact force [N]", "largest eps", "smallest film c - e [um] (negative: penetration)",
          "metal contact [% of the time]", "contact onsets", "RMS slider acc. - ideal [m/s^2]", "solver wall [s]"]


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.lubricated_slider_crank", description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="results/lubricated_slider_crank", help="output directory (default %(default)s)")
    ap.add_argument("--repeats", type=int, default=DEFAULT_REPEATS,
                    help="timed runs of each kind, alternately (default %(default)s)")
    ap.add_argument("--viscosity", type=float, default=OIL_VISCOSITY,
                    help="the oil's dynamic viscosity [Pa s] (default %(default)s: SAE 40, HTHS at 150 degC)")
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error(f"--repeats must be a positive whole number, got {args.repeats}")
    if not args.viscosity > 0.0:
        ap.error(f"--viscosity must be positive, got {args.viscosity}")
    os.makedirs(args.out, exist_ok=True)
    cases = [Case(name, p, run(p)) for name, p in (("dry", paper()), ("lubricated", paper(args.viscosity)),
                                                     ("ideal", paper(ideal=True)))]
    sums = {case.name: summary(case) for case in cases}
    for path in figures(cases, args.out):
        print(f"wrote {path}")
    dry, oiled = timing(args.repeats, args.viscosity)
    ratio = statistics.median(oiled) / statistics.median(dry)
    convergence = sc.check_convergence(cases[1].params)
    de = convergence.joints["B"].max_de
    sweep = [summary(Case(f"{eta:g} Pa s", p, run(p))) for eta in SWEEP_VISCOSITIES for p in [paper(eta)]]
    d, lub, ideal = sums["dry"], sums["lubricated"], sums["ideal"]
    claims = [
        ["(a) film removes the impact peaks", f"peak joint force {lub['peak_joint_force']:.4g} N lubricated, "
         f"{d['peak_joint_force']:.4g} N dry, {ideal['peak_joint_force']:.4g} N ideal",
         f"{d['peak_joint_force'] / lub['peak_joint_force']:.3g} times lower than dry"],
        ["(b) journal stays off the wall", f"largest eps {lub['max_eccentricity_ratio']:.4g}, smallest film c - e "
         f"{lub['min_film_thickness'] * 1e6:.3g} um, metal contact {100 * lub['metal_contact_share']:.3g} % of the "
         "time", "holds" if lub["max_eccentricity_ratio"] < 1.0 else "does not hold at this viscosity (sweep below)"],
        ["(c) slider acceleration close to the ideal", f"RMS deviation {lub['rms_dev']:.4g} m/s^2 lubricated, "
         f"{d['rms_dev']:.4g} m/s^2 dry (ideal RMS {rms_deviation_from_zero(cases[2]):.4g} m/s^2)",
         f"{d['rms_dev'] / lub['rms_dev']:.3g} times closer than dry"],
    ]
    report = "\n\n".join([
        "# The paper's slider-crank with a lubricated joint at B",
        f"Redundant formulation, two revolutions at 500 rpm, the scene's default settings; oil "
        f"{args.viscosity:g} Pa s, {FILM_MODEL} film (`python -m validation.lubricated_slider_crank`).",
        markdown_table(HEADER, [_row(name, s) for name, s in sums.items()]),
        markdown_table(["claim", "measured", "verdict"], claims),
        f"Wall time, lubricated / dry: {ratio:.3g} (medians of {args.repeats} solver runs each, alternately: dry "
        f"{statistics.median(dry):.3g} s, lubricated {statistics.median(oiled):.3g} s; target at most 2).",
        f"Accuracy of the lubricated run (check_convergence, steps / 4 as the reference): largest |de| / c = "
        f"{de:.2g}; path agrees over the whole run: {convergence.path_agrees}.",
        "## Viscosity sweep (the same run, finite film)",
        markdown_table(HEADER, [_row(f"{eta:g} Pa s", s) for eta, s in zip(SWEEP_VISCOSITIES, sweep)]),
    ])
    with open(os.path.join(args.out, "report.md"), "w", encoding="utf-8") as f:
        f.write(report + "\n")
    print(report)
    print(f"wall-time ratio lubricated / dry: {ratio:.3g}; lubricated accuracy max |de|/c = {de:.2g}")
    return 0


def rms_deviation_from_zero(case: Case) -> float:
    """RMS of the ideal mechanism's slider acceleration [m/s^2]: the scale of claim (c)."""
    cols = case.result.columns
    t = cols["time"]
    return math.sqrt(float(np.trapezoid(cols["slider_a"] ** 2, t)) / (t[-1] - t[0]))


if __name__ == "__main__":
    sys.exit(main())
