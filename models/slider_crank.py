"""Slider-crank with a revolute clearance joint: the paper's example 2 (docs/physics.md section 6.2).

::

        Y
        ^        A (ideal revolute)
        |       o.
        |  crank  '.   connecting rod
        |  r /      '.      l
        |   /  theta  '.         B (clearance joint: journal on the rod,
        O--o------------'o.__     bearing in the slider)
      ground pivot,      [slider]====> X   (ideal prismatic guide, y = 0)
      crank turns at a constant omega

Three formulations, all assembled from Exudyn items by the library:

- ``"redundant"``: ``ObjectRigidBody2D`` bodies with ideal ``JointRevolute2D`` (O, A)
  and ``JointPrismatic2D`` (slider) constraints; the crank speed is a velocity-level
  ``CoordinateConstraint`` on the crank angle, whose Lagrange multiplier is the
  driving moment.  Needs an implicit solver.
- ``"minimal"``: an ``ObjectKinematicTree`` with coordinates (crank angle, rod angle
  relative to the crank, slider x), so that explicit adaptive solvers (DOPRI5) apply.
  See :func:`build` for how the crank speed is held there.
- ``"spatial"``: the same mechanism built as an Exudyn user builds 3D models, six
  degrees of freedom per body (``mbs.CreateRigidBody``, ``mbs.CreateRevoluteJoint``,
  ``mbs.CreatePrismaticJoint``, ``exuclear.CreateClearanceJoint``); see
  :func:`_build_spatial`.  Needs an implicit solver.

Run ``python -m exuclear.models.slider_crank --help`` for the command line: one option per
:class:`SliderCrankParams` field (``--crank-length``, ...), the crank speed in rpm and the
solver settings.
"""
from __future__ import annotations

import argparse
import sys
import warnings
from dataclasses import replace

import numpy as np

from exuclear import SolverSettings
from exuclear.engine import AccuracyWarning
from exuclear.engine.outputs import REGIME_CONTACT
from exuclear.settings import METHODS

from ._cli import SceneRun, Table, add_rpm_option, run_main, scene_parser
from ._defaults import PAPER_CLEARANCE, PAPER_CRANK_SPEED, PAPER_RPM  # noqa: F401 - the paper's values, read from the scene too
from ._params import (
    changes_from_args,
    crank_speed_from_rpm,
    positive,
)
from ._slider_crank_build import (  # noqa: F401 - the scene's names, one module per role
    _RXYZ_ANGLE_Z,
    SPATIAL_NODE_TYPE,
    _build_minimal,
    _build_redundant,
    _build_spatial,
    _initial_velocities,
    build,
    out_of_plane,
)
from ._slider_crank_nonlinear import CRANK_ANGLE, DRIVEN_FIXED, TOLERANCE_FACTOR, driven  # noqa: F401 - the scene's names
from ._slider_crank_params import (  # noqa: F401 - the scene's names, one module per role
    COLUMNS,
    CRANK_SPEED_WARN,
    FILM_COLUMNS,
    FLYWHEEL_INERTIA,
    FORMULATIONS,
    SliderCrankParams,
)
from ._slider_crank_run import (  # noqa: F401 - the scene's names, one module per role
    _DEFAULTS,
    MINIMAL_DEFAULTS,
    REDUNDANT_DEFAULTS,
    SIGNALS,
    SPATIAL_DEFAULTS,
    SliderCrankResult,
    _scaled_defaults,
    accuracy_notes,
    check_convergence,
    columns,
    csv_columns,
    default_settings,
    ideal_joint_force,
    record,
    run,
    write_csv,
)
from ._slider_crank_study import (  # noqa: F401 - the scene's names, one module per role
    STUDY_COLUMNS,
    STUDY_EVERY_STEP,
    STUDY_METRICS,
    STUDY_PARAMETERS,
    _elastic_energy,
    _energy_audit,
    _study_defaults,
    check_study,
    ideal_slider_acceleration,
    mechanical_energy,
    study,
    study_params,
)


