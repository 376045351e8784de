"""The compliant and the impulse contact mode side by side (issue 52): cost over the ideal
model, impacts, and distance from the converged compliant run.

Source problems: the zoo's models (``validation/exudyn_examples``), each with one joint
replaced by a clearance joint (revolute, spherical, pin-in-slot, translational) and its own
settings through a plain ``mbs.SolveDynamic``; and the paper's journal impact (``exuclear.models.journal_bearing``, docs/physics.md section 6.1).

Per zoo model: the wall time of each mode over the ideal model's (median of ``--repeats``;
take timings on a quiet machine), the accepted steps and Newton iterations, the impacts, and the probe's distance
(``ZooModel.probe``: observables at the end of the run) from the compliant run at
``--factor`` times the steps, in clearances.  The impulse mode runs with the model's own
settings but generalized-alpha's spectral radius 1, which it needs; a model it does not
take says why (its refusal), and a run it refuses says so.

The issue's target rows:

- ``restitution``: the paper's journal impact (no gravity: the journal crosses the bearing
  and hits the far wall again and again) at steps of 3, 10, 100 and 1000 times the law's
  impact duration; the largest relative error of the ratio of successive impact velocities
  against the law's restitution, and the steps taken (where a step would fly across the
  clearance, the mode has Exudyn's adaptive step shorten it);
- ``elastic``: a journal of cr 1 dropped from the bearing's centre under gravity: its energy
  at the run's end against the start, in shares of the fall's ``m g c``;
- ``resting``: a journal on its wall under gravity: the impacts after the first, and the
  reaction against the ideal joint's ``m g``;
- the spherical and the pin-in-slot joint's rows (``_joint_type_scenes``): a ball thrown
  in 3D at steps of 10 and 1000 contact durations, dropped, elastic and resting; a pin onto
  a slot's flat sides and end caps, and held on the flat side under tilted gravity into the
  end cap;
- the translational joints' rows (``_translational_scenes``): a slider thrown flat and
  turned, a box thrown flat onto two walls, slider and box resting flat, sliding held, and
  an elastic spinning slider; the spatial revolute joint's (``_spatial_scenes``): a journal
  of four slices thrown flat, resting, and elastic and tilting at two steps;
- ``slider-crank``: the paper's slider-crank after 25 ms, slider position and crank moment
  against the compliant run at ``--factor`` times the steps, in shares of their range; the
  impulse mode's moment also against the compliant run with a :data:`STIFFER` times stiffer
  contact (the mode's contact is rigid).

::

    python -m validation.cost modes [--models a,b] [--factor 8] [--repeats 3] [--refine 4] [--no-zoo]
                                    [--no-targets] [--adaptive-step] [--friction LAW] [--iterations N]

(``--repeats 0``: steps, impacts and accuracy without timing, for a busy machine;
``--adaptive-step``: every zoo run with Exudyn's adaptive step, the one change an example
whose fixed step stops at its first contact needs; ``--friction``: every zoo model's
clearance joint with that friction law, in both modes and the reference, for the joint
types the zoo has no friction variant of; ``--iterations``: every zoo run with that many of
Exudyn's discontinuous iterations, where the mode's friction needs more than an example
allows.)
"""
from __future__ import annotations

import argparse
import math
import os
import statistics
import time
import warnings
from dataclasses import replace
from typing import Any

import exudyn as exu
import numpy as np

import exuclear
from exuclear.engine.impulse import ImpulseJointHandle
from exuclear.engine.impulse_group import ImpulsePairsHandle
from exuclear.timescales import closed_form_impact, impact_restitution
from exuclear.engine.modes import ENVIRONMENT_VARIABLE
from exuclear.materials import material
from exuclear.models import journal_bearing as jb
from exuclear.models import slider_crank as sc
from validation._tables import markdown_table
from validation.cost._joint_type_scenes import joint_type_rows
from validation.cost._spatial_scenes import spatial_rows
from validation.cost._translational_scenes import translational_rows
from validation.exudyn_examples._common import REGISTRY, load_models, model_names

#: Standard gravity of the target rows' scenes [m/s^2].
G = 9.81
#: The slider-crank's contact against which the impulse mode's crank moment is also
#: compared: Young's moduli this many times the paper's (the mode's contact is rigid; the
#: compliant contact's own vibration moves the moment by some percent of its range).
STIFFER = 10.0


