"""``python -m validation.contact_follow [orbit|loop|slider-crank|zoo|cost|anatomy|phases] [options]``: the measurements of
docs/guide/contact_following.md (issue 34's contact-following mode against the compliant
contact): solver steps, Newton iterations per step, switches and the agreement with a
compliant reference, on the Python kernel.

- ``orbit``: a journal orbiting on its wall under its centripetal load (frictionless, cr 1),
  at fixed generalized-alpha steps; the reference is the compliant run at 1e-6 s.  Then the
  same journal with Coulomb friction, too heavy in rotation to spin up, against its
  analytic slowing-down ``v = v0 / (1 + mu v0 t / r)``.
- ``loop``: a journal looping inside its bearing under gravity, fast enough at the bottom to
  leave the wall at 120 deg (a point mass on a rigid circle): where it leaves at fixed steps,
  compliant and following, the latter released on the low-passed multiplier (the default)
  and on the multiplier itself (``RELEASE_FILTERED`` off); the reference is the compliant run
  at 1e-6 s.
- ``slider-crank``: the paper's redundant slider-crank through ``exuclear.simulate`` at its
  defaults (``--step`` overrides the largest step); the reference is the compliant run at 2e-6 s;
  the ideal mechanism's steps and Newton iterations at the same settings head the table.
- ``zoo``: zoo models at their own settings (``--models``, ``--end-time``); the reference is
  the compliant run at 4 times the example's steps; ``--index2`` runs every model with
  Exudyn's index-2 constraints (Newmark).
- ``cost``: the zoo models' wall time against their ideal models, side by side in one run
  (medians of ``--repeats``): compliant on the compiled and the Python kernel, following on
  the Python kernel and on the default one (compiled where it covers the joint).
- ``anatomy``: where one run of each (ideal, compliant compiled, following on the Python and
  on the default kernel) spends its time:
  microseconds per step, Newton iterations and Jacobians per step, and the shares of
  Exudyn's own timers (Jacobian, right-hand side, post-Newton); the per-step budget a
  following mode must meet to reach a wall-time ratio.
- ``phases``: where the accepted steps of one run of each (compliant compiled, following) fall:
  free flight, a contact's first FOLLOW_PERIODS contact periods, then the sustained contact
  followed, compliant near stick (the slip within STICK_MARGIN times the friction law's
  smoothing band) or compliant sliding; each phase's steps, time, steps in contact periods
  (percentiles) and the share of its time in steps over 10 contact periods; and the
  compliant run again at ``--refine`` times the steps.  A second table gives the normal
  force over the stretches of sustained contact (mean, standard deviation, strongest
  frequencies): a vibration that the refined run has too is the model's, not the step's.

``orbit``, ``loop``, ``slider-crank``, ``zoo`` and ``phases`` count cost (steps, Newton iterations); ``cost`` and
``anatomy`` time it: run them with nothing else on the machine.
"""
from __future__ import annotations

import argparse
import math
import sys
import warnings
from contextlib import contextmanager
from dataclasses import replace
from functools import partial

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadForceVector,
    MarkerNodePosition,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
    SensorNode,
)

import exuclear
from exuclear.engine import follow_conditions, following
from exuclear.engine._python_kernel import following as rules
from exuclear.timescales import penetration_at

ZOO = ("double_pendulum_2d", "double_pendulum_2d_friction", "rigid_body_tutorial3_friction", "beam_pendulum_2d")


def _row(*cells: object) -> str:
    return "| " + " | ".join(str(c) for c in cells) + " |"


@contextmanager
def _constant(module: object, name: str, value: object):
    """``module.name`` set to ``value`` for the block (a rule of the following mode)."""
    saved = getattr(module, name)
    setattr(module, name, value)
    try:
        yield
    finally:
        setattr(module, name, saved)


def _counts(it: object, steps: int) -> str:
    return f"{it.newtonStepsCount / max(steps, 1):.2f}"


