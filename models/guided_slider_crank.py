"""The slider-crank whose slider has play in its guide (Flores, Leine, Glocker, Multibody
Syst. Dyn. 23 (2010) 165-190, section 4), with compliant corners.

::

                 A o.
           crank  /   ' . rod                    guide walls at y = +-(H/2 + c)
             l1  /         ' .    +----------+  ============================
                / theta1       ' .|  slider  |
           O   o                  B    2a    | 2b   (B: the slider's centre)
          (pivot, not driven)     +----------+  ============================

``ObjectRigidBody2D`` links (nodes at the crank's and the rod's midpoints and at the
slider's centre), ideal ``JointRevolute2D`` joints at O, A and B, and the slider in its guide
on the ground through :func:`exuclear.CreatePrismaticClearanceJoint` (four corners against
two walls).  The crank is not driven: it starts at 150 rad/s, the rod at -75 rad/s (the
ideal mechanism's speeds at theta1 = 0), and slows as the slider strikes the walls.  The
paper's impacts are rigid; the corners' law here is ``K delta^n`` with a damping model of
restitution ``cr``, as :mod:`validation.reference.guided_slider_crank` (the SciPy reference,
whose field names these are) has it.

    python -m exuclear.models.guided_slider_crank --help
"""
from __future__ import annotations

import argparse
import math
import sys
import time
import warnings
from dataclasses import dataclass, field, fields, replace

import exudyn as exu
import numpy as np
from exudyn.itemInterface import (
    LoadMassProportional,
    MarkerBodyMass,
    MarkerBodyRigid,
    NodeRigidBody2D,
    ObjectGround,
    ObjectJointRevolute2D,
    ObjectRigidBody2D,
    SensorNode,
)

import exuclear
from exuclear import SolverSettings
from exuclear.columns import Column
from exuclear.joint import make_prismatic_joint

from ._joint_fields import joint_field
from ._params import check_fields, nonnegative, param, positive, real, study_columns
from .scene import Scene

#: The benchmark's span [s]: two crank turns and a little (the reference's BENCHMARK_END_TIME).
BENCHMARK_END_TIME = 0.15


