"""Work-precision study: simulation wall time against error, for every configuration.

Source problems: examples 1 and 2 of X. Wang, G. Liu, S. Ma, R. Tong, J. Mech. Sci.
Technol. 31(2) (2017) 587-597 (docs/physics.md sections 6.1 and 6.2): the slider-crank with its
clearance joint (cr 0.9 and 0.3, steel, no friction, two crank revolutions) and the
journal-bearing impact (Wang-Liu, cr 0.9).

Every configuration the library offers (formulation x element backend x solver x step
or tolerance) and the independent SciPy reference (:mod:`validation.reference`) with
several ``solve_ivp`` methods and tolerances run the same scene.  Error is measured
against a tightly converged reference (DOP853 at rtol 1e-10, the reference of
:mod:`validation.cross_check`, whose own error is ~2e-6 c there):

- slider-crank: max ``|e - e_ref| / c`` over the run, at the run's own output instants
  (the reference's dense output on a 2e-6 s grid, interpolated linearly: < 4e-5 c), the
  relative error of the peak contact force, and the impact count;
- journal-bearing: the relative error of the departure velocity.

Wall time is the solver call alone (model building reported separately), the median of
``--repeats`` runs, all in one session: run nothing else on the machine meanwhile.
Ratios compare each library point with the fastest SciPy point reaching the same or a
smaller error.

Run from the repository root::

    python -m validation.cost work_precision [--out DIR] [--repeats N] [--quick]

Writes ``work_precision.md``, ``work_precision.csv`` and ``work_precision.png`` to
``results/work_precision/`` and prints the headline figures.
"""
from __future__ import annotations

import argparse
import os
import statistics
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace

import numpy as np

import exuclear
from exuclear.models import journal_bearing as jb_model
from exuclear.models import slider_crank as sc_model
from exuclear.models.journal_bearing import JournalBearingParams
from exuclear.models.slider_crank import SliderCrankParams
from validation import cross_check as cc
from validation._tables import markdown_table, write_csv
from validation.reference import journal_bearing as jb_reference
from validation.reference import slider_crank as sc_reference

DEFAULT_OUT = os.path.join("results", "work_precision")

#: The target of issue 5: eccentricity error at most 1 % of the clearance.
ECC_TARGET = 0.01
#: Output interval of the library runs [s] (the paper's): outputs are part of the work.
OUTPUT_STEP = 1e-5
#: Absolute tolerance per unit of relative tolerance: positions are ~1e-4 m (c) to 0.35 m,
#: so atol = 1e-3 rtol holds the eccentricity to ~rtol * 1e-3 m, below rtol * c.
ATOL_PER_RTOL = 1e-3
#: Output interval of the journal-bearing runs [s]: 1/40 of the ~40 us impact, for its
#: peak force (the departure velocity is read from the journal's final state).
IMPACT_OUTPUT_STEP = 1e-6
#: Largest step of the adaptive explicit runs [s]: with outputs every 1e-5 s a longer
#: step would be interpolated linearly over its free-flight parabola (a 1e-3 s step
#: errs by ~0.2 c there); 1e-4 s keeps that below the target.
DOPRI5_MAX_STEP = 1e-4


# =======================================================================================
# configurations
# =======================================================================================
@dataclass(frozen=True)
class Config:
    """One line of the diagram: a family of runs differing in one accuracy parameter."""

    label: str
    side: str                      # "exuclear" or "scipy"
    points: tuple[object, ...]     # settings changes (exuclear) or (method, rtol) (scipy)
    formulation: str = "minimal"
    backend: str = exuclear.engine.DEFAULT_BACKEND