def _build(name: str, clearance: bool, mode: str | None, adaptive: bool = False, iterations: int = 0,
           **joint: Any) -> Any:
    """A zoo model, its joint in ``mode`` (through the environment variable, as a user's
    unedited script would get it; None: the default); ``adaptive``: with Exudyn's adaptive
    step (``timeIntegration.adaptiveStep``) whatever the example sets; ``iterations`` > 0:
    that many discontinuous iterations; ``joint``: options of the clearance joint
    (``friction``), not given to the ideal model."""
    previous = os.environ.pop(ENVIRONMENT_VARIABLE, None)
    try:
        if mode is not None:
            os.environ[ENVIRONMENT_VARIABLE] = mode
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            model = REGISTRY[name](clearance, None, **(joint if clearance else {}))
        model.fallback = next((str(w.message) for w in caught if "contact_mode='impulse'" in str(w.message)), "")
        if adaptive:
            model.simulation_settings.timeIntegration.adaptiveStep = True
        if iterations:
            model.simulation_settings.timeIntegration.discontinuous.maxIterations = iterations
        return model
    finally:
        os.environ.pop(ENVIRONMENT_VARIABLE, None)
        if previous is not None:
            os.environ[ENVIRONMENT_VARIABLE] = previous


def _run(model: Any, radius: float | None = None, factor: float = 1.0) -> tuple[float, str, bool, str]:
    """Solve with the model's own settings (spectral radius ``radius`` where given, steps times
    ``factor``): wall time [s], accepted steps and Newton iterations ("steps / Newton"),
    success, the error's first line."""
    ss = model.simulation_settings
    if radius is not None:
        ss.timeIntegration.generalizedAlpha.spectralRadius = radius
    ss.timeIntegration.numberOfSteps = int(round(ss.timeIntegration.numberOfSteps * factor))
    start = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the joints' notes are not what this script measures
            ok, problem = bool(model.mbs.SolveDynamic(ss, solverType=model.solver_type)), ""
    except Exception as err:  # Exudyn wraps a refusal raised in the mode's post-Newton function
        ok, problem = False, str(err).strip().splitlines()[0]
    wall = time.perf_counter() - start
    it = model.mbs.sys["dynamicSolver"].it
    return wall, f"{it.currentStepIndex - 1} / {it.newtonStepsCount}", ok, problem


def _median_wall(name: str, clearance: bool, mode: str | None, repeats: int, radius: float | None,
                 adaptive: bool = False, iterations: int = 0) -> float:
    """The median wall time [s] of ``repeats`` runs; NaN where there are none or one fails
    (a run that stops early is no baseline for a cost)."""
    if not repeats:
        return math.nan
    runs = [_run(_build(name, clearance, mode, adaptive, iterations), radius) for _ in range(repeats)]
    return statistics.median(r[0] for r in runs) if all(r[2] for r in runs) else math.nan


