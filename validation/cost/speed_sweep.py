"""Speed sweep of the slider-crank: a bifurcation-style diagram over crank speed.

Source problem: example 2 of X. Wang, G. Liu, S. Ma, R. Tong, J. Mech. Sci. Technol.
31(2) (2017) 587-597 (the slider-crank with a clearance joint at the rod-slider pin,
steel on steel, c = 0.1 mm, Wang-Liu law, no friction), swept over crank speed as the
literature that follows it does: 101 speeds from 100 to 5000 rpm, ``cr`` 0.9 and 0.3,
``--startup`` revolutions (default 2) to let the start-up bounces die out, then
``--revolutions`` (default 10) measured.

Every run goes through the study runner (:mod:`exuclear.study`) with the slider-crank's
study function (:func:`exuclear.models.slider_crank.study`), so the table is written row by row
and an interrupted sweep resumes where it stopped.  For each speed the diagram shows one
point per measured revolution: the impacts in that revolution and its peak contact
force.  A single point per speed is a periodic response with the crank's period; a
spread of points is a response that is not (multi-periodic or chaotic).

Run from the repository root (or anywhere after ``pip install -e .``)::

    python -m validation.cost speed_sweep [--out DIR] [--workers N | --scheduler ADDRESS] [--quick]

Writes ``speed_sweep.csv`` (the study table, with Parquet beside it when pyarrow is
present), ``speed_sweep.png`` and ``speed_sweep.md`` (wall time and the settings) to
``results/speed_sweep/``.  ``--quick`` runs 5 speeds, 0.5 start-up and 1 measured
revolution: a smoke test of the script, not a result.
"""
from __future__ import annotations

import argparse
import os
import time

import numpy as np

from exuclear import study as st
from validation._tables import markdown_table

#: The sweep: crank speeds [rpm] (101 speeds, 49 rpm apart) and restitution coefficients.
SPEEDS = st.parse_values("100:5000:49")
RESTITUTION = (0.9, 0.3)
QUICK_SPEEDS = st.parse_values("100:5000:1225")


def runs(speeds, startup: float, revolutions: float) -> list[dict]:
    return st.grid(cr=list(RESTITUTION), rpm=list(speeds), startup=[startup], revolutions=[revolutions])


def figure(table, path: str) -> str:
    """Impacts per revolution and peak contact force per revolution over crank speed."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from exuclear.study.plot import plot_metric

    columns = st.scene("slider-crank").columns  # axis labels with units, the scene's own
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8.0, 7.5), sharex=True)
    plot_metric(table, "impacts_by_rev", "rpm", by="cr", points=True, ax=top, columns=columns,
                title="slider-crank, clearance 0.1 mm: one point per measured revolution")
    plot_metric(table, "peak_force_by_rev", "rpm", by="cr", points=True, logy=True, ax=bottom, title="",
                columns=columns)
    top.set_xlabel("")  # the shared axis is labelled below
    fig.tight_layout()
    fig.savefig(path, dpi=150)
    plt.close(fig)
    return path


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost speed_sweep", description=__doc__.split("\n")[0])
    ap.add_argument("--out", default="results/speed_sweep", help="output directory (default %(default)s)")
    ap.add_argument("--workers", type=int, help="local worker processes (default: all cores)")
    ap.add_argument("--scheduler", metavar="ADDRESS", help="Dask scheduler address, or 'local'")
    ap.add_argument("--startup", type=float, default=2.0, help="start-up revolutions left out (default %(default)s)")
    ap.add_argument("--revolutions", type=float, default=10.0, help="measured revolutions (default %(default)s)")
    ap.add_argument("--quick", action="store_true", help="5 speeds, 0.5 + 1 revolutions: a smoke test")
    args = ap.parse_args(argv)
    speeds, startup, revolutions = SPEEDS, args.startup, args.revolutions
    if args.quick:
        speeds, startup, revolutions = QUICK_SPEEDS, 0.5, 1.0
    os.makedirs(args.out, exist_ok=True)
    stem = os.path.join(args.out, "speed_sweep" + ("_quick" if args.quick else ""))
    start = time.perf_counter()
    table = st.run_study(st.scene("slider-crank"), runs(speeds, startup, revolutions), stem + ".csv",
                         workers=args.workers, scheduler=args.scheduler)
    wall = time.perf_counter() - start
    print(f"wrote {figure(table, stem + '.png')}")
    failed = table[~table["success"]]
    rows = []
    for cr, group in table[table["success"]].groupby("cr"):
        periodic = group[group["impacts_per_rev"] == 0.0]
        rows.append([cr, len(group), f"{group['rpm'].min():g}-{group['rpm'].max():g}",
                     f"{group['peak_force_steady'].max():.4g}", len(periodic),
                     f"{np.median(group['sim_wall_time']):.3g}"])
    report = "\n\n".join([
        "# Slider-crank speed sweep",
        f"{len(table)} runs ({len(speeds)} speeds x cr {', '.join(map(str, RESTITUTION))}), {startup:g} start-up + "
        f"{revolutions:g} measured revolutions each; {len(failed)} failed.  Wall time of this invocation "
        f"{wall:.1f} s (runs already in the table are not redone; see `wall_time` per row).",
        markdown_table(["cr", "runs", "rpm", "largest steady peak force [N]", "speeds without impacts after start-up",
                        "median solver time [s]"], rows),
        *([markdown_table(["cr", "rpm", "message"], failed[["cr", "rpm", "message"]].values.tolist())]
          if len(failed) else []),
    ])
    with open(stem + ".md", "w", encoding="utf-8") as f:
        f.write(report + "\n")
    print(report)
    return 0 if failed.empty else 1
