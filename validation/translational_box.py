"""The spatial translational clearance joint (a box in a rectangular channel) and the finite
guide, against analytic results and against the planar joint (issue 50).

Source problems (:mod:`exuclear.prismatic`; the channel on the ground along x, gravity along
-y, a 3D box of the benchmark slider's length, height and mass, :data:`SLIDER_WIDTH` wide):

- the box resting flat on the lower wall: each of its four lower corners carries ``m g / 4``
  and sinks ``(m g / (4 K))^(1/n)``;
- the box sliding on the lower wall diagonally (along x and z) with Coulomb friction: its
  speed falls as ``v0 - mu g t`` along its first direction (the slip is 2D on the wall);
- elastic corners (``damping="none"``, no gravity, no friction): the box spinning about all
  three axes and rattling against all four walls keeps its kinetic energy;
- the box kept in the x-y plane (motion in the plane, the far and near walls never touched)
  against the planar joint on the same 3D body: the same motion, with half the planar
  corner's ``K`` per corner (two corners of the box stand where one of the rectangle does);
- a finite guide: a slider sliding out of a guide ``guide_length`` long loses its front
  corner's contact when that corner passes ``guide_length / 2``.

    python -m validation.translational   (prints these with the planar checks)
"""
from __future__ import annotations

import math
import warnings

import exudyn as exu
import numpy as np
from exudyn.utilities import InertiaCuboid, ObjectGround

import exuclear
from validation import translational as planar

#: The box: the benchmark slider's length, height and mass (:mod:`validation.translational`), 40 mm wide.
SLIDER_WIDTH = 0.04  # [m]
DENSITY = planar.MASS / (planar.SLIDER_LENGTH * planar.SLIDER_HEIGHT * SLIDER_WIDTH)  # [kg/m^3]
#: The channel's play across the width for the diagonal slide [m]: the box crosses 15 mm of it in 0.05 s.
WIDE_CLEARANCE = 0.02
#: The finite guide's length [m]: twice the slider's.
GUIDE_LENGTH = 0.2


def box_in_channel(backend: str | None = None, velocity=(0.0, 0.0, 0.0), angular_velocity=(0.0, 0.0, 0.0),
                   start=(0.0, 0.0, 0.0), gravity: float = planar.GRAVITY, spatial: bool = True, **law):
    """A 3D box in a channel on the ground centred at the origin along x, its node a Tait-Bryan
    one (DOPRI5 takes it); ``spatial=False``: the planar joint on the same body.  Returns (mbs,
    joint, box node)."""
    mbs = exu.SystemContainer().AddSystem()
    guide = mbs.AddObject(ObjectGround())
    inertia = InertiaCuboid(DENSITY, sideLengths=[planar.SLIDER_LENGTH, planar.SLIDER_HEIGHT, SLIDER_WIDTH])
    body = mbs.CreateRigidBody(inertia=inertia, nodeType=exu.NodeType.RotationRxyz, referencePosition=[0.0, 0.0, 0.0],
                               initialDisplacement=list(start), initialVelocity=list(velocity),
                               initialAngularVelocity=list(angular_velocity), gravity=[0.0, -gravity, 0.0],
                               returnDict=True)
    parameters = dict(slider_length=planar.SLIDER_LENGTH, slider_height=planar.SLIDER_HEIGHT,
                      clearance=planar.CLEARANCE, stiffness=planar.STIFFNESS / (2.0 if spatial else 1.0),
                      exponent=planar.EXPONENT, damping="lankarani-nikravesh", cr=0.5)
    if spatial:
        parameters["slider_width"] = SLIDER_WIDTH
    parameters.update(law)
    joint = exuclear.CreatePrismaticClearanceJoint(mbs, itemNumbers=[guide, body["bodyNumber"]],
                                                   position=[0.0, 0.0, 0.0], axis=[1.0, 0.0, 0.0], backend=backend,
                                                   **parameters)
    mbs.Assemble()
    return mbs, joint, body["nodeNumber"]


#: Fixed steps for the comparison with the planar joint: RK44 at 2e-6 s, a few dozen steps per
#: corner contact; without step control the two runs take the same steps.
FIXED_SETTINGS = dict(method="rk44", step=2e-6, output_step=1e-4)


def _run(mbs, end_time: float, settings: dict | None = None) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, exuclear.SolverSettings(end_time=end_time, **(settings or planar.SETTINGS)))
    if not result.success:
        raise RuntimeError(result.message)


def _lower(joint) -> list[int]:
    """The pairs of the box's four lower corners with the lower wall (:data:`exuclear.prismatic.BOX_PAIRS`)."""
    from exuclear.prismatic import BOX_CORNER_SIGNS, BOX_PAIRS
    return [k for k, (corner, wall) in enumerate(BOX_PAIRS) if wall == 0 and BOX_CORNER_SIGNS[corner][1] < 0.0]