def crank_configs(quick: bool) -> list[Config]:
    """The slider-crank configurations (fewer points with ``quick``)."""

    def dopri(rtols: Sequence[float], step: float = DOPRI5_MAX_STEP) -> tuple:
        return tuple({"method": "dopri5", "step": step, "rtol": r, "atol": r * ATOL_PER_RTOL} for r in rtols)

    def alpha(steps: Sequence[float], impact: Sequence[float | None]) -> tuple:
        return tuple({"method": "generalized-alpha", "step": h, "impact_step": i} for h, i in zip(steps, impact))

    rtols = (1e-5, 1e-6) if quick else (1e-5, 1e-6, 1e-7, 1e-8)
    impacts = (2e-6, 1e-6) if quick else (4e-6, 2e-6, 1e-6, 5e-7)
    compiled = exuclear.engine.DEFAULT_BACKEND
    configs = [
        Config(f"minimal, {compiled}, dopri5", "exuclear", dopri(rtols)),
        Config("minimal, python, dopri5", "exuclear", dopri(rtols[:3]), backend="python"),
        Config(f"minimal, {compiled}, dopri5 (step <= 1e-5 s, the paper's)", "exuclear",
               dopri((1e-6,) if quick else (1e-6, 1e-8), 1e-5)),
        Config(f"redundant, {compiled}, generalized-alpha, fixed step", "exuclear",
               alpha((1e-5,) if quick else (1e-5, 4e-6, 2e-6), (None,) * 3), formulation="redundant"),
        Config(f"redundant, {compiled}, generalized-alpha, impact-aware steps", "exuclear",
               alpha((2e-5,) * len(impacts), impacts), formulation="redundant"),
        Config("redundant, python, generalized-alpha, impact-aware steps", "exuclear",
               alpha((2e-5,) * 2, impacts[-3:-1] if not quick else impacts[:1]), formulation="redundant",
               backend="python"),
    ]
    scipy_rtols = {"DOP853": (1e-6, 1e-7, 1e-8, 1e-9), "RK45": (1e-5, 1e-6, 1e-7, 1e-8),
                   "LSODA": (1e-5, 1e-6, 1e-7, 1e-8), "Radau": (1e-4, 1e-5, 1e-6, 1e-7)}
    for method, tols in scipy_rtols.items():
        if quick and method in ("LSODA", "Radau"):
            continue
        configs.append(Config(f"SciPy {method}", "scipy", tuple((method, r) for r in (tols[1:3] if quick else tols))))
    return configs


