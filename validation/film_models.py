"""The film models of the lubricated joint against the Reynolds reference (issue 23).

Source problem: the steadily loaded journal bearing of DIN 31652 / Butenschoen (Diss.
Karlsruhe 1976): a journal spinning at omega in a fixed bearing, held at eccentricity
ratio eps; its Sommerfeld number ``So = F psi^2 / (B D eta omega)`` and attitude angle
``beta`` (docs/physics.md section 10).  Outputs, in ``results/film_models/``:

- ``sommerfeld.png``: So(eps) (log scale) and beta(eps) at B/D = 1/8, 1/2, 1 for the short,
  long and finite models of :mod:`exuclear.film` and the finite-difference reference of
  :mod:`validation.reference.reynolds` with both cavitation conditions (half-Sommerfeld;
  Reynolds' condition with the film starting at the largest gap, Butenschoen's);
- ``sommerfeld.md`` / ``.csv``: the same numbers;
- ``squeeze.md``: pure squeeze (no spin), journal approaching and leaving the wall at
  ``|de/dt| = 0.2 c omega``: the force of each model over the reference's (Reynolds'
  condition, no groove; and half-Sommerfeld);
- ``convergence.md``: the reference's mesh convergence at two points, successive meshes
  with steps halved and their Richardson extrapolations.

The reference is the tightly converged one: each point is the Richardson extrapolation of
two meshes (``--n-alpha`` x ``--n-z`` and twice as fine), whose change is reported.

Run from the repository root::

    python -m validation.film_models [--out DIR] [--n-alpha N] [--n-z M]
"""
from __future__ import annotations

import argparse
import math
import os
import sys

from exuclear.film import FILM_MODELS, FINITE_WIDTH_RANGE, attitude_angle, sommerfeld_number
from exuclear.geometry import BearingGeometry
from validation._tables import markdown_table, write_csv
from validation.reference import reynolds

DEFAULT_OUT = os.path.join("results", "film_models")

#: The scene: psi = 1e-3, any viscosity and speed (So and beta do not depend on them).
RADIUS = 0.01        # m
CLEARANCE = 10e-6    # m
VISCOSITY = 0.02     # Pa s
OMEGA = 300.0        # rad/s
WIDTH_RATIOS = (1 / 8, 1 / 2, 1.0)
ECCENTRICITIES = (0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95)
#: The reference's two conditions: (label, cavitation, groove at the largest gap)
REFERENCES = (("reference, half-Sommerfeld", "gumbel", None), ("reference, Reynolds + groove", "reynolds", math.pi))


def model_point(model: str, width_ratio: float, eps: float) -> tuple[float, float]:
    """``(So, beta [deg])`` of a film model; NaN where the model is not defined."""
    geometry = BearingGeometry(RADIUS, RADIUS + CLEARANCE, 2 * RADIUS * width_ratio)
    low, high = FINITE_WIDTH_RANGE
    if model == "finite" and not low <= width_ratio <= high:
        return math.nan, math.nan
    load = FILM_MODELS[model](VISCOSITY, geometry).load(eps * CLEARANCE, 0.0, 0.0, 0.0, OMEGA, 0.0)
    return (sommerfeld_number(math.hypot(load.fx, load.fy), geometry, VISCOSITY, OMEGA),
            math.degrees(attitude_angle(eps * CLEARANCE, 0.0, load.fx, load.fy)))


def reference_point(width_ratio: float, eps: float, cavitation: str, groove: float | None, n_alpha: int,
                    n_z: int) -> tuple[float, float, float]:
    """``(So, beta [deg], mesh change)`` of the reference, extrapolated from two meshes."""
    bearing = reynolds.Bearing(RADIUS, CLEARANCE, 2 * RADIUS * width_ratio, VISCOSITY)
    result = reynolds.converged(bearing, eps * CLEARANCE, 0.0, omega_journal=OMEGA, n_alpha=n_alpha, n_z=n_z,
                                levels=2, cavitation=cavitation, groove=groove)
    so, beta = reynolds.sommerfeld(bearing, reynolds.Solution(None, None, None, result.fx, result.fy, 0), OMEGA,
                                   eps * CLEARANCE, 0.0)
    return so, beta, result.change


def sweep(n_alpha: int, n_z: int) -> list[dict[str, object]]:
    records = []
    for width_ratio in WIDTH_RATIOS:
        for eps in ECCENTRICITIES:
            row: dict[str, object] = {"B/D": width_ratio, "eps": eps}
            for model in FILM_MODELS:
                row[f"So {model}"], row[f"beta {model}"] = model_point(model, width_ratio, eps)
            for label, cavitation, groove in REFERENCES:
                so, beta, change = reference_point(width_ratio, eps, cavitation, groove, n_alpha, n_z)
                row[f"So {label}"], row[f"beta {label}"], row[f"change {label}"] = so, beta, change
            records.append(row)
            print(f"B/D = {width_ratio:.3g}, eps = {eps}: done", flush=True)
    return records