def orbit(mode: str, step: float, end: float = 0.05, mass: float = 0.03, speed: float = 0.05, cr: float = 1.0,
          friction: str = "none", inertia: float = 1e-5, gravity: float = 0.0,
          radii: tuple[float, float] = (9.9e-3, 10e-3), backend: str = "python") -> dict:
    """The orbiting journal of tests/test_contact_follow.py (journal and bearing ``radii``),
    started on its wall at +x with ``speed`` along +y at the law's static penetration under
    its load, ``gravity`` [m/s^2] along +x (the start is the bottom), on the ``backend``
    kernel; returns its path and counts."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    joint = exuclear.make_joint(journal_radius=radii[0], bearing_radius=radii[1], length=15e-3, cr=cr,
                                friction=friction)
    c = r = joint.geometry.clearance
    for _ in range(3):
        r = c + penetration_at(joint.law, mass * (speed**2 / r + gravity))
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0], initialCoordinates=[r, 0, 0],
                                       initialVelocities=[0, speed, 0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=mass, inertia=inertia))
    if gravity:
        marker = mbs.AddMarker(MarkerNodePosition(nodeNumber=node))
        mbs.AddLoad(LoadForceVector(markerNumber=marker, loadVector=[mass * gravity, 0, 0]))
    handle = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, body], position=[0, 0, 0], joint=joint,
                                           backend=backend, contact_mode=mode)
    sensor = mbs.AddSensor(SensorNode(nodeNumber=node, storeInternal=True,
                                      outputVariableType=exu.OutputVariableType.Position))
    velocity = mbs.AddSensor(SensorNode(nodeNumber=node, storeInternal=True,
                                        outputVariableType=exu.OutputVariableType.Velocity))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.timeIntegration.endTime, ss.timeIntegration.numberOfSteps = end, int(round(end / step))
    ss.timeIntegration.verboseMode, ss.solution.file.write = 0, False
    ss.solution.sensors.writePeriod = step  # every step (Exudyn's default: every 0.01 s)
    mbs.SolveDynamic(ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    it = mbs.sys["dynamicSolver"].it
    return {"path": mbs.GetSensorStoredData(sensor), "velocity": mbs.GetSensorStoredData(velocity),
            "steps": it.currentStepIndex - 1, "it": it, "c": c,
            "counts": handle.follow_counts(), "static": r - c}


def run_orbit(args: argparse.Namespace) -> None:
    ref = orbit("compliant", 1e-6)
    print(_row("run", "steps", "Newton / step", "path off reference [c]", "|e| - c / static", "kinetic energy change",
               "switches"))
    runs = [(mode, step, True, "python") for step in (4e-4, 1e-4, 1e-5) for mode in ("compliant", "follow")]
    runs.insert(4, ("follow", 1e-4, False, "python"))  # the step end's normal predicted to second order
    runs.insert(5, ("follow", 1e-4, True, "compiled"))  # following.hpp: the first iterate, its end acceleration added
    for mode, step, predict, backend in runs:
        with _constant(follow_conditions, "PREDICT_JERK", predict):
            r = orbit(mode, step, backend=backend)
        p, q = r["path"], ref["path"]
        off = np.hypot(p[:, 1] - np.interp(p[:, 0], q[:, 0], q[:, 1]),
                       p[:, 2] - np.interp(p[:, 0], q[:, 0], q[:, 2]))
        pen = (np.hypot(p[:, 1], p[:, 2]) - r["c"]) / r["static"]
        speed = np.hypot(r["velocity"][:, 1], r["velocity"][:, 2])
        label = f"{mode}, {step:g} s" + ("" if predict else ", PREDICT_JERK off") + (", compiled" if backend == "compiled" else "")
        print(_row(label, r["steps"], _counts(r["it"], r["steps"]), f"{off.max() / r['c']:.4f}",
                   f"{pen.min():.4f}..{pen.max():.4f}", f"{(speed[-1] / speed[0]) ** 2 - 1:+.2e}", r["counts"] or "-"))
    # Coulomb friction mu on a journal too heavy in rotation to spin up: its slip is its
    # centre's speed, and dv/dt = -mu v^2 / r gives v = v0 / (1 + mu v0 t / r).
    mu, speed0 = 0.1, 0.05
    print()
    print(_row("Coulomb friction 0.1, cr 0.9, 1e-4 s", "steps", "Newton / step", "speed off v0 / (1 + mu v0 t / r)",
               "switches"))
    for mode in ("compliant", "follow"):
        r = orbit(mode, 1e-4, speed=speed0, cr=0.9, friction=f"coulomb:{mu}", inertia=1e3)
        v, p = r["velocity"], r["path"]
        exact = speed0 / (1.0 + mu * speed0 * v[:, 0] / np.hypot(p[0, 1], p[0, 2]))
        off = np.abs(np.hypot(v[:, 1], v[:, 2]) / exact - 1.0).max()
        print(_row(mode, r["steps"], _counts(r["it"], r["steps"]), f"{100 * off:.3f} %", r["counts"] or "-"))


#: The looping journal: a journal of 19 mm in a bearing of 20 mm (c = 1 mm), 0.5 kg, under
#: gravity, started at the bottom of its wall fast enough to leave it at LOOP_RELEASE_DEG.
LOOP_RADII, LOOP_MASS, LOOP_RELEASE_DEG, LOOP_GRAVITY = (19e-3, 20e-3), 0.5, 120.0, 9.81


def loop(mode: str, step: float, end: float = 0.03, backend: str = "python") -> dict:
    """The looping journal (LOOP_RADII), frictionless with cr 0.9, at fixed steps: where it
    leaves its wall.  On a wall of radius ``r`` the normal force of a point mass started at
    the bottom at ``v0`` is ``m (v0^2 - 2 g r + 3 g r cos(theta)) / r`` at the angle ``theta``
    from the bottom: it leaves at ``cos(theta) = (2 g r - v0^2) / (3 g r)``, so
    ``v0^2 = g r (2 - 3 cos(theta))`` (``r = c``; the penetration adds micrometres).  Returns
    the angle [deg] and time [s] where ``|e|`` first falls below c (linear between steps),
    with the run's counts, on the ``backend`` kernel."""
    c = LOOP_RADII[1] - LOOP_RADII[0]
    speed = math.sqrt(LOOP_GRAVITY * c * (2.0 - 3.0 * math.cos(math.radians(LOOP_RELEASE_DEG))))
    run = orbit(mode, step, end, mass=LOOP_MASS, speed=speed, cr=0.9, gravity=LOOP_GRAVITY, radii=LOOP_RADII,
                backend=backend)
    t, x, y = run["path"][:, 0], run["path"][:, 1], run["path"][:, 2]
    e, angle = np.hypot(x, y), np.unwrap(np.arctan2(y, x))
    i = int(np.argmax(e < run["c"]))
    if i == 0:
        raise RuntimeError(f"the looping journal ({mode}, {step:g} s) did not leave its wall by {end:g} s")
    share = (e[i - 1] - run["c"]) / (e[i - 1] - e[i])
    run["release_deg"] = math.degrees(angle[i - 1] + share * (angle[i] - angle[i - 1]))
    run["release_time"] = t[i - 1] + share * (t[i] - t[i - 1])
    return run


