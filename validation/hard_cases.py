"""Hard cases: numerical stability of the clearance joint at the edges of its use.

Source problem: the revolute clearance joint of ``docs/physics.md`` (X. Wang, G. Liu,
S. Ma, R. Tong, J. Mech. Sci. Technol. 31(2) (2017) 587-597): its journal-bearing scene
(docs/physics.md section 6.1) and its slider-crank (docs/physics.md section 6.2), pushed to where integrators and
contact laws get into trouble (docs/physics.md section 8).  Every case states its pass criterion
before it runs (:data:`CASES`); the report is a table of case, criterion, measured
value, pass/fail and wall time, written to ``results/hard_cases/hard_cases.md`` with a
CSV copy and figures.

Cases:

- grazing and permanent contact: a journal resting on its bearing under gravity, one
  dropped onto it from the centre, and an impact at ``v0 = 1e-6 m/s``;
- low restitution: ``cr = 0.05`` and ``0.1`` with every law that accepts them;
- clearances of 1 micrometre and 1 mm; 5000 rpm; 20 crank revolutions;
- soft journals: aluminium, and a polymer with ``E = 3 GPa``, ``nu = 0.4``;
- stick-slip with the paper's modified Coulomb law (``mu_s = 0.3``, ``mu_d = 0.25``);
- clearance at all three revolute joints of the slider-crank (redundant coordinates,
  generalized-alpha).

Static penetration of the resting journal.  Under its weight ``W = m g`` the journal
settles where the elastic part of the law carries it (``delta_dot = 0``):

    K_eff(delta_s) * delta_s^1.5 = m g,   K_eff(delta) = (pi E* L / 2) sqrt(1 / (2 (c + delta)))

for the Wang-Liu law (docs/physics.md eqs. (9), (11)).  ``K_eff`` depends on ``delta``, so ``delta_s`` is
the root of ``F_el(delta) - m g`` on ``(0, c]`` (:func:`static_penetration`, Brent's
method; ``F_el`` rises monotonically there).  For the paper's journal (0.04 kg, steel,
L = 15 mm, c = 0.1 mm) it is 16.25 nm.  The largest penetration after the journal is set
down at ``delta = 0`` with no speed is bounded by the elastic step-load response,
``m g delta_max = E_el(delta_max)`` with ``E_el(delta) = int_0^delta F_el`` (damping only
lowers it): :func:`step_load_penetration`.

Energy audit.  Work put in (the drive, or gravity) = change of kinetic and potential
energy + energy absorbed by the contacts.  The absorbed energy is split into the
elastic energy stored at the end, a function of the state (exact), and the dissipated
energy ``int ((F_N - F_el) delta_dot + F_T v_T) dt``, integrated by the trapezoid rule
over every accepted step.  The drive work of the minimal slider-crank is the energy the
flywheel gives up, ``-J_fly (omega_end^2 - omega_0^2) / 2``, exact but blurred by the
round-off of the flywheel's 1.4e9 J (:func:`flywheel_roundoff`); each slider-crank case
is therefore audited again in redundant coordinates (no flywheel: the drive constraint's
multiplier), where the contact work is summed as generalized-alpha's own energy balance
does (:func:`_contact_energy`).  The residual is judged against the gross work of the
contact forces (:data:`AUDIT_LIMIT`).

The floor ``v_min`` of the onset velocity (docs/physics.md eq. (17)) is compared at 1e-4, 1e-3 (the
default) and 1e-2 m/s on the low-speed cases (:func:`floor_study`).

Run from the repository root::

    python -m validation.hard_cases [--out DIR] [--quick]

``--quick`` shortens the runs (under a minute).  Exit status 0 if every case passes,
1 otherwise; failing cases are listed, never dropped.
"""
from __future__ import annotations

import argparse
import math
import os
import sys
import time
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from typing import NamedTuple

import exudyn as exu
import numpy as np
from exudyn.itemInterface import SensorNode
from scipy.integrate import quad
from scipy.optimize import brentq

import exuclear
from models import journal_bearing as jb_model
from models import slider_crank as sc_model
from models.journal_bearing import JournalBearingParams
from models.slider_crank import FLYWHEEL_INERTIA, SliderCrankParams
from validation import cross_check as cc
from validation._tables import markdown_table, write_csv
from validation.reference import journal_bearing as jb_reference
from validation.reference import slider_crank as sc_reference

DEFAULT_OUT = os.path.join("results", "hard_cases")

# -- scenes -----------------------------------------------------------------------------

#: Gravitational acceleration of the resting and dropped journal [m/s^2].
GRAVITY = 9.81
#: Restitution of the resting and dropped journal: the paper's slider-crank value and the
#: least damped of its sweep, so the slowest to settle.
RESTING_CR = 0.9
#: Simulated time of the resting journal [s]: its oscillation about delta_s (about
#: 4.8 kHz) decays as exp(-zeta omega t) with zeta ~ 0.03 at the default floor, by
#: 1e-7 in 20 ms.
RESTING_TIME = 0.02
#: Simulated time of the dropped journal [s]: 35 bounces, the last one at 80 ms (measured).
DROPPED_TIME = 0.12
#: Settings of the resting and dropped journal: DOPRI5 with steps up to 1e-5 s (20 per
#: period of the contact oscillation), rtol 1e-8; atol 1e-14 m is 6e-7 of delta_s.
RESTING_RTOL, RESTING_ATOL, RESTING_STEP = 1e-8, 1e-14, 1e-5
#: Outputs at every accepted step (Exudyn records at the first step at or after each
#: output instant), so the audits integrate over the solver's own steps.
EVERY_STEP = 1e-12
#: Impact speed of the grazing impact [m/s] (the issue) and its simulated time [s]: the
#: contact lasts about 0.5 ms (Hertz duration ~ v^-1/5: 40 us * (0.3 / 1e-6)^0.2).
SLOW_IMPACT_SPEED = 1e-6
SLOW_IMPACT_TIME = 1.5e-3
#: Library settings of the grazing impact: the peak penetration is only 0.15 nm, so the
#: absolute tolerance is 1e-17 m (1e-7 of it) and rtol 1e-13 (positions are ~c = 1e-4 m).
SLOW_RTOL, SLOW_ATOL, SLOW_STEP = 1e-13, 1e-17, 1e-6
#: Restitution coefficients of the low-restitution cases (the issue).
LOW_CRS = (0.05, 0.1)
#: Largest step of the low-restitution impacts [s].  The library reads its peak force
#: at accepted steps; at low cr the pulse is sharper than the sine-like one behind the
#: cross-check's 1e-4 bound (Flores at cr 0.05, D = 30: 2e-4 low at the 1e-7 s steps of
#: :func:`models.journal_bearing.settings_for`), so the steps are 5 times shorter here,
#: which cuts the sampling error 25-fold.
LOW_CR_STEP = 2e-8
#: Polymer journal of the soft-material case (the issue): E = 3 GPa, nu = 0.4.
POLYMER = exuclear.Material(3e9, 0.4, "polymer")
#: Slider-crank cases run at the material sweep's restitution (docs/physics.md section 6.2: cr = 0.3).
MATERIAL_CR = 0.3
#: High crank speed [rpm] and the long run [revolutions] (the issue).
HIGH_RPM = 5000.0
LONG_REVOLUTIONS = 20.0
#: Revolutions of the slider-crank audit runs: docs/physics.md section 6.2 asks for at least two.
REVOLUTIONS = 2.0
#: Revolutions in the quick run.
QUICK_REVOLUTIONS = 0.5
QUICK_LONG_REVOLUTIONS = 3.0

# -- reference comparison -----------------------------------------------------------------

#: Horizon of the point-by-point comparison with the reference [s] (quick: half of it):
#: every case starts with its impacts there, and the perturbed reference shows whether
#: the motion is still insensitive (it is checked, not assumed).
COMPARE_TIME = 0.02
#: Relative perturbation of the clearance in the sensitivity check: 1e-5 c, as the
#: cross-check's 1e-9 m is for the paper's c = 0.1 mm, so the check scales with c.
PERTURBATION = 1e-5
#: Library settings of the comparison runs: the cross-check's converged DOPRI5 settings
#: (rtol 1e-9, atol 1e-12), with the largest step scaled to the crank speed: 1e-5 s at the
#: paper's 500 rpm (0.03 degrees of crank angle), 1e-6 s at 5000 rpm.  The contact-onset
#: velocity is interpolated within the step where contact begins, with an error of
#: order step^2 * acceleration (exuclear.ContactState), and accelerations grow as the
#: speed squared.  (Measured at 5000 rpm over 20 ms with a fixed 1e-5 s bound: max |de|
#: = 2.7 % of c; with 1e-6 s: 0.06 %.)
CONVERGED = (("rtol", 1e-9), ("atol", 1e-12))
CONVERGED_STEP_ANGLE = 1e-5 * sc_model.PAPER_CRANK_SPEED  # [rad]