def convergence_table(n_alpha: int, n_z: int) -> str:
    """Successive refinement at B/D = 1/2, eps = 0.5 and 0.9 (Reynolds' condition with groove)."""
    rows = []
    for eps in (0.5, 0.9):
        bearing = reynolds.Bearing(RADIUS, CLEARANCE, RADIUS, VISCOSITY)
        forces = []
        for level in range(4):
            s = reynolds.solve(bearing, eps * CLEARANCE, 0.0, omega_journal=OMEGA, n_alpha=n_alpha * 2 ** level // 4,
                               n_z=max(2, n_z * 2 ** level // 4), cavitation="reynolds", groove=math.pi)
            forces.append((s.fx, s.fy, len(s.alpha), len(s.z) - 1))
        for k, (fx, fy, na, nz) in enumerate(forces):
            f = math.hypot(fx, fy)
            change = math.hypot(fx - forces[k - 1][0], fy - forces[k - 1][1]) / f if k else math.nan
            if k >= 2:
                ex = [b + (b - a) / 3 for a, b in zip(forces[k - 1][:2], (fx, fy))]
                ex_prev = [b + (b - a) / 3 for a, b in zip(forces[k - 2][:2], forces[k - 1][:2])]
                ex_change = math.hypot(ex[0] - ex_prev[0], ex[1] - ex_prev[1]) / math.hypot(*ex)
            else:
                ex_change = math.nan
            rows.append([eps, f"{na} x {nz}", f"{f:.6g}", f"{change:.2e}", f"{ex_change:.2e}"])
    return markdown_table(["eps", "mesh (alpha x z)", "force [N]", "change to coarser", "change of extrapolation"],
                          rows)


def squeeze_table(n_alpha: int, n_z: int) -> str:
    """Pure squeeze: each model's force over the reference's, both cavitation conditions."""
    rows = []
    speed = 0.2 * CLEARANCE * OMEGA
    for width_ratio in WIDTH_RATIOS:
        geometry = BearingGeometry(RADIUS, RADIUS + CLEARANCE, 2 * RADIUS * width_ratio)
        bearing = reynolds.Bearing(RADIUS, CLEARANCE, geometry.length, VISCOSITY)
        for eps in (0.3, 0.6, 0.9):
            for direction, vx in (("in", speed), ("out", -speed)):
                refs = [reynolds.converged(bearing, eps * CLEARANCE, 0.0, vx, n_alpha=n_alpha, n_z=n_z, levels=2,
                                           cavitation=cavitation).fx for cavitation in ("reynolds", "gumbel")]
                row = [f"{width_ratio:.3g}", eps, direction, f"{refs[0]:.4g}"]
                for model in FILM_MODELS:
                    fx = FILM_MODELS[model](VISCOSITY, geometry).load(eps * CLEARANCE, 0.0, vx, 0.0).fx
                    row += [f"{fx / refs[0]:.3f}", f"{fx / refs[1]:.3f}"]
                rows.append(row)
    header = ["B/D", "eps", "squeeze", "F ref. Reynolds [N]"]
    for model in FILM_MODELS:
        header += [f"{model} / ref. Reynolds", f"{model} / ref. half-Sommerfeld"]
    return markdown_table(header, rows)


def plot(records: list[dict[str, object]], path: str) -> str:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax_so, ax_beta) = plt.subplots(1, 2, figsize=(12, 5))
    colours = dict(zip(WIDTH_RATIOS, ("tab:blue", "tab:orange", "tab:green")))
    styles = {"short": ":", "long": "-.", "finite": "-"}
    markers = {REFERENCES[0][0]: "x", REFERENCES[1][0]: "o"}
    for width_ratio in WIDTH_RATIOS:
        rows = [r for r in records if r["B/D"] == width_ratio]
        eps = [r["eps"] for r in rows]
        colour = colours[width_ratio]
        for model, style in styles.items():
            if model == "long" and width_ratio != WIDTH_RATIOS[0]:
                continue  # So and beta of the long model do not depend on B/D: one black line
            c = "black" if model == "long" else colour
            label = "long, any B/D" if model == "long" else f"{model}, B/D = {width_ratio:.3g}"
            ax_so.semilogy(eps, [r[f"So {model}"] for r in rows], style, color=c, label=label)
            ax_beta.plot(eps, [r[f"beta {model}"] for r in rows], style, color=c)
        for label, marker in markers.items():
            ax_so.semilogy(eps, [r[f"So {label}"] for r in rows], marker, color=colour, mfc="none",
                           label=f"{label}, B/D = {width_ratio:.3g}")
            ax_beta.plot(eps, [r[f"beta {label}"] for r in rows], marker, color=colour, mfc="none")
    ax_so.set_xlabel("eccentricity ratio eps")
    ax_so.set_ylabel("Sommerfeld number So = F psi^2 / (B D eta omega)")
    ax_beta.set_xlabel("eccentricity ratio eps")
    ax_beta.set_ylabel("attitude angle beta [deg]")
    ax_so.grid(True, which="both", alpha=0.3)
    ax_beta.grid(True, alpha=0.3)
    ax_so.legend(fontsize=6, ncol=2)
    fig.suptitle("Film models (lines) and the finite-difference Reynolds reference (markers)")
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)
    return path


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.film_models", description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=DEFAULT_OUT, help="output directory (default %(default)s)")
    ap.add_argument("--n-alpha", type=int, default=256, help="reference nodes around, coarser mesh (default %(default)s)")
    ap.add_argument("--n-z", type=int, default=16, help="reference steps over the half width, coarser mesh (default %(default)s)")
    args = ap.parse_args(argv)
    os.makedirs(args.out, exist_ok=True)

    records = sweep(args.n_alpha, args.n_z)
    write_csv(os.path.join(args.out, "sommerfeld.csv"), records)
    header = list(records[0])
    rows = [[f"{v:.4g}" if isinstance(v, float) else v for v in r.values()] for r in records]
    with open(os.path.join(args.out, "sommerfeld.md"), "w", encoding="utf-8") as f:
        f.write(markdown_table(header, rows) + "\n")
    with open(os.path.join(args.out, "squeeze.md"), "w", encoding="utf-8") as f:
        f.write(squeeze_table(args.n_alpha, args.n_z) + "\n")
    with open(os.path.join(args.out, "convergence.md"), "w", encoding="utf-8") as f:
        f.write(convergence_table(args.n_alpha, args.n_z) + "\n")
    print(plot(records, os.path.join(args.out, "sommerfeld.png")))
    return 0


if __name__ == "__main__":
    sys.exit(main())
