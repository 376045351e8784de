"""Four-bar linkage (crank-rocker) with one revolute clearance joint, between coupler and rocker.

::

                      B (clearance joint: journal on the coupler,
              coupler   .o      bearing hole in the rocker)
         A o'''''''''''' |
          /   b          |  rocker
       a / theta         |  c
        /                |
   O2  o-----------------o  O4        ground link d, O2 at the origin, O4 at (d, 0)
   crank turns at a constant omega     (ideal revolute joints at O2, A, O4)

Built as the slider-crank's redundant formulation is: ``ObjectRigidBody2D`` links
(nodes at the link midpoints), ideal ``JointRevolute2D`` joints at O2, A and O4, the
crank speed held by a velocity-level ``CoordinateConstraint`` on the crank angle (its
Lagrange multiplier is the driving moment), and the clearance joint at B through
:func:`exuclear.AddClearanceJoint`.  Needs an implicit solver (generalized-alpha by
default, with impact-aware steps).

The four-bar is the textbook scene where clearance-joint motion turns chaotic: after
a few start-up impacts, runs at different steps follow different impact sequences
(see :func:`exuclear.check_convergence` and ``--check-convergence``).

Run ``python -m exuclear.models.four_bar --help`` for the command line: one option per
:class:`FourBarParams` field, the crank speed in rpm and the solver settings.
"""
from __future__ import annotations

import argparse
import math
import sys
import time
from dataclasses import dataclass, field, replace

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadMassProportional,
    MarkerBodyMass,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    NodePointGround,
    NodeRigidBody2D,
    ObjectConnectorCoordinate,
    ObjectGround,
    ObjectJointRevolute2D,
    ObjectRigidBody2D,
    SensorNode,
    SensorObject,
)

import exuclear
from exuclear import SolverSettings
from exuclear import convergence as _convergence
from exuclear.settings import METHODS

from ._cli import SceneRun, Table, add_rpm_option, run_main, scene_parser
from ._joint_fields import joint_fields, scene_joint, scene_params
from ._params import (
    changes_from_args,
    check_fields,
    crank_speed_from_rpm,
    nonnegative,
    nonzero,
    param,
    positive,
    real,
)
from .scene import Scene

#: Output columns of a run (SI units, angles in degrees), in CSV order.
COLUMNS = ("time", "crank_angle", "coupler_angle", "rocker_angle", "rocker_rate", "crank_moment",
           "contact_force", "ecc_x", "ecc_y", "penetration", "in_contact")

#: Default settings: those of the slider-crank's redundant formulation (generalized-alpha,
#: 2e-5 s in free flight and steady contact, 1e-6 s from each contact onset), chosen there
#: by ``validation/cost/work_precision.py`` for impacts of the same contact law and clearance.
DEFAULT_SETTINGS = {"method": "generalized-alpha", "step": 2e-5, "impact_step": 1e-6}


