"""What the generalized-alpha method's numerical damping does to a clearance model's cost
and results (issue 20).

Source problem: the zoo's models (``validation/exudyn_examples``) that Exudyn integrates
with the generalized-alpha method proper (not its Newmark/trapezoidal variant, which has no
spectral radius), each with its own settings through a plain ``mbs.SolveDynamic``, run again
with the method's spectral radius (``timeIntegration.generalizedAlpha.spectralRadius``,
rho_inf) lowered.  Where a journal rests on its wall at steps longer than the contact
period, the contact's vibration is not resolved, and at rho_inf near 1 the method hardly
damps it (a component with ``omega h >> 1`` keeps about rho_inf of its amplitude per step;
Chung and Hulbert, J. Appl. Mech. 60 (1993) 371-375), where the contact's own damping would
have ended it within a few periods.  Newton then needs more iterations and Exudyn does not
lengthen the step (its ``adaptiveStepRecoveryIterations``).

Printed per model, restitution and rho_inf: the wall time of the clearance model over the
ideal model's at the same rho_inf, the accepted steps, the impacts, and against the 4x
refined run (``--factor``) at the model's own rho_inf (``exuclear.check_convergence``; one reference per
model and restitution, shared by the rho_inf compared) the impacts, the distance of the
|e|/c spectrum (agrees below 0.1) and whether all its statistics agree.  Run nothing else
meanwhile::

    python -m validation.cost spectral_radius [--models a,b] [--restitutions 0.9] [--radii 0.7,0.5] [--factor 4]

(about a minute with the defaults, two with ``--factor 16``).
"""
from __future__ import annotations

import argparse
import time
import warnings
from typing import Any

import exudyn as exu

import exuclear
from validation._tables import markdown_table
from validation.cost.jacobian_steps import parse_restitutions
from validation.exudyn_examples._common import REGISTRY, ZooModel, model_names

#: The zoo's models the comparison applies to (generalized-alpha proper, own settings).
DEFAULT_MODELS = "beam_pendulum_2d,piston_engine,double_pendulum_2d_friction,four_bar_3d,double_pendulum_2d"


def generalized_alpha(model: ZooModel) -> bool:
    """Whether the model's own solver is the generalized-alpha method with a spectral radius."""
    ss = model.simulation_settings
    return (model.solver_type == exu.DynamicSolverType.GeneralizedAlpha
            and not ss.timeIntegration.generalizedAlpha.useNewmark)


def solve(model: ZooModel, rho: float | None) -> float:
    """Run ``model`` with its own settings, rho_inf ``rho`` (None: its own); the wall time [s]."""
    ss = model.simulation_settings
    if rho is not None:
        ss.timeIntegration.generalizedAlpha.spectralRadius = rho
    start = time.perf_counter()
    model.mbs.SolveDynamic(ss, solverType=model.solver_type)
    return time.perf_counter() - start


def compare(name: str, cr: float, radii: list[float | None], factor: float) -> list[list[str]]:
    """One row per rho_inf in ``radii`` (None first: the model's own), against the run at
    ``factor`` times the steps with the model's own rho_inf."""
    reference: list[exuclear.RunRecord] = []

    def refined(settings: Any) -> exuclear.RunRecord:  # the own rho_inf's refined run, made once
        if not reference:
            m = REGISTRY[name](True, None, cr=cr)
            ok = bool(m.mbs.SolveDynamic(settings, solverType=m.solver_type))
            reference.append(exuclear.RunRecord.from_mbs(m.mbs, {"joint": m.joint}, success=ok))
        return reference[0]

    rows = []
    own_settings = REGISTRY[name](True, None, cr=cr).simulation_settings
    own = own_settings.timeIntegration.generalizedAlpha.spectralRadius
    for rho in radii:
        ideal = solve(REGISTRY[name](False, None), rho)
        model = REGISTRY[name](True, None, cr=cr)
        wall = solve(model, rho)
        steps = model.mbs.sys["dynamicSolver"].it.currentStepIndex - 1
        record = exuclear.RunRecord.from_mbs(model.mbs, {"joint": model.joint})
        check = exuclear.check_convergence(refined, own_settings, factor=factor, baseline=record)
        joint = check.joints["joint"]
        spectrum = next(s for s in joint.statistics if s.name.startswith("spectrum"))
        rows.append([name, f"{cr:g}", f"{own:g} (own)" if rho is None else f"{rho:g}",
                     f"{wall / ideal:.1f}x", str(steps), f"{joint.impacts} / {joint.impacts_ref}",
                     f"{spectrum.value:.3f}", "yes" if all(s.agrees for s in joint.statistics) else "no"])
    return rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost spectral_radius", description=__doc__.split("\n")[0])
    ap.add_argument("--models", default=DEFAULT_MODELS, help="zoo models, comma-separated (default %(default)s)")
    ap.add_argument("--restitutions", type=parse_restitutions, default=parse_restitutions("0.9"),
                    help="coefficients of restitution of the joint, comma-separated (default 0.9)")
    ap.add_argument("--radii", default="0.7,0.5", help="spectral radii compared with each model's own, in [0, 1], "
                                                        "comma-separated (default %(default)s)")
    ap.add_argument("--factor", type=float, default=4.0, help="the reference's steps per step of the model's own "
                                                               "(default 4; check_convergence's factor)")
    args = ap.parse_args(argv)
    if not args.factor > 1.0:
        ap.error(f"--factor must exceed 1, got {args.factor}")
    try:
        names = model_names(args.models)
        radii = [float(x) for x in args.radii.split(",") if x.strip()]
    except ValueError as err:
        ap.error(str(err))
    if not radii or not all(0.0 <= r <= 1.0 for r in radii):
        ap.error(f"--radii: spectral radii in [0, 1], comma-separated, got {args.radii!r}")
    skipped = [n for n in names if not generalized_alpha(REGISTRY[n](False, None))]
    if skipped:
        ap.error(f"not solved by the generalized-alpha method proper (no spectral radius): {', '.join(skipped)}")
    rows = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joints' notes are not what this script measures
        for name in names:
            for cr in args.restitutions:
                rows += compare(name, cr, [None, *radii], args.factor)
            print(f"{name}: done", flush=True)
    print("\n" + markdown_table(["model", "cr", "spectral radius", "wall / ideal", "steps",
                                 f"impacts / {args.factor:g}x refined (own radius)", "spectrum distance", "statistics agree"], rows))
    return 0
