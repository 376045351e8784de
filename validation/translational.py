"""The translational clearance joint (a slider in a guide) against analytic results and the
SciPy reference of the Flores-Leine-Glocker slider-crank (issue 50).

Source problems (:mod:`exuclear.prismatic`; planar, gravity along -y, the guide on the ground):

- a slider resting flat on its guide: each lower corner carries ``m g / 2`` and the slider
  sinks ``(m g / (2 K))^(1/n)``;
- a slider sliding along the lower wall under gravity at 0.5 m/s: Coulomb's ``F_T = mu N``
  at each lower corner, and the slider's speed falling as ``v0 - mu g t``;
- elastic corners (``damping="none"``, no gravity, no friction): a slider spinning and
  rattling between the walls keeps its kinetic energy;
- a pin in a slot of length 0 against the revolute clearance joint; a pin sliding along a
  flat side under gravity (Coulomb's ``mu N``, its speed and spin);
- the spatial joint (a box in a channel) and the finite guide: :mod:`validation.translational_box`;
- the Flores-Leine-Glocker slider-crank (:mod:`models.guided_slider_crank`): the scene
  against :mod:`validation.reference.guided_slider_crank` over the benchmark at two steps,
  its energy with elastic corners over the benchmark's two crank turns, and a table over the
  corners' stiffness K.

    python -m validation.translational [--no-slider-crank]
"""
from __future__ import annotations

import argparse
import warnings
from dataclasses import replace

import exudyn as exu
import numpy as np
from exudyn.itemInterface import Force, MarkerNodePosition, NodeRigidBody2D, ObjectGround, ObjectRigidBody2D

import exuclear
from exuclear.joint import make_pin_slot_joint
from models import guided_slider_crank as slider_crank
from models.guided_slider_crank import BENCHMARK_END_TIME
from validation._tables import markdown_table
from validation.reference import guided_slider_crank as reference

#: The benchmark's slider (Flores, Leine, Glocker 2010, table 1): 0.10 m x 0.05 m, 0.076 kg,
#: 2.7e-6 kg m^2, 1 mm of clearance per side.
SLIDER_LENGTH, SLIDER_HEIGHT, CLEARANCE = 0.10, 0.05, 1e-3  # [m]
MASS, INERTIA, GRAVITY = 0.076, 2.7e-6, 9.81  # [kg], [kg m^2], [m/s^2]
#: A corner's stiffness for the analytic checks [N/m^1.5]: soft enough for steps of 1e-5 s.
STIFFNESS, EXPONENT = 1e8, 1.5
#: Coulomb's coefficient of the sliding check, and the slider's initial speed along the wall [m/s].
SLIDE_MU, SLIDE_SPEED = 0.2, 0.5
#: DOPRI5 at tolerances the sliding slider meets (its corners' friction couples the stiff rocking mode).
SETTINGS = dict(method="dopri5", step=1e-5, rtol=1e-8, atol=1e-12, output_step=1e-4)


def slider_in_guide(backend: str | None = None, velocity=(0.0, 0.0, 0.0), gravity: float = GRAVITY,
                    guide_spin: float | None = None, **law):
    """A 2D slider in a guide centred at the origin along x; the guide on the ground or, with
    ``guide_spin`` [rad/s], a free heavy body turning at that rate.  Returns (mbs, joint,
    slider node)."""
    mbs = exu.SystemContainer().AddSystem()
    if guide_spin is None:
        guide = mbs.AddObject(ObjectGround())
    else:
        guide_node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0],
                                                 initialVelocities=[0.0, 0.0, guide_spin]))
        guide = mbs.AddObject(ObjectRigidBody2D(nodeNumber=guide_node, mass=2.0, inertia=5e-3))
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0], initialVelocities=list(velocity)))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=MASS, inertia=INERTIA))
    if gravity:
        marker = mbs.AddMarker(MarkerNodePosition(nodeNumber=node))
        mbs.AddLoad(Force(markerNumber=marker, loadVector=[0.0, -MASS * gravity, 0.0]))
    parameters = dict(slider_length=SLIDER_LENGTH, slider_height=SLIDER_HEIGHT, clearance=CLEARANCE,
                      stiffness=STIFFNESS, exponent=EXPONENT, damping="lankarani-nikravesh", cr=0.5)
    parameters.update(law)
    joint = exuclear.CreatePrismaticClearanceJoint(mbs, itemNumbers=[guide, body], position=[0.0, 0.0, 0.0],
                                                   axis=[1.0, 0.0, 0.0], backend=backend, **parameters)
    mbs.Assemble()
    return mbs, joint, node