@dataclass(frozen=True)
class GuidedSliderCrankParams:
    """Parameters of the scene (SI units; each field's meaning and unit in its help);
    :meth:`benchmark` gives the paper's values.  The names and meanings are those of
    :class:`validation.reference.guided_slider_crank.GuidedSliderCrank` (centres of mass at
    the links' midpoints, inertias about them); ``friction`` as :func:`exuclear.friction_law`
    takes it, ``backend`` that of the clearance joint.  The bodies' values are checked here,
    the joint's by :meth:`joint`."""

    crank_length: float = field(metadata=param("crank length l1 [m]", positive))
    rod_length: float = field(metadata=param("rod length l2 [m]", positive))
    # the joint's values (slider, clearance, corners' law) are checked by the joint (joint())
    slider_length: float = field(metadata=param("slider length 2a [m]"))
    slider_height: float = field(metadata=param("slider height 2b [m]"))
    clearance: float = field(metadata=param("clearance c per side [m]"))
    crank_mass: float = field(metadata=param("crank mass [kg]", positive))
    rod_mass: float = field(metadata=param("rod mass [kg]", positive))
    slider_mass: float = field(metadata=param("slider mass [kg]", positive))
    crank_inertia: float = field(metadata=param("crank inertia about its centre of mass [kg m^2]", positive))
    rod_inertia: float = field(metadata=param("rod inertia about its centre of mass [kg m^2]", positive))
    slider_inertia: float = field(metadata=param("slider inertia about its centre [kg m^2]", positive))
    gravity: float = field(metadata=param("gravity along -y [m/s^2]", nonnegative))
    crank_speed: float = field(metadata=param("initial crank speed [rad/s]", real))
    rod_speed: float = field(metadata=param("initial rod speed [rad/s]", real))
    stiffness: float = field(metadata=param("corner stiffness K [N/m^n]"))
    exponent: float = field(metadata=param("corner stiffness exponent n"))
    damping: str = field(metadata=param("corners' damping model (none: elastic corners)"))
    # the clearance joint's fields every scene shares, described once (models/_joint_fields.py)
    cr: float = joint_field("cr")
    friction: str = joint_field("friction", help="friction law along the walls: none | coulomb:MU")
    v_min: float = joint_field("v_min")
    backend: str = joint_field("backend")

    @classmethod
    def benchmark(cls, **changes: object) -> GuidedSliderCrankParams:
        """Flores, Leine, Glocker (2010) section 4: crank 0.153 m, rod 0.306 m, slider 0.10 x
        0.05 m, 1 mm clearance per side, masses 0.038, 0.038, 0.076 kg, inertias 7.4e-5,
        5.9e-4, 2.7e-6 kg m^2, gravity, restitution 0.4, friction 0.01, the crank at 150
        rad/s and the rod at -75 rad/s; the corners ``K = 1e10 N/m^1.5`` with the
        Carvalho-Martins damping (the reference's compliant stand-in for the rigid impacts)."""
        base = cls(crank_length=0.153, rod_length=0.306, slider_length=0.10, slider_height=0.05, clearance=1e-3,
                   crank_mass=0.038, rod_mass=0.038, slider_mass=0.076, crank_inertia=7.4e-5, rod_inertia=5.9e-4,
                   slider_inertia=2.7e-6, gravity=9.81, crank_speed=150.0, rod_speed=-75.0, stiffness=1e10,
                   exponent=1.5, damping="carvalho-martins", cr=0.4, friction="coulomb:0.01", v_min=1e-4)
        return replace(base, **changes)

    def __post_init__(self) -> None:
        check_fields(self)

    def joint(self) -> exuclear.ClearanceJoint:
        """The slider-in-guide joint's physics (:func:`exuclear.joint.make_prismatic_joint`),
        which refuses a bad slider, clearance or corner law naming the argument."""
        return make_prismatic_joint(
            slider_length=self.slider_length, slider_height=self.slider_height, clearance=self.clearance,
            stiffness=self.stiffness, exponent=self.exponent, damping=self.damping,
            cr=None if self.damping == "none" else self.cr, friction=self.friction, v_min=self.v_min)


def build(params: GuidedSliderCrankParams) -> Scene:
    """Assemble the mechanism with all angles 0 (crank and rod along +x, the slider centred
    and aligned in its guide) at the given speeds; its clearance joint is ``"guide"``."""
    p = params
    start = time.perf_counter()
    joint = p.joint()  # the joint's values are checked before anything is built
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    l1, l2 = p.crank_length, p.rod_length
    w1, w2 = p.crank_speed, p.rod_speed
    v_a = w1 * l1  # A's speed along +y
    # (centre x, centre velocity y, angular speed, mass, inertia) of crank, rod, slider; all along +x
    bodies = {"crank": (0.5 * l1, 0.5 * w1 * l1, w1, p.crank_mass, p.crank_inertia),
              "rod": (l1 + 0.5 * l2, v_a + 0.5 * w2 * l2, w2, p.rod_mass, p.rod_inertia),
              "slider": (l1 + l2, v_a + w2 * l2, 0.0, p.slider_mass, p.slider_inertia)}
    nodes, items = {}, {}
    for name, (x, vy, w, mass, inertia) in bodies.items():
        nodes[name] = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[x, 0.0, 0.0], initialVelocities=[0.0, vy, w]))
        items[name] = mbs.AddObject(ObjectRigidBody2D(nodeNumber=nodes[name], mass=mass, inertia=inertia))
        if p.gravity:
            mbs.AddLoad(LoadMassProportional(markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=items[name])),
                                             loadVector=[0.0, -p.gravity, 0.0]))

    def rigid(item: int, x: float) -> int:
        return mbs.AddMarker(MarkerBodyRigid(bodyNumber=item, localPosition=[x, 0.0, 0.0]))

    for (b0, x0), (b1, x1) in (((ground, 0.0), (items["crank"], -0.5 * l1)),
                               ((items["crank"], 0.5 * l1), (items["rod"], -0.5 * l2)),
                               ((items["rod"], 0.5 * l2), (items["slider"], 0.0))):
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[rigid(b0, x0), rigid(b1, x1)]))
    guide = exuclear.CreatePrismaticClearanceJoint(
        mbs, name="guide", itemNumbers=[ground, items["slider"]], position=[l1 + l2, 0.0, 0.0], axis=[1.0, 0.0, 0.0],
        joint=joint, backend=p.backend)
    store = dict(storeInternal=True, writeToFile=False)
    sensors = {name: mbs.AddSensor(SensorNode(nodeNumber=nodes[body], outputVariableType=kind, **store))
               for name, body, kind in (("crank_t", "crank", exu.OutputVariableType.Coordinates_t),
                                        ("slider", "slider", exu.OutputVariableType.Coordinates))}
    mbs.Assemble()
    return Scene(p, mbs, {"guide": guide}, sensors, nodes, build_time=time.perf_counter() - start, main_joint="guide")