@scene_params
class FourBarParams:
    """Parameters of the four-bar (SI units); :meth:`crank_rocker` gives the documented case.

    Parameters
    ----------
    crank_length, coupler_length, rocker_length, ground_length : float
        ``a`` (O2-A), ``b`` (A-B), ``c`` (O4-B), ``d`` (O2-O4) [m]; the crank must turn
        fully (Grashof: the crank is the shortest link and ``s + l < p + q``).
    crank_mass, coupler_mass, rocker_mass : float
        Masses [kg], centres of mass at the link midpoints.
    crank_inertia, coupler_inertia, rocker_inertia : float
        Inertias about the centres of mass [kg m^2].
    crank_speed : float
        Constant crank angular speed [rad/s], non-zero, positive counter-clockwise; crank
        angle ``crank_angle0`` at t = 0.
    crank_angle0 : float
        Crank angle at t = 0 [rad], from O2 towards O4.
    revolutions : float
        Simulated crank revolutions (end time ``2 pi revolutions / |crank_speed|``).
    gravity : float
        Gravitational acceleration along -Y [m/s^2].
    bearing_radius, clearance, bearing_length : float
        The clearance joint at B: ``R_B``, ``c = R_B - R_J`` and ``L`` [m].
    law, cr, journal_material, bearing_material, friction, v_min
        The clearance joint's physics, as in :func:`exuclear.make_joint`.
    backend : str
        How the clearance joint's forces are evaluated (:data:`exuclear.engine.BACKENDS`).
    max_penetration : float, optional
        Penetration [m] beyond which a run stops; None: the library's default bound.
    """

    crank_length: float = field(metadata=param("crank length a, O2-A [m]", positive))
    coupler_length: float = field(metadata=param("coupler length b, A-B [m]", positive))
    rocker_length: float = field(metadata=param("rocker length c, O4-B [m]", positive))
    ground_length: float = field(metadata=param("ground length d, O2-O4 [m]", positive))
    crank_mass: float = field(metadata=param("crank mass [kg]", positive))
    coupler_mass: float = field(metadata=param("coupler mass [kg]", positive))
    rocker_mass: float = field(metadata=param("rocker mass [kg]", positive))
    crank_inertia: float = field(metadata=param("crank inertia about its centre of mass [kg m^2]", positive))
    coupler_inertia: float = field(metadata=param("coupler inertia about its centre of mass [kg m^2]", positive))
    rocker_inertia: float = field(metadata=param("rocker inertia about its centre of mass [kg m^2]", positive))
    crank_speed: float = field(metadata=param(
        "crank speed [rad/s]", nonzero("positive counter-clockwise, negative clockwise"), cli=False))  # --rpm
    revolutions: float = field(metadata=param("crank revolutions", positive))
    gravity: float = field(metadata=param("gravity along -Y [m/s^2]", nonnegative))
    _joint_fields = joint_fields("bearing_radius", "clearance", "bearing_length", "law", "cr", "journal_material",
                                 "bearing_material", "friction", help={"bearing_radius": "bearing radius R_B at B [m]"})
    crank_angle0: float = field(default=0.0, metadata=param("crank angle at t = 0, from O2 towards O4 [rad]", real))
    _more_joint_fields = joint_fields("v_min", "backend", "max_penetration", "wear_coefficient", "wear_surface",
                                      "wear_pressure")
    _joint: exuclear.ClearanceJoint | None = field(default=None, init=False, repr=False, compare=False)

    @classmethod
    def crank_rocker(cls, **changes: object) -> FourBarParams:
        """A stated plausible crank-rocker, not a published case (no paper's table of a
        four-bar with a clearance joint could be found with all its numbers).

        Links: crank a = 0.05 m, coupler b = 0.25 m, rocker c = 0.20 m, ground d = 0.30 m
        (Grashof crank-rocker: 0.05 + 0.30 < 0.25 + 0.20).  Steel bars of the slider-crank
        paper's section (Wang et al. 2017: 0.194 kg for its 0.05 m crank, i.e. 3.9 kg/m)
        give 0.194, 0.97 and 0.78 kg, inertias ``m l^2 / 12``.  The joint at B is the
        slider-crank paper's (R_B = 10 mm, L = 15 mm, steel on steel, Wang-Liu law with
        cr = 0.9, no friction) with a worn clearance of c = 0.5 mm, the size four-bar
        studies of clearance joints commonly use.  300 rpm, gravity 9.81 m/s^2,
        4 revolutions (0.8 s): about 100 impacts, and no settling into permanent contact
        (with c = 0.1 mm at 500 rpm the journal settles after 19 impacts).
        """
        line_density = 0.194 / 0.05  # [kg/m], the paper's crank
        a, b, c, d = 0.05, 0.25, 0.20, 0.30
        m = {k: line_density * length for k, length in (("crank", a), ("coupler", b), ("rocker", c))}
        base = cls(crank_length=a, coupler_length=b, rocker_length=c, ground_length=d,
                   crank_mass=m["crank"], coupler_mass=m["coupler"], rocker_mass=m["rocker"],
                   crank_inertia=m["crank"] * a**2 / 12.0, coupler_inertia=m["coupler"] * b**2 / 12.0,
                   rocker_inertia=m["rocker"] * c**2 / 12.0, crank_speed=300.0 * math.pi / 30.0,
                   revolutions=4.0, gravity=9.81, bearing_radius=10e-3, clearance=0.5e-3, bearing_length=15e-3,
                   law="wang-liu", cr=0.9, journal_material="steel", bearing_material="steel", friction="none")
        return replace(base, **changes)

    def __post_init__(self) -> None:
        check_fields(self)
        lengths = {k: float(getattr(self, k)) for k in ("crank_length", "coupler_length", "rocker_length",
                                                        "ground_length")}
        s, l = min(lengths.values()), max(lengths.values())
        if s != lengths["crank_length"] or s + l >= sum(lengths.values()) - s - l:
            raise ValueError(f"the link lengths {lengths} do not make a crank-rocker: the crank must be the shortest "
                             "link and shortest + longest < sum of the other two (Grashof)")
        object.__setattr__(self, "_joint", scene_joint(self))

    @property
    def joint(self) -> exuclear.ClearanceJoint:
        """The clearance joint at B (checked at construction)."""
        return self._joint

    @property
    def end_time(self) -> float:
        return 2.0 * math.pi * self.revolutions / abs(self.crank_speed)