def zoo_row(name: str, factor: float, repeats: int, refine: float = 0.0, adaptive: bool = False,
            iterations: int = 0, **joint: Any) -> list[str]:
    """One zoo model's row (module docstring); ``repeats`` 0: no timing (the costs print "-");
    ``refine`` > 1: the impulse run's probe at that many times the steps too (its order in
    the step), else "-"; ``adaptive``: every run with Exudyn's adaptive step; ``iterations``
    > 0: every run with that many discontinuous iterations; ``joint``: the clearance joint's
    options (``friction``)."""
    ideal = _median_wall(name, False, None, repeats, None, adaptive, iterations) if repeats else math.nan
    compliant = _build(name, True, None, adaptive, iterations, **joint)
    c = compliant.clearance
    wall_c, steps_c, ok_c, _ = _run(compliant)
    probe_c = np.asarray(compliant.probe(compliant.mbs), dtype=float)
    impacts_c = len(compliant.joint.impacts())
    reference = _build(name, True, None, adaptive, iterations, **joint)
    _run(reference, factor=factor)
    probe_ref = np.asarray(reference.probe(reference.mbs), dtype=float)
    wall_c = statistics.median([wall_c] + [_run(_build(name, True, None, adaptive, iterations, **joint))[0]
                                           for _ in range(repeats - 1)])
    row = [name, _ratio(wall_c, ideal), str(steps_c), str(impacts_c),
           f"{np.abs(probe_c - probe_ref).max() / c:.3g}" if ok_c else "failed"]
    impulse = _build(name, True, "impulse", adaptive, iterations, **joint)
    if not isinstance(impulse.joint, (ImpulseJointHandle, ImpulsePairsHandle)):
        return row + ["-", "-", "-", "falls back: " + impulse.fallback.split(": ", 2)[-1], "-"]
    ideal_1 = _median_wall(name, False, None, repeats, 1.0, adaptive, iterations)
    wall_i, steps_i, ok_i, problem = _run(impulse, 1.0)
    if not ok_i:
        # a joint with several contacts (exuclear.engine.impulse_group)
        contacts = list(impulse.joint.pairs.values()) if isinstance(impulse.joint, ImpulsePairsHandle) \
            else [impulse.joint]
        stopped = next((c._problem for c in contacts if c._problem), "")
        if not stopped:  # Exudyn's Newton failed: the joint's results say where (impulse_run.check_ran)
            try:
                impulse.joint.impacts()
            except (RuntimeError, ValueError) as err:  # ValueError: a solver the mode refuses (an explicit one)
                stopped = str(err)
        reason = stopped.split(": ", 1)[-1].replace("contact_mode='impulse' ", "") or problem
        return row + ["-", steps_i, str(sum(len(c._impacts) for c in contacts)), reason, "-"]
    probe_i = np.asarray(impulse.probe(impulse.mbs), dtype=float)
    try:
        impacts_i = len(impulse.joint.impacts())
    except RuntimeError as err:  # Exudyn did not call the mode (impulse.ImpulseJointHandle._check_ran)
        return row + ["-", "-", "-", "stopped: " + str(err).split(": ", 1)[-1], "-"]
    wall_i = statistics.median([wall_i] + [_run(_build(name, True, "impulse", adaptive, iterations, **joint), 1.0)[0]
                                           for _ in range(repeats - 1)])
    refined = "-"
    if refine > 1.0:
        finer = _build(name, True, "impulse", adaptive, iterations, **joint)
        ok_f = _run(finer, 1.0, factor=refine)[2]
        refined = f"{np.abs(np.asarray(finer.probe(finer.mbs), dtype=float) - probe_ref).max() / c:.3g}" if ok_f \
            else "stopped"
    cost_i = _ratio(wall_i, ideal_1)
    if repeats and math.isnan(ideal_1) and not math.isnan(ideal):
        cost_i = f"{_ratio(wall_i, ideal)} (over the ideal model at its own settings: at radius 1 it fails)"
    return row + [cost_i, str(steps_i), str(impacts_i),
                  f"{np.abs(probe_i - probe_ref).max() / c:.3g}", refined]


def _ratio(wall: float, ideal: float) -> str:
    return "-" if math.isnan(ideal) else f"{wall / ideal:.2f}x"


def _journal(step: float, end_time: float, **changes: Any) -> Any:
    """The paper's journal scene in the impulse mode, solved at ``step`` with radius 1."""
    os.environ[ENVIRONMENT_VARIABLE] = "impulse"
    try:
        scene = jb.build(jb.JournalBearingParams.paper(**changes))
    finally:
        os.environ.pop(ENVIRONMENT_VARIABLE, None)
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime = end_time
    ss.timeIntegration.numberOfSteps = int(round(end_time / step))
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0
    ss.timeIntegration.verboseMode = 0
    try:
        scene.mbs.SolveDynamic(ss)
    except Exception:  # Exudyn wraps the mode's refusal; the joint keeps it (impacts() raises it)
        pass
    return scene


def _slider_crank(mode: str | None, stiffer: float = 1.0, **changes: Any) -> tuple[np.ndarray, int, list[float]]:
    """The paper's slider-crank (redundant formulation, the one Exudyn's implicit solver
    integrates) at its default settings with ``changes``, its materials' Young's moduli
    ``stiffer`` times the paper's: columns time, slider x [m], crank moment [N m]; accepted
    steps; the impacts' onset times [s]."""
    previous = os.environ.pop(ENVIRONMENT_VARIABLE, None)
    if mode is not None:
        os.environ[ENVIRONMENT_VARIABLE] = mode
    try:
        paper = sc.SliderCrankParams.paper(formulation="redundant")
        stiff = {side: replace(material(getattr(paper, side)), E=stiffer * material(getattr(paper, side)).E)
                 for side in ("journal_material", "bearing_material")}
        params = replace(paper, **stiff) if stiffer != 1.0 else paper
        model = sc.build(params)
    finally:
        os.environ.pop(ENVIRONMENT_VARIABLE, None)
        if previous is not None:
            os.environ[ENVIRONMENT_VARIABLE] = previous
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joints' notes are not what this script measures
        result = exuclear.simulate(model.mbs, replace(sc.default_settings(params), **changes))
    x = np.asarray(model.mbs.GetSensorStoredData(model.sensors["slider_x"]))
    moment = np.asarray(model.mbs.GetSensorStoredData(model.sensors["moment"]))
    # the drive's multiplier is the constraint's reaction on the crank: the moment is its negative
    onsets = [i.onset_time for i in model.joint.impacts()]
    return np.column_stack([x[:, 0], x[:, 1], -moment[:, 1]]), result.steps, onsets


