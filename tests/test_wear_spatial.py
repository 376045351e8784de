"""Wear per slice of the spatial joint (docs/physics.md section 11.7): an aligned journal
wears every slice as the planar joint wears its bearing (each slice carries 1/N of the force
on L/N of the length: the same pressure); a misaligned journal wears the bearing's edges
(Zhang et al., Chin. J. Mech. Eng. 36 (2023)); the two kernels agree to round-off; a joint
whose wear stays zero runs bit for bit as the unworn one; the profiles' shape and the
starting profiles are checked."""
from __future__ import annotations

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (
    Force,
    MarkerBodyRigid,
    NodeRigidBody2D,
    ObjectGround,
    ObjectJointGeneric,
    ObjectRigidBody2D,
    SensorNode,
)
from exudyn.rigidBodyUtilities import RotationMatrixX
from exudyn.utilities import InertiaCylinder, RigidBodyInertia

import exuclear
from exuclear.engine import kernel
from validation.wear import worn_in_journal as scene

COMPILED = pytest.mark.skipif(kernel.STATUS != kernel.STATUS_DIRECT, reason=f"compiled kernel: {kernel.STATUS}")

#: The worn-in journal of validation/wear/worn_in_journal.py: the paper's bearing (R = 10 mm,
#: c = 0.1 mm, L = 15 mm), a journal turning at 100 rad/s, pressed along -x by 500 N.
RADIUS, CLEARANCE, LENGTH = scene.RADIUS, scene.CLEARANCE, scene.LENGTH
FORCE, SPIN = scene.FORCE, scene.SPIN
R_J = RADIUS - CLEARANCE
PROFILES = ("bearing", "journal", "slip", "stability")


def _settings(end_time: float, step: float) -> exu.SimulationSettings:
    s = exu.SimulationSettings()
    s.timeIntegration.endTime = end_time
    s.timeIntegration.numberOfSteps = int(round(end_time / step))
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    s.solution.sensors.writePeriod = 1e-9  # every accepted step
    return s


def worn_in_journal(backend: str, slices: int | None, end_time: float, wear: exuclear.Wear | None, *,
                    spin: float = SPIN, force: float = FORCE, velocity: float = 0.0, step: float = 1e-4) -> dict:
    """The worn-in journal (a planar rigid body, its spin held by a velocity constraint) in a
    fixed bearing, as the planar joint (``slices`` None) or the spatial joint of ``slices``
    slices: with the planar body the journal's axis stays parallel to the bearing's (the
    aligned spatial joint of tests/test_spatial_joint.py).  Its outputs, the body's
    coordinates per accepted step, its profiles (where it wears) and whether the solve raised."""
    mbs, handle, node = scene.build(wear, backend=backend, spin=spin, force=force, velocity=velocity, slices=slices)
    sensor = mbs.AddSensor(SensorNode(nodeNumber=node, storeInternal=True, writeToFile=False,
                                      outputVariableType=exu.OutputVariableType.Coordinates))
    mbs.Assemble()
    raised = False
    try:
        mbs.SolveDynamic(_settings(end_time, step))
    except Exception:  # Exudyn's own error type, from the kernel's failure
        raised = True
    return {"raised": raised, "handle": handle, "outputs": handle.outputs(),
            "coordinates": mbs.GetSensorStoredData(sensor),
            "profile": handle.wear_profile() if wear is not None else None}