def run_loop(args: argparse.Namespace) -> None:
    ref = loop("compliant", 1e-6)
    print(f"Leaves the wall at {LOOP_RELEASE_DEG:g} deg (analytic, path radius c); the compliant contact at 1e-6 s: "
          f"{ref['release_deg']:.2f} deg at {1e3 * ref['release_time']:.3f} ms")
    print()
    print(_row("step [s]", "compliant [deg]", "follow [deg]", "follow, released on the multiplier itself [deg]",
               "follow: steps, switches on / off, steps redone", "the same, on the multiplier itself"))
    for step in (2.5e-4, 3e-4, 4e-4, 5e-4):  # 2.5e-4 s: under FOLLOW_STEP, not engaged
        compliant, follow = loop("compliant", step), loop("follow", step)
        with _constant(rules, "RELEASE_FILTERED", False):  # the step redone to end at the zero (RELEASE_REDO)
            raw = loop("follow", step)
        print(_row(f"{step:g}", f"{compliant['release_deg']:.2f}", f"{follow['release_deg']:.2f}",
                   f"{raw['release_deg']:.2f}", *(f"{r['steps']}, {r['counts']['on']} / {r['counts']['off']}, "
                                                  f"{r['counts']['redone']}" for r in (follow, raw))), flush=True)


def slider_crank(mode: str, revolutions: float, step: float | None, ideal: bool = False) -> tuple:
    from exuclear.models import _slider_crank_run as run_module
    from exuclear.models.slider_crank import SliderCrankParams

    params = replace(SliderCrankParams.paper(), formulation="redundant", backend="python", revolutions=revolutions)
    settings = run_module.default_settings(params)
    params = replace(params, ideal=ideal)  # the ideal mechanism at the clearance model's settings
    if step:
        settings = replace(settings, step=step)
    built, original, saved = {}, run_module.build, following.DEFAULT_CONTACT_MODE

    def build(p: object) -> object:
        built["model"] = original(p)
        return built["model"]

    following.DEFAULT_CONTACT_MODE, run_module.build = mode, build
    try:
        result = run_module.run(params, settings)
    finally:
        following.DEFAULT_CONTACT_MODE, run_module.build = saved, original
    model = built["model"]
    return result, model.mbs.sys["dynamicSolver"].it, model.joint.follow_counts() if model.joint else {}