def default_settings(params: GuidedSliderCrankParams, end_time: float = BENCHMARK_END_TIME) -> SolverSettings:
    """Generalized-alpha (the ideal revolute joints are constraints) with steps the corners'
    contact resolves (the slider rocking on a corner, some 1e-5 s at K = 1e10, is the fastest
    mode): 1e-6 s, the joint's own step rules at its impacts, output every 1e-5 s."""
    return SolverSettings(end_time=end_time, method="generalized-alpha", step=1e-6, output_step=1e-5)


@dataclass
class GuidedSliderCrankResult:
    """A run's outputs on the sensors' grid (SI units): ``time``; ``crank_speed`` [rad/s];
    ``slider`` (times, 3): the slider's x, y, angle; ``penetration``, ``normal_force`` (times,
    8): each corner-wall pair's (:data:`exuclear.prismatic.PAIRS`); ``impacts``:
    ``joint.impacts()``, each naming its corner and wall; ``success``, ``message``,
    ``wall_time`` [s] and ``steps`` of the solver."""

    time: np.ndarray
    crank_speed: np.ndarray
    slider: np.ndarray
    penetration: np.ndarray
    normal_force: np.ndarray
    impacts: list
    success: bool
    message: str
    wall_time: float
    steps: int


def run(params: GuidedSliderCrankParams, settings: SolverSettings | None = None) -> GuidedSliderCrankResult:
    """Build and simulate the scene (default :func:`default_settings`)."""
    return run_scene(build(params), settings)


def run_scene(scene: Scene, settings: SolverSettings | None = None) -> GuidedSliderCrankResult:
    """Simulate a built scene (default :func:`default_settings`) and read its outputs; the
    scene keeps its end state (:func:`energy`)."""
    params = scene.params
    settings = default_settings(params) if settings is None else settings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(scene.mbs, settings)
    mbs, joint = scene.mbs, scene.joint
    out = joint.outputs()
    crank = np.asarray(mbs.GetSensorStoredData(scene.sensors["crank_t"]))
    slider = np.asarray(mbs.GetSensorStoredData(scene.sensors["slider"]))
    n = min(len(out["time"]), len(crank), len(slider))
    slider_xy = slider[:n, 1:4] + np.array([params.crank_length + params.rod_length, 0.0, 0.0])  # displacement + reference
    return GuidedSliderCrankResult(out["time"][:n], crank[:n, 3], slider_xy, out["penetration"][:n],
                                   out["normal_force"][:n], joint.impacts(), result.success, result.message,
                                   result.wall_time, result.steps)