def run(mbs, end_time: float) -> None:
    """Simulates ``mbs`` to ``end_time`` [s] with the checks' settings (``SETTINGS``)."""
    _run_settings(mbs, exuclear.SolverSettings(end_time=end_time, **SETTINGS))


def _run_settings(mbs, settings: exuclear.SolverSettings) -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(mbs, settings)
    if not result.success:
        raise RuntimeError(result.message)


def resting() -> dict[str, float]:
    """The slider dropped from the guide's centre, at rest after 0.3 s: the lower corners'
    forces against ``m g / 2`` and their penetration against ``(m g / (2 K))^(1/n)``."""
    mbs, joint, _ = slider_in_guide()
    run(mbs, 0.3)
    out = joint.outputs()
    return {"force": out["normal_force"][-1, :2].tolist(), "half_weight": MASS * GRAVITY / 2.0,
            "sink": out["penetration"][-1, :2].tolist(),
            "static_sink": (MASS * GRAVITY / (2.0 * STIFFNESS)) ** (1.0 / EXPONENT)}


def sliding() -> dict[str, float]:
    """The slider resting on the lower wall and pushed along it at :data:`SLIDE_SPEED`, with
    Coulomb friction :data:`SLIDE_MU`: after 0.05 s its speed against ``v0 - mu g t`` and the
    lower corners' ``F_T / F_N`` against ``mu`` while it slides."""
    sink = (MASS * GRAVITY / (2.0 * STIFFNESS)) ** (1.0 / EXPONENT)
    mbs, joint, node = slider_in_guide(velocity=(SLIDE_SPEED, 0.0, 0.0), friction=f"coulomb:{SLIDE_MU}")
    # start on the wall, at the static sink: no drop before the slide
    mbs.SetNodeParameter(node, "referenceCoordinates", [0.0, -(CLEARANCE + sink), 0.0])
    mbs.Assemble()
    end = 0.05
    run(mbs, end)
    out = joint.outputs()
    v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)[0]
    sliding_rows = out["normal_force"][:, 0] > 0.0
    ratio = out["tangential_force"][sliding_rows, :2] / out["normal_force"][sliding_rows, :2]
    return {"speed": float(v), "coulomb_speed": SLIDE_SPEED - SLIDE_MU * GRAVITY * end,
            "ratio_min": float(ratio.min()), "ratio_max": float(ratio.max()), "mu": SLIDE_MU}


def elastic_rattle(end_time: float = 0.05) -> dict[str, float]:
    """A slider spinning and rattling between the walls with elastic corners, no gravity, no
    friction: its kinetic energy at the end against its start, and the contacts it made."""
    omega, vy = 2.0, 0.2
    mbs, joint, node = slider_in_guide(velocity=(0.3, vy, omega), gravity=0.0, damping="none", cr=None)
    run(mbs, end_time)
    v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)
    w = mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity)[2]
    start = 0.5 * MASS * (0.3**2 + vy**2) + 0.5 * INERTIA * omega**2
    end = 0.5 * MASS * (v[0] ** 2 + v[1] ** 2) + 0.5 * INERTIA * w**2
    return {"start": start, "end": end, "contacts": len(joint.impacts())}


#: The pin-in-slot checks: a steel pin of 10 mm radius, 20 mm long, in a slot 20.2 mm wide.
PIN_RADIUS, SLOT_WIDTH, PIN_LENGTH = 10e-3, 20.2e-3, 20e-3  # [m]
PIN_MASS = 7850.0 * np.pi * PIN_RADIUS**2 * PIN_LENGTH  # [kg]
PIN_INERTIA = 0.5 * PIN_MASS * PIN_RADIUS**2  # a solid pin [kg m^2]