def _parser() -> argparse.ArgumentParser:
    """The command line: one option per :class:`SliderCrankParams` field
    (:func:`~exuclear.models._params.add_param_options`); defaults :meth:`SliderCrankParams.paper`."""
    p = SliderCrankParams.paper()
    ap = scene_parser("slider_crank", __doc__, p)
    add_rpm_option(ap, p.crank_speed)
    ap.add_argument("--formulation", choices=FORMULATIONS, default=None,
                    help="minimal (kinematic tree, DOPRI5; default), redundant (2D bodies and joints, implicit "
                         "solver; the default for --ideal and for clearance at O or A, said so in the output) or "
                         "spatial (3D bodies and joints made by Exudyn's Create functions, implicit solver)")
    ap.add_argument("--clearance-joints", default="B",
                    help="joints with clearance, letters of OAB (crank-ground, crank-rod, rod-slider); "
                         "more than B needs --formulation redundant or spatial (default %(default)s)")
    ap.add_argument("--method", choices=list(METHODS),
                    help="solver (default: per formulation); an implicit method gets the implicit default steps "
                         f"({REDUNDANT_DEFAULTS['step']:g} s, {REDUNDANT_DEFAULTS['impact_step']:g} s from each "
                         "contact onset) in either formulation unless --step is given")
    ap.add_argument("--step", type=float, help="fixed step, or largest step of adaptive and impact-aware methods [s]")
    ap.add_argument("--rtol", type=float, help="relative tolerance of adaptive methods")
    ap.add_argument("--atol", type=float, help="absolute tolerance of adaptive methods")
    ap.add_argument("--dt-out", type=float, default=1e-5,
                    help="output interval [s]; outputs are taken at the first accepted step at or after each "
                         "interval, so where the adaptive steps are longer (up to --step) every step is recorded. "
                         "Impacts are counted at every accepted step whatever the interval, but the printed peak "
                         "force, the CSV and the plots see only the outputs: above 1e-5 s an impact (~40 us) is "
                         "sampled coarsely or missed (default %(default)s)")
    ap.add_argument("--csv", metavar="FILE", help="write the time series (columns: " + ", ".join(COLUMNS) + ")")
    ap.add_argument("--plot", metavar="DIR", help="write the plots, with the ideal mechanism as baseline, to DIR")
    ap.add_argument("--verbose", action="store_true", help="Exudyn's progress output during the run")
    ap.add_argument("--check-convergence", action="store_true",
                    help="run again at a tighter step or tolerance and print what agrees with it, and over which "
                         "horizon (exuclear.check_convergence)")
    return ap


def _settings(args: argparse.Namespace, params: SliderCrankParams) -> SolverSettings:
    method = args.method or default_settings(params).method
    # the defaults of the method's family, whatever the formulation: an implicit method at
    # the explicit default's 1e-4 s fixed step overshoots the impacts (peak force 2.4e7 N
    # on the paper's case instead of 2.1e3 N)
    family = MINIMAL_DEFAULTS if METHODS[method][1] else (
        SPATIAL_DEFAULTS if params.formulation == "spatial" else REDUNDANT_DEFAULTS)
    base = SolverSettings(end_time=params.end_time, **_scaled_defaults(params, {**family, "method": method}))
    changes = {k: v for k, v in (("step", args.step), ("rtol", args.rtol), ("atol", args.atol)) if v is not None}
    if base.impact_step is not None and args.step is not None and args.step <= base.impact_step:
        changes["impact_step"] = None  # a step at or below the impact step: the joints' own step control
    return replace(base, output_step=positive("--dt-out", args.dt_out),
                   verbose=int(args.verbose), **changes)


def _formulation(args: argparse.Namespace) -> tuple[str, str]:
    """The formulation asked for or implied by the options, and why, if it was implied."""
    if args.formulation:
        return args.formulation, ""
    if args.ideal:
        return "redundant", " (chosen for --ideal: a kinematic tree cannot close the loop)"
    if set(args.clearance_joints) - {"B"}:
        return "redundant", f" (chosen for --clearance-joints {args.clearance_joints}: the tree has O and A built in)"
    return "minimal", ""


