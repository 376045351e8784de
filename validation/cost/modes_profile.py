"""Where the impulse contact mode's run time goes: Exudyn's own solve against the mode's
decisions in Python.

Each zoo model named runs once with its own settings in the impulse mode (spectral radius
1, as ``python -m validation.cost modes`` runs it) under :mod:`cProfile`; the script prints
the run's wall time, the time spent inside the mode's post-Newton functions (the carriers'
``_post_newton``, the mode's decisions, Python), the rest (Exudyn's solve and everything
it calls that is not the mode), the calls and the time per call, and the held steps
computed again in the normal they reached (refines).  Profiling slows Python code more than
compiled code, so the shares are upper bounds of the mode's share in an unprofiled run;
take them on a quiet machine.  ``--calls N``: per model, the ``N`` functions with the most
time of their own, with their calls per accepted step (deterministic, unlike the times:
comparable on a busy machine).

::

    python -m validation.cost modes_profile [--models a,b] [--calls N]
"""
from __future__ import annotations

import argparse
import cProfile
import pstats
import warnings

from validation._tables import markdown_table
from validation.cost.modes import _build, _run
from validation.exudyn_examples._common import load_models

#: Models profiled by default: a held contact on rigid bodies, one on a flexible body, a
#: translational joint's corners.
DEFAULT_MODELS = ("double_pendulum_3d_rxyz", "ancf_pendulum", "slider_crank_floating")


def _profile(name: str) -> tuple[float, str, bool, str, dict]:
    """A zoo model's impulse run under cProfile: wall [s], "steps / Newton", success, the
    error's first line, and the profiler's stats ((file, line, function) -> (cc, calls,
    own time, cumulative time, callers))."""
    model = _build(name, True, "impulse")
    profiler = cProfile.Profile()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        profiler.enable()
        wall, steps, ok, problem = _run(model, 1.0)
        profiler.disable()
    return wall, steps, ok, problem, pstats.Stats(profiler).stats


def profile_row(name: str, stats: dict, wall: float, steps: str, ok: bool, problem: str) -> list[str]:
    """One model's row: wall [s], the mode's decisions [s] and share, calls, per call [us],
    refines."""
    decisions = [v for k, v in stats.items() if k[2] == "_post_newton" and "exuclear" in k[0]]
    # a joint with several contacts extends the one-contact handle's function (super()): its
    # calls from another _post_newton are inside the outer one's time already
    nested = [c for v in decisions for key, c in v[4].items() if key[2] == "_post_newton"]
    calls = sum(v[1] for v in decisions) - sum(c[1] for c in nested)
    mode = sum(v[3] for v in decisions) - sum(c[3] for c in nested)
    # a held step computed again in the normal it reached: _refine sets the condition anew
    refines = sum(c[1] for k, v in stats.items() if k[2] == "_aim" for key, c in v[4].items() if key[2] == "_refine")
    return [name, steps if ok else f"stopped: {problem[:60]}", f"{wall:.3g}", f"{mode:.3g}", f"{mode / wall:.0%}",
            f"{wall - mode:.3g}", str(calls), f"{1e6 * mode / max(calls, 1):.0f}", str(refines)]


def calls_rows(stats: dict, steps: str, count: int) -> list[list[str]]:
    """The ``count`` functions with the most time of their own: calls per accepted step,
    calls, own time [s]."""
    accepted = max(int(steps.split("/")[0]), 1)
    top = sorted(stats.items(), key=lambda item: -item[1][2])[:count]
    return [[f"{function} ({path.rsplit('/', 1)[-1]}:{line})", f"{v[1] / accepted:.3f}", str(v[1]), f"{v[2]:.3g}"]
            for (path, line, function), v in top]


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(prog="python -m validation.cost modes_profile",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--models", default=",".join(DEFAULT_MODELS),
                    help="zoo models, comma-separated (default: %(default)s)")
    ap.add_argument("--calls", type=int, default=0,
                    help="also list each model's N functions with the most time of their own (default: none)")
    args = ap.parse_args(argv)
    if args.calls < 0:
        ap.error(f"--calls must be at least 0, got {args.calls}")
    load_models(None)
    rows = []
    for name in (n for n in args.models.split(",") if n):
        wall, steps, ok, problem, stats = _profile(name)
        rows.append(profile_row(name, stats, wall, steps, ok, problem))
        if args.calls:
            print(f"\n{name}:\n" + markdown_table(["function", "calls per step", "calls", "own time [s]"],
                                                   calls_rows(stats, steps, args.calls)), flush=True)
    print("\n" + markdown_table(["model", "steps / Newton", "wall [s]", "mode's decisions [s]", "share",
                                 "the rest [s]", "calls", "per call [us]", "refines"], rows))


if __name__ == "__main__":
    main()