def impact_configs(quick: bool) -> list[Config]:
    """The journal-bearing configurations."""
    rtols = (1e-6, 1e-8) if quick else (1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
    # steps of at most 1e-7 s (exuclear.models.journal_bearing.IMPACT_STEP): ~400 steps per run, so
    # that the evaluation cost of the backends shows beside the fixed costs
    dopri = tuple({"method": "dopri5", "step": jb_model.IMPACT_STEP, "rtol": r, "atol": r * 1e-7} for r in rtols)
    steps = (1e-7, 2e-8) if quick else (1e-6, 3e-7, 1e-7, 3e-8, 1e-8)
    alpha = tuple({"method": "generalized-alpha", "step": h} for h in steps)
    configs = [Config(f"{b}, {name}", "exuclear", pts, backend=b)
               for b in exuclear.engine.BACKENDS for name, pts in (("dopri5", dopri), ("generalized-alpha", alpha))]
    for method in ("DOP853", "RK45", "LSODA"):
        configs.append(Config(f"SciPy {method}", "scipy", tuple((method, r) for r in rtols)))
    return configs


# =======================================================================================
# measuring
# =======================================================================================
@dataclass
class Point:
    """One run: its accuracy parameter, error, wall time and what else it reports."""

    scene: str
    config: Config
    setting: str
    error: float            # the scene's main error (eccentricity / c, or departure velocity, relative)
    wall: float             # median simulation wall time [s]
    walls: list[float]
    build: float            # model building [s] (exuclear), 0 for SciPy
    steps: int
    impacts: int
    peak_force_error: float
    success: bool
    message: str
    settings: exuclear.SolverSettings | None = None  # of an exuclear run


def _median_wall(run: Callable[[], tuple[float, object]], repeats: int) -> tuple[list[float], object]:
    walls, last = [], None
    for _ in range(repeats):
        wall, last = run()
        walls.append(wall)
    return walls, last


def _describe(changes: dict) -> str:
    parts = [f"{k} {v:g}" for k, v in changes.items() if k != "method" and v is not None]
    return f"{changes['method']} " + ", ".join(parts)


@dataclass
class CrankReference:
    """The converged slider-crank reference of one scene."""

    params: SliderCrankParams
    columns: dict[str, np.ndarray]
    peak_force: float
    impacts: int


def crank_reference(params: SliderCrankParams) -> CrankReference:
    ref = cc.reference_run(params)  # on cross_check's grid, fine enough to interpolate (cc.GRID_STEP)
    if not ref.success:
        raise RuntimeError(f"the reference failed: {ref.message}")
    return CrankReference(params, ref.columns, cc.reference_peak_force(params, ref), ref.n_impacts)


def _ecc_error(columns: dict[str, np.ndarray], ref: CrankReference) -> float:
    # the reference interpolated onto the run's own output instants
    return float(cc.eccentricity_difference(ref.columns, columns).max() / ref.params.clearance)


def crank_point(scene: str, config: Config, point: object, ref: CrankReference, repeats: int) -> Point:
    """Run one point of a slider-crank configuration ``repeats`` times."""
    if config.side == "scipy":
        method, rtol = point

        def run_scipy():
            r = sc_reference.simulate(ref.params, method=method, rtol=rtol, atol=rtol * ATOL_PER_RTOL,
                                      output_step=OUTPUT_STEP)
            return r.wall_time, r

        walls, r = _median_wall(run_scipy, repeats)
        return Point(scene, config, f"{method} rtol {rtol:g}", _ecc_error(r.columns, ref), statistics.median(walls),
                     walls, 0.0, r.n_rhs, r.n_impacts, float(r.columns["contact_force"].max()) / ref.peak_force - 1.0,
                     r.success, r.message)
    params = replace(ref.params, formulation=config.formulation, backend=config.backend)
    settings = replace(sc_model.default_settings(params), output_step=OUTPUT_STEP, **point)

    def run_exuclear():
        result = sc_model.run(params, settings)
        return result.wall_time, result

    walls, r = _median_wall(run_exuclear, repeats)
    return Point(scene, config, _describe(point), _ecc_error(r.columns, ref), statistics.median(walls), walls,
                 r.build_time, r.steps, r.impacts, r.peak_force / ref.peak_force - 1.0, r.success, r.message, settings)


def impact_point(scene: str, config: Config, point: object, params: JournalBearingParams, reference: dict,
                 repeats: int) -> Point:
    """Run one point of a journal-bearing configuration ``repeats`` times."""
    v_ref, f_ref = reference["departure_velocity"], reference["max_force"]
    if config.side == "scipy":
        method, rtol = point

        def run_scipy():
            r = jb_reference.simulate(params, method=method, rtol=rtol, atol=rtol * 1e-7)
            return r["wall_time"], r

        walls, r = _median_wall(run_scipy, repeats)
        return Point(scene, config, f"{method} rtol {rtol:g}", abs(r["departure_velocity"] / v_ref - 1.0),
                     statistics.median(walls), walls, 0.0, r["n_rhs"], 1, r["max_force"] / f_ref - 1.0, r["success"],
                     r["message"])
    p = replace(params, backend=config.backend)
    settings = replace(jb_model.default_settings(p), output_step=IMPACT_OUTPUT_STEP, **point)

    def run_exuclear():
        start = time.perf_counter()
        scene = jb_model.build(p)
        mbs, handle, node = scene.mbs, scene.joint, scene.nodes["journal"]
        build = time.perf_counter() - start
        sim = exuclear.simulate(mbs, settings)
        return sim.wall_time, (sim, mbs, handle, node, build)

    walls, (sim, mbs, handle, node, build) = _median_wall(run_exuclear, repeats)
    import exudyn as exu

    departure = -float(mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)[0])
    force = float(handle.outputs()["normal_force"].max())
    return Point(scene, config, _describe(point), abs(departure / v_ref - 1.0), statistics.median(walls), walls,
                 build, sim.steps, len(handle.history.onset_times), force / f_ref - 1.0, sim.success, sim.message)


