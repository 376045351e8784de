"""The two kernels on a worn joint (docs/physics.md section 11): the compiled kernel's
``wear.hpp`` states node by node what the Python kernel's ``wear.py`` and
``exuclear/wear/surface.py`` state with NumPy, in the same order, so the two agree to
round-off on the profiles, the contact's outputs and the bodies' motion; an unstable update
stops both with the same message; a joint whose wear stays zero runs bit for bit as the
unworn one."""
from __future__ import annotations

import math
from dataclasses import replace

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import SensorNode

import exuclear
from exuclear.engine import kernel
from validation.wear import worn_in_journal as scene

COMPILED = pytest.mark.skipif(kernel.STATUS != kernel.STATUS_DIRECT, reason=f"compiled kernel: {kernel.STATUS}")

#: The spinning journal (validation.wear.worn_in_journal): the paper's bearing (R = 10 mm,
#: c = 0.1 mm, L = 15 mm), a 1 kg journal turning at 100 rad/s, pressed along -x by 500 N.
FORCE, SPIN = scene.FORCE, scene.SPIN
#: What the kernels must agree to, relative to each quantity's largest magnitude in the run.
ROUND_OFF = 1e-9
PROFILES = ("bearing", "journal", "slip", "stability")
CONTACT_OUTPUTS = ("penetration", "penetration_rate", "ecc_x", "ecc_y", "normal_force", "tangential_force",
                   "slip_velocity")


def spinning_journal(backend: str, end_time: float, wear: exuclear.Wear | None, *, friction: str = "none",
                     spin: float = SPIN, force: float = FORCE, velocity: float = 0.0, step: float = 1e-4,
                     adaptive: bool = True, hold_spin: bool = False) -> dict:
    """The journal of the module docstring over ``end_time`` [s] (Exudyn's generalized-alpha
    with steps of at most ``step``), started against the wall at ``(-c, 0)`` with the speed
    ``velocity`` along -x, its spin held by a velocity constraint where ``hold_spin`` (else
    friction brakes it to a stick-slip rattle in the imprint, which amplifies round-off);
    the joint's outputs, the body's coordinates and their rates per accepted step, the worn
    profiles (where it wears), its failure, and whether the solve raised."""
    mbs, handle, node = scene.build(wear, friction=friction, backend=backend, spin=spin, force=force,
                                    velocity=velocity, hold_spin=hold_spin)
    sensors = [mbs.AddSensor(SensorNode(nodeNumber=node, storeInternal=True, writeToFile=False, outputVariableType=kind))
               for kind in (exu.OutputVariableType.Coordinates, exu.OutputVariableType.Coordinates_t)]
    mbs.Assemble()
    s = scene.settings(end_time, step, adaptive)
    s.timeIntegration.verboseMode = 0
    s.solution.sensors.writePeriod = 1e-9  # every accepted step
    raised = False
    try:
        mbs.SolveDynamic(s)
    except Exception:  # Exudyn's own error type, from the kernel's failure
        raised = True
    out = {"raised": raised, "failure": handle.failure(), "outputs": handle.outputs(),
           "coordinates": mbs.GetSensorStoredData(sensors[0]), "velocities": mbs.GetSensorStoredData(sensors[1])}
    if wear is not None:
        p = handle.wear_profile()
        out["profiles"] = {name: getattr(p, name) for name in PROFILES}
    return out


def assert_round_off(compiled: dict, python: dict) -> dict[str, float]:
    """The two runs agree to :data:`ROUND_OFF` on every profile, contact output and body
    coordinate and velocity, each relative to its largest magnitude in the Python run (the
    components of the eccentricity, of the body's position and of its velocity relative to
    the vector's: a component that stays near zero holds only round-off); returns the largest
    relative differences by name."""
    pairs = {f"profile {k}": (compiled["profiles"][k], python["profiles"][k], None) for k in PROFILES}
    for k in ("time", *CONTACT_OUTPUTS):
        pairs[k] = (compiled["outputs"][k], python["outputs"][k], None)
    e = np.hypot(python["outputs"]["ecc_x"], python["outputs"]["ecc_y"])
    pairs["ecc_x"], pairs["ecc_y"] = ((*pairs[k][:2], e) for k in ("ecc_x", "ecc_y"))
    for k in ("coordinates", "velocities"):  # the sensor's time, x, y, angle
        c, p = compiled[k], python[k]
        assert c.shape == p.shape, f"body {k}: {c.shape} against {p.shape} (the runs took other steps)"
        pairs[f"body {k} x, y"] = (c[:, 1:3], p[:, 1:3], np.hypot(p[:, 1], p[:, 2]))
        pairs[f"body {k} angle"] = (c[:, 3], p[:, 3], None)
    found = {}
    for name, (c, p, vector) in pairs.items():
        assert c.shape == p.shape, f"{name}: {c.shape} against {p.shape} (the runs took other steps)"
        scale = np.max(np.abs(p if vector is None else vector))
        found[name] = float(np.max(np.abs(c - p)) / scale) if scale > 0.0 else float(np.max(np.abs(c)))
        assert found[name] <= ROUND_OFF, f"{name}: {found[name]:.2e} relative"
    return found


