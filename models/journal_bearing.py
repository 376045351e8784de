"""Journal-bearing impact: the paper's example 1 (docs/physics.md section 6.1), in Exudyn.

::

        bearing hole, radius R_B, fixed to the ground
           .-------.
          /  .---.  \\
         |  ( J   )->|   journal, radius R_J, mass m, touching the wall at t = 0
          \\  '---'  /    and moving along the normal into it at v_impact
           '-------'

One impact: the journal (an ``ObjectRigidBody2D``) starts at eccentricity ``e = c``
(``delta = 0``) with velocity ``v_impact`` along ``n``; no gravity, no friction, no
rotation.  The run ends once the journal has left the wall.

The same scene with gravity (``JournalBearingParams.gravity``, along +X: the bearing is
drawn lying on its side, "down" points at the wall) and a gap at the start
(``start_gap``) is a journal resting on its bearing (``start_gap = 0``,
``v_impact = 0``) or dropped onto it from the centre (``start_gap = c``): build it with
:func:`build` and integrate it with :func:`exuclear.simulate`.

**With oil** (``viscosity``, ``film_model``) the paper's start means nothing: a journal
touching the wall has no film between it and the wall.  The lubricated scene is the
*approach* (:meth:`JournalBearingParams.approach`, :func:`run_approach`): the paper's journal
starts at the centre of its bearing and moves towards the wall at the paper's impact
velocity, through the clearance the dry journal crosses in free flight.  Dry, it hits the
wall at that velocity; lubricated, the squeeze film between journal and wall slows it down
(docs/physics.md eq. (66)), and the summary says how far it came (largest eccentricity
ratio, smallest film thickness) and with which forces (metal contact, film, the two
together), dry and lubricated side by side on the command line (``--viscosity``).

Run ``python -m exuclear.models.journal_bearing --help`` for the options: one per
:class:`JournalBearingParams` field of the paper's scene, and the outputs.
"""
from __future__ import annotations

import argparse
import json
import math
import sys
import time
from dataclasses import asdict, dataclass, field, replace

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadMassProportional,
    MarkerBodyMass,
    MarkerBodyRigid,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
)

import exuclear
from exuclear import SolverSettings
from exuclear.columns import Column
from exuclear.engine import OUTPUT_COLUMNS
from exuclear.engine.outputs import FILM_OUTPUT_COLUMNS

from ._cli import SceneRun, Table, run_main, scene_parser
from ._joint_fields import joint_field, joint_fields, scene_joint, scene_params
from ._lubricant import FILM_MODEL_DEFAULT, joint_force, lubrication
from ._params import (
    changes_from_args,
    check_fields,
    nonnegative,
    param,
    positive,
    study_columns,
)
from .scene import Scene

#: Resolution of the impact: the largest step and the output interval [s].  A paper
#: impact lasts about 40 us (docs/physics.md section 8), so this samples it ~400 times.
IMPACT_STEP = 1e-7
#: Relative slack on ``start_gap <= c``: R_B - R_J is not exact in floating point
#: (10 mm - 9.9 mm = 0.1 mm - 3e-20 m), and a journal started 1e-20 m past the centre is
#: still centred.
GAP_ROUNDOFF = 1e-9
#: The run stops this long after the start [s]: several impact durations.  The result
#: reports an error if the journal has not left the wall by then.
DEFAULT_END_TIME = 4e-4
#: End of the approach scene [s] (:meth:`JournalBearingParams.approach`): three times the
#: dry journal's flight across the paper's clearance (0.1 mm at 0.3 m/s: 0.33 ms), so that
#: the dry journal's impact and rebound lie inside it, and a lubricated journal has come
#: to rest on its squeeze film (the film's damping time ``m / d`` is microseconds here).
APPROACH_END_TIME = 1e-3