def static_sink(corners: int, stiffness: float) -> float:
    """The sink [m] of a slider whose weight ``corners`` corners of stiffness ``stiffness`` share."""
    return (planar.MASS * planar.GRAVITY / (corners * stiffness)) ** (1.0 / planar.EXPONENT)


def resting() -> dict:
    """The box dropped from the channel's centre, at rest after 0.3 s: its lower corners' forces
    against ``m g / 4`` and their penetration against ``(m g / (4 K))^(1/n)``."""
    mbs, joint, _ = box_in_channel(stiffness=planar.STIFFNESS)
    _run(mbs, 0.3)
    out, lower = joint.outputs(), _lower(joint)
    return {"force": out["normal_force"][-1, lower].tolist(), "quarter_weight": planar.MASS * planar.GRAVITY / 4.0,
            "sink": out["penetration"][-1, lower].tolist(), "static_sink": static_sink(4, planar.STIFFNESS)}


def sliding(end_time: float = 0.05) -> dict:
    """The box at its static sink on the lower wall, pushed along (0.8, 0, 0.6) at
    :data:`planar.SLIDE_SPEED` with Coulomb friction :data:`planar.SLIDE_MU`, the channel
    :data:`WIDE_CLEARANCE` deep each side: after ``end_time`` its velocity against ``(v0 - mu
    g t)`` along the same direction, and ``F_T / F_N`` at the lower corners."""
    direction = np.array([0.8, 0.0, 0.6])
    sink = static_sink(4, planar.STIFFNESS)
    mbs, joint, node = box_in_channel(velocity=planar.SLIDE_SPEED * direction,
                                      start=(0.0, -(planar.CLEARANCE + sink), 0.0), stiffness=planar.STIFFNESS,
                                      clearance_width=WIDE_CLEARANCE, friction=f"coulomb:{planar.SLIDE_MU}")
    _run(mbs, end_time)
    out, lower = joint.outputs(), _lower(joint)
    v = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity))
    rows = (out["normal_force"][:, lower] > 0.0).all(axis=1)
    ratio = out["tangential_force"][rows][:, lower] / out["normal_force"][rows][:, lower]
    expected = (planar.SLIDE_SPEED - planar.SLIDE_MU * planar.GRAVITY * end_time) * direction
    turn = math.atan2(v[2], v[0]) - math.atan2(direction[2], direction[0])
    return {"velocity": v.tolist(), "coulomb_velocity": expected.tolist(), "speed": float(np.linalg.norm(v)),
            "coulomb_speed": float(np.linalg.norm(expected)), "turn": turn, "ratio_min": float(ratio.min()),
            "ratio_max": float(ratio.max()), "mu": planar.SLIDE_MU}


def kinetic_energy(mbs, node) -> float:
    """The box's kinetic energy [J]: translation and rotation about its centre (body-fixed spin)."""
    v = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity))
    w = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocityLocal))
    inertia = InertiaCuboid(DENSITY, sideLengths=[planar.SLIDER_LENGTH, planar.SLIDER_HEIGHT, SLIDER_WIDTH])
    return float(0.5 * inertia.Mass() * v @ v + 0.5 * w @ inertia.InertiaCOM() @ w)


def elastic_rattle(end_time: float = 0.05) -> dict:
    """The box spinning about all three axes and rattling against the four walls with elastic
    corners, no gravity, no friction: its kinetic energy at the end against its start, the
    contacts it made and the walls they were on."""
    mbs, joint, node = box_in_channel(velocity=(0.3, 0.2, 0.15), angular_velocity=(1.0, 1.5, 2.0), gravity=0.0,
                                      damping="none", cr=None)
    start = kinetic_energy(mbs, node)
    _run(mbs, end_time)
    walls = {r.pair.split(" / ")[1].removesuffix(" wall") for r in joint.impacts()}
    return {"start": start, "end": kinetic_energy(mbs, node), "contacts": len(joint.impacts()),
            "walls": sorted(walls)}


