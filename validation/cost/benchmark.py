"""The speed targets of the native connector (issue 11), measured side by side in one run.

Source problems: the paper's slider-crank (docs/physics.md section 6.2; cr 0.9, steel, no
friction, two revolutions) and journal-bearing impact (section 6.1).  Prints one table:

- the default minimal and redundant slider-crank: wall time (median of ``--repeats``),
  max |e - e_ref| / c against the converged reference (:mod:`validation.cross_check`), and
  the fastest SciPy run (:mod:`validation.reference`) reaching the same or a smaller error;
- the element overhead on the journal impact: the same run with the compiled and the
  Python kernel (steps of at most 1e-7 s, so that the joint's evaluations dominate);
- the spatial slider-crank (``CreateRigidBody`` bodies) against the 2D one, where the
  model has the ``spatial`` formulation.

Every number is measured now, on this machine; run nothing else meanwhile.  Run::

    python -m validation.cost benchmark [--repeats N]
"""
from __future__ import annotations

import argparse
import statistics
import time
from dataclasses import replace

import numpy as np

import exuclear
from exuclear.models import journal_bearing as jb_model
from exuclear.models import slider_crank as sc_model
from validation.cost import work_precision as wp

#: SciPy solvers and tolerances searched for the fastest run at a given error.
SCIPY_POINTS = tuple((method, rtol) for method in ("LSODA", "RK45", "DOP853", "Radau")
                     for rtol in (1e-5, 1e-6, 1e-7, 1e-8, 1e-9))


#: The redundant slider-crank at its defaults but Newton as the joint sets it (contractivity
#: 0.2 instead of the defaults' 0.01): what ``newton_contractivity`` saves there.
JOINT_CONTRACTIVITY = {"newton_contractivity": None}


def _median(run, repeats: int) -> float:
    return statistics.median(run() for _ in range(repeats))


def crank_rows(repeats: int) -> list[tuple[str, str, str]]:
    params = sc_model.SliderCrankParams.paper(cr=0.9)
    ref = wp.crank_reference(params)
    scipy = [wp.crank_point("crank", wp.Config(f"SciPy {m}", "scipy", ()), (m, r), ref, repeats)
             for m, r in SCIPY_POINTS]
    rows = []
    for formulation, target, changes in (
            ("minimal", "<= 0.1 s and >= 2x faster than the fastest SciPy", {}),
            ("redundant", "<= 0.35 s (issue 11); <= 0.25 s at <= 1 % c (issue 20)", {}),
            ("redundant", "-, for comparison", JOINT_CONTRACTIVITY)):
        config = wp.Config(f"{formulation} default", "exuclear", (), formulation=formulation)
        defaults = sc_model.default_settings(replace(params, formulation=formulation))
        point = wp.crank_point("crank", config, {"method": defaults.method, **changes}, ref, repeats)
        rivals = [p for p in scipy if p.success and p.error <= point.error]
        fastest = min(rivals, key=lambda p: p.wall) if rivals else None
        versus = (f"fastest SciPy at that error: {fastest.setting}, {fastest.wall:.3f} s = "
                  f"{fastest.wall / point.wall:.2f}x ours" if fastest else "no SciPy run reached that error")
        what = (f"{formulation} slider-crank, defaults with the joint's Newton contractivity" if changes
                else f"default {formulation} slider-crank ({defaults.method})")
        rows.append((f"{what}, 2 rev.", target,
                     f"{point.wall:.3f} s, error {point.error:.1e} c, {point.steps} steps; {versus}"))
    return rows


def impact_row(repeats: int) -> tuple[str, str, str]:
    params = jb_model.JournalBearingParams.paper()
    walls = {}
    for backend in ("python", exuclear.engine.DEFAULT_BACKEND):
        settings = replace(jb_model.default_settings(params), step=1e-7, output_step=1e-6)

        def run(backend=backend, settings=settings):
            return exuclear.simulate(jb_model.build(replace(params, backend=backend)).mbs, settings).wall_time

        walls[backend] = _median(run, repeats)
    ratio = walls["python"] / walls[exuclear.engine.DEFAULT_BACKEND]
    return ("element overhead, journal impact (steps <= 1e-7 s)", "compiled >= 2.5x faster than Python",
            f"python {walls['python'] * 1e3:.2f} ms, {exuclear.engine.DEFAULT_BACKEND} "
            f"{walls[exuclear.engine.DEFAULT_BACKEND] * 1e3:.2f} ms: {ratio:.1f}x")