class _SliderCrankRun(SceneRun):
    """The command line's run (:func:`~exuclear.models._cli.run_main`): the paper's case with
    the options' changes in the formulation asked for or implied, its summary with the
    convergence check, and its figures against the ideal mechanism."""

    notes: tuple[str, ...] = ()

    def prepare(self, law: str, cr: float) -> None:
        args = self.args
        self.formulation, self.chosen = _formulation(args)
        self.params = SliderCrankParams.paper(
            **changes_from_args(args, SliderCrankParams), law=law, cr=cr, crank_speed=crank_speed_from_rpm("rpm", args.rpm),
            formulation=self.formulation, clearance_joints=tuple(args.clearance_joints))
        self.settings = _settings(args, self.params)

    def simulate(self) -> None:
        args = self.args
        self.result = run(self.params, self.settings)
        defaults = args.step is None and args.rtol is None and args.atol is None
        self.notes = tuple(accuracy_notes(self.params, self.settings)) if defaults else ()
        for note in self.notes:  # after the run: a model that cannot be built is refused without them
            warnings.warn(note, AccuracyWarning, stacklevel=1)

    @property
    def kind(self) -> str:
        """What joint B is: the summary's first line and the figures' title."""
        params = self.params
        return "ideal joint at B" if params.ideal else (
            f"clearance {params.clearance * 1e3:g} mm, {params.law} cr = {params.cr}, {params.journal_material} journal, "
            f"{params.bearing_material} bearing, friction {params.friction}"
            + ("" if params.viscosity is None else f", oil {params.viscosity:g} Pa s ({params.film_model} film)"))

    def summary(self) -> None:
        params, settings, result = self.params, self.settings, self.result
        print(f"slider-crank, {self.formulation} coordinates{self.chosen}, {settings.method}: {self.kind}")
        if result.success:
            print(f"  simulated {params.end_time:.4g} s ({params.revolutions:g} revolutions) in {result.steps} steps "
                  f"({result.rejected} rejected)")
        else:
            reached = float(result.columns["time"][-1]) if len(result.columns["time"]) else 0.0
            print(f"  STOPPED EARLY: last output at t = {reached:.4g} s of {params.end_time:.4g} s "
                  f"({reached / params.end_time * params.revolutions:.3g} of {params.revolutions:g} revolutions), "
                  f"{result.steps} steps ({result.rejected} rejected); see the error below")
        sampled = f" (in the outputs every {settings.output_step:g} s)" if settings.output_step > 1e-5 else ""
        if params.ideal:
            print(f"  joint force at B {np.nanmin(result.columns['contact_force']):.1f} to "
                  f"{np.nanmax(result.columns['contact_force']):.1f} N (closed form of the ideal mechanism)")
        else:
            print(f"  peak contact force {result.peak_force:.1f} N{sampled}, impacts {result.impacts}")
            if "film_force" in result.columns:
                cols, t = result.columns, result.columns["time"]
                contact = float(np.trapezoid((cols["regime"] == REGIME_CONTACT).astype(float), t)) / (t[-1] - t[0])
                print(f"  oil film: peak joint force (film and contact) {cols['joint_force'].max():.1f} N, largest "
                      f"eccentricity ratio {cols['eccentricity_ratio'].max():.4g}, smallest film thickness "
                      f"{max(cols['min_film_thickness'].min(), 0.0) * 1e6:.3g} um, metal contact {100.0 * contact:.3g} % "
                      "of the time")
        if result.wear is not None:
            depth, angle = result.wear.deepest()
            print(f"  wear at B: largest bearing depth {depth * 1e9:.4g} nm at {np.degrees(angle):.1f} deg of the joint "
                  f"frame, worn volume {result.wear.volume['bearing'] * 1e9:.4g} mm^3 (bearing), "
                  f"{result.wear.volume['journal'] * 1e9:.4g} mm^3 (journal)")
        print(f"  wall time {result.wall_time:.2f} s (model building {result.build_time:.3f} s)")
        if self.args.check_convergence:
            print(check_convergence(params, settings).report())

    def table(self) -> Table:
        cols = self.result.columns
        return Table(cols, csv_columns(cols), self.incomplete, self.notes + self.result.notes)

    def plots(self, directory: str) -> list[str]:
        from exuclear.models.figures import slider_crank_figures

        params, result = self.params, self.result
        baseline = result if params.ideal else run(replace(params, ideal=True, formulation="redundant"))
        cases = [] if params.ideal else [(f"cr = {params.cr}", result.columns)]
        return slider_crank_figures(cases, baseline.columns, params.clearance, directory, "slider_crank",
                                    title=f"slider-crank: {self.kind}")

    def errors(self) -> list[str]:
        csv = self.args.csv
        written = f"; the outputs up to then were written to {csv} and are INCOMPLETE" if csv else ""
        return [message + written for message in super().errors()]


def main(argv: list[str] | None = None) -> int:
    return run_main(argv, _parser(), _SliderCrankRun)


if __name__ == "__main__":
    sys.exit(main())
