"""Where the impulse contact mode's run time goes: Exudyn's own solve against the mode's
decisions in Python.

Each zoo model named runs once with its own settings in the impulse mode (spectral radius
1, as ``python -m validation.cost modes`` runs it) under :mod:`cProfile`; the script prints
the run's wall time, the time spent inside the mode's post-Newton functions (the carriers'
``_post_newton``, the mode's decisions, Python), the rest (Exudyn's solve and everything
it calls that is not the mode), the calls and the time per call.  Profiling slows Python
code more than compiled code, so the shares are upper bounds of the mode's share in an
unprofiled run; take them on a quiet machine.

::

    python -m validation.cost modes_profile [--models a,b]
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


def profile_row(name: str) -> list[str]:
    """One model's row: wall [s], the mode's decisions [s] and share, calls, per call [us]."""
    model = _build(name, True, "impulse")
    profiler = cProfile.Profile()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        profiler.enable()
        wall, steps, ok, problem = _run(model, 1.0)
        profiler.disable()
    stats = pstats.Stats(profiler).stats  # (file, line, function) -> (cc, calls, tottime, cumtime, callers)
    decisions = [v for k, v in stats.items() if k[2] == "_post_newton" and "exuclear" in k[0]]
    # a joint with several contacts extends the one-contact handle's function (super()): its
    # calls from another _post_newton are inside the outer one's time already
    nested = [c for v in decisions for key, c in v[4].items() if key[2] == "_post_newton"]
    calls = sum(v[1] for v in decisions) - sum(c[1] for c in nested)
    mode = sum(v[3] for v in decisions) - sum(c[3] for c in nested)
    return [name, steps if ok else f"stopped: {problem[:60]}", f"{wall:.3g}", f"{mode:.3g}", f"{mode / wall:.0%}",
            f"{wall - mode:.3g}", str(calls), f"{1e6 * mode / max(calls, 1):.0f}"]


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(prog="python -m validation.cost modes_profile",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--models", default=",".join(DEFAULT_MODELS),
                    help="zoo models, comma-separated (default: %(default)s)")
    args = ap.parse_args(argv)
    load_models(None)
    rows = [profile_row(name) for name in args.models.split(",") if name]
    print(markdown_table(["model", "steps / Newton", "wall [s]", "mode's decisions [s]", "share",
                          "the rest [s]", "calls", "per call [us]"], rows))


if __name__ == "__main__":
    main()