@COMPILED
def test_the_kernels_agree_on_bearing_wear_of_the_spinning_journal():
    """Bearing wear, Winkler pressure, over 0.1 s (an imprint of some 36 um, 18 times the
    elastic approach, with the journal carried in it)."""
    wear = exuclear.Wear(coefficient=1e-10)
    compiled, python = spinning_journal("compiled", 0.1, wear), spinning_journal("python", 0.1, wear)
    assert not python["raised"] and python["profiles"]["bearing"].max() > 3e-5
    assert_round_off(compiled, python)


@COMPILED
def test_the_kernels_agree_on_both_surfaces_with_friction_and_hertz_pressure():
    """Both surfaces wear under the Hertz strip, with Coulomb friction and the spin held, from
    a bearing worn before the run (the profiles set_wear gives the compiled kernel).  Slowly
    (k_D = 1e-12): the imprint stays within the elastic approach; the Hertz strip's narrow
    groove, worn deeper, makes the journal rattle in it under friction, and that motion
    amplifies round-off (a last-bit change of the load moves the Python kernel's own
    profiles by 1e-5 in 0.01 s)."""
    theta = 2.0 * math.pi * np.arange(720) / 720
    worn = 5e-7 * np.maximum(-np.cos(theta), 0.0) ** 2  # a shallow imprint under the load
    wear = exuclear.Wear(coefficient=1e-12, surface="both", pressure="hertz", bearing=tuple(worn))
    compiled, python = (spinning_journal(b, 0.03, wear, friction="coulomb:0.1", hold_spin=True)
                        for b in ("compiled", "python"))
    assert not python["raised"] and python["profiles"]["journal"].max() > 0.0
    assert python["profiles"]["bearing"].max() > worn.max()
    assert_round_off(compiled, python)


@COMPILED
@pytest.mark.filterwarnings("ignore:.*Exudyn's solver ended the run:exuclear.exceptions.AccuracyWarning")
def test_an_unstable_update_stops_both_kernels_with_the_same_message():
    """A large coefficient at a long fixed step: k_D K ds > 1 (eq. (81)) stops the run at the
    same step in both kernels, naming the cause and the step to take."""
    wear = exuclear.Wear(coefficient=1e-7)
    runs = [spinning_journal(b, 0.01, wear, step=1e-3, adaptive=False) for b in ("compiled", "python")]
    (message, time), (python_message, python_time) = (r["failure"] for r in runs)
    assert all(r["raised"] for r in runs)
    assert message.startswith("the wear update is unstable: k_D K ds = ") and "give a step of at most" in message
    assert (message, time) == (python_message, python_time)


@COMPILED
def test_a_worn_joint_that_never_slips_runs_bit_for_bit_as_the_unworn_one():
    """A journal thrown along -x without spin or friction bounces on the wall with no slip
    (v_T = 0): its wear stays zero, and the compiled kernel runs it to the last bit as the
    same joint without wear (the Jacobian steering included: a worn joint asks for a
    Jacobian per step only once it has worn)."""
    kwargs = {"spin": 0.0, "force": 50.0, "velocity": 0.5}
    worn = spinning_journal("compiled", 0.02, exuclear.Wear(coefficient=1e-10), **kwargs)
    plain = spinning_journal("compiled", 0.02, None, **kwargs)
    assert worn["outputs"]["in_contact"].any() and np.all(worn["profiles"]["bearing"] == 0.0)
    for name in ("time", *CONTACT_OUTPUTS):
        assert np.array_equal(worn["outputs"][name], plain["outputs"][name]), name
    for name in ("coordinates", "velocities"):
        assert np.array_equal(worn[name], plain[name]), name


@COMPILED
def test_the_compiled_backend_takes_a_new_joints_wear_between_runs():
    """The handle's joint setter gives the compiled kernel the new wear's initial profiles
    (CompiledBackend.set_joint), as the Python kernel's joint setter takes them."""
    _, handle, _ = scene.build(exuclear.Wear(coefficient=1e-10, nodes=16), backend="compiled")
    assert handle.backend == "compiled" and np.all(handle.wear_profile().bearing == 0.0)
    start = tuple(1e-6 * (k % 3) for k in range(16))
    handle.joint = replace(handle.joint, wear=exuclear.Wear(coefficient=1e-10, nodes=16, bearing=start))
    assert tuple(handle.wear_profile().bearing) == start