def ideal_configuration(p: FourBarParams, theta: float, omega: float) -> dict[str, tuple[float, float]]:
    """Angles and angular rates of the ideal four-bar (open branch, B above O2-O4) at crank
    angle ``theta`` and crank rate ``omega`` [rad, rad/s]: ``{"crank"|"coupler"|"rocker":
    (angle, rate)}``, each angle that of the link's axis from its first to its second joint
    (O2->A, A->B, O4->B).

    Position: B is the upper intersection of the circles of radius ``b`` about A and ``c``
    about O4.  Rates: the loop closure ``a w2 e2' + b w3 e3' - c w4 e4' = 0`` (``e'`` the
    unit vectors turned by 90 degrees), solved for ``w3``, ``w4``.
    """
    a, b, c, d = p.crank_length, p.coupler_length, p.rocker_length, p.ground_length
    ax, ay = a * math.cos(theta), a * math.sin(theta)
    ex, ey = d - ax, -ay  # A -> O4
    f = math.hypot(ex, ey)
    along = (b**2 - c**2 + f**2) / (2.0 * f)  # distance from A to the foot of B on A-O4
    h = math.sqrt(b**2 - along**2)
    ux, uy = ex / f, ey / f
    bx, by = ax + along * ux - h * uy, ay + along * uy + h * ux  # the branch left of A->O4: B above
    phi3, phi4 = math.atan2(by - ay, bx - ax), math.atan2(by, bx - d)
    # a w (-sin t, cos t) + b w3 (-sin p3, cos p3) = c w4 (-sin p4, cos p4)
    m = np.array([[-b * math.sin(phi3), c * math.sin(phi4)], [b * math.cos(phi3), -c * math.cos(phi4)]])
    rhs = -a * omega * np.array([-math.sin(theta), math.cos(theta)])
    w3, w4 = np.linalg.solve(m, rhs)
    return {"crank": (theta, omega), "coupler": (phi3, float(w3)), "rocker": (phi4, float(w4))}


def build(params: FourBarParams) -> Scene:
    """Assemble the four-bar in Exudyn, in the ideal mechanism's configuration and velocities
    at ``crank_angle0`` (the journal centred in its bearing); its one clearance joint is
    ``"B"`` (``Scene.joint``)."""
    p = params
    start = time.perf_counter()
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    state = ideal_configuration(p, p.crank_angle0, p.crank_speed)
    a, b, c, d = p.crank_length, p.coupler_length, p.rocker_length, p.ground_length
    th, w = state["crank"]
    phi3, w3 = state["coupler"]
    phi4, w4 = state["rocker"]
    pivot_a = np.array([a * math.cos(th), a * math.sin(th)])
    pivot_o4 = np.array([d, 0.0])

    def body(origin: np.ndarray, origin_velocity: np.ndarray, angle: float, rate: float, length: float,
             mass: float, inertia: float) -> tuple[int, int]:
        """A bar from ``origin`` along ``angle``: node at its midpoint, velocities of a rigid body."""
        u = np.array([math.cos(angle), math.sin(angle)])
        centre = origin + 0.5 * length * u
        v = origin_velocity + rate * 0.5 * length * np.array([-u[1], u[0]])
        node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[centre[0], centre[1], angle],
                                           initialVelocities=[v[0], v[1], rate]))
        return node, mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=mass, inertia=inertia))

    v_a = w * a * np.array([-math.sin(th), math.cos(th)])
    n_crank, crank = body(np.zeros(2), np.zeros(2), th, w, a, p.crank_mass, p.crank_inertia)
    n_coupler, coupler = body(pivot_a, v_a, phi3, w3, b, p.coupler_mass, p.coupler_inertia)
    n_rocker, rocker = body(pivot_o4, np.zeros(2), phi4, w4, c, p.rocker_mass, p.rocker_inertia)
    if p.gravity > 0.0:
        for item in (crank, coupler, rocker):
            mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=item)),
                                             loadVector=[0.0, -p.gravity, 0.0]))

    def rigid(item: int, x: float) -> int:
        return mbs.AddMarker(MarkerBodyRigid(bodyNumber=item, localPosition=[x, 0.0, 0.0]))

    # ideal joints: O2 (ground-crank), A (crank-coupler), O4 (ground-rocker)
    for m0, m1 in ((rigid(ground, 0.0), rigid(crank, -a / 2)), (rigid(crank, a / 2), rigid(coupler, -b / 2)),
                   (mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=[d, 0.0, 0.0])),
                    rigid(rocker, -c / 2))):
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[m0, m1]))
    handle = exuclear.AddClearanceJoint(mbs, [rigid(rocker, c / 2), rigid(coupler, b / 2)], joint=p.joint, name="B",
                                        backend=p.backend, maxPenetration=p.max_penetration)
    # drive: crank angle rate = omega (velocity-level coordinate constraint; its multiplier
    # is minus the driving moment)
    n_ground = mbs.AddNode(NodePointGround())
    drive = mbs.AddObject(ObjectConnectorCoordinate(
        markerNumbers=[mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_ground, coordinate=0)),
                       mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_crank, coordinate=2))],
        velocityLevel=True, offset=w))
    store = dict(storeInternal=True, writeToFile=False)
    coords, rates = exu.OutputVariableType.Coordinates, exu.OutputVariableType.Coordinates_t
    sensors = {
        "crank": mbs.AddSensor(SensorNode(nodeNumber=n_crank, outputVariableType=coords, **store)),
        "coupler": mbs.AddSensor(SensorNode(nodeNumber=n_coupler, outputVariableType=coords, **store)),
        "rocker": mbs.AddSensor(SensorNode(nodeNumber=n_rocker, outputVariableType=coords, **store)),
        "rocker_t": mbs.AddSensor(SensorNode(nodeNumber=n_rocker, outputVariableType=rates, **store)),
        "moment": mbs.AddSensor(SensorObject(objectNumber=drive, outputVariableType=exu.OutputVariableType.Force,
                                             **store)),
    }
    mbs.Assemble()
    return Scene(p, mbs, {"B": handle}, sensors, build_time=time.perf_counter() - start, main_joint="B")