def pin_in_slot(slot_length: float | None, backend: str | None = None, axis=(1.0, 0.0, 0.0),
                velocity=(0.0, 0.0, 0.0), start=(0.0, 0.0), slot_spin: float | None = None, gravity: float = GRAVITY,
                **law):
    """A 2D steel pin in a slot centred at the origin: the slot on the ground or, with
    ``slot_spin`` [rad/s], a free heavy body turning at that rate; ``slot_length`` None: the
    revolute clearance joint of the same pin and hole (``CreateClearanceJoint``).  Returns
    (mbs, joint, pin node)."""
    mbs = exu.SystemContainer().AddSystem()
    if slot_spin is None:
        slot = mbs.AddObject(ObjectGround())
    else:
        slot_node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0],
                                                initialVelocities=[0.0, 0.0, slot_spin]))
        slot = mbs.AddObject(ObjectRigidBody2D(nodeNumber=slot_node, mass=5.0, inertia=1e-2))
    # the pin's centre is the slot's in the reference configuration, ``start`` away from it initially
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0], initialCoordinates=[start[0], start[1], 0.0],
                                       initialVelocities=list(velocity)))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=PIN_MASS, inertia=PIN_INERTIA))
    if gravity:
        mbs.AddLoad(Force(markerNumber=mbs.AddMarker(MarkerNodePosition(nodeNumber=node)),
                          loadVector=[0.0, -PIN_MASS * gravity, 0.0]))
    parameters = dict(law="hertz+lankarani-nikravesh", cr=0.7)
    parameters.update(law)
    if slot_length is None:
        joint = exuclear.CreateClearanceJoint(mbs, itemNumbers=[slot, body], position=[0.0, 0.0, 0.0],
                                              journal_radius=PIN_RADIUS, bearing_radius=0.5 * SLOT_WIDTH,
                                              length=PIN_LENGTH, backend=backend, **parameters)
    else:
        joint = exuclear.CreatePinSlotClearanceJoint(mbs, itemNumbers=[slot, body], position=[0.0, 0.0, 0.0],
                                                     axis=list(axis), pin_radius=PIN_RADIUS, slot_width=SLOT_WIDTH,
                                                     slot_length=slot_length, length=PIN_LENGTH, backend=backend,
                                                     **parameters)
    mbs.Assemble()
    return mbs, joint, node


def pin_against_revolute(axis=(0.0, -1.0, 0.0), end_time: float = 0.05) -> dict[str, float]:
    """The pin in a slot of length 0 on a slot turning at 20 rad/s, the pin flung across it
    spinning, Coulomb friction: its coordinates against the revolute clearance joint's (whose
    joint frame for the z axis has x along -y: ``axis=(0, -1, 0)`` is the same frame).
    Returns the largest difference [m or rad] and the impacts."""
    runs = []
    for slot_length in (0.0, None):
        mbs, joint, node = pin_in_slot(slot_length, axis=axis, velocity=(0.3, 0.2, 40.0), slot_spin=20.0,
                                       friction="coulomb:0.15")
        run(mbs, end_time)
        runs.append((np.asarray(mbs.systemData.GetODE2Coordinates()), len(joint.impacts())))
    (q_slot, n_slot), (q_rev, n_rev) = runs
    return {"difference": float(np.abs(q_slot - q_rev).max()), "impacts": n_slot, "revolute_impacts": n_rev}