def floor_rows(repeats: int) -> list[tuple[str, str, str]]:
    """What Exudyn itself costs in these runs: the minimal model's connector evaluated on
    its two kinematic-tree markers with and without the kernel, per evaluation (RK44 at a
    fixed step, 4 evaluations per step, so that every variant takes the same steps); and
    the ideal redundant mechanism at the redundant defaults."""
    import exudyn as exu

    params = sc_model.SliderCrankParams.paper()
    steps = 9000
    settings = exuclear.SolverSettings(end_time=params.end_time, method="rk44", step=params.end_time / steps,
                                       output_step=params.end_time)
    ss = exuclear.engine.simulation_settings(settings)
    model = sc_model.build(params)

    def solve() -> float:
        start = time.perf_counter()
        model.mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.RK44)
        return time.perf_counter() - start

    joint = model.joint.objectNumber
    with_kernel = _median(solve, repeats)
    model.mbs.SetObjectParameter(joint, "postNewtonStepUserFunction", 0)
    model.mbs.SetObjectParameter(joint, "springForceTorqueUserFunction", 0)
    model.mbs.SetObjectParameter(joint, "stiffness", np.zeros((6, 6)).tolist())
    bare = _median(solve, repeats)
    model.mbs.SetObjectParameter(joint, "activeConnector", False)
    none = _median(solve, repeats)
    evaluations = 4 * steps
    ideal = replace(params, formulation="redundant", ideal=True)
    ideal_wall = _median(lambda: sc_model.run(ideal, sc_model.default_settings(replace(ideal, ideal=False))).wall_time,
                         repeats)
    return [("context: Exudyn's connector on the minimal model's two kinematic-tree markers", "-",
             f"{(bare - none) / evaluations * 1e6:.2f} us per evaluation without a user function, "
             f"{(with_kernel - none) / evaluations * 1e6:.2f} us with the compiled kernel (RK44, {steps} steps)"),
            ("context: the ideal redundant mechanism at the redundant defaults", "-", f"{ideal_wall:.3f} s")]


def spatial_row() -> tuple[str, str, str] | None:
    if "spatial" not in sc_model.FORMULATIONS:
        return None
    params = sc_model.SliderCrankParams.paper(cr=0.9)
    runs = {}
    for formulation in ("redundant", "spatial"):
        p = replace(params, formulation=formulation)
        start = time.perf_counter()
        runs[formulation] = sc_model.run(p, replace(sc_model.default_settings(p), output_step=1e-5))
        runs[formulation + " wall"] = time.perf_counter() - start
    a, b = runs["redundant"].columns, runs["spatial"].columns
    ecc = np.hypot(np.interp(a["time"], b["time"], b["ecc_x"]) - a["ecc_x"],
                   np.interp(a["time"], b["time"], b["ecc_y"]) - a["ecc_y"])
    return ("3D bodies (CreateRigidBody), clearance at B", "matches the 2D result to 1 % of c",
            f"max |e_3D - e_2D| / c = {ecc.max() / params.clearance:.1e} (default settings of each), impacts "
            f"{len(runs['spatial'].onset_times)} / {len(runs['redundant'].onset_times)}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost benchmark", description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=5, help="runs per point; the median is quoted (default 5)")
    args = ap.parse_args(argv)
    if args.repeats < 1:
        ap.error("--repeats must be at least 1")
    print(f"compiled kernel: {exuclear.engine.kernel.STATUS}; default backend: {exuclear.engine.DEFAULT_BACKEND}; "
          f"medians of {args.repeats}")
    rows = crank_rows(args.repeats) + [impact_row(args.repeats)] + floor_rows(args.repeats)
    spatial = spatial_row()
    if spatial is not None:
        rows.append(spatial)
    print()
    print("| measure | target | measured |")
    print("|---|---|---|")
    for row in rows:
        print("| " + " | ".join(row) + " |")
    return 0