# -- criteria -------------------------------------------------------------------------------

#: Energy audit bound, relative to the gross work of the contact forces,
#: ``int |F_N delta_dot + F_T v_T| dt`` (for the journal under gravity: the work of
#: gravity).  A force mapped wrongly (a lost moment arm, a sign) errs in proportion to
#: the work the contact forces do in and out, which the gross work measures; the part of
#: it that stays absorbed can be tiny (0.05 mJ at a 1 um clearance, against ~1e-6 of the
#: mechanism's 3 J of kinetic energy that the integrators' own energy errors reach).  The
#: dissipated part is a trapezoid rule over accepted steps, the only instants at which
#: Exudyn reports.
AUDIT_LIMIT = 0.01
#: Resting journal: relative error of the final penetration against delta_s.  Its
#: oscillation has decayed below 1e-7 and the tolerances allow ~6e-7 (see above); a load
#: or a stiffness off by 0.15 % moves delta_s by 0.1 %.
STATIC_LIMIT = 1e-3
#: Slack on the step-load bound of the largest penetration: the tolerance, 1e-14 m on
#: 30 nm, is far below it.
STEP_LOAD_SLACK = 1e-3
#: Share of the dropped journal's run at whose start it must have come to rest: the
#: last 20 % of the run without a new impact.
SETTLED_SHARE = 0.8
#: Friction coefficient bound: |F_T| <= mu_s F_N up to round-off.
MU_SLACK = 1e-9


class Outcome(NamedTuple):
    """Result of one case: the measured value (text), pass/fail, values for the CSV, and
    what a figure needs (``{name: data}``, see :func:`write_outputs`)."""

    measured: str
    passed: bool
    values: dict[str, float]
    figures: dict[str, object] = {}


@dataclass(frozen=True)
class Case:
    """A hard case: its title, its criterion (fixed before it runs) and how to run it."""

    key: str
    title: str
    criterion: str
    run: Callable[[bool], Outcome]


@dataclass
class Row:
    """A case after its run."""

    case: Case
    outcome: Outcome
    wall_time: float


@dataclass
class Study:
    """Everything a run of the study produced."""

    quick: bool
    rows: list[Row]
    floor: list[FloorRow]
    figures: dict[str, object] = field(default_factory=dict)
    runtime: float = 0.0

    def failures(self) -> list[Row]:
        return [r for r in self.rows if not r.outcome.passed]


# =======================================================================================
# analytic values
# =======================================================================================


def static_penetration(law: exuclear.ContactLaw, load: float) -> float:
    """``delta_s`` [m] with ``F_el(delta_s) = load`` [N], by Brent's method on ``(0, c]``.

    ``F_el(delta) = K_eff(delta) delta^n`` rises monotonically from 0 for every law of
    :mod:`exuclear.contact`; a load beyond ``F_el(c)`` raises ``ValueError``.
    """
    c = law.geometry.clearance
    if not 0.0 < load < law.elastic_force(c):
        raise ValueError(f"`load` must lie in (0, F_el(c) = {law.elastic_force(c):.3g} N), got {load}")
    return brentq(lambda d: law.elastic_force(d) - load, 0.0, c, xtol=1e-15 * c, rtol=1e-14)


def elastic_energy(law: exuclear.ContactLaw, delta: float) -> float:
    """``E_el(delta) = int_0^delta F_el`` [J]: the energy stored elastically (0 for delta <= 0)."""
    if delta <= 0.0:
        return 0.0
    return quad(law.elastic_force, 0.0, delta, epsabs=0.0, epsrel=1e-12)[0]


def step_load_penetration(law: exuclear.ContactLaw, load: float) -> float:
    """Largest penetration of an elastic contact set down at rest under ``load`` [N]:
    the root of ``load delta = E_el(delta)`` beyond ``delta_s`` [m]."""
    d_s = static_penetration(law, load)
    hi = 2.0 * d_s
    while load * hi > elastic_energy(law, hi):
        hi *= 2.0
    return brentq(lambda d: load * d - elastic_energy(law, d), d_s, hi, xtol=1e-15 * hi, rtol=1e-14)


# =======================================================================================
# energy audits
# =======================================================================================


class Audit(NamedTuple):
    """Energy balance of a run [J]: ``work = change + stored + dissipated + residual``.

    ``gross`` is the work the contact forces did in and out, ``int |F_N delta_dot +
    F_T v_T| dt``; ``scale`` the energy the residual is judged against: ``gross`` for the
    slider-crank, the work of gravity for the journal under gravity.  ``floor`` [J] is
    what the measurement of ``work`` cannot resolve (the flywheel's round-off,
    :func:`audit_minimal`; 0 elsewhere).
    """

    work: float
    change: float
    stored: float
    dissipated: float
    gross: float
    residual: float
    scale: float
    floor: float = 0.0

    @property
    def absorbed(self) -> float:
        return self.stored + self.dissipated

    @property
    def relative(self) -> float:
        return self.residual / self.scale

    @property
    def passed(self) -> bool:
        return abs(self.residual) <= AUDIT_LIMIT * abs(self.scale) + self.floor


def _contact_energy(handle: exuclear.ClearanceJointHandle, in_penetration: bool = False) -> tuple[float, float, float]:
    """Elastic energy stored at the end, the rest of the energy one joint absorbed, and the
    gross work of its forces [J].

    ``in_penetration`` False: the dissipated power ``(F_N - F_el) delta_dot + F_T v_T`` by
    the trapezoid rule in time (the elastic part is a function of the state, exact).
    True: the normal work ``sum (F_N,k + F_N,k+1) / 2 (delta_k+1 - delta_k)``, which is the
    work the trapezoidal family (generalized-alpha at spectral radius 1) does in its own
    discrete energy balance (``dT = F_avg . dq``), and the friction in time.
    """
    out = handle.outputs()
    law = handle.joint.law
    delta, f_n, t = out["penetration"], out["normal_force"], out["time"]
    stored = elastic_energy(law, float(delta[-1])) - elastic_energy(law, float(delta[0]))
    friction_power = out["tangential_force"] * out["slip_velocity"]
    gross = float(np.trapezoid(np.abs(f_n * out["penetration_rate"] + friction_power), t))
    friction = float(np.trapezoid(friction_power, t))
    if in_penetration:
        normal = float(np.sum(0.5 * (f_n[1:] + f_n[:-1]) * np.diff(delta)))
        return stored, normal - stored + friction, gross
    elastic = np.array([law.elastic_force(d) for d in delta])
    return stored, float(np.trapezoid((f_n - elastic) * out["penetration_rate"], t)) + friction, gross


def _audit(work: float, change: float, joints: Sequence[exuclear.ClearanceJointHandle], *, scale: float | None = None,
           floor: float = 0.0, in_penetration: bool = False) -> Audit:
    terms = [_contact_energy(h, in_penetration) for h in joints]
    stored, dissipated, gross = (sum(t[k] for t in terms) for k in range(3))
    residual = work - change - stored - dissipated
    return Audit(work, change, stored, dissipated, gross, residual, gross if scale is None else scale, floor)


def flywheel_roundoff(omega: float, steps: int) -> float:
    """What the flywheel's energy cannot resolve over ``steps`` steps [J].

    The crank speed changes by ~1e-12 of itself per step, so every step rounds the
    increment to the spacing ``ulp(omega)`` of doubles; ``steps`` roundings of up to half a
    spacing add up like a random walk, ``ulp / 2 sqrt(steps)``, and ``J_fly omega`` turns a
    speed error into an energy error.  The bound is 4 of those standard deviations (the
    walk is not quite random: residuals of 1-2 of them were measured).
    """
    return 4.0 * FLYWHEEL_INERTIA * abs(omega) * float(np.spacing(abs(omega))) / 2.0 * math.sqrt(steps)


def audit_minimal(model: sc_model.SliderCrankModel, steps: int) -> Audit:
    """Energy audit of a minimal-coordinate slider-crank run (outputs at every step).

    Kinetic and potential energy of crank (its own inertia), rod and slider from
    :func:`models.slider_crank.mechanical_energy`.  The drive work is what the flywheel gave up, ``-J_fly (omega_end^2 - omega_0^2) / 2``:
    exact, but only to the round-off of :func:`flywheel_roundoff` (some 1e-5 J at 500
    rpm).  (The trapezoid rule on the recorded crank moment misses by 4 to 30 %: the
    moment varies by its own size within one step at an impact.)
    """
    p = model.params
    _, energy, thd = sc_model.mechanical_energy(model)
    work = -0.5 * FLYWHEEL_INERTIA * (thd[-1] - thd[0]) * (thd[-1] + thd[0])
    return _audit(work, float(energy[-1] - energy[0]), list(model.joints.values()),
                  floor=flywheel_roundoff(p.crank_speed, steps))