def default_settings(params: FourBarParams) -> SolverSettings:
    """:data:`DEFAULT_SETTINGS` over the run; outputs every 1e-5 s."""
    return SolverSettings(end_time=params.end_time, **DEFAULT_SETTINGS)


@dataclass
class FourBarResult:
    """Outputs of a run: :data:`COLUMNS` as arrays, the run's summary and the joint's records."""

    columns: dict[str, np.ndarray]
    success: bool
    message: str
    wall_time: float
    build_time: float
    steps: int
    rejected: int
    onset_times: np.ndarray  # contact onsets [s], found at accepted steps
    record: _convergence.RunRecord  # what exuclear.check_convergence compares

    @property
    def impacts(self) -> int:
        return len(self.onset_times)

    @property
    def peak_force(self) -> float:
        return float(np.nanmax(self.columns["contact_force"]))


def columns(model: Scene) -> dict[str, np.ndarray]:
    """The recorded :data:`COLUMNS` of a finished run (angles in degrees, unwrapped)."""
    mbs, s = model.mbs, model.sensors

    def data(key: str) -> np.ndarray:
        return np.asarray(mbs.GetSensorStoredData(s[key]))

    crank = data("crank")
    out = model.joint.outputs()
    cols = {"time": crank[:, 0], "crank_angle": np.degrees(crank[:, 3]),
            "coupler_angle": np.degrees(data("coupler")[:, 3]), "rocker_angle": np.degrees(data("rocker")[:, 3]),
            "rocker_rate": data("rocker_t")[:, 3],
            "crank_moment": -data("moment")[:, 1],  # the drive is minus the constraint's reaction
            "contact_force": np.hypot(out["normal_force"], out["tangential_force"]), "ecc_x": out["ecc_x"],
            "ecc_y": out["ecc_y"], "penetration": out["penetration"], "in_contact": out["in_contact"]}
    return {k: cols[k] for k in COLUMNS}


#: The columns :func:`run` hands to :func:`exuclear.check_convergence` as named signals.
SIGNALS = ("rocker_angle", "rocker_rate", "crank_moment")


def run(params: FourBarParams, settings: SolverSettings | None = None) -> FourBarResult:
    """Build and simulate; returns the recorded :data:`COLUMNS` and the run's summary."""
    model = build(params)
    sim = exuclear.simulate(model.mbs, settings or default_settings(params))
    cols = columns(model)
    record = _convergence.RunRecord.from_handles(sim, {"B": model.joint},
                                             {k: (cols["time"], cols[k]) for k in SIGNALS})
    return FourBarResult(cols, sim.success, sim.message, sim.wall_time, model.build_time, sim.steps, sim.rejected,
                         np.asarray(model.joint.history.onset_times), record)