def pin_sliding(end_time: float = 0.04) -> dict[str, float]:
    """The pin resting on the slot's lower flat side, pushed along it at :data:`SLIDE_SPEED`
    with Coulomb friction :data:`SLIDE_MU`: while it slips (until ``v0 / (3 mu g)`` for a
    solid pin) its speed falls as ``v0 - mu g t`` and its spin grows as ``2 mu g t / R_P``;
    ``F_T / F_N = mu``."""
    law = make_pin_slot_joint(pin_radius=PIN_RADIUS, slot_width=SLOT_WIDTH, slot_length=0.2, length=PIN_LENGTH,
                              law="hertz+lankarani-nikravesh", cr=0.7).law
    sink = (PIN_MASS * GRAVITY / law.stiffness(0.0)) ** (1.0 / law.exponent)  # Hertz's static penetration
    c = 0.5 * SLOT_WIDTH - PIN_RADIUS
    mbs, joint, node = pin_in_slot(0.2, velocity=(SLIDE_SPEED, 0.0, 0.0), start=(0.0, -(c + sink)),
                                   friction=f"coulomb:{SLIDE_MU}")
    run(mbs, end_time)
    out = joint.outputs()
    v = mbs.GetNodeOutput(node, exu.OutputVariableType.Velocity)[0]
    w = mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity)[2]
    rows = out["normal_force"] > 0.0
    ratio = np.abs(out["tangential_force"][rows]) / out["normal_force"][rows]
    g = SLIDE_MU * GRAVITY * end_time
    return {"speed": float(v), "coulomb_speed": SLIDE_SPEED - g, "spin": float(abs(w)),
            "coulomb_spin": 2.0 * g / PIN_RADIUS, "ratio_min": float(ratio.min()), "ratio_max": float(ratio.max()),
            "mu": SLIDE_MU}


#: The scene's steps of the agreement check [s]: its default, and a quarter of it.
AGREEMENT_STEPS = (1e-6, 2.5e-7)
#: The corners' stiffness of the table over K [N/m^1.5], each with a step that resolves its contact [s].
STIFFNESS_STEPS = ((1e8, 1e-6), (1e9, 1e-6), (1e10, 1e-6), (1e11, 2.5e-7))


def _scene_run(step: float, end_time: float = BENCHMARK_END_TIME, **changes):
    params = slider_crank.GuidedSliderCrankParams.benchmark(**changes)
    return params, slider_crank.run(params, replace(slider_crank.default_settings(params, end_time), step=step))


def reference_agreement(end_time: float = BENCHMARK_END_TIME) -> list[dict[str, float]]:
    """The scene against the SciPy reference over the benchmark, at each of :data:`AGREEMENT_STEPS`:
    until when the slider's place across the guide agrees within 1e-3 c and 1e-2 c, and the
    crank's speed within 1 %, and the largest differences."""
    theirs = reference.simulate(reference.GuidedSliderCrank.benchmark(), end_time, output_step=1e-5)
    rows = []
    for step in AGREEMENT_STEPS:
        params, mine = _scene_run(step, end_time)
        y = np.interp(mine.time, theirs.time, theirs.slider[:, 1])
        speed = np.interp(mine.time, theirs.time, theirs.u[:, 0])
        dy, dw = np.abs(mine.slider[:, 1] - y) / params.clearance, np.abs(mine.crank_speed - speed)

        def until(bad: np.ndarray) -> float:
            return float(mine.time[np.argmax(bad)]) if bad.any() else float(mine.time[-1])

        rows.append({"step": step, "y 1e-3 c": until(dy > 1e-3), "y 1e-2 c": until(dy > 1e-2),
                     "speed 1 %": until(dw > 0.01 * np.abs(speed)), "max dy / c": float(dy.max()),
                     "max dw [rad/s]": float(dw.max()), "contacts": len(mine.impacts), "reference onsets": len(theirs.impacts)})
    return rows


def elastic_benchmark(end_time: float = BENCHMARK_END_TIME) -> dict[str, float]:
    """The benchmark with elastic corners and no friction over its two crank turns: the
    energy at the end against the start (generalized-alpha without numerical damping)."""
    params = slider_crank.GuidedSliderCrankParams.benchmark(damping="none", friction="none")
    scene = slider_crank.build(params)
    start = slider_crank.energy(scene)
    _run_settings(scene.mbs, replace(slider_crank.default_settings(params, end_time), spectral_radius=1.0))
    return {"start": start, "end": slider_crank.energy(scene), "contacts": len(scene.joint.impacts())}