def slider_crank_rows(factor: float) -> list[list[str]]:
    """The issue's slider-crank row: slider position and crank moment after the first 25 ms
    against the compliant run at ``factor`` times fewer steps (and impact steps), in shares
    of their range, for the compliant and the impulse mode at the default step; for the
    impulse mode also against that run with a contact :data:`STIFFER` times stiffer (the
    impulse mode's contact is rigid)."""
    settle = 0.025  # s, the start of the comparison
    base = sc.default_settings(sc.SliderCrankParams.paper(formulation="redundant"))
    fine = {"step": base.step / factor, "impact_step": base.impact_step / factor}
    reference, _, _ = _slider_crank(None, **fine)
    rows = []
    for mode, changes in (("compliant", {}), ("impulse", {"spectral_radius": 1.0, "impact_step": None})):
        data, steps, onsets = _slider_crank(mode, **changes)
        late = data[:, 0] >= settle
        # an impact step's multipliers are its impulse over the step, not a force, and the
        # step after it starts from the mean of its free computation's accelerations and its
        # own (exuclear.engine.settling): the impulse mode's crank moment is compared outside
        # the impact step and the step after it
        jump = np.zeros(len(data), dtype=bool)
        for t in onsets if changes else []:
            jump |= (data[:, 0] > t) & (data[:, 0] <= t + 2.0 * base.step * (1.0 + 1e-9))
        offs = [_off(data, reference, settle, k, mask) for k, mask in ((1, late), (2, late), (2, late & ~jump))]
        rows.append([f"paper's slider-crank, {mode}, default step{' (radius 1)' if changes else ''}",
                     f"{steps} steps, {len(onsets)} impacts",
                     f"slider x off by {offs[0]:.2%}, crank moment by {offs[1]:.2%} of their range"
                     + (f" ({offs[2]:.2%} outside impact steps and the step after)" if changes else ""),
                     "within 1 %: " + ("yes" if max(offs[:2]) <= 0.01 else "no")])
    stiff, _, _ = _slider_crank(None, stiffer=STIFFER, **fine)
    settled = max(onsets) + 2.0 * base.step  # the impulse mode's last impact and the step after
    offs = [_off(data, stiff, settle, 2, mask) for mask in (late & ~jump, data[:, 0] > settled)]
    compliance = [_off(reference, stiff, settle, 2, reference[:, 0] > start) for start in (settle, settled)]
    rows.append([f"paper's slider-crank, impulse, against the compliant run with a {STIFFER:g} times stiffer contact",
                 f"{len(onsets)} impacts, the last at {max(onsets) * 1e3:.1f} ms",
                 f"crank moment off by {offs[0]:.2%} of its range outside impact steps and the step after, "
                 f"{offs[1]:.2%} after the last impact (the paper's contact's compliant run off the stiffer one's by "
                 f"{compliance[0]:.2%} and {compliance[1]:.2%})",
                 "within 1 %: " + ("yes" if offs[0] <= 0.01 else "no")])
    return rows


def _off(data: np.ndarray, reference: np.ndarray, settle: float, column: int, mask: np.ndarray) -> float:
    """The largest distance of ``data``'s ``column`` at the rows ``mask`` from ``reference``'s
    (interpolated in time), in shares of the reference's range after ``settle`` [s]."""
    span = np.ptp(reference[reference[:, 0] >= settle, column])
    return float(np.abs(data[mask, column] - np.interp(data[mask, 0], reference[:, 0], reference[:, column])).max()
                 / span)