# =======================================================================================
# the study
# =======================================================================================
CRANK_SCENES = (("slider-crank cr 0.9", 0.9), ("slider-crank cr 0.3", 0.3))
IMPACT_SCENE = "journal-bearing cr 0.9"


def study(quick: bool, repeats: int, progress: Callable[[str], None] = print) -> list[Point]:
    """Run every configuration on every scene; returns the points."""
    points: list[Point] = []
    crank, impact = crank_configs(quick), impact_configs(quick)
    total = len(CRANK_SCENES) * sum(len(c.points) for c in crank) + sum(len(c.points) for c in impact)
    count = 0

    def report(p: Point) -> None:
        nonlocal count
        count += 1
        status = "" if p.success else f"  FAILED: {p.message}"
        progress(f"run {count}/{total}: {p.scene}, {p.config.label}, {p.setting}: error {p.error:.2e}, "
                 f"wall {p.wall:.3f} s (median of {len(p.walls)}), {p.steps} steps{status}")

    for scene, cr in CRANK_SCENES:
        params = SliderCrankParams.paper(cr=cr)
        progress(f"reference for {scene} (DOP853 rtol {cc.REF_RTOL:g})")
        ref = crank_reference(params)
        for config in crank:
            for point in config.points:
                points.append(crank_point(scene, config, point, ref, repeats))
                report(points[-1])
    params = JournalBearingParams.paper()
    reference = jb_reference.simulate(params)
    for config in impact:
        for point in config.points:
            points.append(impact_point(IMPACT_SCENE, config, point, params, reference, repeats))
            report(points[-1])
    return points


def fastest_scipy(points: Sequence[Point], scene: str, error: float) -> Point | None:
    """The fastest SciPy point of ``scene`` with an error at most ``error``."""
    fits = [p for p in points if p.scene == scene and p.config.side == "scipy" and p.success and p.error <= error]
    return min(fits, key=lambda p: p.wall) if fits else None


def ratio_text(points: Sequence[Point], p: Point) -> str:
    best = fastest_scipy(points, p.scene, p.error)
    return f"{best.wall / p.wall:.1f}x ({best.config.label[6:]})" if best else "no SciPy run this accurate"


def cheapest_within(points: Sequence[Point], scene: str, label: str, target: float) -> Point | None:
    """The cheapest point of configuration ``label`` in ``scene`` with error <= ``target``."""
    fits = [p for p in points if p.scene == scene and p.config.label == label and p.success and p.error <= target]
    return min(fits, key=lambda p: p.wall) if fits else None


# =======================================================================================
# where the time goes
# =======================================================================================
@dataclass
class Profile:
    """Split of one default run (default backend) by cProfile: calls and inclusive time of
    the element's force callback, the per-step hooks and the output sensor; the rest is
    Exudyn's own solver (C++), obtained as the difference.  cProfile slows Python code,
    so the shares are upper bounds for Python; the un-profiled wall time is beside them."""

    scene: str
    formulation: str
    wall: float
    profiled: float
    steps: int
    groups: dict[str, tuple[int, float]]   # name -> (calls, inclusive seconds)


#: Python functions of a run (with the compiled kernel, only simulate's watchdog step hooks remain).
_PROFILE_GROUPS = {"Python force callback": ("force_torque", "probe", "torque"),
                   "Python post-Newton": ("post_newton", "probe_post_newton"),
                   "simulate's step hooks": ("post_step", "pre_step")}


def profile_default(scene: str, cr: float, formulation: str) -> Profile:
    import cProfile
    import pstats

    params = SliderCrankParams.paper(cr=cr, formulation=formulation)
    settings = sc_model.default_settings(params)
    wall = sc_model.run(params, settings).wall_time
    model = sc_model.build(params)
    profiler = cProfile.Profile()
    profiler.enable()
    sim = exuclear.simulate(model.mbs, settings)
    profiler.disable()
    stats = pstats.Stats(profiler).stats
    groups = {}
    for group, names in _PROFILE_GROUPS.items():
        rows = [v for (_, _, name), v in stats.items() if name in names]
        groups[group] = (sum(r[1] for r in rows), sum(r[3] for r in rows))
    return Profile(scene, formulation, wall, sim.wall_time, sim.steps, groups)