def run_slider_crank(args: argparse.Namespace) -> None:
    ref, _, _ = slider_crank("compliant", args.revolutions, 2e-6)
    a = ref.columns
    print(_row("run", "steps", "Newton / step", "impacts", "path off reference [c]", "switches"))
    result, it, _ = slider_crank("compliant", args.revolutions, args.step, ideal=True)
    print(_row("ideal mechanism", result.steps, _counts(it, result.steps), "-", "-", "-"))
    for mode in ("compliant", "follow"):
        result, it, counts = slider_crank(mode, args.revolutions, args.step)
        b = result.columns
        off = np.hypot(a["ecc_x"] - np.interp(a["time"], b["time"], b["ecc_x"]),
                       a["ecc_y"] - np.interp(a["time"], b["time"], b["ecc_y"]))
        print(_row(mode, result.steps, _counts(it, result.steps), result.impacts, f"{off.max() / 1e-4:.4f}",
                   counts or "-"))


def zoo(name: str, mode: str, end: float, refine: int = 1, index2: bool = False) -> tuple:
    from validation.exudyn_examples._common import load_models

    model = load_models()[name](clearance=True, end_time=end, backend="python", contact_mode=mode)
    ss = model.simulation_settings
    ss.timeIntegration.numberOfSteps *= refine
    if index2:
        ss.timeIntegration.generalizedAlpha.useIndex2Constraints = True
        ss.timeIntegration.generalizedAlpha.useNewmark = True
    message = ""
    try:
        model.mbs.SolveDynamic(ss, solverType=model.solver_type)
    except Exception as err:  # Exudyn raises its own error types when it stops
        message = str(err).splitlines()[0][:60]
    it = model.mbs.sys["dynamicSolver"].it
    return model, it, np.asarray(model.probe(model.mbs)), message


def run_zoo(args: argparse.Namespace) -> None:
    from exuclear.engine.bodies import joint_contact_period

    print(_row("model", "run", "h / T_c", "t reached", "steps", "Newton / step", "switches on/off",
               "probe off reference [c]"))
    for name in args.models.split(","):
        ref, _, ref_probe, _ = zoo(name, "compliant", args.end_time, 4, args.index2)
        for mode in ("compliant", "follow"):
            model, it, probe, message = zoo(name, mode, args.end_time, 1, args.index2)
            steps = it.currentStepIndex - 1
            counts = model.joint.follow_counts()
            switches = f"{counts['on']} / {counts['off']}" + (f" ({counts['lost']} lost)" if counts.get("lost") else "") \
                if counts else ""
            off = np.abs(probe - ref_probe).max() / ref.clearance
            ti = model.simulation_settings.timeIntegration
            ratio = ti.endTime / ti.numberOfSteps / joint_contact_period(model.mbs, model.joint)
            print(_row(name, mode, f"{ratio:.2g}", f"{model.mbs.systemData.GetTime():.4g}", steps, _counts(it, steps), switches,
                       f"{off:.2f}" + (f" ({message})" if message else "")), flush=True)


def _kernel_of(model: object) -> str:
    """Which kernel the model's clearance joint ran on."""
    return "compiled" if model.joint.backend == "compiled" else "Python"


def _wall(build: object, repeats: int, **options: object) -> tuple[float, int, float, str]:
    """Median wall time [s] of ``repeats`` plain ``SolveDynamic`` runs of a fresh
    ``build(**options)``, the steps and Newton iterations per step of the last, and the
    kernel its joint ran on."""
    import statistics
    import time

    walls = []
    for _ in range(repeats):
        model = build(**options)
        start = time.perf_counter()
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
        walls.append(time.perf_counter() - start)
    it = model.mbs.sys["dynamicSolver"].it
    steps = it.currentStepIndex - 1
    kernel = _kernel_of(model) if model.joint is not None else "-"
    return statistics.median(walls), steps, it.newtonStepsCount / max(steps, 1), kernel