def target_rows() -> list[list[str]]:
    """The issue's target rows (module docstring)."""
    rows = []
    law = jb.JournalBearingParams.paper().joint().law
    c = jb.JournalBearingParams.paper().joint().geometry.clearance
    duration = closed_form_impact(law, 0.04, 0.3)[1]
    expected = impact_restitution(law, 0.3)
    for periods in (3, 10, 100, 1000):
        step = periods * duration
        scene = _journal(step, max(8.0 * 2.0 * c / 0.3 / 0.9**8, 40 * step))
        try:
            impacts = scene.joints["journal-bearing"].impacts()
        except ValueError as err:
            rows.append([f"restitution, step {periods} impact durations ({step:.3g} s)", "-",
                         "stopped: " + str(err).split(": ", 2)[-1], "refused"])
            continue
        ratios = [b.onset_velocity / a.onset_velocity for a, b in zip(impacts, impacts[1:])]
        error = max(abs(r / expected - 1.0) for r in ratios)
        # where a step would fly across the clearance the mode has Exudyn shorten it
        taken = scene.mbs.sys["dynamicSolver"].it.currentStepIndex - 1
        asked = int(scene.mbs.sys["simulationSettings"].timeIntegration.numberOfSteps)
        rows.append([f"restitution, step {periods} impact durations ({step:.3g} s)",
                     f"{len(impacts)} impacts, {taken} steps ({asked} asked)",
                     f"largest error {error:.2e} of e = {expected:.6f}", "within 2 %: " + ("yes" if error <= 0.02 else "no")])
    scene = _journal(1e-5, 0.1, gravity=G, impact_velocity=0.0, cr=1.0, start_gap=c)
    node = scene.nodes["journal"]
    x = scene.mbs.GetNodeOutput(node, exu.OutputVariableType.Position)[0]
    v = scene.mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)[0]
    drift = abs(0.5 * v * v - G * x) / (G * c)  # the journal starts at rest at x = 0, gravity along +x
    rows.append(["elastic journal (cr 1), dropped from the centre, 1e-5 s, 0.1 s",
                 f"{len(scene.joints['journal-bearing'].impacts())} impacts",
                 f"energy change {drift:.2e} of m g c", "within 1 %: " + ("yes" if drift <= 0.01 else "no")])
    scene = _journal(1e-4, 0.05, gravity=G, impact_velocity=0.0)
    joint = scene.joints["journal-bearing"]
    out = joint.outputs()
    held = out["normal_force"][out["time"] > 0.01]
    error = np.abs(held / (0.04 * G) - 1.0).max()
    rows.append(["resting journal under gravity, 1e-4 s, 0.05 s", f"{len(joint.impacts()) - 1} impacts after the first",
                 f"reaction off m g by {error:.1e} after 100 steps", "yes" if len(joint.impacts()) == 1 else "no"])
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost modes", description=__doc__.split("\n")[0])
    ap.add_argument("--models", default="", help="zoo models, comma-separated (default: all)")
    ap.add_argument("--factor", type=float, default=8.0, help="the reference's steps per step (default %(default)s)")
    ap.add_argument("--repeats", type=int, default=3, help="timed runs per model and mode (default %(default)s; 0: "
                                                                "no timing, steps and accuracy only)")
    ap.add_argument("--no-zoo", action="store_true", help="the target rows only")
    ap.add_argument("--no-targets", action="store_true", help="the zoo's rows only")
    ap.add_argument("--adaptive-step", action="store_true",
                    help="every zoo run with Exudyn's adaptive step, for examples whose own fixed step stops where a "
                         "contact begins (scissor_pin_slot)")
    ap.add_argument("--refine", type=float, default=0.0, help="also run the impulse mode at this many times the "
                                                                 "steps (its order in the step; default: not run)")
    ap.add_argument("--friction", default="", help="every zoo model's clearance joint with this friction law (e.g. "
                                                     "paper, coulomb:0.2; default: each model's own)")
    ap.add_argument("--iterations", type=int, default=0, help="every zoo run with this many discontinuous iterations "
                                                               "(default: each example's own)")
    args = ap.parse_args(argv)
    if not args.factor > 1.0:
        ap.error(f"--factor must exceed 1, got {args.factor}")
    if args.repeats < 0:
        ap.error(f"--repeats must be at least 0, got {args.repeats}")
    if args.iterations < 0:
        ap.error(f"--iterations must be at least 0, got {args.iterations}")
    if not args.no_zoo:
        load_models()
        try:
            names = model_names(args.models) if args.models else list(REGISTRY)
        except ValueError as err:
            ap.error(str(err))
        rows = []
        for name in names:
            joint = {"friction": args.friction} if args.friction else {}
            rows.append(zoo_row(name, args.factor, args.repeats, args.refine, args.adaptive_step, args.iterations,
                                **joint))
            print(f"{name}: done", flush=True)
        print("\n" + markdown_table(
            ["model", "compliant / ideal", "steps / Newton", "impacts", f"probe off {args.factor:g}x compliant [c]",
             "impulse / ideal (radius 1)", "steps / Newton", "impacts", f"probe off {args.factor:g}x compliant [c]",
             f"at {args.refine:g}x the steps" if args.refine > 1.0 else "refined"],
            rows))
    if not args.no_targets:
        print("\n" + markdown_table(["target", "count", "measured", "met"],
                                    target_rows() + joint_type_rows() + translational_rows()
                                    + spatial_rows() + slider_crank_rows(args.factor)))
    return 0
