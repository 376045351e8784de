"""Throughput of the study runner: one slider-crank study, three ways to run it.

Source problem: example 2 of X. Wang, G. Liu, S. Ma, R. Tong, J. Mech. Sci. Technol.
31(2) (2017) 587-597 (the paper's slider-crank with its clearance joint), as a 200-run
study (:func:`exuclear.models.slider_crank.study`): ``cr`` 0.3, 0.5, 0.7, 0.9 x 50 crank speeds
from 300 to 1280 rpm, one crank revolution each (no start-up left out).

The same study runs (a) serially in this process, (b) on 2 local worker processes and
(c) on a 2-worker Dask ``LocalCluster`` (processes).  Wall time covers everything a
user waits for: starting the workers, the runs, writing the table.  Each way writes a
fresh table, and the rows of (b) and (c) are checked equal to those of (a) value by
value (wall times aside).  The issue's target: both parallel ways reach at least 1.7
times the serial throughput on a 2-core machine.  Run nothing else meanwhile; on a
machine shared with others the numbers move with their load.

Run from the repository root (or anywhere after ``pip install -e .``)::

    python -m validation.cost study_benchmark [--runs N] [--revolutions R] [--quick] [--out DIR]

``--quick``: 8 runs of a quarter revolution, a smoke test of the script.  Prints the
table and writes ``study_benchmark.md`` to ``--out`` (default ``results/study_benchmark``).
"""
from __future__ import annotations

import argparse
import os
import tempfile
import time

from exuclear import study as st
from validation._tables import markdown_table

#: The target ratio of parallel to serial throughput on 2 cores (issue 12).
TARGET_RATIO = 1.7
#: The ways to run, as keyword arguments of :func:`exuclear.study.run_study`.
WAYS = (("serial", {"workers": 1}), ("2 local processes", {"workers": 2}),
        ("2-worker Dask LocalCluster", {"workers": 2, "scheduler": "local"}))


def runs(count: int, revolutions: float) -> list[dict]:
    """``count`` runs: 4 restitution coefficients x ``count / 4`` speeds from 300 rpm, 20 rpm apart."""
    speeds = [300 + 20 * k for k in range(max(1, count // 4))]
    return st.grid(cr=[0.3, 0.5, 0.7, 0.9], rpm=speeds, startup=[0.0], revolutions=[revolutions])[:count]


def _values(df):
    return df.drop(columns=[c for c in df.columns if "wall_time" in c]).reset_index(drop=True)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost study_benchmark", description=__doc__.split("\n")[0])
    ap.add_argument("--runs", type=int, default=200, help="runs in the study (default %(default)s)")
    ap.add_argument("--revolutions", type=float, default=1.0, help="crank revolutions per run (default %(default)s)")
    ap.add_argument("--quick", action="store_true", help="8 runs of a quarter revolution: a smoke test")
    ap.add_argument("--out", default="results/study_benchmark", help="output directory (default %(default)s)")
    args = ap.parse_args(argv)
    count, revolutions = (8, 0.25) if args.quick else (args.runs, args.revolutions)
    study, plan = st.scene("slider-crank"), runs(count, revolutions)
    results = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, options in WAYS:
            start = time.perf_counter()
            table = st.run_study(study, plan, os.path.join(tmp, f"{len(results)}.csv"), progress=False, **options)
            wall = time.perf_counter() - start
            results.append((label, wall, table))
            print(f"{label}: {len(table)} runs in {wall:.2f} s", flush=True)
    serial_wall, serial = results[0][1], results[0][2]
    rows, ok = [], True
    for label, wall, table in results:
        same = _values(table).equals(_values(serial))
        ratio = serial_wall / wall
        ok &= same and table["success"].all()
        rows.append([label, f"{wall:.2f}", f"{len(table) / wall:.2f}", f"{ratio:.2f}",
                     "" if label == "serial" else ("yes" if ratio >= TARGET_RATIO else "no"),
                     "yes" if same else "NO", f"{table['wall_time'].mean():.3f}"])
    report = "\n\n".join([
        "# Study runner throughput",
        f"{count} slider-crank runs ({revolutions:g} revolutions each){' (--quick)' if args.quick else ''}, "
        f"on {os.cpu_count()} cores.",
        markdown_table(["way", "wall [s]", "runs/s", "x serial", f">= {TARGET_RATIO}x", "rows equal serial",
                        "mean run [s]"], rows),
    ])
    os.makedirs(args.out, exist_ok=True)
    path = os.path.join(args.out, "study_benchmark" + ("_quick" if args.quick else "") + ".md")
    with open(path, "w", encoding="utf-8") as f:
        f.write(report + "\n")
    print(report)
    print(f"wrote {path}")
    return 0 if ok else 1