def run_cost(args: argparse.Namespace) -> None:
    """Wall time against the ideal model, side by side in one run (medians of ``--repeats``):
    the compliant joint on the compiled kernel (the default) and on the Python kernel, and
    the following mode on the Python kernel and on the default one (the compiled kernel
    where it can follow the joint: rigid bodies)."""
    from validation.exudyn_examples._common import load_models

    models = load_models()
    print(_row("model", "run", "kernel", "wall [s]", "/ ideal", "steps", "Newton / step"))
    for name in args.models.split(","):
        build = partial(models[name], end_time=args.end_time if args.end_time > 0.0 else None)
        ideal, steps, newton, _ = _wall(build, args.repeats, clearance=False)
        print(_row(name, "ideal", "-", f"{ideal:.3f}", "1", steps, f"{newton:.2f}"), flush=True)
        for label, options in (("compliant", {}), ("compliant", {"backend": "python"}),
                               ("follow", {"backend": "python", "contact_mode": "follow"}),
                               ("follow", {"contact_mode": "follow"})):
            wall, steps, newton, kernel = _wall(build, args.repeats, clearance=True, **options)
            print(_row(name, label, kernel, f"{wall:.3f}", f"{wall / ideal:.2f}", steps, f"{newton:.2f}"), flush=True)


def run_anatomy(args: argparse.Namespace) -> None:
    """One run each (the ideal model, the compliant joint compiled, the following mode on the
    Python kernel and on the default one):
    microseconds per step, Newton iterations and Jacobians per step, the steps redone at a
    post-Newton function's request (Exudyn's discontinuous iterations beyond one per step:
    the joint's own step control), and the shares of Exudyn's timers
    (``displayComputationTime``).  The last column is the per-step cost a run
    with the clearance run's steps may have to stay at twice the ideal model's wall time."""
    import time

    from validation.exudyn_examples._common import load_models

    models = load_models()
    print(_row("model", "run", "wall [s]", "/ ideal", "steps", "redone", "us / step", "Newton / step",
               "Jacobians / step", "Jacobian %", "RHS %", "post-Newton %", "us / step for 2x ideal"))
    for name in args.models.split(","):
        ideal = None
        for label, options in (("ideal", {"clearance": False}), ("compliant", {"clearance": True}),
                               ("follow", {"clearance": True, "backend": "python", "contact_mode": "follow"}),
                               ("follow", {"clearance": True, "contact_mode": "follow"})):
            model = models[name](end_time=args.end_time if args.end_time > 0.0 else None, **options)
            if model.joint is not None:
                label = f"{label}, {_kernel_of(model)}"
            model.simulation_settings.displayComputationTime = True  # fills the solver's timers
            start = time.perf_counter()
            model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
            wall = time.perf_counter() - start
            solver = model.mbs.sys["dynamicSolver"]
            it, timer = solver.it, solver.timer
            steps = it.currentStepIndex - 1
            ideal = ideal or wall
            share = [f"{100.0 * x / max(timer.total, 1e-12):.0f}" for x in
                     (timer.totalJacobian, timer.ODE2RHS, timer.postNewton)]
            redone = it.discontinuousIterationsCount - steps
            print(_row(name, label, f"{wall:.3f}", f"{wall / ideal:.2f}", steps, redone, f"{1e6 * wall / steps:.1f}",
                       _counts(it, steps), f"{it.newtonJacobiCount / max(steps, 1):.2f}", *share,
                       f"{1e6 * 2.0 * ideal / steps:.1f}"), flush=True)


#: The phases of ``phases``, in the order printed.
PHASES = ("free flight", "contact, first periods", "sustained, followed", "sustained, compliant near stick",
          "sustained, compliant sliding")


class PhaseRecorder:
    """A post-step function: each accepted step's end time, length and phase (:data:`PHASES`),
    and the joint's normal force, from the joint's state at the step's end."""

    def __init__(self, joint: object, period: float) -> None:
        self.joint, self.period, self.last = joint, period, 0.0
        self.friction = joint.joint.friction
        self.steps: list[tuple[float, float, int, float]] = []

    def __call__(self, mbs: object, t: float) -> bool:
        state = self.joint.state()
        if not state.in_contact:
            phase = 0
        elif t - state.onset_time < rules.FOLLOW_PERIODS * self.period:
            phase = 1
        elif self.joint.follow_counts().get("active"):
            phase = 2
        else:
            phase = 3 if rules.FollowState.sticking(self.friction, state.slip_velocity) else 4
        self.steps.append((t, t - self.last, phase, state.normal_force))
        self.last = t
        return True


#: ``phases``: the normal force's spectrum over windows of this length [s] in which the
#: contact is sustained throughout, sampled at WINDOW / 2500.
WINDOW = 0.05