def stiffness_table(end_time: float = BENCHMARK_END_TIME) -> list[dict[str, float]]:
    """The benchmark's features over the corners' stiffness K (:data:`STIFFNESS_STEPS`): the
    contacts, the slider's excursion across the guide, the crank's lowest and last speed
    and the largest corner force; as K grows they settle to the rigid-impact solution's."""
    rows = []
    for stiffness, step in STIFFNESS_STEPS:
        params, r = _scene_run(step, end_time, stiffness=stiffness)
        rows.append({"K": stiffness, "contacts": len(r.impacts), "y/c min": r.slider[:, 1].min() / params.clearance,
                     "y/c max": r.slider[:, 1].max() / params.clearance, "crank min": r.crank_speed.min(),
                     "crank end": r.crank_speed[-1], "largest force": r.normal_force.max()})
    return rows


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-slider-crank", action="store_true",
                        help="leave out the slider-crank (its reference run and the table over K take a minute)")
    args = parser.parse_args(argv)
    rows = []
    r = resting()
    rows.append(("resting: lower corners' force [N]", f"{r['force'][0]:.6g}, {r['force'][1]:.6g}",
                 f"m g / 2 = {r['half_weight']:.6g}"))
    rows.append(("resting: sink [m]", f"{r['sink'][0]:.6g}", f"(m g / (2K))^(1/n) = {r['static_sink']:.6g}"))
    s = sliding()
    rows.append(("sliding: speed after 0.05 s [m/s]", f"{s['speed']:.6g}", f"v0 - mu g t = {s['coulomb_speed']:.6g}"))
    rows.append(("sliding: F_T / F_N at the lower corners", f"{s['ratio_min']:.6g} ... {s['ratio_max']:.6g}",
                 f"mu = {s['mu']:g}"))
    e = elastic_rattle()
    rows.append(("elastic rattle: kinetic energy [J]", f"{e['end']:.8g} ({e['contacts']} contacts)",
                 f"{e['start']:.8g}"))
    p = pin_against_revolute()
    rows.append(("pin in a slot of length 0 vs revolute joint: largest coordinate difference",
                 f"{p['difference']:.3g} ({p['impacts']} impacts)", f"0 ({p['revolute_impacts']} impacts)"))
    p = pin_against_revolute(axis=(0.8, 0.6, 0.0))
    rows.append(("the same, the slot frame turned by 126.87 degrees", f"{p['difference']:.3g}", "round-off"))
    s = pin_sliding()
    rows.append(("pin sliding on a flat: speed after 0.04 s [m/s]", f"{s['speed']:.6g}",
                 f"v0 - mu g t = {s['coulomb_speed']:.6g}"))
    rows.append(("pin sliding on a flat: spin after 0.04 s [rad/s]", f"{s['spin']:.6g}",
                 f"2 mu g t / R_P = {s['coulomb_spin']:.6g}"))
    rows.append(("pin sliding on a flat: F_T / F_N", f"{s['ratio_min']:.6g} ... {s['ratio_max']:.6g}", f"mu = {s['mu']:g}"))
    from validation import translational_box  # it builds on this module's slider

    rows += translational_box.rows()
    print(markdown_table(("check", "exuclear", "analytic"), rows))
    if args.no_slider_crank:
        return 0
    print("\nThe Flores-Leine-Glocker slider-crank against the SciPy reference (times until the first departure):")
    agreement = reference_agreement()
    print(markdown_table(tuple(agreement[0]), [[f"{v:.4g}" for v in row.values()] for row in agreement]))
    e = elastic_benchmark()
    print(f"\nElastic corners over the benchmark's {BENCHMARK_END_TIME} s: energy {e['start']:.10g} J -> "
          f"{e['end']:.10g} J (relative {(e['end'] - e['start']) / e['start']:.3g}, {e['contacts']} contacts)")
    print("\nThe benchmark over the corners' stiffness K:")
    table = stiffness_table()
    print(markdown_table(tuple(table[0]), [[f"{v:.4g}" for v in row.values()] for row in table]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