def energy(scene: Scene) -> float:
    """The scene's energy at its current state [J]: the links' kinetic and gravitational
    energy and the closed corners' elastic energy ``K delta^(n+1) / (n+1)`` (their last
    accepted penetrations); conserved with ``damping="none"`` and no friction."""
    p, mbs = scene.params, scene.mbs
    total = 0.0
    for name, mass, inertia in (("crank", p.crank_mass, p.crank_inertia), ("rod", p.rod_mass, p.rod_inertia),
                                ("slider", p.slider_mass, p.slider_inertia)):
        node = scene.nodes[name]
        v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)
        w = mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity)[2]
        y = mbs.GetNodeOutput(node, exu.OutputVariableType.Position)[1]
        total += 0.5 * mass * (v[0] ** 2 + v[1] ** 2) + 0.5 * inertia * w**2 + mass * p.gravity * y
    for state in scene.joint.pair_states():
        if state.delta > 0.0:
            total += p.stiffness * state.delta ** (p.exponent + 1.0) / (p.exponent + 1.0)
    return total


# =======================================================================================
# the scene as a parameter study (exuclear.study)
# =======================================================================================

#: The fields of :class:`GuidedSliderCrankParams` a study sweeps (defaults: the benchmark's).
STUDY_FIELDS = ("clearance", "stiffness", "exponent", "damping", "cr", "friction", "crank_speed", "gravity", "backend")

#: Parameters of :func:`study` and their defaults: the benchmark (:meth:`GuidedSliderCrankParams.benchmark`)
#: and its span ``end_time`` [s].  The rod starts at the ideal mechanism's speed for the
#: crank's, ``-crank_speed l1 / l2`` (the benchmark's -75 rad/s at 150), so that the slider
#: starts moving along its guide, not across it.
STUDY_PARAMETERS = {**{name: getattr(GuidedSliderCrankParams.benchmark(), name) for name in STUDY_FIELDS},
                    "end_time": BENCHMARK_END_TIME}

#: The metrics of :func:`study`: what each is, its unit (axis labels of study plots).
STUDY_METRICS = {
    "max_y_over_c": Column("largest |y| / c of the slider's centre"),
    "crank_speed_end": Column("crank speed at the end", "rad/s"),
    "impacts": Column("contacts, every corner against every wall"),
    "peak_force": Column("peak corner force", "N"),
    # energy() at the start minus at the end: what the corners' damping and friction took,
    # and generalized-alpha's numerical damping
    "energy_lost": Column("energy lost, start minus end", "J"),
    "energy_lost_rel": Column("energy lost / energy at the start"),
    "steps": Column("solver steps"),
    "sim_wall_time": Column("solver wall time", "s"),
}

#: Parameters (from the :class:`GuidedSliderCrankParams` fields: help, unit) and metrics of
#: the study, for ``python -m exuclear.study guided-slider-crank`` and its plots.
STUDY_COLUMNS = {**study_columns(GuidedSliderCrankParams, STUDY_PARAMETERS),
                 "end_time": Column("simulated time", "s"), **STUDY_METRICS}


def study_params(values: dict) -> tuple[GuidedSliderCrankParams, float]:
    """The :class:`GuidedSliderCrankParams` and the end time [s] of a study's parameter set
    (defaults :data:`STUDY_PARAMETERS`); ``ValueError`` naming a value the scene refuses."""
    v = {**STUDY_PARAMETERS, **values}
    unknown = sorted(set(v) - set(STUDY_PARAMETERS))
    if unknown:
        raise ValueError(f"unknown study parameters {unknown}; known: {', '.join(STUDY_PARAMETERS)}")
    end_time = positive("end_time", v["end_time"])
    params = GuidedSliderCrankParams.benchmark(**{name: v[name] for name in STUDY_FIELDS})
    params = replace(params, rod_speed=-params.crank_speed * (params.crank_length / params.rod_length))
    params.joint()  # the slider, clearance and corner law
    return params, end_time


def check_study(values: dict) -> None:
    """Raise ``ValueError`` for a study parameter set the scene refuses (before any run)."""
    study_params(values)