@scene_params
class JournalBearingParams:
    """Parameters of the journal-bearing impact (SI units).

    Use :meth:`paper` for the paper's values.  ``gravity`` and ``start_gap`` (both 0 in
    the paper) turn the scene into a journal resting on, or dropped onto, its bearing.
    """

    _joint_fields = joint_fields("law", "cr", "journal_material", "bearing_material", "journal_radius", "bearing_radius",
                                 "length")
    mass: float = field(metadata=param("journal mass [kg]", positive))
    impact_velocity: float = field(metadata=param("impact velocity [m/s]", nonnegative, option="velocity"))
    v_min: float = joint_field("v_min")
    end_time: float = field(default=DEFAULT_END_TIME, metadata=param(
        "simulated time [s]; the journal must have left the wall by then", positive))
    #: Gravitational acceleration [m/s^2] along +X, towards the wall the journal starts
    #: at; 0 in the paper's scene (so not an option of its command line, which summarises it).
    gravity: float = field(default=0.0, metadata=param("gravity along +X [m/s^2]", nonnegative, cli=False))
    #: Distance [m] between journal and wall at t = 0, in [0, c]: 0 touching (the paper),
    #: c centred.
    start_gap: float = field(default=0.0, metadata=param("gap at t = 0 [m]", nonnegative, cli=False))
    # viscosity None (the default): a dry joint, the paper's scene
    _more_joint_fields = joint_fields("backend", "max_penetration", "viscosity", "film_model", help={"viscosity": (
        "dynamic viscosity of the oil in the clearance [Pa s] (default: none, dry); given, the command line runs "
        "the approach scene (the journal from the centre, 1 ms unless --end-time is given), dry and lubricated")})

    @classmethod
    def paper(cls, **changes: object) -> JournalBearingParams:
        """The paper's example 1: steel on steel, L = 15 mm, R_B = 10 mm, R_J = 9.9 mm,
        m = 0.04 kg, 0.3 m/s, Wang-Liu law, cr = 0.9 (its bearing-length sweep)."""
        base = cls(law="wang-liu", cr=0.9, journal_material="steel", bearing_material="steel",
                   journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, mass=0.04,
                   impact_velocity=0.3)
        return replace(base, **changes)

    @classmethod
    def approach(cls, **changes: object) -> JournalBearingParams:
        """The approach scene (module docstring): the paper's journal and bearing, the journal
        started at the centre (``start_gap`` = c) towards the wall at the paper's 0.3 m/s,
        :data:`APPROACH_END_TIME`; dry unless ``viscosity`` is given."""
        base = cls.paper(**{"end_time": APPROACH_END_TIME, **changes})
        if "start_gap" in changes:
            return base
        return replace(base, start_gap=base.bearing_radius - base.journal_radius)

    def __post_init__(self) -> None:
        check_fields(self)
        lubrication(self.viscosity, self.film_model)  # a film model without oil is refused here, not at joint()

    def joint(self) -> exuclear.ClearanceJoint:
        return scene_joint(self)


def build(params: JournalBearingParams) -> Scene:
    """Build the scene: its joint ``"journal-bearing"`` (``Scene.joint``) and the journal's
    node ``nodes["journal"]``."""
    start = time.perf_counter()
    joint = params.joint()  # checks all physical parameters before anything is built
    c = joint.geometry.clearance
    gap = params.start_gap
    if gap > c * (1.0 + GAP_ROUNDOFF):
        raise ValueError(f"`start_gap` must not exceed the clearance {c:g} m (the journal starts inside the "
                         f"bearing), got {gap:g}")
    if params.impact_velocity == 0.0 and params.gravity == 0.0:
        raise ValueError("nothing moves: give a positive `impact_velocity` or `gravity`")
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[c - gap, 0.0, 0.0],
                                       initialVelocities=[params.impact_velocity, 0.0, 0.0]))
    # a solid cylinder; the inertia never matters here (no friction, no rotation)
    journal = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=params.mass,
                                              inertia=0.5 * params.mass * params.journal_radius**2))
    if params.gravity > 0.0:
        mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=journal)),
                                         loadVector=[params.gravity, 0.0, 0.0]))
    markers = [mbs.AddMarker(MarkerBodyRigid(bodyNumber=body, localPosition=[0.0, 0.0, 0.0]))
               for body in (ground, journal)]  # bearing, journal: each at its body's reference point
    handle = exuclear.AddClearanceJoint(mbs, markers, joint=joint, name="journal-bearing", backend=params.backend,
                                        maxPenetration=params.max_penetration)
    mbs.Assemble()
    return Scene(params, mbs, {handle.name: handle}, nodes={"journal": int(node)},
                 build_time=time.perf_counter() - start, main_joint=handle.name)