def check_convergence(params: FourBarParams, settings: SolverSettings | None = None,
                      **options: object) -> _convergence.ConvergenceResult:
    """:func:`exuclear.check_convergence` of this scene at ``settings`` (default
    :func:`default_settings`); ``options`` go to it (``factor``, ``bound``, ...)."""
    return _convergence.check_convergence(lambda s: run(params, s).record, settings or default_settings(params),
                                          **options)


def _parser() -> argparse.ArgumentParser:
    """The command line: one option per :class:`FourBarParams` field; defaults
    :meth:`FourBarParams.crank_rocker`."""
    p = FourBarParams.crank_rocker()
    ap = scene_parser("four_bar", __doc__, p)
    add_rpm_option(ap, p.crank_speed)
    ap.add_argument("--method", choices=[m for m, (_, explicit, _) in METHODS.items() if not explicit],
                    default=DEFAULT_SETTINGS["method"],
                    help="implicit solver (the joints are constraints) (default %(default)s)")
    ap.add_argument("--step", type=float, default=DEFAULT_SETTINGS["step"],
                    help="largest step [s] (default %(default)s)")
    ap.add_argument("--impact-step", type=float, default=DEFAULT_SETTINGS["impact_step"],
                    help="step from each contact onset [s]; 0: none, the joints' own step control up to --step (default %(default)s)")
    ap.add_argument("--dt-out", type=float, default=1e-5, help="output interval [s] (default %(default)s)")
    ap.add_argument("--csv", metavar="FILE", help="write the time series (columns: " + ", ".join(COLUMNS) + ")")
    ap.add_argument("--check-convergence", action="store_true",
                    help="run again at a tighter step and print what agrees with it, and over which horizon "
                         "(exuclear.check_convergence)")
    ap.add_argument("--verbose", action="store_true", help="Exudyn's progress output during the run")
    return ap


class _FourBarRun(SceneRun):
    """The command line's run (:func:`~exuclear.models._cli.run_main`): the crank-rocker with
    the options' changes, its summary, and the convergence check after the CSV."""

    def prepare(self, law: str, cr: float) -> None:
        args = self.args
        self.params = FourBarParams.crank_rocker(**changes_from_args(args, FourBarParams), law=law, cr=cr,
                                                 crank_speed=crank_speed_from_rpm("rpm", args.rpm))
        impact_step = nonnegative("--impact-step", args.impact_step) or None
        self.settings = SolverSettings(end_time=self.params.end_time, method=args.method, step=args.step,
                                       impact_step=impact_step, output_step=args.dt_out, verbose=int(args.verbose))

    def simulate(self) -> None:
        self.result = run(self.params, self.settings)

    def summary(self) -> None:
        params, settings, result = self.params, self.settings, self.result
        print(f"four-bar, {settings.method}, step {settings.step:g} s"
              f"{f', {settings.impact_step:g} s from each contact onset' if settings.impact_step else ''}: clearance "
              f"{params.clearance * 1e3:g} mm at B, {params.law} cr = {params.cr}, {params.journal_material} journal, "
              f"{params.bearing_material} bearing, friction {params.friction}")
        reached = float(result.columns["time"][-1]) if len(result.columns["time"]) else 0.0
        status = "simulated" if result.success else "STOPPED EARLY at"
        print(f"  {status} {reached:.4g} s of {params.end_time:.4g} s ({params.revolutions:g} revolutions) in "
              f"{result.steps} steps ({result.rejected} rejected)")
        print(f"  peak contact force {result.peak_force:.1f} N, impacts {result.impacts}, max |e|/c "
              f"{np.max(np.hypot(result.columns['ecc_x'], result.columns['ecc_y'])) / params.clearance:.3f}")
        print(f"  wall time {result.wall_time:.2f} s (model building {result.build_time:.3f} s)")

    def table(self) -> Table:
        return Table(self.result.columns, COLUMNS, self.incomplete)

    def finish(self) -> None:
        if self.args.check_convergence:
            print(check_convergence(self.params, self.settings, baseline=self.result.record).report())


def main(argv: list[str] | None = None) -> int:
    return run_main(argv, _parser(), _FourBarRun)


if __name__ == "__main__":
    sys.exit(main())