def profile_md(profiles: Sequence[Profile]) -> str:
    rows = []
    for p in profiles:
        python = sum(t for _, t in p.groups.values())
        cells = [f"{calls} / {t:.3f} s" for calls, t in p.groups.values()]
        rows.append((p.scene, p.formulation, f"{p.wall:.3f}", str(p.steps), *cells,
                     f"{max(p.profiled - python, 0.0):.3f}", f"{p.profiled:.3f}"))
    header = ("scene", "default formulation", "wall [s] (not profiled)", "steps",
              *(f"{g}: calls / time" for g in _PROFILE_GROUPS), "Exudyn solver and rest [s]", "profiled total [s]")
    return markdown_table(header, rows)


# =======================================================================================
# outputs
# =======================================================================================
def records(points: Sequence[Point]) -> list[dict[str, object]]:
    return [{"scene": p.scene, "configuration": p.config.label, "setting": p.setting, "error": f"{p.error:.4e}",
             "wall_median_s": f"{p.wall:.5f}", "walls_s": " ".join(f"{w:.5f}" for w in p.walls),
             "build_s": f"{p.build:.5f}", "steps_or_rhs": p.steps, "impacts": p.impacts,
             "peak_force_error": f"{p.peak_force_error:+.4e}", "success": p.success} for p in points]