@dataclass(frozen=True)
class ImpactResult:
    """Summary of one impact (SI units); ``success`` False with ``message`` if it failed."""

    law: str
    cr: float
    length: float
    journal_material: str
    bearing_material: str
    impact_velocity: float
    departure_velocity: float
    max_force: float
    max_penetration: float
    contact_duration: float
    newton_departure_velocity: float
    effective_restitution: float
    wall_time: float
    success: bool
    message: str


def default_settings(params: JournalBearingParams) -> SolverSettings:
    """DOPRI5 with steps no longer than :data:`IMPACT_STEP`; tolerances far below the
    micrometre penetrations (atol 1e-13 m)."""
    return SolverSettings(end_time=params.end_time, method="dopri5", step=IMPACT_STEP,
                          rtol=1e-9, atol=1e-13, output_step=IMPACT_STEP / 10)


def run(params: JournalBearingParams, settings: SolverSettings | None = None) -> tuple[ImpactResult, dict[str, np.ndarray]]:
    """Simulate one impact; returns the summary and the joint's recorded outputs.

    The summary is that of the paper's scene: contact from t = 0 at ``impact_velocity``
    (> 0), no gravity, no gap at the start.
    """
    if params.gravity != 0.0 or params.start_gap != 0.0:
        raise ValueError("run() summarises one impact that starts at t = 0 without gravity; for a resting or "
                         "dropped journal (`gravity`, `start_gap`) use build() and exuclear.simulate()")
    if params.viscosity is not None:
        raise ValueError("run() summarises the paper's impact, which starts touching the wall: no oil film is "
                         "left there; for a lubricated journal use the approach scene (run_approach, "
                         "JournalBearingParams.approach)")
    positive("impact_velocity", params.impact_velocity)
    scene = build(params)
    settings = settings or default_settings(params)
    sim = exuclear.simulate(scene.mbs, settings)
    out = scene.joint.outputs()
    v_end = scene.mbs.GetNodeOutput(scene.nodes["journal"], exu.OutputVariableType.Velocity)
    departure = -float(v_end[0])  # free flight after the impact: velocity is constant
    delta = out["penetration"]
    left = np.flatnonzero((delta[:-1] > 0.0) & (delta[1:] <= 0.0))
    success, message = sim.success, sim.message
    if success and len(left) == 0:
        success, message = False, f"the journal had not left the wall at t = {params.end_time} s; raise `end_time` (--end-time)"
    duration = math.nan
    if len(left):
        k = left[0]  # interpolate the release instant between the two samples
        t = out["time"]
        duration = float(t[k] + (t[k + 1] - t[k]) * delta[k] / (delta[k] - delta[k + 1]))
    result = ImpactResult(
        law=params.law, cr=params.cr, length=params.length, journal_material=params.journal_material,
        bearing_material=params.bearing_material, impact_velocity=params.impact_velocity,
        departure_velocity=departure, max_force=float(out["normal_force"].max()),
        max_penetration=float(delta.max()), contact_duration=duration,
        newton_departure_velocity=params.cr * params.impact_velocity,
        effective_restitution=departure / params.impact_velocity, wall_time=sim.wall_time,
        success=success, message=message)
    return result, out


@dataclass(frozen=True)
class ApproachResult:
    """Summary of the approach scene (SI units); ``success`` False with ``message`` if it
    failed.  Forces: ``peak_contact_force`` the metal contact's, ``peak_film_force`` the oil
    film's (0 dry), ``peak_joint_force`` the two together (:func:`joint_force`)."""

    viscosity: float | None
    film_model: str | None
    impact_velocity: float
    start_gap: float
    peak_contact_force: float
    peak_film_force: float
    peak_joint_force: float
    max_eccentricity_ratio: float
    min_film_thickness: float  # c - |e| at its smallest: negative where the journal penetrated the wall
    max_penetration: float
    contact_onsets: int
    final_velocity: float  # the journal's velocity along the approach at the end [m/s]; negative: rebounding
    wall_time: float
    success: bool
    message: str