def _add_body_sensors(model: sc_model.SliderCrankModel) -> dict[str, tuple[int, int]]:
    """Position and velocity sensors (x, y, phi) of crank, rod and slider of a redundant model.

    Crank and slider nodes are those of the model's own sensors; the rod's node is the
    journal node of joint B, or the bearing node of joint A.
    """
    mbs = model.mbs
    crank = int(mbs.GetSensor(model.sensors["crank"])["nodeNumber"])
    slider = int(mbs.GetSensor(model.sensors["slider_x"])["nodeNumber"])
    rods = {n for h in model.joints.values() for n in h.nodes} - {crank, slider}
    if len(rods) != 1:
        raise ValueError("the rod's node is found through a clearance joint at A or B")
    store = dict(storeInternal=True, writeToFile=False)
    sensors = {}
    for name, node in (("crank", crank), ("rod", rods.pop()), ("slider", slider)):
        sensors[name] = tuple(int(mbs.AddSensor(SensorNode(nodeNumber=node, outputVariableType=kind, **store)))
                              for kind in (exu.OutputVariableType.Coordinates, exu.OutputVariableType.Coordinates_t))
    mbs.Assemble()
    return sensors


def audit_redundant(model: sc_model.SliderCrankModel, sensors: dict[str, tuple[int, int]]) -> Audit:
    """Energy audit of a redundant-coordinate slider-crank run (outputs at every step).

    Bodies' energies from their node sensors (:func:`_add_body_sensors`): the nodes sit
    at the centres of mass.  Drive work ``int M omega dt`` by the trapezoid rule, with
    the moment from the drive constraint's multiplier and omega held exactly; contact
    work in the generalized-alpha method's own terms (see :func:`_contact_energy`).
    """
    p, mbs = model.params, model.mbs
    masses = {"crank": (p.crank_mass, p.crank_inertia), "rod": (p.rod_mass, p.rod_inertia),
              "slider": (p.slider_mass, 0.0)}  # the slider does not rotate
    energy = 0.0
    for name, (pos, vel) in sensors.items():
        m, inertia = masses[name]
        q, v = np.asarray(mbs.GetSensorStoredData(pos)), np.asarray(mbs.GetSensorStoredData(vel))
        y0 = mbs.GetNodeParameter(int(mbs.GetSensor(pos)["nodeNumber"]), "referenceCoordinates")[1]
        energy = energy + 0.5 * m * (v[:, 1] ** 2 + v[:, 2] ** 2) + 0.5 * inertia * v[:, 3] ** 2 \
            + m * p.gravity * (y0 + q[:, 2])
    drive = np.asarray(mbs.GetSensorStoredData(model.sensors["moment"]))
    # the multiplier is the constraint's reaction on the crank: the drive is its negative
    work = float(np.trapezoid(-drive[:, 1] * p.crank_speed, drive[:, 0]))
    return _audit(work, float(energy[-1] - energy[0]), list(model.joints.values()), in_penetration=True)


def audit_journal(params: JournalBearingParams, handle: exuclear.ClearanceJointHandle) -> Audit:
    """Energy audit of the journal under gravity: gravity's work ``m g (x_end - x_0)`` =
    kinetic energy + absorbed; the journal moves along X only, ``e = (x, 0)``, so its
    speed is ``delta_dot`` (sign of ``x`` aside).  Relative to the work of gravity."""
    out = handle.outputs()
    x, rate = out["ecc_x"], out["penetration_rate"]
    v = np.where(x < 0.0, -rate, rate)
    work = params.mass * params.gravity * float(x[-1] - x[0])
    change = 0.5 * params.mass * float(v[-1] ** 2 - v[0] ** 2)
    return _audit(work, change, [handle], scale=work)


def _audit_text(a: Audit, label: str = "audit") -> str:
    bound = f"1 % + flywheel round-off {a.floor / a.scale:.2%}" if a.floor else "1 %"
    return (f"{label} residual {a.relative:+.2%} of the {a.gross * 1e3:.4g} mJ the contact exchanged (bound {bound}; "
            f"{a.residual / a.absorbed:+.2%} of the {a.absorbed * 1e3:.4g} mJ absorbed)")


def _finite(*tables: dict[str, np.ndarray]) -> bool:
    return all(bool(np.all(np.isfinite(v))) for t in tables for v in t.values())


# =======================================================================================
# journal under gravity
# =======================================================================================


class JournalRun(NamedTuple):
    """A run of the journal under gravity."""

    params: JournalBearingParams
    sim: exuclear.SimulationResult
    out: dict[str, np.ndarray]
    onsets: list[float]
    audit: Audit
    delta_s: float
    wall: float


def resting_params(start_gap: float = 0.0, v_min: float = exuclear.V_MIN_DEFAULT, gravity: float = GRAVITY,
                   end_time: float = RESTING_TIME) -> JournalBearingParams:
    """The paper's journal (docs/physics.md section 6.1) at rest under gravity, ``start_gap`` from the wall."""
    return JournalBearingParams.paper(cr=RESTING_CR, impact_velocity=0.0, gravity=gravity, start_gap=start_gap,
                                      v_min=v_min, end_time=end_time)


def run_journal(params: JournalBearingParams) -> JournalRun:
    """Build and integrate the journal under gravity; outputs at every step."""
    start = time.perf_counter()
    mbs, handle, _ = jb_model.build(params)
    settings = exuclear.SolverSettings(end_time=params.end_time, method="dopri5", step=RESTING_STEP, rtol=RESTING_RTOL,
                                       atol=RESTING_ATOL, output_step=EVERY_STEP)
    sim = exuclear.simulate(mbs, settings)
    out = handle.outputs()
    law = handle.joint.law
    return JournalRun(params, sim, out, list(handle.history.onset_times), audit_journal(params, handle),
                      static_penetration(law, params.mass * params.gravity), time.perf_counter() - start)


def settle_time(run: JournalRun, band: float = 0.01) -> float:
    """First time after which the penetration stays within ``band`` of ``delta_s`` [s]
    (NaN if it never does)."""
    t, d = run.out["time"], run.out["penetration"]
    outside = np.flatnonzero(np.abs(d / run.delta_s - 1.0) > band)
    if len(outside) == 0:
        return float(t[0])
    k = outside[-1] + 1
    return float(t[k]) if k < len(t) else math.nan


def final_error(run: JournalRun) -> float:
    """Mean penetration over the last 10 % of the run, relative to ``delta_s``, minus 1."""
    t, d = run.out["time"], run.out["penetration"]
    tail = t >= 0.9 * t[-1]
    return float(d[tail].mean() / run.delta_s - 1.0)


def case_resting(quick: bool) -> Outcome:
    run = run_journal(resting_params())
    law = JournalBearingParams.paper(cr=RESTING_CR).joint().law
    bound = step_load_penetration(law, run.params.mass * run.params.gravity)
    err, peak = final_error(run), float(run.out["penetration"].max())
    passed = (run.sim.success and _finite(run.out) and abs(err) <= STATIC_LIMIT and len(run.onsets) == 1
              and peak <= bound * (1.0 + STEP_LOAD_SLACK) and abs(run.audit.relative) <= AUDIT_LIMIT)
    measured = (f"delta_s = {run.delta_s * 1e9:.3f} nm (analytic); final penetration {err:+.1e} off; "
                f"{len(run.onsets)} onset; peak {peak / run.delta_s:.3f} delta_s (bound {bound / run.delta_s:.3f}); "
                f"settled to 1 % at {settle_time(run) * 1e3:.2f} ms; {run.sim.steps} steps; audit residual "
                f"{run.audit.relative:+.2%} of gravity's work")
    if not run.sim.success:
        measured += f"; FAILED: {run.sim.message}"
    return Outcome(measured, passed, {"delta_s_m": run.delta_s, "final_error": err, "onsets": len(run.onsets),
                                      "peak_over_delta_s": peak / run.delta_s, "audit": run.audit.relative})


