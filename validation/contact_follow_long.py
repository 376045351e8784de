"""``python -m validation.contact_follow_long [--models ...] [--refines 1,4,16,64,256] [--ensemble 4]``:
the contact-following mode (``contact_mode="follow"``, docs/guide/contact_following.md) over
each zoo example's own end time, against a converged compliant reference.

For each model (default: the four whose follow run ended 0.26 c to 85 c off the compliant run
at the example's steps), the probe (``ZooModel.probe``, recorded after every accepted step and
interpolated onto the grid of the example's own steps) is compared in units of the clearance c
(largest difference, at the end, first time above 0.1 c and 1 c):

1. **Compliant refinements**: the compliant joint (compiled kernel) at 1x, 4x, 16x, 64x, 256x the
   example's number of steps to its own end time, successive refinements against each other.
2. **Sensitivity**: the finest run and the 1x run again with ``--kick`` (1e-9 m/s) added to every
   initial velocity.  A kick that grows to a clearance means chaotic motion: paths cannot be
   compared over that time, only statistics.  Also the compliant 1x run on the Python kernel.
3. **Following**: the follow run (Python kernel) at 1x and 4x against the finest compliant run and
   against the compliant run at its steps; the follow event (on, off, lost, a step redone
   shorter) last before the difference first exceeds 0.1 c and 1 c.
4. **Statistics** of every run, and of an ensemble at 1x per mode (the run and ``--ensemble``
   runs kicked by 1, 2, ... times ``--kick``): the normal force's mean over the accepted steps
   and its two-step swing, the peak normal force, the contact onsets, the share of time in
   contact, the energy change (models with an energy function), the probe's RMS and spectral
   peak, and its distance from the finest compliant run.

A run is stopped after ``--time-limit`` seconds of wall time (its row says where).  The script
prints each run's wall time: run it with nothing else on the machine (about 13 minutes for the
four default models on one core).
"""
from __future__ import annotations

import argparse
import sys
import time
import warnings
from array import array
from dataclasses import dataclass, field

import exudyn as exu
import numpy as np

from exuclear.engine.layout import DATA_COLUMNS
from validation._tables import markdown_table
from validation.exudyn_examples._common import load_models, model_names

MODELS = ("rigid_body_tutorial3", "double_pendulum_2d", "beam_pendulum_2d", "double_pendulum_2d_friction")
#: Slower than this [m/s] an onset is not counted among the fast ones (a journal settling on its wall).
FAST_ONSET = 0.01
#: The follow mode's events (``follow_counts()`` keys): switched on, let go, lost, a step redone shorter.
EVENTS = ("on", "off", "lost", "redone")
#: The statistics of the ensemble table: key, heading, format.
STATISTICS = (("mean_force", "mean F_n [N]", ".4g"), ("peak_force", "peak F_n [N]", ".4g"), ("onsets", "onsets", ".4g"),
              ("fast_onsets", f"onsets > {FAST_ONSET} m/s", ".3g"), ("contact_share", "time in contact", ".4f"),
              ("energy", "energy change [J]", ".4g"), ("off_end", "probe off the finest at the end [c]", ".3g"),
              ("off_max", "probe off the finest, largest [c]", ".3g"))


@dataclass
class Run:
    """One run's probe on the example's grid (NaN past the reached time), its joint's
    statistics and its cost."""

    label: str
    h: float
    probe: np.ndarray
    reached: float
    steps: int
    wall: float
    stats: dict[str, float]
    counts: dict = field(default_factory=dict)
    events: list[tuple[float, str]] = field(default_factory=list)
    message: str = ""