def run_approach(params: JournalBearingParams,
                 settings: SolverSettings | None = None) -> tuple[ApproachResult, dict[str, np.ndarray]]:
    """Simulate the approach scene (:meth:`JournalBearingParams.approach`; any ``start_gap``
    > 0) and summarise it; returns the summary and the joint's recorded outputs."""
    if params.start_gap <= 0.0:
        raise ValueError("the approach starts with a gap between journal and wall: give `start_gap` > 0 "
                         "(JournalBearingParams.approach starts at the centre)")
    scene = build(params)
    sim = exuclear.simulate(scene.mbs, settings or default_settings(params))
    out = scene.joint.outputs()
    c = scene.joint.joint.geometry.clearance
    ecc = np.hypot(out["ecc_x"], out["ecc_y"])
    lubricated = params.viscosity is not None
    contact = np.hypot(out["normal_force"], out["tangential_force"])
    velocity = scene.mbs.GetNodeOutput(scene.nodes["journal"], exu.OutputVariableType.Velocity)
    result = ApproachResult(
        viscosity=params.viscosity, film_model=params.film_model if lubricated else None,
        impact_velocity=params.impact_velocity, start_gap=params.start_gap,
        peak_contact_force=float(contact.max()),
        peak_film_force=float(out["film_force"].max()) if lubricated else 0.0,
        peak_joint_force=float((joint_force(out) if lubricated else contact).max()),
        max_eccentricity_ratio=float(ecc.max() / c), min_film_thickness=float(c - ecc.max()),
        max_penetration=max(float(out["penetration"].max()), 0.0),
        contact_onsets=len(scene.joint.history.onset_times), final_velocity=float(velocity[0]),
        wall_time=sim.wall_time, success=sim.success, message=sim.message)
    return result, out


def plot(results: list[tuple[str, dict[str, np.ndarray]]], directory: str, stem: str = "journal_bearing") -> list[str]:
    """Write the force-penetration and rate-penetration plots of the paper's Figs. 4-7."""
    from exuclear.models.figures import impact_curves

    return impact_curves(results, directory, stem)


def _parser() -> argparse.ArgumentParser:
    """The command line: one option per :class:`JournalBearingParams` field;
    defaults :meth:`JournalBearingParams.paper`."""
    ap = scene_parser("journal_bearing", __doc__, JournalBearingParams.paper())
    ap.add_argument("--dt-out", type=float, default=IMPACT_STEP / 10,
                    help="output interval [s]; the summary's peak force, peak penetration and contact duration "
                         "come from these outputs, so a coarser interval samples the impact (~40 us) coarsely "
                         "(default %(default)s)")
    ap.add_argument("--csv", metavar="FILE",
                    help="write the joint's time series (columns: time, " + ", ".join(OUTPUT_COLUMNS) + ")")
    ap.add_argument("--json", action="store_true", help="print one JSON object instead of the summary")
    ap.add_argument("--plot", metavar="DIR", help="write force-penetration and rate-penetration plots to DIR")
    return ap


class _ImpactRun(SceneRun):
    """The command line's run (:func:`~exuclear.models._cli.run_main`): the paper's impact with
    the options' changes, its summary (or JSON) and its force-penetration figures."""

    def prepare(self, law: str, cr: float) -> None:
        self.params = JournalBearingParams.paper(**changes_from_args(self.args, JournalBearingParams), law=law, cr=cr)
        self.settings = replace(default_settings(self.params), output_step=positive("--dt-out", self.args.dt_out))

    def simulate(self) -> None:
        self.result, self.out = run(self.params, self.settings)

    def summary(self) -> None:
        result = self.result
        if self.args.json:
            print(json.dumps(asdict(result)))
            return
        incomplete = "" if result.success else " (INCOMPLETE: see the error below; values up to the stop)"
        print(f"journal-bearing impact{incomplete}: {result.law}, cr = {result.cr}, L = {result.length * 1e3:g} mm, "
              f"{result.journal_material} journal in {result.bearing_material} bearing")
        print(f"  impact velocity     {result.impact_velocity:.4f} m/s")
        print(f"  departure velocity  {result.departure_velocity:.4f} m/s  (Newton cr*v: {result.newton_departure_velocity:.4f})")
        print(f"  max contact force   {result.max_force:.1f} N")
        print(f"  max penetration     {result.max_penetration * 1e6:.4f} um")
        print(f"  contact duration    {result.contact_duration * 1e6:.2f} us")
        print(f"  wall time           {result.wall_time:.3f} s")

    def table(self) -> Table:
        return Table(self.out, ("time", *OUTPUT_COLUMNS), self.incomplete)

    def plots(self, directory: str) -> list[str]:
        return plot([(f"{self.result.law}, cr = {self.result.cr}", self.out)], directory)