def case_dropped(quick: bool) -> Outcome:
    c = JournalBearingParams.paper().joint().geometry.clearance
    run = run_journal(resting_params(start_gap=c, end_time=DROPPED_TIME))
    err = final_error(run)
    last = run.onsets[-1] if run.onsets else math.nan
    passed = (run.sim.success and _finite(run.out) and abs(err) <= STATIC_LIMIT
              and last <= SETTLED_SHARE * run.params.end_time and abs(run.audit.relative) <= AUDIT_LIMIT)
    measured = (f"{len(run.onsets)} impacts, the last at {last * 1e3:.1f} ms; final penetration {err:+.1e} off "
                f"delta_s; settled to 1 % at {settle_time(run) * 1e3:.1f} ms; {run.sim.steps} steps; "
                f"audit residual {run.audit.relative:+.2%} of gravity's work")
    if not run.sim.success:
        measured += f"; FAILED: {run.sim.message}"
    return Outcome(measured, passed, {"impacts": len(run.onsets), "last_onset_s": last, "final_error": err,
                                      "audit": run.audit.relative})


# =======================================================================================
# single impacts
# =======================================================================================


class ImpactComparison(NamedTuple):
    """An impact in the library and in the reference, and their relative differences."""

    library: jb_model.ImpactResult
    out: dict[str, np.ndarray]
    reference: dict
    errors: dict[str, float]


def compare_impact(params: JournalBearingParams, settings: exuclear.SolverSettings | None = None) -> ImpactComparison:
    """Run one impact in the library and in the reference; errors keyed as
    :data:`validation.cross_check.JB_CRITERIA`."""
    lib, out = jb_model.run(params, settings)
    ref = jb_reference.simulate(params)
    pairs = {"departure": (lib.departure_velocity, ref["departure_velocity"]),
             "peak_force": (lib.max_force, ref["max_force"]),
             "peak_penetration": (lib.max_penetration, ref["max_penetration"]),
             "duration": (lib.contact_duration, ref["contact_duration"])}
    return ImpactComparison(lib, out, ref, {k: (a - b) / b for k, (a, b) in pairs.items()})


def _impact_checks(x: ImpactComparison, keys: Sequence[str]) -> tuple[bool, list[str]]:
    """Completed, left the wall, finite, F_N >= 0, and the given criteria of the cross-check."""
    problems = []
    if not (x.library.success and x.reference["success"]):
        problems.append(f"FAILED: {x.library.message} {x.reference['message']}".strip())
    if not _finite(x.out):
        problems.append("non-finite outputs")
    if x.out["normal_force"].min() < 0.0:
        problems.append("negative normal force")
    limits = {c.key: c.limit for c in cc.JB_CRITERIA}
    problems += [f"{k} off by {x.errors[k]:.1e} (bound {limits[k]:g})" for k in keys if not abs(x.errors[k]) <= limits[k]]
    return not problems, problems


def case_slow_impact(quick: bool) -> Outcome:
    params = JournalBearingParams.paper(impact_velocity=SLOW_IMPACT_SPEED, end_time=SLOW_IMPACT_TIME)
    settings = exuclear.SolverSettings(end_time=params.end_time, method="dopri5", step=SLOW_STEP, rtol=SLOW_RTOL,
                                       atol=SLOW_ATOL, output_step=SLOW_STEP / 10)
    x = compare_impact(params, settings)
    passed, problems = _impact_checks(x, ("departure",))
    cr_eff = x.library.effective_restitution
    measured = (f"effective restitution {cr_eff:.6f} (cr = {params.cr:g}: v0 = 1e-6 m/s is below the floor "
                f"v_min = {params.v_min:g} m/s); departure velocity {x.errors['departure']:+.1e} off the reference; "
                f"peak penetration {x.library.max_penetration * 1e9:.3f} nm, contact {x.library.contact_duration * 1e3:.3f} ms")
    if problems:
        measured += "; " + "; ".join(problems)
    return Outcome(measured, passed, {"effective_restitution": cr_eff, "departure_error": x.errors["departure"]})


def low_restitution_case(law: str, cr: float) -> Callable[[bool], Outcome]:
    def run(quick: bool) -> Outcome:
        params = JournalBearingParams.paper(law=law, cr=cr)
        settings = replace(jb_model.settings_for(params), step=LOW_CR_STEP, output_step=LOW_CR_STEP / 10)
        x = compare_impact(params, settings)
        passed, problems = _impact_checks(x, tuple(c.key for c in cc.JB_CRITERIA))
        worst = max(abs(v) for v in x.errors.values())
        measured = (f"effective restitution {x.library.effective_restitution:.4f}; min F_N "
                    f"{x.out['normal_force'].min():g} N; largest difference from the reference {worst:.1e}")
        if problems:
            measured += "; " + "; ".join(problems)
        return Outcome(measured, passed, {"effective_restitution": x.library.effective_restitution,
                                          "min_force_N": float(x.out["normal_force"].min()), "worst_error": worst})
    return run


def low_restitution_laws() -> tuple[list[str], list[str]]:
    """Laws that accept every cr of :data:`LOW_CRS`, and notes on the others."""
    laws, notes = [], []
    for law in exuclear.CONTACT_LAWS:
        try:
            for cr in LOW_CRS:
                JournalBearingParams.paper(law=law, cr=cr).joint()
        except ValueError as err:
            notes.append(f"{law}: {err}")
            continue
        laws.append(law)
    return laws, notes


# =======================================================================================
# slider-crank
# =======================================================================================


def _with_horizon(params: SliderCrankParams, seconds: float) -> SliderCrankParams:
    return replace(params, revolutions=seconds * params.crank_speed / (2.0 * math.pi))


class CrankRun(NamedTuple):
    """A slider-crank run at the library's default settings, outputs at every step."""

    model: sc_model.SliderCrankModel
    sim: exuclear.SimulationResult
    audit: Audit
    wall: float


def run_crank(params: SliderCrankParams, settings: exuclear.SolverSettings | None = None) -> CrankRun:
    """Build, integrate and audit (minimal or redundant formulation)."""
    start = time.perf_counter()
    model = sc_model.build(params)
    sensors = _add_body_sensors(model) if params.formulation == "redundant" else None
    settings = settings or replace(sc_model.default_settings(params), output_step=EVERY_STEP)
    sim = exuclear.simulate(model.mbs, settings)
    audit = audit_minimal(model, sim.steps) if sensors is None else audit_redundant(model, sensors)
    return CrankRun(model, sim, audit, time.perf_counter() - start)


class Agreement(NamedTuple):
    """The library at converged settings against the reference over a short horizon."""

    ecc: float          # max |delta e| / c up to the horizon
    peak_force: float   # relative difference of the peak contact force
    impacts: tuple[int, int]
    horizon: float      # [s]
    end: float          # [s]
    passed: bool
    note: str


def converged_settings(params: SliderCrankParams) -> exuclear.SolverSettings:
    """:data:`CONVERGED` tolerances, steps up to :data:`CONVERGED_STEP_ANGLE` of crank angle,
    outputs at every step longer than 1e-7 s (as the cross-check)."""
    variant = cc.Variant("minimal", "converged", (*CONVERGED, ("step", CONVERGED_STEP_ANGLE / params.crank_speed)))
    return cc.library_settings(params, variant)


def agreement(params: SliderCrankParams, seconds: float, step: float | None = None) -> Agreement:
    """Point-by-point comparison with the SciPy reference, as :mod:`validation.cross_check`
    does, over ``seconds`` (cut where a perturbed reference shows the motion sensitive);
    library settings :func:`converged_settings`, with the largest ``step`` [s] if given."""
    p = _with_horizon(params, seconds)
    ref = cc.reference_run(p)
    perturbed = cc.reference_run(replace(p, clearance=p.clearance * (1.0 + PERTURBATION)))
    t = ref.columns["time"]
    divergence = cc.eccentricity_difference(perturbed.columns, ref.columns) / p.clearance
    beyond = np.flatnonzero(divergence > cc.SENSITIVITY_LIMIT)
    horizon = float(t[beyond[0] - 1]) if len(beyond) else float(t[-1])
    settings = converged_settings(p)
    lib = sc_model.run(p, settings if step is None else replace(settings, step=step))
    # as the cross-check: at the library's own output instants, the reference (sampled every
    # cc.GRID_STEP) interpolated onto them
    keep = lib.columns["time"] <= horizon
    ecc = float(cc.eccentricity_difference(ref.columns, lib.columns)[keep].max() / p.clearance)
    ref_peak = cc.reference_peak_force(p, ref)
    peak = (lib.peak_force - ref_peak) / ref_peak
    impacts = (int(np.sum(lib.onset_times <= horizon)), int(np.sum(ref.onsets <= horizon)))
    limits = {c.key: c.limit for c in cc.SC_CRITERIA}
    passed = (lib.success and ref.success and ecc <= limits["ecc"] and abs(peak) <= limits["peak_force"]
              and impacts[0] == impacts[1])
    note = "" if lib.success and ref.success else f"library: {lib.message}; reference: {ref.message}"
    return Agreement(ecc, peak, impacts, horizon, float(t[-1]), passed, note)