def force_spectrum(steps: np.ndarray) -> tuple[int, float, float, list[float]]:
    """Over the WINDOW-long stretches of a run in which the contact is sustained throughout
    (``steps``: rows of :class:`PhaseRecorder`): their count, the normal force's mean and
    standard deviation there, and the three strongest frequencies [Hz] of its summed power
    spectrum (mean removed per window, Hann window), between 20 Hz and 2 kHz."""
    samples = 2500
    dt = WINDOW / samples
    grid = np.arange(0.0, steps[-1, 0], dt)
    sustained = np.interp(grid, steps[:, 0], (steps[:, 2] >= 2).astype(float)) > 0.5
    force = np.interp(grid, steps[:, 0], steps[:, 3])
    power, values = 0.0, []
    for start in range(0, len(grid) - samples, samples):
        window = slice(start, start + samples)
        if sustained[window].all():
            x = force[window]
            values.append(x)
            power = power + np.abs(np.fft.rfft((x - x.mean()) * np.hanning(samples))) ** 2
    if not values:
        return 0, math.nan, math.nan, []
    frequencies = np.fft.rfftfreq(samples, dt)
    band = (frequencies > 20.0) & (frequencies < 2000.0)
    strongest = frequencies[band][np.argsort(power[band])[::-1][:3]]
    x = np.concatenate(values)
    return len(values), float(x.mean()), float(x.std()), [float(f) for f in strongest]


def run_phases(args: argparse.Namespace) -> None:
    from exuclear.engine.bodies import joint_contact_period
    from validation.exudyn_examples._common import load_models

    models = load_models()
    spectra = []
    print(_row("model", "run", "phase", "steps", "time [s]", "step / T_c: 10th, 50th, 90th percentile",
               "time in steps over 10 T_c"))
    for name in args.models.split(","):
        runs = [("compliant, compiled", 1, {}), ("follow, Python", 1, {"backend": "python", "contact_mode": "follow"})]
        if args.refine > 1:
            runs.append((f"compliant, compiled, {args.refine}x steps", args.refine, {}))
        for label, refine, options in runs:
            model = models[name](clearance=True, end_time=args.end_time if args.end_time > 0.0 else None, **options)
            model.simulation_settings.timeIntegration.numberOfSteps *= refine
            period = joint_contact_period(model.mbs, model.joint)
            recorder = PhaseRecorder(model.joint, period)
            model.mbs.SetPostStepUserFunction(recorder)
            model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
            steps = np.asarray(recorder.steps)
            for number, phase in enumerate(PHASES):
                h = steps[steps[:, 2] == number, 1]
                if h.size:
                    share = h[h > 10.0 * period].sum() / h.sum()
                    print(_row(name, label, phase, h.size, f"{h.sum():.3f}",
                               ", ".join(f"{x:.2g}" for x in np.percentile(h, [10, 50, 90]) / period),
                               f"{100.0 * share:.0f} %"), flush=True)
            spectra.append((name, label, *force_spectrum(steps)))
    print()
    print(_row("model", "run", f"sustained {WINDOW * 1e3:g} ms windows", "mean F_n [N]", "std F_n [N]",
               "strongest frequencies [Hz]"))
    for name, label, count, mean, std, strongest in spectra:
        print(_row(name, label, count, f"{mean:.3g}", f"{std:.3g}", ", ".join(f"{f:.0f}" for f in strongest)))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m validation.contact_follow", description=__doc__.split("\n\n")[0])
    parser.add_argument("case", choices=["orbit", "loop", "slider-crank", "zoo", "cost", "anatomy", "phases"])
    parser.add_argument("--revolutions", type=float, default=2.0, help="slider-crank revolutions (default 2)")
    parser.add_argument("--step", type=float, default=None, help="slider-crank largest step [s] (default its own)")
    parser.add_argument("--models", default=",".join(ZOO), help=f"zoo models (default {','.join(ZOO)})")
    parser.add_argument("--end-time", type=float, default=0.5,
                        help="zoo end time [s] (default 0.5; cost, anatomy, phases: 0 for each example's own)")
    parser.add_argument("--index2", action="store_true", help="zoo: Exudyn's index-2 constraints (Newmark)")
    parser.add_argument("--repeats", type=int, default=3, help="cost: runs per median (default 3)")
    parser.add_argument("--refine", type=int, default=16,
                        help="phases: the compliant run again at this many times the example's steps (default 16; 1: none)")
    args = parser.parse_args(argv)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        {"orbit": run_orbit, "loop": run_loop, "slider-crank": run_slider_crank, "zoo": run_zoo, "cost": run_cost,
         "anatomy": run_anatomy, "phases": run_phases}[args.case](args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