#: The approach scene's summary lines: (label, :class:`ApproachResult` field, scale, unit).
APPROACH_LINES = (
    ("peak contact force (metal)", "peak_contact_force", 1.0, "N"),
    ("peak film force", "peak_film_force", 1.0, "N"),
    ("peak joint force", "peak_joint_force", 1.0, "N"),
    ("largest eccentricity ratio", "max_eccentricity_ratio", 1.0, ""),
    ("smallest film c - |e|", "min_film_thickness", 1e6, "um"),
    ("contact onsets", "contact_onsets", 1.0, ""),
    ("velocity at the end", "final_velocity", 1.0, "m/s"),
    ("wall time", "wall_time", 1.0, "s"),
)


class _ApproachRun(SceneRun):
    """``--viscosity``: the approach scene (module docstring), dry and lubricated side by side;
    its own end time unless ``--end-time`` was given."""

    def prepare(self, law: str, cr: float) -> None:
        args = self.args
        if args.plot is not None:
            raise ValueError("`--plot` draws the paper's impact (force against penetration); with --viscosity the "
                             "scene is the approach from the centre: use --csv for its time series")
        changes = changes_from_args(args, JournalBearingParams)
        if not any(a.split("=")[0] == "--end-time" for a in self.argv):  # the paper impact's default: the approach has its own
            del changes["end_time"]
        self.oiled = JournalBearingParams.approach(**changes, law=law, cr=cr)
        self.dry = replace(self.oiled, viscosity=None, film_model=FILM_MODEL_DEFAULT)
        self.settings = replace(default_settings(self.oiled), output_step=positive("--dt-out", args.dt_out))

    def simulate(self) -> None:
        (self.dry_result, _), (self.result, self.out) = [run_approach(p, self.settings) for p in (self.dry, self.oiled)]

    def summary(self) -> None:
        r_dry, r_oil, oiled = self.dry_result, self.result, self.oiled
        if self.args.json:
            print(json.dumps({"dry": asdict(r_dry), "lubricated": asdict(r_oil)}))
            return
        print(f"journal-bearing approach: from the centre towards the wall at {oiled.impact_velocity:g} m/s, "
              f"{oiled.law}, cr = {oiled.cr}; oil {oiled.viscosity:g} Pa s, {oiled.film_model} film")
        print(f"  {'':28s} {'dry':>12s} {'lubricated':>12s}")
        for label, name, scale, unit in APPROACH_LINES:
            values = [getattr(r, name) * scale for r in (r_dry, r_oil)]
            print(f"  {label:28s} {values[0]:12.4g} {values[1]:12.4g}  {unit}")

    def table(self) -> Table:
        """The lubricated run's outputs; INCOMPLETE where that run stopped early."""
        return Table(self.out, ("time", *OUTPUT_COLUMNS, *FILM_OUTPUT_COLUMNS), self.incomplete)

    def errors(self) -> list[str]:
        return [f"{kind}: {r.message}" for kind, r in (("dry", self.dry_result), ("lubricated", self.result))
                if not r.success]


def _scene_run(args: argparse.Namespace, argv: list[str]) -> SceneRun:
    """The paper's impact, or with ``--viscosity`` the approach scene."""
    return (_ImpactRun if args.viscosity is None else _ApproachRun)(args, argv)


def main(argv: list[str] | None = None) -> int:
    return run_main(argv, _parser(), _scene_run)