def _agreement_text(a: Agreement) -> str:
    span = f"{a.end * 1e3:.0f} ms" if a.horizon >= a.end else f"{a.horizon * 1e3:.1f} of {a.end * 1e3:.0f} ms (sensitive)"
    return (f"vs reference over {span}: max abs(de)/c {a.ecc:.1e}, peak force {a.peak_force:+.2%}, "
            f"impacts {a.impacts[0]}/{a.impacts[1]}" + (f" ({a.note})" if a.note else ""))


def _crank_summary(run: CrankRun, label: str = "audit") -> tuple[bool, str, dict[str, float]]:
    """Completion, finiteness, penetration limits and the audit of a slider-crank run."""
    problems, worst, peak, impacts = [], 0.0, 0.0, 0
    for name, handle in run.model.joints.items():
        out = handle.outputs()
        if not _finite(out):
            problems.append(f"non-finite outputs at {name}")
        worst = max(worst, float(out["penetration"].max() / handle.max_penetration))
        peak = max(peak, float(np.hypot(out["normal_force"], out["tangential_force"]).max()))
        impacts += handle.history.onsets
    if not run.sim.success:
        problems.append(f"FAILED: {run.sim.message}")
    if not run.audit.passed:
        problems.append(f"{label} beyond its bound")
    text = (f"{run.sim.time_reached:.3g} s in {run.sim.steps} steps; {impacts} impacts; peak force {peak:.0f} N; "
            f"max penetration {worst:.0%} of the limit; {_audit_text(run.audit, label)}")
    values = {"steps": run.sim.steps, "impacts": impacts, "peak_force_N": peak, "penetration_over_limit": worst,
              "audit": run.audit.relative}
    return not problems, text + ("; " + "; ".join(problems) if problems else ""), values


def _redundant_audit(params: SliderCrankParams) -> tuple[bool, str, float]:
    """The same case in redundant coordinates (generalized-alpha at its default steps),
    audited without a flywheel: completes, finite, audit within 1 %."""
    run = run_crank(replace(params, formulation="redundant"))
    finite = all(_finite(h.outputs()) for h in run.model.joints.values())
    passed = run.sim.success and finite and run.audit.passed
    text = _audit_text(run.audit, "redundant-coordinate audit")
    if not run.sim.success:
        text += f" (FAILED: {run.sim.message})"
    elif not finite:
        text += " (non-finite outputs)"
    return passed, text, run.audit.relative


def _slider_crank(params: SliderCrankParams, compare: bool, quick: bool,
                  settings: exuclear.SolverSettings | None = None) -> tuple[CrankRun, bool, str, dict[str, float]]:
    """Minimal run with its audit, the redundant-coordinate audit and, if ``compare``, the reference."""
    run = run_crank(params, settings)
    passed, text, values = _crank_summary(run, "minimal-coordinate audit")
    ok, audit_text, relative = _redundant_audit(params)
    passed, text = passed and ok, f"{text}; {audit_text}"
    values["redundant_audit"] = relative
    if compare:
        a = agreement(params, min(COMPARE_TIME / (2 if quick else 1), params.end_time))
        passed, text = passed and a.passed, f"{text}; {_agreement_text(a)}"
        values.update(ref_ecc=a.ecc, ref_peak_force=a.peak_force, ref_impacts=a.impacts[0])
    return run, passed, text, values


def crank_case(changes: dict[str, object], compare: bool = True, revolutions: float = REVOLUTIONS,
               quick_revolutions: float = QUICK_REVOLUTIONS) -> Callable[[bool], Outcome]:
    """A slider-crank case (see :func:`_slider_crank`)."""
    def run(quick: bool) -> Outcome:
        with warnings.catch_warnings(record=True) as caught:  # shown in the table, not on the console
            warnings.simplefilter("always", exuclear.UnitWarning)
            params = SliderCrankParams.paper(revolutions=quick_revolutions if quick else revolutions, **changes)
            _, passed, text, values = _slider_crank(params, compare, quick)
        if caught:
            text = f"UnitWarning (expected): {caught[0].message}; " + text
        return Outcome(text, passed, values)
    return run


def case_high_speed(quick: bool) -> Outcome:
    """5000 rpm: the slider-crank case, plus the reference comparison at the step bound of
    500 rpm (1e-5 s), reported but not judged (it shows why the bound scales with speed)."""
    outcome = crank_case({"crank_speed": HIGH_RPM * math.pi / 30.0})(quick)
    params = SliderCrankParams.paper(crank_speed=HIGH_RPM * math.pi / 30.0)
    fixed = agreement(params, COMPARE_TIME / (2 if quick else 1), step=1e-5)
    note = (f" (not judged: the same comparison with steps up to 1e-5 s, as at 500 rpm: max abs(de)/c {fixed.ecc:.1e}, "
            f"impacts {fixed.impacts[0]}/{fixed.impacts[1]})")
    return Outcome(outcome.measured + note, outcome.passed, {**outcome.values, "ref_ecc_step_1e-5": fixed.ecc})


def case_stick_slip(quick: bool) -> Outcome:
    """The paper's modified Coulomb law on the slider-crank: the slip must reverse in contact."""
    params = SliderCrankParams.paper(friction="paper", revolutions=QUICK_REVOLUTIONS * 2 if quick else REVOLUTIONS)
    run, passed, text, values = _slider_crank(params, True, quick)
    out = run.model.joint.outputs()
    law = run.model.joint.joint.friction
    reversals, stick, mu = slip_statistics(out, law.v_s)
    ok = reversals >= params.revolutions and mu <= law.mu_s + MU_SLACK
    text = (f"{reversals} slip reversals in contact over {params.revolutions:g} revolutions; {stick:.1%} of the "
            f"contact time in the stiction band abs(v_T) < v_s; max abs(F_T)/F_N {mu:.6f}; " + text)
    values.update(reversals=reversals, stick_share=stick, max_mu=mu)
    return Outcome(text, passed and ok, values, {"stick_slip": (params, out, law)})


def slip_statistics(out: dict[str, np.ndarray], v_s: float) -> tuple[int, float, float]:
    """Sign changes of the slip velocity between consecutive in-contact records, the share
    of contact time with ``|v_T| < v_s``, and the largest ``|F_T| / F_N``."""
    contact = out["in_contact"] > 0.0
    v = out["slip_velocity"]
    both = contact[1:] & contact[:-1]
    reversals = int(np.sum(both & (v[1:] * v[:-1] < 0.0)))
    dt = np.diff(out["time"])
    in_band = both & (np.abs(v[1:]) < v_s)
    stick = float(dt[in_band].sum() / dt[both].sum()) if both.any() else 0.0
    f_n = out["normal_force"][contact]
    mu = float(np.max(np.abs(out["tangential_force"][contact]) / f_n, initial=0.0, where=f_n > 0.0))
    return reversals, stick, mu


def case_three_joints(quick: bool) -> Outcome:
    """Clearance at O, A and B: redundant formulation, generalized-alpha."""
    params = SliderCrankParams.paper(formulation="redundant", clearance_joints=("O", "A", "B"),
                                     revolutions=QUICK_REVOLUTIONS if quick else REVOLUTIONS)
    run = run_crank(params)
    passed, text, values = _crank_summary(run)
    # slider against the ideal mechanism: each joint shifts the loop by at most c + its
    # penetration; along X directly, across through the rod angle (|tan phi| <= r / sqrt(l^2 - r^2))
    p, mbs = params, run.model.mbs
    x = np.asarray(mbs.GetSensorStoredData(run.model.sensors["slider_x"]))
    ideal = sc_reference.ideal_kinematics(p, x[:, 0])["slider_x"]
    deviation = float(np.abs(x[:, 1] - ideal).max())
    slack = sum(p.clearance + max(h.outputs()["penetration"].max(), 0.0) for h in run.model.joints.values())
    bound = (1.0 + p.crank_length / math.sqrt(p.rod_length**2 - p.crank_length**2)) * slack
    text = f"slider off the ideal mechanism by {deviation * 1e6:.1f} um (bound {bound * 1e6:.1f} um); " + text
    values.update(slider_deviation_m=deviation, deviation_bound_m=bound)
    return Outcome(text, passed and deviation <= bound, values)


# =======================================================================================
# the floor v_min
# =======================================================================================