def in_plane(end_time: float = 0.05, backend: str | None = None) -> dict:
    """The box spinning about z and rattling between the lower and upper walls in the x-y
    plane, under gravity with Coulomb friction, through the spatial joint (``K / 2`` per
    corner) and the planar joint (``K``) on the same 3D body, at the same fixed steps
    (:data:`FIXED_SETTINGS`; an adaptive run's step choices amplify the loads' last-bit
    differences through the impacts): the largest difference of their coordinates, and the
    box's largest coordinate out of the plane (z, turns about x and y)."""
    runs = []
    for spatial in (True, False):
        mbs, joint, node = box_in_channel(backend, velocity=(0.2, 0.3, 0.0), angular_velocity=(0.0, 0.0, 3.0),
                                          spatial=spatial, friction="coulomb:0.2")
        _run(mbs, end_time, FIXED_SETTINGS)
        runs.append((np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.Coordinates)),
                     len(joint.impacts())))
    (q_box, n_box), (q_plane, n_plane) = runs
    return {"difference": float(np.abs(q_box - q_plane).max()), "out_of_plane": float(np.abs(q_box[[2, 3, 4]]).max()),
            "contacts": n_box, "planar_contacts": n_plane}


def guide_exit(spatial: bool = False, end_time: float = 0.12) -> dict:
    """A slider resting on the lower wall of a guide :data:`GUIDE_LENGTH` long, sliding
    without friction at :data:`planar.SLIDE_SPEED` out of its end: the front lower corner's
    place along the axis at the last output in contact and the first one out of it, against
    ``guide_length / 2``."""
    if spatial:
        sink = static_sink(4, planar.STIFFNESS)
        mbs, joint, _ = box_in_channel(velocity=(planar.SLIDE_SPEED, 0.0, 0.0), stiffness=planar.STIFFNESS,
                                       start=(0.0, -(planar.CLEARANCE + sink), 0.0), guide_length=GUIDE_LENGTH)
        front = 1  # front-lower-far / lower wall (BOX_PAIRS)
    else:
        sink = static_sink(2, planar.STIFFNESS)
        mbs, joint, node = planar.slider_in_guide(velocity=(planar.SLIDE_SPEED, 0.0, 0.0), guide_length=GUIDE_LENGTH)
        mbs.SetNodeParameter(node, "referenceCoordinates", [0.0, -(planar.CLEARANCE + sink), 0.0])
        mbs.Assemble()
        front = 1  # front-lower / lower wall
    _run(mbs, end_time)
    out = joint.outputs()
    touching = out["in_contact"][:, front] > 0.0
    last = int(np.flatnonzero(touching)[-1])
    return {"x_last_in": float(out["ecc_x"][last, front]), "x_first_out": float(out["ecc_x"][last + 1, front]),
            "touching_beyond": int((touching & (np.abs(out["ecc_x"][:, front]) > 0.5 * GUIDE_LENGTH)).sum()),
            "half_guide": 0.5 * GUIDE_LENGTH, "time_out": float(out["time"][last + 1])}


def rows() -> list[tuple[str, str, str]]:
    """The checks as (check, exuclear, analytic) rows for :func:`validation.translational.main`."""
    out = []
    r = resting()
    out.append(("box resting: lower corners' force [N]", ", ".join(f"{f:.6g}" for f in r["force"]),
                f"m g / 4 = {r['quarter_weight']:.6g}"))
    out.append(("box resting: sink [m]", f"{r['sink'][0]:.6g}", f"(m g / (4K))^(1/n) = {r['static_sink']:.6g}"))
    s = sliding()
    out.append(("box sliding diagonally (mu 0.2): speed after 0.05 s [m/s]", f"{s['speed']:.10g}",
                f"v0 - mu g t = {s['coulomb_speed']:.10g}"))
    out.append(("the same: its direction's turn [rad]", f"{s['turn']:.3g}", "0 (rigid; the compliant corners rock)"))
    out.append(("box sliding: F_T / F_N at the lower corners", f"{s['ratio_min']:.6g} ... {s['ratio_max']:.6g}",
                f"mu = {s['mu']:g}"))
    e = elastic_rattle()
    out.append(("box elastic rattle: kinetic energy [J]",
                f"{e['end']:.8g} ({e['contacts']} contacts on the {', '.join(e['walls'])} walls)", f"{e['start']:.8g}"))
    p = in_plane()
    out.append(("box in the x-y plane (K/2 per corner) vs the planar joint (K), RK44 at 2e-6 s: largest "
                "coordinate difference", f"{p['difference']:.3g} ({p['contacts']} contacts)",
                f"0 ({p['planar_contacts']} planar contacts)"))
    out.append(("the same: largest z, turn about x or y", f"{p['out_of_plane']:.3g}", "0"))
    for spatial in (False, True):
        g = guide_exit(spatial)
        out.append((f"{'box' if spatial else 'slider'} leaving a guide 0.2 m long: front corner's x at the last "
                    "output in contact / the first out", f"{g['x_last_in']:.6g} / {g['x_first_out']:.6g}",
                    f"guide_length / 2 = {g['half_guide']:g}"))
    return out