def figure(points: Sequence[Point], path: str) -> str:
    from matplotlib.figure import Figure  # a file only: no pyplot, no backend chosen

    scenes = list(dict.fromkeys(p.scene for p in points))
    fig = Figure(figsize=(6.2 * len(scenes), 5.6))
    axes = fig.subplots(1, len(scenes), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        labels = list(dict.fromkeys(p.config.label for p in points if p.scene == scene))
        for k, label in enumerate(labels):
            line = sorted((p for p in points if p.scene == scene and p.config.label == label and p.success),
                          key=lambda p: p.error)
            style = "--" if label.startswith("SciPy") else "-"
            ax.loglog([max(p.error, 1e-12) for p in line], [p.wall for p in line], style, marker="o^sDvP<>"[k % 8],
                      label=label, markersize=5)
        if scene.startswith("slider"):
            ax.axvline(ECC_TARGET, color="0.5", lw=0.8, ls=":")
            ax.set_xlabel("max |e - e_ref| / c over the run")
        else:
            ax.set_xlabel("departure velocity, relative error")
        ax.set_ylabel("simulation wall time [s] (median)")
        ax.set_title(scene)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    return path


def report_md(points: Sequence[Point], repeats: int, runtime: float, profiles: Sequence[Profile] = ()) -> str:
    lines = ["# Work-precision study", "",
             "Source problems: docs/physics.md sections 6.1 (journal-bearing impact, Wang-Liu cr 0.9) and 6.2 (slider-crank, steel, "
             "no friction, 2 crank revolutions). Command: `python -m validation.cost work_precision` "
             f"(median of {repeats} runs per point; total runtime {runtime:.0f} s).", "",
             "Error: slider-crank, max |e - e_ref| / c over the run at the run's output instants, against DOP853 at "
             f"rtol {cc.REF_RTOL:g}; journal-bearing, relative error of the departure velocity against DOP853 at "
             "rtol 1e-11. Wall time: the solver call alone (median); model building separately. Ratio: the fastest "
             "SciPy run with the same or a smaller error, divided by this run's wall time.", "",
             "![work-precision diagram](work_precision.png)", ""]
    for scene in dict.fromkeys(p.scene for p in points):
        lines += [f"## {scene}", ""]
        rows = []
        for p in (q for q in points if q.scene == scene):
            rows.append((p.config.label, p.setting, f"{p.error:.2e}", f"{p.wall:.3f}", f"{p.build * 1e3:.1f}",
                         str(p.steps), str(p.impacts), f"{p.peak_force_error:+.2%}",
                         ratio_text(points, p) if p.config.side == "exuclear" else "",
                         "ok" if p.success else f"FAILED: {p.message}"))
        lines += [markdown_table(("configuration", "setting", "error", "wall [s]", "build [ms]",
                                     "steps (SciPy: rhs calls)", "impacts", "peak force", "vs fastest SciPy",
                                     "status"), rows), ""]
    lines += ["## At the target: eccentricity error <= 1 % of c", ""]
    rows = []
    for scene, _ in CRANK_SCENES:
        for label in dict.fromkeys(p.config.label for p in points if p.scene == scene):
            best = cheapest_within(points, scene, label, ECC_TARGET)
            rows.append((scene, label, best.setting if best else "none reaches it",
                         f"{best.wall:.3f}" if best else "", f"{best.error:.2e}" if best else "",
                         ratio_text(points, best) if best and best.config.side == "exuclear" else ""))
    lines += [markdown_table(("scene", "configuration", "cheapest setting", "wall [s]", "error",
                                 "vs fastest SciPy at that error"), rows), ""]
    if profiles:
        lines += [f"## Where the time goes (default settings, {exuclear.engine.DEFAULT_BACKEND} backend)", "", _PROFILE_NOTE, "",
                  profile_md(profiles), ""]
    return "\n".join(lines)


_PROFILE_NOTE = ("cProfile of one run each: calls and inclusive time of the joint's Python user functions (zero "
                 "with the compiled kernel, which Exudyn calls without Python) and of the step hooks that "
                 "exuclear.simulate installs for its watchdogs; the remainder is Exudyn's solver in C++ (time "
                 "integration, the markers' kinematics, the kinematic tree's or the constraints' equations, the "
                 "compiled kernel) and the profiler's own overhead.")


def headline(points: Sequence[Point]) -> list[str]:
    """The figures the README quotes: each formulation's default settings (default backend)."""
    out = []
    for scene, cr in CRANK_SCENES:
        for formulation in sc_model.FORMULATIONS:
            params = SliderCrankParams.paper(cr=cr, formulation=formulation)
            default = replace(sc_model.default_settings(params), output_step=OUTPUT_STEP)
            for p in points:
                if (p.scene == scene and p.settings == default and p.config.formulation == formulation
                        and p.config.backend == exuclear.engine.DEFAULT_BACKEND):
                    out.append(f"{scene}, default {formulation} ({p.setting}): {p.wall:.3f} s, error {p.error:.2e} c, "
                               f"fastest SciPy at that error: {ratio_text(points, p)}")
    return out


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m validation.cost work_precision", description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=DEFAULT_OUT, help="output directory (default %(default)s)")
    ap.add_argument("--repeats", type=int, default=3, help="runs per point; the median is reported (default 3)")
    ap.add_argument("--quick", action="store_true", help="fewer points and solvers (a smoke run)")
    return ap


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    if args.repeats < 1:
        print(f"error: `--repeats` must be at least 1, got {args.repeats}", file=sys.stderr)
        return 2
    start = time.perf_counter()
    points = study(args.quick, args.repeats)
    profiles = [profile_default(scene, cr, f) for scene, cr in CRANK_SCENES for f in sc_model.FORMULATIONS]
    runtime = time.perf_counter() - start
    os.makedirs(args.out, exist_ok=True)
    paths = [write_csv(os.path.join(args.out, "work_precision.csv"), records(points)),
             figure(points, os.path.join(args.out, "work_precision.png"))]
    path = os.path.join(args.out, "work_precision.md")
    with open(path, "w", encoding="utf-8") as f:
        f.write(report_md(points, args.repeats, runtime, profiles))
    paths.append(path)
    for p in paths:
        print(f"wrote {p}")
    for line in headline(points):
        print(line)
    for p in profiles:
        python = ", ".join(f"{g}: {calls} calls, {seconds:.3f} s" for g, (calls, seconds) in p.groups.items())
        print(f"{p.scene}, default {p.formulation}: {p.steps} steps; {python}; of {p.profiled:.3f} s profiled "
              f"({p.wall:.3f} s not profiled)")
    print(f"total runtime {runtime:.0f} s")
    failed = [p for p in points if not p.success]
    return 1 if failed else 0