class Recorder:
    """A post-step function: the probe interpolated onto ``grid`` between accepted steps, the
    joint's normal force at every accepted step, the follow events (on, off, lost); it ends
    the run after ``limit`` seconds of wall time."""

    def __init__(self, model: object, grid: np.ndarray, limit: float) -> None:
        self.model, self.grid, self.limit = model, grid, limit
        self.last_t, self.last_p = 0.0, np.asarray(model.probe(model.mbs), dtype=float)
        self.probe = np.full((len(grid), len(self.last_p)), np.nan)
        self.probe[0], self.next = self.last_p, 1
        self.t, self.force = array("d"), array("d")
        self.events: list[tuple[float, str]] = []
        self.counts = dict(model.joint.follow_counts())
        self.column = DATA_COLUMNS.index("normal_force")
        self.start = time.perf_counter()

    def __call__(self, mbs: object, t: float) -> bool:
        p = np.asarray(self.model.probe(mbs), dtype=float)
        grid = self.grid
        while self.next < len(grid) and grid[self.next] <= t + 1e-9 * grid[1]:
            w = min(1.0, (grid[self.next] - self.last_t) / (t - self.last_t))
            self.probe[self.next] = self.last_p + w * (p - self.last_p)
            self.next += 1
        self.last_t, self.last_p = t, p
        self.t.append(t)
        self.force.append(mbs.GetSensorValues(self.model.joint.sensorNumber)[self.column])
        now = self.model.joint.follow_counts()
        self.events += [(t, kind) for kind in EVENTS if now and now[kind] > self.counts[kind]]
        self.counts = dict(now)
        return time.perf_counter() - self.start < self.limit


def solve(name: str, label: str, refine: int, end: float | None, limit: float, kick: float = 0.0,
          **options: object) -> Run:
    """Run model ``name`` with its clearance joint at ``refine`` times the example's steps to
    ``end`` (None: the example's end time), ``kick`` [m/s] added to every initial velocity."""
    model = load_models()[name](clearance=True, end_time=end, **options)
    mbs, ss = model.mbs, model.simulation_settings
    ti = ss.timeIntegration
    end, steps = ti.endTime, int(ti.numberOfSteps)
    ti.numberOfSteps = steps * refine
    if kick:
        initial = exu.ConfigurationType.Initial
        velocities = np.asarray(mbs.systemData.GetODE2Coordinates_t(configuration=initial))
        mbs.systemData.SetODE2Coordinates_t(velocities + kick, configuration=initial)
    energy0 = sum(model.energy(mbs)) if model.energy else np.nan
    recorder = Recorder(model, np.linspace(0.0, end, steps + 1), limit)
    mbs.SetPostStepUserFunction(recorder)
    message = ""
    try:
        mbs.SolveDynamic(ss, solverType=model.solver_type)
    except Exception as err:  # Exudyn raises its own error types when it stops
        message = str(err).strip().splitlines()[0][:80]
    wall = time.perf_counter() - recorder.start
    reached = recorder.last_t
    if reached < end * (1 - 1e-9) and not message:
        message = f"time limit at {reached:.4g} s"
    energy = sum(model.energy(mbs)) - energy0 if model.energy else np.nan
    steps_taken = int(mbs.sys["dynamicSolver"].it.currentStepIndex) - 1
    return Run(label, end / steps, recorder.probe, reached, steps_taken, wall,
               statistics(model.joint, recorder, energy) | {"c": model.clearance},
               recorder.counts, recorder.events, message)