#: Floors compared [m/s]; 1e-3 is the default (docs/physics.md eq. (17)).
FLOORS = (1e-4, 1e-3, 1e-2)
#: Impact speeds of the effective-restitution comparison [m/s] (Wang-Liu, cr = 0.5: a
#: damped law, where the floor shows).
FLOOR_SPEEDS = (1e-6, 1e-4, 1e-3, 1e-2, 0.3)
FLOOR_CR = 0.5
#: Gravity of the loaded resting journal [m/s^2]: 0.04 kg * 2500 m/s^2 = 100 N, a
#: contact force of the slider-crank's permanent contact, on the light journal: there
#: the damping term of a contact begun at v0 < v_min is stiffest, D F / (v_min m).
LOADED_GRAVITY = 2500.0


@dataclass
class FloorRow:
    """The cases of the floor study at one ``v_min``."""

    v_min: float
    restitution: dict[float, float]     # impact speed -> effective restitution
    resting_settle: float               # [s]
    resting_steps: int
    loaded_steps: int
    loaded_settle: float
    dropped_impacts: int
    dropped_last: float                 # [s]
    dropped_error: float
    crank_steps: int
    crank_impacts: int
    crank_peak: float
    wall: float


def floor_study(quick: bool, progress: Callable[[str], None]) -> tuple[list[FloorRow], dict[str, object]]:
    """Every floor of :data:`FLOORS` on the low-speed cases; the rows, and the resting
    runs (every floor) and the dropped run (default floor) for the figure."""
    rows = []
    figures: dict[str, object] = {"resting": []}
    c = JournalBearingParams.paper().joint().geometry.clearance
    speeds = FLOOR_SPEEDS[:3] if quick else FLOOR_SPEEDS
    for v_min in FLOORS:
        start = time.perf_counter()
        restitution = {}
        for v in speeds:
            p = JournalBearingParams.paper(cr=FLOOR_CR, impact_velocity=v, v_min=v_min,
                                           end_time=SLOW_IMPACT_TIME if v < 1e-2 else jb_model.DEFAULT_END_TIME)
            settings = exuclear.SolverSettings(end_time=p.end_time, method="dopri5", step=SLOW_STEP if v < 1e-2 else 1e-7,
                                               rtol=SLOW_RTOL, atol=SLOW_ATOL, output_step=1e-7)
            restitution[v] = jb_model.run(p, settings)[0].effective_restitution
        resting = run_journal(resting_params(v_min=v_min))
        loaded = run_journal(resting_params(v_min=v_min, gravity=LOADED_GRAVITY))
        dropped = run_journal(resting_params(start_gap=c, v_min=v_min, end_time=DROPPED_TIME))
        figures["resting"].append((v_min, resting))
        if v_min == exuclear.V_MIN_DEFAULT:
            figures["dropped"] = dropped
        crank = sc_model.run(SliderCrankParams.paper(v_min=v_min, revolutions=QUICK_REVOLUTIONS if quick else REVOLUTIONS))
        rows.append(FloorRow(v_min, restitution, settle_time(resting), resting.sim.steps, loaded.sim.steps,
                             settle_time(loaded), len(dropped.onsets), dropped.onsets[-1] if dropped.onsets else math.nan,
                             final_error(dropped), crank.steps, crank.impacts, crank.peak_force,
                             time.perf_counter() - start))
        progress(f"floor v_min = {v_min:g} m/s: done ({rows[-1].wall:.1f} s)")
    return rows, figures


# =======================================================================================
# the cases
# =======================================================================================

_LAWS, LAW_NOTES = low_restitution_laws()

#: Criterion shared by the slider-crank cases.
_AUDITS = ("energy audit of the minimal run within 1 % of the contact's gross work plus the flywheel's round-off, "
           "and of the same case in redundant coordinates within 1 %")
_CRANK = ("completes; all outputs finite; penetration below the joint's limit; " + _AUDITS + "; against the SciPy "
          "reference (library at rtol 1e-9, steps up to 0.03 deg of crank angle; first 20 ms, cut where a 1e-5 c "
          "perturbation of the reference exceeds 1e-3 c): max abs(de) <= 1 % of c, peak force within 1 %, same impacts")

CASES: tuple[Case, ...] = (
    Case("resting", "resting journal: set down on the bearing under gravity (Wang-Liu, cr 0.9)",
         f"settles to the analytic delta_s within {STATIC_LIMIT:g} (mean of the last 10 %); one contact onset, never "
         f"leaves the wall (no chatter); peak penetration <= the elastic step-load bound (no blow-up); finite; "
         f"audit within 1 % of gravity's work", case_resting),
    Case("dropped", "dropped journal: released at the bearing centre, falls c = 0.1 mm, bounces, comes to rest",
         f"completes; finite; no impact in the last {1 - SETTLED_SHARE:.0%} of the run (at rest); final penetration "
         f"within {STATIC_LIMIT:g} of delta_s; audit within 1 % of gravity's work", case_dropped),
    Case("slow_impact", "grazing impact at v0 = 1e-6 m/s (journal-bearing, Wang-Liu, cr 0.9)",
         "completes; the journal leaves the wall; finite; F_N >= 0; departure velocity within 1e-6 of the SciPy "
         "reference; effective restitution reported", case_slow_impact),
    *(Case(f"low_cr_{law}_{cr:g}", f"low restitution cr = {cr:g}, {law} (journal-bearing, 0.3 m/s)",
           "completes; leaves the wall; finite; F_N >= 0 at every step; departure velocity (1e-6), peak force, "
           "peak penetration and contact duration (1e-4) as the SciPy reference; effective restitution reported",
           low_restitution_case(law, cr)) for cr in LOW_CRS for law in _LAWS),
    Case("tiny_clearance", "slider-crank, clearance 1 um", _CRANK, crank_case({"clearance": 1e-6})),
    Case("large_clearance", "slider-crank, clearance 1 mm (warns: c > R_J / 10)", _CRANK,
         crank_case({"clearance": 1e-3})),
    Case("high_speed", f"slider-crank at {HIGH_RPM:g} rpm", _CRANK, case_high_speed),
    Case("long_run", f"slider-crank, {LONG_REVOLUTIONS:g} revolutions (paper case)",
         "completes; finite; penetration below the limit; " + _AUDITS + " (no reference: the motion is sensitive "
         "over long horizons)",
         crank_case({}, compare=False, revolutions=LONG_REVOLUTIONS, quick_revolutions=QUICK_LONG_REVOLUTIONS)),
    Case("long_run_friction", f"slider-crank, {LONG_REVOLUTIONS:g} revolutions with the paper's friction",
         "as the long run", crank_case({"friction": "paper"}, compare=False, revolutions=LONG_REVOLUTIONS,
                                       quick_revolutions=QUICK_LONG_REVOLUTIONS)),
    Case("aluminium", f"slider-crank, aluminium journal in a steel bearing (cr {MATERIAL_CR:g})", _CRANK,
         crank_case({"journal_material": "aluminium", "cr": MATERIAL_CR})),
    Case("polymer", f"slider-crank, polymer journal (E = 3 GPa, nu = 0.4) in a steel bearing (cr {MATERIAL_CR:g})",
         _CRANK, crank_case({"journal_material": POLYMER, "cr": MATERIAL_CR})),
    Case("stick_slip", "stick-slip: slider-crank with the modified Coulomb law (mu_s 0.3, mu_d 0.25)",
         "the slip velocity reverses in contact at least once per revolution; abs(F_T) <= mu_s F_N; " + _CRANK,
         case_stick_slip),
    Case("three_joints", "clearance at O, A and B (redundant coordinates, generalized-alpha at its default steps)",
         "completes; finite; penetrations below the limits; energy audit within 1 % of the contacts' gross work; slider "
         "within (1 + r / sqrt(l^2 - r^2)) * sum(c + max penetration) of the ideal mechanism (no reference covers "
         "three joints)", case_three_joints),
)

def _print(line: str) -> None:
    print(line, flush=True)


def run_study(quick: bool = False, progress: Callable[[str], None] = _print,
              keys: Sequence[str] | None = None) -> Study:
    """Run every case (or those in ``keys``) and the floor study."""
    start = time.perf_counter()
    cases = [c for c in CASES if keys is None or c.key in keys]
    rows = []
    for k, case in enumerate(cases, 1):
        progress(f"case {k}/{len(cases)}: {case.title} ...")
        t0 = time.perf_counter()
        try:
            outcome = case.run(quick)
        except Exception as err:  # a case that raises is a failing case, shown as such
            outcome = Outcome(f"FAILED with {type(err).__name__}: {err}", False, {})
        rows.append(Row(case, outcome, time.perf_counter() - t0))
        progress(f"case {k}/{len(cases)}: {'pass' if outcome.passed else 'FAILING'} ({rows[-1].wall_time:.1f} s)")
    floor, figures = floor_study(quick, progress) if keys is None else ([], {})
    for row in rows:
        figures.update(row.outcome.figures)
    return Study(quick, rows, floor, figures, time.perf_counter() - start)