def study(values: dict) -> dict:
    """One run of a guided slider-crank study (:mod:`exuclear.study`); parameters
    :data:`STUDY_PARAMETERS`, the scene's :func:`default_settings` up to ``end_time``.

    Returns
    -------
    dict
        The metrics of :data:`STUDY_METRICS` (meaning and unit there); ``success`` and
        ``message`` of the run.
    """
    params, end_time = study_params(values)
    scene = build(params)
    start = energy(scene)
    r = run_scene(scene, default_settings(params, end_time))
    lost = start - energy(scene)
    return {
        "max_y_over_c": float(np.abs(r.slider[:, 1]).max() / params.clearance),
        "crank_speed_end": float(r.crank_speed[-1]),
        "impacts": len(r.impacts),
        "peak_force": max((i.peak_force for i in r.impacts), default=0.0),
        # a mechanism started at rest has no energy to lose a share of
        "energy_lost": float(lost), "energy_lost_rel": float(lost / start) if start > 0.0 else math.nan,
        "steps": r.steps, "sim_wall_time": r.wall_time,
        "success": r.success, "message": r.message,
    }

def figure(params: GuidedSliderCrankParams, r: GuidedSliderCrankResult, path: str) -> None:
    """The papers' panels: the slider's path in the guide (x/l1 against y/c), the crank's
    speed, and the corners' gaps and forces against time (matplotlib, imported here)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from exuclear.prismatic import pair_name

    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    ax[0, 0].plot(r.slider[:, 0] / params.crank_length, r.slider[:, 1] / params.clearance, lw=0.8)
    ax[0, 0].set(xlabel="x / l1", ylabel="y / c", title="slider's centre in the guide")
    ax[0, 1].plot(r.time, r.crank_speed, lw=0.8)
    ax[0, 1].set(xlabel="t [s]", ylabel="crank speed [rad/s]")
    for k in range(r.penetration.shape[1]):
        if r.normal_force[:, k].max() > 0.0:
            ax[1, 0].plot(r.time, -r.penetration[:, k] * 1e3, lw=0.7, label=pair_name(k))
            ax[1, 1].plot(r.time, r.normal_force[:, k], lw=0.7, label=pair_name(k))
    ax[1, 0].set(xlabel="t [s]", ylabel="gap [mm]", ylim=(-0.1, 2.2 * params.clearance * 1e3))
    ax[1, 1].set(xlabel="t [s]", ylabel="normal force [N]")
    ax[1, 1].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=130)
    plt.close(fig)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m exuclear.models.guided_slider_crank",
                                     description=__doc__.splitlines()[0])
    parser.add_argument("--end-time", type=float, default=BENCHMARK_END_TIME, help="simulated time [s]")
    helps = {f.name: f.metadata["help"] + " (default the benchmark's)" for f in fields(GuidedSliderCrankParams)}
    parser.add_argument("--stiffness", type=float, default=None, help=helps["stiffness"])
    parser.add_argument("--damping", default=None, help=helps["damping"])
    parser.add_argument("--friction", default=None, help=helps["friction"])
    parser.add_argument("--backend", choices=("compiled", "python"), default=None, help=helps["backend"])
    parser.add_argument("--figure", default=None, help="write the papers' panels to this PNG file")
    args = parser.parse_args(argv)
    changes = {k: v for k, v in (("stiffness", args.stiffness), ("damping", args.damping),
                                 ("friction", args.friction), ("backend", args.backend)) if v is not None}
    try:
        params = GuidedSliderCrankParams.benchmark(**changes)
        r = run(params, default_settings(params, args.end_time))
    except ValueError as err:
        print(f"error: {err}", file=sys.stderr)
        return 2
    print(f"{'finished' if r.success else 'stopped: ' + r.message}; {len(r.impacts)} contacts, y/c in "
          f"[{r.slider[:, 1].min() / params.clearance:.3f}, {r.slider[:, 1].max() / params.clearance:.3f}], "
          f"crank speed {r.crank_speed[-1]:.2f} rad/s at t = {r.time[-1]:.4f} s, largest corner force "
          f"{r.normal_force.max():.4g} N, {r.wall_time:.1f} s")
    if args.figure:
        figure(params, r, args.figure)
        print(f"wrote {args.figure}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