# =======================================================================================
# the journal-bearing impact as a parameter study (exuclear.study)
# =======================================================================================

#: Parameters of :func:`study` and their defaults (:meth:`JournalBearingParams.paper`):
#: :class:`JournalBearingParams` fields of the paper's scene (no gravity, no start gap).
STUDY_PARAMETERS = {name: getattr(JournalBearingParams.paper(), name) for name in (
    "law", "cr", "length", "journal_material", "bearing_material", "journal_radius", "bearing_radius", "mass",
    "impact_velocity", "v_min", "backend")}


#: The metrics of :func:`study`: what each is, its unit (axis labels of study plots).
STUDY_METRICS = {
    "peak_force": Column("peak contact force", "N"),
    "max_penetration": Column("largest penetration", "m"),
    "max_ecc_over_c": Column("largest |e| / c (1 + max penetration / c)"),
    "departure_velocity": Column("departure velocity", "m/s"),
    "effective_restitution": Column("effective restitution (departure / impact velocity)"),
    "contact_duration": Column("contact duration", "s"),
    "impacts": Column("impacts (1 when the journal left the wall)"),
    # the energy audit: kinetic energy before minus after, against int (F_N - F_el) delta' dt
    # (trapezoid rule over the outputs)
    "energy_lost": Column("kinetic energy lost", "J"),
    "contact_dissipated": Column("energy dissipated by the contact", "J"),
    "energy_residual_rel": Column("energy residual / energy lost"),
    "sim_wall_time": Column("solver wall time", "s"),
}

#: Parameters (from the :class:`JournalBearingParams` fields: help, unit, the command line's
#: other spellings) and metrics of the study, for ``python -m exuclear.study`` and its plots.
STUDY_COLUMNS = {**study_columns(JournalBearingParams, STUDY_PARAMETERS), **STUDY_METRICS}


def study_params(values: dict) -> JournalBearingParams:
    """The :class:`JournalBearingParams` of a study's parameter set (defaults
    :data:`STUDY_PARAMETERS`); ``ValueError`` for a value the scene refuses."""
    unknown = sorted(set(values) - set(STUDY_PARAMETERS))
    if unknown:
        raise ValueError(f"unknown study parameters {unknown}; known: {', '.join(STUDY_PARAMETERS)}")
    params = JournalBearingParams.paper(**{**STUDY_PARAMETERS, **values})
    params.joint()  # checks the physical parameters
    positive("impact_velocity", params.impact_velocity)
    return params


def check_study(values: dict) -> None:
    """Raise ``ValueError`` for a study parameter set the scene refuses (before any run)."""
    study_params(values)


def study(values: dict) -> dict:
    """One impact of a journal-bearing study (:mod:`exuclear.study`); parameters
    :data:`STUDY_PARAMETERS`.

    Returns
    -------
    dict
        The metrics of :data:`STUDY_METRICS` (meaning and unit there); ``success`` and
        ``message`` of the run.
    """
    params = study_params(values)
    result, out = run(params)
    law = params.joint().law
    delta, rate = out["penetration"], out["penetration_rate"]
    elastic = np.array([law.elastic_force(d) if d > 0.0 else 0.0 for d in delta])
    dissipated = float(np.trapezoid((out["normal_force"] - elastic) * rate, out["time"]))
    lost = 0.5 * params.mass * (params.impact_velocity**2 - result.departure_velocity**2)
    clearance = params.bearing_radius - params.journal_radius
    return {
        "peak_force": result.max_force, "max_penetration": result.max_penetration,
        "max_ecc_over_c": 1.0 + result.max_penetration / clearance,
        "departure_velocity": result.departure_velocity, "effective_restitution": result.effective_restitution,
        "contact_duration": result.contact_duration, "impacts": int(math.isfinite(result.contact_duration)),
        "energy_lost": lost, "contact_dissipated": dissipated,
        "energy_residual_rel": (lost - dissipated) / lost if lost > 0.0 else math.nan,
        "sim_wall_time": result.wall_time, "success": result.success, "message": result.message,
    }


if __name__ == "__main__":
    sys.exit(main())