# =======================================================================================
# report
# =======================================================================================




def cases_md(rows: Sequence[Row]) -> str:
    """The main table: case, criterion, measured value, pass/fail, wall time."""
    body = [(r.case.title, r.case.criterion, r.outcome.measured, "pass" if r.outcome.passed else "**FAILING**",
             f"{r.wall_time:.1f}") for r in rows]
    return markdown_table(("case", "criterion (fixed before the run)", "measured", "status", "wall [s]"), body)


def floor_md(rows: Sequence[FloorRow]) -> str:
    """The floor study table."""
    speeds = list(rows[0].restitution)
    header = ("v_min [m/s]", *(f"cr_eff at {v:g} m/s" for v in speeds), "resting: settled to 1 % / steps",
              "loaded resting (100 N): steps / settled to 1 %", "dropped: impacts / last [ms] / final error",
              "slider-crank: steps / impacts / peak force [N]", "wall [s]")
    body = []
    for r in rows:
        body.append((f"{r.v_min:g}", *(f"{r.restitution[v]:.4f}" for v in speeds),
                     f"{_ms(r.resting_settle)} / {r.resting_steps}",
                     f"{r.loaded_steps} / {_ms(r.loaded_settle)}",
                     f"{r.dropped_impacts} / {r.dropped_last * 1e3:.1f} / {r.dropped_error:+.1e}",
                     f"{r.crank_steps} / {r.crank_impacts} / {r.crank_peak:.0f}", f"{r.wall:.1f}"))
    return markdown_table(header, body)


def floor_conclusion(rows: Sequence[FloorRow]) -> str:
    """What the floor study shows, in numbers taken from ``rows``."""
    by = {r.v_min: r for r in rows}
    lo, mid, hi = by[FLOORS[0]], by[exuclear.V_MIN_DEFAULT], by[FLOORS[-1]]
    slow = min(lo.restitution)
    lines = [
        f"- Impacts faster than the floor do not see it: at {max(lo.restitution):g} m/s the effective restitution is "
        f"{lo.restitution[max(lo.restitution)]:.4f} / {mid.restitution[max(mid.restitution)]:.4f} / "
        f"{hi.restitution[max(hi.restitution)]:.4f} for v_min = {lo.v_min:g} / {mid.v_min:g} / {hi.v_min:g} m/s.",
        f"- Impacts slower than the floor lose less energy than cr asks: at {slow:g} m/s the effective restitution is "
        f"{lo.restitution[slow]:.4f} / {mid.restitution[slow]:.4f} / {hi.restitution[slow]:.4f} (cr = {FLOOR_CR:g}): the "
        "damping term is scaled by v0 / v_min. Such impacts carry (v0 / 0.3 m/s)^2 of a paper impact's energy, "
        f"below {(mid.v_min / 0.3) ** 2:.2g} at the default floor.",
        f"- The dropped journal makes {lo.dropped_impacts} / {mid.dropped_impacts} / {hi.dropped_impacts} impacts, the "
        f"last at {lo.dropped_last * 1e3:.1f} / {mid.dropped_last * 1e3:.1f} / {hi.dropped_last * 1e3:.1f} ms of "
        f"{DROPPED_TIME * 1e3:.0f} ms; its final penetration is off delta_s by {lo.dropped_error:+.1e} / "
        f"{mid.dropped_error:+.1e} / {hi.dropped_error:+.1e}.",
        f"- The resting journal settles to 1 % of delta_s in {_ms(lo.resting_settle)} / "
        f"{_ms(mid.resting_settle)} / {_ms(hi.resting_settle)} ({lo.resting_steps} / "
        f"{mid.resting_steps} / {hi.resting_steps} steps).",
        f"- The loaded resting journal (100 N on 0.04 kg) needs {lo.loaded_steps} / {mid.loaded_steps} / "
        f"{hi.loaded_steps} DOPRI5 steps: the damping term of a contact begun at v0 < v_min has the rate "
        "D F / (v_min m), stiff for an explicit method once it exceeds ~3 / step (and, overdamped, it creeps to "
        f"delta_s: settled in {_ms(lo.loaded_settle)} / {_ms(mid.loaded_settle)} / {_ms(hi.loaded_settle)}).",
        f"- The paper's slider-crank does not depend on the floor: {lo.crank_steps} / {mid.crank_steps} / "
        f"{hi.crank_steps} steps, {lo.crank_impacts} / {mid.crank_impacts} / {hi.crank_impacts} impacts, peak force "
        f"{lo.crank_peak:.0f} / {mid.crank_peak:.0f} / {hi.crank_peak:.0f} N.",
    ]
    # the verdict as it was written from the numbers, and the facts it rests on: checked,
    # so that a change in the numbers does not leave a verdict standing that they no longer carry
    facts = {
        f"{hi.v_min:g} m/s keeps the dropped journal bouncing longer": hi.dropped_impacts > 1.5 * mid.dropped_impacts,
        f"{lo.v_min:g} m/s makes the loaded journal stiffer": lo.loaded_steps > 2 * mid.loaded_steps,
        f"{hi.v_min:g} m/s leaves the set-down journal ringing":
            math.isnan(hi.resting_settle) or hi.resting_settle > 5 * mid.resting_settle,
        "the paper's slider-crank does not depend on the floor":
            lo.crank_impacts == mid.crank_impacts and abs(lo.crank_peak / mid.crank_peak - 1) < 1e-3,
    }
    v = mid.v_min
    if all(facts.values()):
        lines += ["", (
            f"**The floor stays at {mid.v_min:g} m/s.** {hi.v_min:g} m/s is worse on every low-speed case: slow "
            f"impacts return almost all their energy (effective restitution {hi.restitution[v]:.4f} at {v:g} m/s, "
            f"cr = {FLOOR_CR:g}), the dropped journal is still bouncing late in the run ({hi.dropped_impacts} impacts, "
            f"the last at {hi.dropped_last * 1e3:.0f} ms), and the set-down journal rings for the whole run. "
            f"{lo.v_min:g} m/s damps slow impacts as cr asks down to {lo.v_min:g} m/s and settles the set-down "
            f"journal sooner, but a contact that begins below the floor then has a damping rate "
            f"{mid.v_min / lo.v_min:.0f} times higher: {lo.loaded_steps} instead of {mid.loaded_steps} DOPRI5 steps "
            f"for the loaded journal. Impacts slower than {mid.v_min:g} m/s carry less than {(v / 0.3) ** 2:.2g} of "
            "a paper impact's energy, so the better restitution there does not pay for that stiffness. No other "
            "treatment is proposed: none was shown to be better on these cases.")]
    else:
        lines += ["", "**Review the floor**: the verdict of this study (keep 1e-3 m/s) rested on facts that these "
                      "numbers no longer show: " + "; ".join(k for k, ok in facts.items() if not ok) + "."]
    return "\n".join(lines)


def _ms(seconds: float) -> str:
    return "not within the run" if math.isnan(seconds) else f"{seconds * 1e3:.2f} ms"


def case_records(rows: Sequence[Row]) -> list[dict[str, object]]:
    return [{"case": r.case.key, "title": r.case.title, "criterion": r.case.criterion, "measured": r.outcome.measured,
             "passed": r.outcome.passed, "wall_time_s": round(r.wall_time, 3)} for r in rows]


def floor_records(rows: Sequence[FloorRow]) -> list[dict[str, object]]:
    out = []
    for r in rows:
        rec: dict[str, object] = {"v_min": r.v_min}
        rec.update({f"cr_eff_at_{v:g}": e for v, e in r.restitution.items()})
        rec.update(resting_settle_s=r.resting_settle, resting_steps=r.resting_steps, loaded_steps=r.loaded_steps,
                   loaded_settle_s=r.loaded_settle, dropped_impacts=r.dropped_impacts, dropped_last_onset_s=r.dropped_last,
                   dropped_final_error=r.dropped_error, crank_steps=r.crank_steps, crank_impacts=r.crank_impacts,
                   crank_peak_force_N=r.crank_peak, wall_time_s=round(r.wall, 3))
        out.append(rec)
    return out