def statistics(joint: object, recorder: Recorder, energy: float) -> dict[str, float]:
    """The joint's contact statistics over the run: the normal force's mean over time and the
    90th percentile of its two-step swing ``|F_k - (F_k-1 + F_k+1) / 2| / 2`` over the
    accepted steps; the probe's RMS and spectral peak (its component of largest variance,
    mean removed, Hann window)."""
    history = joint.history
    impacts, reached = history.impacts, recorder.last_t
    in_contact = sum(r.duration for r in impacts)
    if history.in_contact:
        in_contact += reached - history.state.onset_time
    peaks = [r.peak_force for r in impacts] + [history.state.peak_force]
    onset_speeds = [abs(r.onset_velocity) for r in impacts] + ([abs(history.v0)] if history.in_contact else [])
    t, force = np.asarray(recorder.t), np.asarray(recorder.force)
    swing = np.abs(force[1:-1] - 0.5 * (force[:-2] + force[2:])) / 2
    p = recorder.probe[~np.isnan(recorder.probe).any(axis=1)]
    x = p[:, np.argmax(p.var(axis=0))]
    x = x - x.mean()
    spectrum = np.abs(np.fft.rfft(x * np.hanning(len(x))))
    frequencies = np.fft.rfftfreq(len(x), recorder.grid[1])
    return {"mean_force": float(np.sum(force * np.diff(t, prepend=0.0)) / reached),
            "swing": float(np.percentile(swing, 90)) if swing.size else 0.0, "peak_force": max(peaks),
            "onsets": history.onsets, "fast_onsets": sum(v > FAST_ONSET for v in onset_speeds),
            "contact_share": in_contact / reached, "energy": energy, "rms": float(np.sqrt(np.mean(x**2))),
            "peak_hz": float(frequencies[1 + np.argmax(spectrum[1:])])}


def difference(a: Run, b: Run) -> tuple[np.ndarray, list[str]]:
    """The probe difference [c] of ``a`` against ``b`` on the grid, and the cells: largest, at
    the end, first time above 0.1 c and 1 c."""
    d = np.nanmax(np.abs(a.probe - b.probe), axis=1) / a.stats["c"]
    both = ~np.isnan(d)
    cells = [f"{np.max(d[both]):.3g}", f"{d[both][-1]:.3g}"]
    for bound in (0.1, 1.0):
        above = np.flatnonzero(d[both] > bound)
        cells.append(f"{above[0] * a.h:.3f}" if above.size else "-")
    return d, cells


def before(run: Run, d: np.ndarray, bound: float) -> str:
    """The follow event last before the difference ``d`` first exceeds ``bound``."""
    above = np.flatnonzero(d > bound)
    if not above.size:
        return "-"
    earlier = [e for e in run.events if e[0] <= above[0] * run.h + 1e-12]
    return f"{earlier[-1][1]} at {earlier[-1][0]:.4f}" if earlier else "none"


def first_events(run: Run) -> str:
    """The first time of each follow event."""
    first = {}
    for t, kind in run.events:
        first.setdefault(kind, t)
    return ", ".join(f"{kind} {t:.4f}" for kind, t in sorted(first.items(), key=lambda item: item[1]))


