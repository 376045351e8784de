"""What wear costs: the same run with and without ``wear=`` on the joint, side by side.

Source problems: the worn-in journal (:mod:`validation.wear.worn_in_journal`; 0.2 s, a
journal turning at 100 rad/s under 500 N, wearing the bearing 61 um deep at k_D = 1e-10
1/Pa, and at a steel-like k_D = 1e-14 1/Pa, 24 nm) and the paper's slider-crank (two
revolutions; wear at B with k_D = 1e-14 1/Pa).  Each run in each kernel, median of
``--repeats`` wall times taken in turn; prints the ratio with wear / without.  Run nothing
else meanwhile::

    python -m validation.cost wear [--repeats N] [--backend compiled|python]
"""
from __future__ import annotations

import argparse
import statistics
import time
from collections.abc import Callable

from exuclear.models import slider_crank as sc_model
from validation._tables import markdown_table
from validation.wear import worn_in_journal as wij


def _journal(coefficient: float | None, backend: str) -> Callable[[], float]:
    def run() -> float:
        start = time.perf_counter()
        wij.run(0.2, backend=backend, coefficient=coefficient or 1.0, worn=coefficient is not None)
        return time.perf_counter() - start
    return run


def _slider_crank(coefficient: float | None, backend: str) -> Callable[[], float]:
    params = sc_model.SliderCrankParams.paper(backend=backend, wear_coefficient=coefficient)

    def run() -> float:
        start = time.perf_counter()
        sc_model.run(params)
        return time.perf_counter() - start
    return run


CASES = (
    ("worn-in journal, k_D 1e-10 (61 um)", _journal, 1e-10),
    ("worn-in journal, k_D 1e-14 (24 nm)", _journal, 1e-14),
    ("slider-crank at B, k_D 1e-14", _slider_crank, 1e-14),
)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost wear", description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=3, help="runs of each case (default %(default)s); the median")
    ap.add_argument("--backend", default="compiled", choices=("compiled", "python"), help="the joint's kernel")
    args = ap.parse_args(argv)
    rows = []
    for label, make, coefficient in CASES:
        plain, worn = make(None, args.backend), make(coefficient, args.backend)
        plain(), worn()  # warm-up: imports, the kernel's first call
        times: dict[str, list[float]] = {"plain": [], "worn": []}
        for _ in range(args.repeats):
            times["plain"].append(plain())
            times["worn"].append(worn())
        a, b = statistics.median(times["plain"]), statistics.median(times["worn"])
        rows.append([label, f"{a:.3f}", f"{b:.3f}", f"{b / a:.2f}"])
        print(f"{label}: {a:.3f} s without wear, {b:.3f} s with, {b / a:.2f}x", flush=True)
    print()
    print(markdown_table(["run", "without wear [s]", "with wear [s]", "ratio"], rows))
    print(f"\n{args.backend} kernel, medians of {args.repeats} runs taken in turn")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