def plot_resting(data: dict[str, object], directory: str) -> str:
    """Penetration against time of the resting journal at every floor (and the dropped
    journal at the default floor), with the analytic static penetration as a line."""
    import matplotlib

    matplotlib.use("Agg")  # files only
    import matplotlib.pyplot as plt

    resting = data["resting"]
    fig, axes = plt.subplots(2, 1, figsize=(7.0, 6.5))
    ax = axes[0]
    for v_min, run in resting:
        ax.plot(run.out["time"] * 1e3, run.out["penetration"] * 1e9, lw=0.9, label=f"v_min = {v_min:g} m/s")
    d_s = resting[0][1].delta_s
    ax.axhline(d_s * 1e9, color="k", ls="--", lw=1.0, label=f"static penetration (analytic) {d_s * 1e9:.2f} nm")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("penetration [nm]")
    ax.set_title("journal set down on its bearing under gravity (Wang-Liu, cr 0.9)", fontsize=10)
    ax.set_xlim(0, 8)
    ax.legend(fontsize=8)
    ax.grid(True, alpha=0.3)
    ax = axes[1]
    dropped = data.get("dropped")
    if dropped is not None:
        ax.plot(dropped.out["time"] * 1e3, dropped.out["penetration"] * 1e9, lw=0.7, label="dropped from the centre")
        ax.axhline(dropped.delta_s * 1e9, color="k", ls="--", lw=1.0, label="static penetration (analytic)")
        ax.set_ylim(-5 * dropped.delta_s * 1e9, 50 * dropped.delta_s * 1e9)
        ax.set_title(f"journal dropped from the bearing centre (v_min = {exuclear.V_MIN_DEFAULT:g} m/s); free flight "
                     "below the axis", fontsize=10)
        ax.legend(fontsize=8)
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("penetration [nm]")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    path = os.path.join(directory, "resting_journal.png")
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def plot_stick_slip(data: dict[str, object], directory: str) -> str:
    """Slip velocity and |F_T| / F_N against crank angle, with the law's v_s and v_d."""
    import matplotlib

    matplotlib.use("Agg")  # files only
    import matplotlib.pyplot as plt

    params, out, law = data["stick_slip"]
    contact = out["in_contact"] > 0.0
    angle = np.degrees(out["time"] * params.crank_speed)
    v = np.where(contact, out["slip_velocity"], np.nan)
    fig, axes = plt.subplots(2, 1, figsize=(7.5, 6.0), sharex=True)
    ax = axes[0]
    ax.plot(angle, v, lw=0.7, label="slip velocity v_T (in contact)")
    for level, style, name in ((law.v_s, ":", "v_s"), (law.v_d, "--", "v_d")):
        ax.axhline(level, color="k", ls=style, lw=0.8, label=f"±{name} = {level:g} m/s")
        ax.axhline(-level, color="k", ls=style, lw=0.8)
    ax.set_yscale("symlog", linthresh=law.v_s / 10)
    ax.set_ylabel("v_T [m/s]")
    ax.set_title("stick-slip at the clearance joint B (modified Coulomb law, mu_s 0.3, mu_d 0.25)", fontsize=10)
    ax.legend(fontsize=8, loc="upper right")
    ax.grid(True, alpha=0.3)
    ax = axes[1]
    f_n = out["normal_force"]
    mu = np.divide(out["tangential_force"], f_n, out=np.full_like(f_n, np.nan), where=contact & (f_n > 0.0))
    ax.plot(angle, mu, lw=0.7)
    for level in (law.mu_s, law.mu_d):
        ax.axhline(level, color="k", ls=":", lw=0.8)
        ax.axhline(-level, color="k", ls=":", lw=0.8)
    ax.set_ylabel("F_T / F_N")
    ax.set_xlabel("crank angle [deg]")
    # the rod turns back relative to the slider where the crank is at 90 and 270 degrees
    for turn in np.arange(90.0, angle[-1], 180.0):
        for a in axes:
            a.axvline(turn, color="0.6", lw=0.8, ls="-.")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    path = os.path.join(directory, "stick_slip.png")
    fig.savefig(path, dpi=130)
    plt.close(fig)
    return path


def _describe_defaults() -> str:
    """The slider-crank's default settings of both formulations, in words."""
    p = SliderCrankParams.paper()
    return "; ".join(f"{f}: {cc.describe_settings(sc_model.default_settings(replace(p, formulation=f)))}"
                     for f in sc_model.FORMULATIONS)


def write_report(path: str, study: Study, figures: Sequence[str]) -> str:
    failing = study.failures()
    parts = [
        "# Hard cases: numerical stability of the clearance joint\n",
        "Source problem: the clearance joint of `docs/physics.md` (Wang, Liu, Ma, Tong, J. Mech. Sci. Technol. "
        "31(2) (2017) 587-597): the journal-bearing scene (5.1) and the slider-crank (5.2), at the edges of their "
        f"use. Command: `python -m validation.hard_cases{' --quick' if study.quick else ''}`"
        f"{' (quick run: shorter runs)' if study.quick else ''}; total runtime {study.runtime:.0f} s. Wall times are "
        "single runs on a shared 2-core machine: indicative only.\n",
        "Defaults unless a case says otherwise: Wang-Liu law, steel on steel, no friction, the paper's dimensions; "
        f"slider-crank in minimal coordinates at `models.slider_crank.default_settings` ({_describe_defaults()}), outputs at every "
        "accepted step; energy audit as in the module docstring (drive work from the flywheel, elastic energy "
        "exact, dissipation by the trapezoid rule over the steps).\n",
        "Static penetration of the resting journal: K_eff(delta_s) delta_s^1.5 = m g with K_eff(delta) = "
        "(pi E* L / 2) sqrt(1 / (2 (c + delta))), solved by Brent's method: "
        + (f"delta_s = {study.rows[0].outcome.values['delta_s_m'] * 1e9:.4f} nm for m = "
           f"{JournalBearingParams.paper().mass:g} kg, g = {GRAVITY:g} m/s^2.\n"
           if study.rows and "delta_s_m" in study.rows[0].outcome.values else "see the module docstring.\n"),
        "## Cases\n",
        cases_md(study.rows) + "\n",
    ]
    if LAW_NOTES:
        parts.append("Not run at low restitution (the law rejects it): " + "; ".join(LAW_NOTES) + ".\n")
    parts.append("## Failing cases\n")
    parts.append("\n".join(f"- {r.case.title}: {r.outcome.measured}" for r in failing) + "\n" if failing
                 else "No case fails.\n")
    if study.floor:
        parts += [
            "## The floor v_min of the onset velocity\n",
            "Grazing and permanent contact make the onset velocity v0 tiny; the damping term D delta_dot / v0 is "
            f"then evaluated with max(v0, v_min) (docs/physics.md eq. (17)). Floors compared: {', '.join(f'{v:g}' for v in FLOORS)} m/s. "
            f"Effective restitution: Wang-Liu law, cr = {FLOOR_CR:g}, the paper's journal-bearing scene at the impact "
            "speeds shown. Resting: the journal set down at rest under gravity (as in the case above); loaded "
            f"resting: the same under {LOADED_GRAVITY:g} m/s^2 (100 N); dropped: released at the centre; slider-crank: "
            "the paper case (cr 0.9).\n",
            floor_md(study.floor) + "\n",
            floor_conclusion(study.floor) + "\n",
        ]
    if figures:
        parts.append("## Figures\n")
        parts += [f"![{os.path.basename(f)}]({os.path.basename(f)})\n" for f in figures]
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(parts))
    return path


def write_outputs(study: Study, directory: str) -> list[str]:
    """Report, CSV tables and figures; returns the paths."""
    os.makedirs(directory, exist_ok=True)
    figures = []
    if "resting" in study.figures:
        figures.append(plot_resting(study.figures, directory))
    if "stick_slip" in study.figures:
        figures.append(plot_stick_slip(study.figures, directory))
    paths = [write_csv(os.path.join(directory, "hard_cases.csv"), case_records(study.rows))]
    if study.floor:
        paths.append(write_csv(os.path.join(directory, "v_min_floor.csv"), floor_records(study.floor)))
    paths.append(write_report(os.path.join(directory, "hard_cases.md"), study, figures))
    return paths + figures


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="python -m validation.hard_cases", description=__doc__.split("\n")[0])
    ap.add_argument("--out", metavar="DIR", default=DEFAULT_OUT, help="directory of the report (default %(default)s)")
    ap.add_argument("--quick", action="store_true", help="shorter runs (under a minute)")
    return ap


def main(argv: list[str] | None = None) -> int:
    """Run the study and write the report; 1 if a case failed."""
    args = _parser().parse_args(argv)
    study = run_study(quick=args.quick)
    for path in write_outputs(study, args.out):
        print(f"wrote {path}")
    print(f"total runtime {study.runtime:.1f} s")
    for row in study.failures():
        print(f"error: FAILING: {row.case.title}: {row.outcome.measured}", file=sys.stderr)
    return 1 if study.failures() else 0


if __name__ == "__main__":
    sys.exit(main())