def report(name: str, refines: list[int], end: float | None, limit: float, kick: float, ensemble: int,
           follow_backend: str = "python") -> None:
    print(f"\n## {name}\n", flush=True)
    runs: dict[str, Run] = {}

    def add(run: Run) -> Run:
        runs[run.label] = run
        print(f"- {run.label}: {run.wall:.1f} s wall", flush=True)
        return run

    compliant = [add(solve(name, f"compliant {r}x", r, end, limit)) for r in refines]
    finest, r0 = compliant[-1], refines[0]
    kicked = add(solve(name, f"compliant {refines[-1]}x, kick 1", refines[-1], end, limit, kick))
    python = add(solve(name, f"compliant {r0}x, Python", r0, end, limit, backend="python"))
    follow = [add(solve(name, f"follow {r}x", r, end, limit, backend=follow_backend, contact_mode="follow"))
              for r in refines[:2]]
    members = {"compliant": [compliant[0]], "follow": [follow[0]]}
    for j in range(1, ensemble + 1):
        members["compliant"].append(add(solve(name, f"compliant {r0}x, kick {j}", r0, end, limit, j * kick)))
        members["follow"].append(add(solve(name, f"follow {r0}x, kick {j}", r0, end, limit, j * kick,
                                           backend=follow_backend, contact_mode="follow")))

    print("\nRuns\n")
    print(markdown_table(["run", "reached [s]", "steps", "wall [s]", "follow on / off / lost / redone",
                          "first follow events [s]", "stopped"],
                         [[r.label, f"{r.reached:.4g}", r.steps, f"{r.wall:.1f}",
                           " / ".join(str(r.counts[k]) for k in EVENTS) if r.counts else "", first_events(r), r.message]
                          for r in runs.values()]))

    pairs = list(zip(compliant, compliant[1:]))  # successive refinements
    pairs += [(r, finest) for r in (*compliant[:-2], kicked, *follow)]
    pairs += [(python, compliant[0]), *(m[1::-1] for m in members.values() if len(m) > 1), *zip(follow, compliant)]
    rows = []
    for a, b in pairs:
        d, cells = difference(a, b)
        events = f"{before(a, d, 0.1)}; {before(a, d, 1.0)}" if a.counts else ""
        rows.append([f"{a.label} - {b.label}", *cells, events])
    print(f"\nProbe differences [c] (kick j: j {kick:g} m/s added to every initial velocity)\n")
    print(markdown_table(["pair", "largest", "at end", "t > 0.1 c [s]", "t > 1 c [s]",
                          "follow event last before 0.1 c; 1 c"], rows))

    for run in runs.values():
        d = difference(run, finest)[0]
        run.stats |= {"off_end": d[~np.isnan(d)][-1], "off_max": np.nanmax(d)}
    print("\nStatistics\n")
    print(markdown_table(["run", "mean F_n [N]", "F_n two-step swing, 90 % [N]", "peak F_n [N]", "onsets",
                          f"onsets > {FAST_ONSET} m/s", "time in contact", "energy change [J]", "probe RMS [m]",
                          "spectral peak [Hz]"],
                         [[r.label, f"{s['mean_force']:.4g}", f"{s['swing']:.3g}", f"{s['peak_force']:.4g}",
                           s["onsets"], s["fast_onsets"], f"{s['contact_share']:.4f}", f"{s['energy']:.4g}",
                           f"{s['rms']:.5g}", f"{s['peak_hz']:.3g}"] for r in runs.values() for s in [r.stats]]))

    print(f"\nEnsembles at {r0}x (the run and its {ensemble} kicked runs): mean +- standard deviation, [min, max]; "
          f"the finest compliant run and its kicked one\n")

    def spread(values: list[float], fmt: str) -> str:
        return (f"{np.mean(values):{fmt}} +- {np.std(values, ddof=1) if len(values) > 1 else 0.0:.2g} "
                f"[{min(values):{fmt}}, {max(values):{fmt}}]")

    rows = [[heading, *(spread([r.stats[key] for r in m], fmt) for m in members.values()),
             f"{finest.stats[key]:{fmt}}; {kicked.stats[key]:{fmt}}"] for key, heading, fmt in STATISTICS]
    print(markdown_table(["statistic", *(f"{mode} {r0}x (n {len(m)})" for mode, m in members.items()),
                          f"compliant {refines[-1]}x; kick 1"], rows), flush=True)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m validation.contact_follow_long",
                                     description=__doc__.split("\n\n")[0])
    parser.add_argument("--models", default=",".join(MODELS), help=f"zoo models (default {','.join(MODELS)})")
    parser.add_argument("--refines", default="1,4,16,64,256",
                        help="compliant refinements of the steps (default 1,4,16,64,256; follow: the first two)")
    parser.add_argument("--end-time", type=float, default=None, help="end time [s] (default each example's own)")
    parser.add_argument("--kick", type=float, default=1e-9, help="initial velocity perturbation [m/s] (default 1e-9)")
    parser.add_argument("--ensemble", type=int, default=4, help="kicked runs at 1x per mode (default 4)")
    parser.add_argument("--time-limit", type=float, default=600.0, help="wall time limit of one run [s] (default 600)")
    parser.add_argument("--follow-backend", choices=["python", "compiled"], default="python",
                        help="the following runs' kernel (default python; compiled: where it covers the joint)")
    args = parser.parse_args(argv)
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in model_names(args.models):
            report(name, [int(r) for r in args.refines.split(",")], args.end_time, args.time_limit, args.kick,
                   args.ensemble, args.follow_backend)
    print(f"\nTotal wall time: {time.perf_counter() - start:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