def tilted_journal(backend: str, slices: int, end_time: float, wear: exuclear.Wear | None, tilt: float,
                   step: float = 1e-4, friction: str = "none", adaptive: bool = True,
                   inertia: RigidBodyInertia | None = None) -> dict:
    """A journal (a steel cylinder of the bearing's length) tilted by ``tilt`` [rad] about x,
    the axis normal to its load (500 N along -x), held in that tilt and along the axis by a
    generic joint that leaves it free to move across the axis and to turn about it; it
    spins at 100 rad/s (without ``friction`` the spin stays).  Each bearing edge sees the
    journal's axis ``L/2 tilt`` further off the middle's.  ``inertia``: the journal's in place
    of the steel cylinder's."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    rotation = RotationMatrixX(tilt)
    # the reference configuration is aligned (the joint takes the journal's axis from it); the
    # initial one is tilted, its edges at the wall: |e| = sqrt(x^2 + (L/2 tilt)^2) = c there
    x = np.sqrt(CLEARANCE**2 - (0.5 * LENGTH * np.tan(tilt)) ** 2)
    journal = mbs.CreateRigidBody(inertia=inertia or InertiaCylinder(7800.0, LENGTH, R_J, 2),
                                  referencePosition=[0.0, 0.0, 0.0], initialDisplacement=[-x, 0.0, 0.0], initialRotationMatrix=rotation,
                                  initialAngularVelocity=(rotation @ [0.0, 0.0, SPIN]).tolist(),
                                  nodeType=exu.NodeType.RotationRxyz, returnDict=True)
    m_ground = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground))
    m_body = mbs.AddMarker(MarkerBodyRigid(bodyNumber=journal["bodyNumber"]))
    mbs.AddLoad(Force(markerNumber=m_body, loadVector=[-FORCE, 0.0, 0.0]))
    # the tilt and the axial position held: rotations about the tilted frame's x and y and its
    # z translation constrained; free across the axis and about it
    m_tilted = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localHT=exu.HT(rotation=rotation, translation=[0, 0, 0])))
    mbs.AddObject(ObjectJointGeneric(markerNumbers=[m_tilted, m_body], constrainedAxes=[0, 0, 1, 1, 1, 0]))
    handle = exuclear.AddClearanceJoint(mbs, [m_ground, m_body], journal_radius=R_J, bearing_radius=RADIUS,
                                        length=LENGTH, law="lankarani-nikravesh", cr=0.5, friction=friction, wear=wear,
                                        backend=backend, slices=slices, show=False)
    mbs.Assemble()
    settings = _settings(end_time, step)
    settings.timeIntegration.adaptiveStep = adaptive
    raised = False
    try:
        mbs.SolveDynamic(settings)
    except Exception:  # Exudyn's own error type, from the kernel's failure
        raised = True
    return {"raised": raised, "handle": handle, "outputs": handle.outputs(), "failure": handle.failure(),
            "profile": handle.wear_profile() if wear is not None else None}


# -- physics -----------------------------------------------------------------------------------
@pytest.mark.parametrize("slices", [1, 5])
@pytest.mark.parametrize("backend", ["python", pytest.param("compiled", marks=COMPILED)])
def test_an_aligned_journal_wears_every_slice_as_the_planar_joint_wears(backend, slices):
    """Each slice carries 1/N of the force on L/N of the length: the same pressure, so each
    slice's profile is the planar joint's (the worn-in journal over 0.1 s, an imprint of some
    36 um; the Python kernel's over 0.05 s, 26 um, on 360 nodes); measured: 6e-14 relative
    (1e-6 asked), the volume the planar one's."""
    compiled = backend == "compiled"
    wear = exuclear.Wear(coefficient=1e-10, nodes=720 if compiled else 360)
    end_time = 0.1 if compiled else 0.05
    planar = worn_in_journal(backend, None, end_time, wear)
    spatial = worn_in_journal(backend, slices, end_time, wear)
    p, s = planar["profile"], spatial["profile"]
    assert not spatial["raised"] and p.bearing.max() > 2e-5
    assert s.slices == slices and s.bearing.shape == (slices, wear.nodes) and p.slices == 0
    for k in range(slices):
        for name in ("bearing", "slip"):
            ref = getattr(p, name)
            assert np.abs(getattr(s, name)[k] - ref).max() <= 1e-6 * ref.max(), (k, name)
        assert s.slice(k).volume["bearing"] == pytest.approx(p.volume["bearing"] / slices, rel=1e-6)
    assert s.volume["bearing"] == pytest.approx(p.volume["bearing"], rel=1e-6)
    assert s.deepest() == pytest.approx(p.deepest(), rel=1e-6)


@COMPILED
def test_an_aligned_3d_journal_wears_every_slice_as_the_planar_joint_wears():
    """The worn-in journal as a 3D rigid body of the planar one's mass and polar inertia, held
    in the bearing's axis (its tilt and axial position) by a generic joint, its spin kept by
    the absence of friction: each slice's profile is the planar joint's (measured: 4e-14
    relative)."""
    wear = exuclear.Wear(coefficient=1e-10)
    planar = worn_in_journal("compiled", None, 0.1, wear)["profile"]
    inertia = RigidBodyInertia(mass=1.0, inertiaTensor=np.diag([1e-4, 1e-4, 0.5 * R_J**2]))
    run = tilted_journal("compiled", 5, 0.1, wear, 0.0, inertia=inertia)
    assert not run["raised"] and np.all(run["outputs"]["tilt_x"] == 0.0) and np.all(run["outputs"]["tilt_y"] == 0.0)
    for row in run["profile"].bearing:
        assert np.abs(row - planar.bearing).max() <= 1e-6 * planar.bearing.max()


@COMPILED
def test_a_misaligned_journal_wears_the_bearing_edges():
    """A journal tilted by 5 mrad across its load presses the bearing's edges hardest
    (section 9.5), and there the bearing wears most (Zhang et al. 2023, the largest wear at
    the bearing's edges): over 0.02 s at k_D = 1e-11 1/Pa the edge slices' depth is 6.3
    times the middle slice's (3.65 um against 0.58 um), symmetric about the middle."""
    run = tilted_journal("compiled", 9, 0.02, exuclear.Wear(coefficient=1e-11), 5e-3)
    depth = run["profile"].bearing.max(axis=1)
    assert not run["raised"] and run["outputs"]["in_contact"][-1].all()  # every slice carries load
    assert np.all(np.diff(depth[:5]) < 0.0) and np.all(np.diff(depth[4:]) > 0.0)  # deepest at the edges
    assert depth[0] == pytest.approx(depth[-1], rel=1e-2)
    ratio = min(depth[0], depth[-1]) / depth[4]
    assert ratio > 2.0, ratio
    # the middle slice's force is the lowest, the edges' the highest
    f = run["outputs"]["normal_force"][-1]
    assert f.argmin() == 4 and f.argmax() in (0, 8)


# -- the kernels -----------------------------------------------------------------------------
@COMPILED
@pytest.mark.parametrize(("surface", "pressure", "friction"), [("both", "winkler", "none"),
                                                              ("bearing", "hertz", "coulomb:0.1")])
def test_the_kernels_agree_on_the_worn_slices_of_a_misaligned_journal(surface, pressure, friction):
    """The tilted journal with its bearing (and journal) wearing: the compiled kernel's
    profiles, contact outputs and steps are the Python kernel's to round-off (1e-9 relative;
    measured 2e-11 on the profiles, 8e-11 on the outputs)."""
    wear = exuclear.Wear(coefficient=1e-10, surface=surface, nodes=360, pressure=pressure)
    runs = {b: tilted_journal(b, 3, 0.004, wear, 5e-3, friction=friction) for b in ("compiled", "python")}
    c, p = runs["compiled"], runs["python"]
    assert not c["raised"] and not p["raised"]
    assert p["profile"].bearing.max() > 5e-7 and (surface == "bearing" or p["profile"].journal.max() > 1e-6)
    for name in PROFILES:
        ref = getattr(p["profile"], name)
        assert getattr(c["profile"], name).shape == ref.shape == (3, 360)
        assert np.abs(getattr(c["profile"], name) - ref).max() <= 1e-9 * max(np.abs(ref).max(), 1e-300), name
    for name in ("time", "penetration", "normal_force", "slip_velocity", "ecc_x", "ecc_y"):
        ref = p["outputs"][name]
        assert c["outputs"][name].shape == ref.shape, name  # the same steps
        assert np.abs(c["outputs"][name] - ref).max() <= 1e-9 * np.abs(ref).max(), name


@COMPILED
@pytest.mark.filterwarnings("ignore:.*Exudyn's solver ended the run:exuclear.exceptions.AccuracyWarning")
def test_an_unstable_update_in_a_slice_stops_both_kernels_with_the_same_message():
    """A large coefficient at a long fixed step: a slice's k_D K ds > 1 (eq. (81)) stops the
    run at the same step in both kernels, naming the cause and the step to take."""
    wear = exuclear.Wear(coefficient=1e-7, nodes=180)
    runs = [tilted_journal(b, 3, 0.01, wear, 5e-3, step=1e-3, adaptive=False) for b in ("compiled", "python")]
    (message, time), (python_message, python_time) = (r["failure"] for r in runs)
    assert all(r["raised"] for r in runs)
    assert message.startswith("the wear update is unstable: k_D K ds = ") and "give a step of at most" in message
    assert "in one step of slice " in message
    assert (message, time) == (python_message, python_time)


@pytest.mark.parametrize("backend", ["python", pytest.param("compiled", marks=COMPILED)])
def test_the_end_faces_of_an_axial_clearance_do_not_wear(backend):
    """With an axial clearance the end faces follow the slices among the contacts; only the
    slices have profiles."""
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.CreateGround()
    journal = mbs.CreateRigidBody(inertia=InertiaCylinder(7800.0, LENGTH, R_J, 2), referencePosition=[0.0, 0.0, 0.0],
                                  initialVelocity=[-0.2, 0.0, -0.3], initialAngularVelocity=[0.0, 0.0, SPIN],
                                  returnDict=True)
    handle = exuclear.CreateClearanceJoint(mbs, itemNumbers=[ground, journal["bodyNumber"]], position=[0, 0, 0],
                                           axis=[0, 0, 1], slices=3, journal_radius=R_J, bearing_radius=RADIUS,
                                           length=LENGTH, cr=0.5, axial_clearance=2e-4, shoulder_radius=1.5 * RADIUS,
                                           friction="coulomb:0.2", wear=exuclear.Wear(coefficient=1e-10, nodes=90),
                                           backend=backend, show=False)
    mbs.Assemble()
    mbs.SolveDynamic(_settings(0.004, 1e-5))
    out = handle.outputs()
    assert out["face_in_contact"].any() and out["in_contact"].any()  # both kinds of contact touched
    profile = handle.wear_profile()
    assert profile.bearing.shape == (3, 90) and profile.bearing.max() > 0.0


@COMPILED
def test_a_worn_spatial_joint_that_never_slips_runs_bit_for_bit_as_the_unworn_one():
    """A journal thrown along -x without spin or friction bounces on the wall with no slip:
    the slices' wear stays zero, and the compiled kernel runs it to the last bit as the same
    spatial joint without wear."""
    kwargs = {"spin": 0.0, "force": 50.0, "velocity": 0.5}
    worn = worn_in_journal("compiled", 4, 0.02, exuclear.Wear(coefficient=1e-10), **kwargs)
    plain = worn_in_journal("compiled", 4, 0.02, None, **kwargs)
    assert worn["outputs"]["in_contact"].any() and np.all(worn["profile"].bearing == 0.0)
    for name in ("time", "penetration", "penetration_rate", "ecc_x", "ecc_y", "normal_force", "slip_velocity"):
        assert np.array_equal(worn["outputs"][name], plain["outputs"][name]), name
    assert np.array_equal(worn["coordinates"], plain["coordinates"])


# -- the profiles and their input ---------------------------------------------------------------
@pytest.mark.parametrize("backend", ["python", pytest.param("compiled", marks=COMPILED)])
def test_a_spatial_joint_starts_from_its_slices_profiles(backend):
    """``Wear.bearing`` of slices x nodes: each slice starts from its row; one profile: every slice."""
    nodes, slices = 16, 3
    rows = np.array([[1e-6 * (k + 1) * (j % 2) for j in range(nodes)] for k in range(slices)])
    run = worn_in_journal(backend, slices, 1e-4, exuclear.Wear(coefficient=1e-15, nodes=nodes, bearing=rows),
                          spin=0.0)
    assert run["handle"].wear_profile().bearing.shape == (slices, nodes)
    handle = run["handle"]
    handle.joint = exuclear.make_joint(journal_radius=R_J, bearing_radius=RADIUS, length=LENGTH, cr=0.5,
                                       wear=exuclear.Wear(coefficient=1e-15, nodes=nodes, bearing=rows))
    assert np.array_equal(handle.wear_profile().bearing, rows)
    handle.joint = exuclear.make_joint(journal_radius=R_J, bearing_radius=RADIUS, length=LENGTH, cr=0.5,
                                       wear=exuclear.Wear(coefficient=1e-15, nodes=nodes, bearing=rows[1]))
    assert np.array_equal(handle.wear_profile().bearing, np.tile(rows[1], (slices, 1)))


@pytest.mark.parametrize(("slices", "words"), [(None, "the planar joint (slices=None) takes one profile"),
                                               (4, "has 3 rows but the joint has 4 slices")])
def test_a_profile_of_other_slices_is_refused(slices, words):
    wear = exuclear.Wear(coefficient=1e-12, nodes=16, bearing=np.zeros((3, 16)))
    mbs = exu.SystemContainer().AddSystem()
    g = mbs.AddObject(ObjectGround())
    b = mbs.AddObject(ObjectRigidBody2D(nodeNumber=mbs.AddNode(NodeRigidBody2D()), mass=1.0, inertia=1e-4))
    with pytest.raises(ValueError, match=words.replace("(", r"\(").replace(")", r"\)")):
        exuclear.AddClearanceJoint(mbs, [mbs.AddMarker(MarkerBodyRigid(bodyNumber=g)),
                                         mbs.AddMarker(MarkerBodyRigid(bodyNumber=b))], slices=slices,
                                   journal_radius=R_J, bearing_radius=RADIUS, length=LENGTH, cr=0.9, show=False,
                                   wear=wear)


def test_bad_slice_profiles_are_refused():
    with pytest.raises(ValueError, match="16 depths, got shape"):
        exuclear.Wear(coefficient=1e-12, nodes=16, bearing=np.zeros((3, 15)))
    with pytest.raises(ValueError, match=">= 0"):
        exuclear.Wear(coefficient=1e-12, nodes=16, bearing=-np.ones((3, 16)))


@COMPILED
def test_predict_wear_extrapolates_the_slices_profiles():
    """predict_wear on a spatial joint: slices x nodes profiles, each update the cycle's wear
    times dN from the last update's profiles (the aligned journal: every slice the same)."""
    def run_cycle(wear):
        return worn_in_journal("compiled", 3, 0.01, wear)["handle"]

    wear = exuclear.Wear(coefficient=1e-11)
    out = exuclear.predict_wear(run_cycle, wear, 4, dN=2, progress=False)
    assert out.complete and out.cycles == [2, 4]
    final = out.final
    assert final.bearing.shape == (3, 720) and final.slices == 3
    assert np.abs(final.bearing - final.bearing[0]).max() <= 1e-9 * final.bearing.max()
    once = run_cycle(wear).wear_profile()
    assert out.profiles[0].bearing == pytest.approx(2 * once.bearing, rel=1e-12, abs=1e-18)
    assert final.bearing.max() > out.profiles[0].bearing.max()


def test_a_new_joint_with_profiles_of_other_slices_is_refused():
    run = worn_in_journal("python", 3, 1e-4, exuclear.Wear(coefficient=1e-15, nodes=16), spin=0.0)
    with pytest.raises(ValueError, match="has 2 rows but the joint has 3 slices"):
        run["handle"].joint = exuclear.make_joint(
            journal_radius=R_J, bearing_radius=RADIUS, length=LENGTH, cr=0.5,
            wear=exuclear.Wear(coefficient=1e-15, nodes=16, bearing=np.zeros((2, 16))))
