"""The Exudyn element on general bodies, the solver guard, and bad input."""
from __future__ import annotations

import math
import subprocess
import sys

import exudyn as exu
import numpy as np
import pytest
from exudyn.itemInterface import (
    MarkerBodyRigid,
    NodeRigidBody2D,
    ObjectGround,
    ObjectJointRevolute2D,
    ObjectRigidBody2D,
)

import exuclear

R_J, R_B, L = 9.9e-3, 10e-3, 15e-3
ARM_I, ARM_J = (0.05, 0.01), (-0.02, 0.03)  # journal and bearing centres in the body frames


def _rotate(phi, p):
    c, s = math.cos(phi), math.sin(phi)
    return np.array([c * p[0] - s * p[1], s * p[0] + c * p[1]])


def _two_body_system(friction="none", law="hertz", cr=None, backend="python"):
    mbs = exu.SystemContainer().AddSystem()
    bodies = []
    for ref in ([0.0, 0.0, 0.3], [0.1, 0.0, -0.2]):
        node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=ref))
        bodies.append(mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=1.0, inertia=1e-3)))
    handle = exuclear.add_clearance_joint(
        mbs, bodies[0], bodies[1], journal_point=ARM_I, bearing_point=ARM_J, journal_radius=R_J,
        bearing_radius=R_B, length=L, law=law, cr=cr, friction=friction, record=False, backend=backend)
    mbs.Assemble()
    return mbs, handle


def _contact_state(delta, angle=0.8):
    """Displacement coordinates q (6) putting P_J at |e| = c + delta along ``angle``."""
    p_b = np.array([0.1, 0.0]) + _rotate(-0.2, ARM_J)
    p_j = p_b + (R_B - R_J + delta) * np.array([math.cos(angle), math.sin(angle)])
    node_i = p_j - _rotate(0.3, ARM_I)  # body i: reference at the origin
    return np.array([node_i[0], node_i[1], 0.0, 0.0, 0.0, 0.0])


def test_elastic_generalized_forces_are_the_potential_gradient():
    # Hertz: V = K delta^2.5 / 2.5 with delta from the body poses computed here by hand;
    # Q = -grad V checks arms, rotations and the node mapping of section 4.
    # Central differences with h = 1e-9 have error ~ V''' h^2, far below 1e-6 relative.
    mbs, handle = _two_body_system()
    k = handle.joint.law.stiffness(0.0)
    rot_i, rot_j = 0.01, -0.02  # small rotations on top of the reference angles

    def potential(q):
        p_j = q[:2] + _rotate(0.3 + q[2], ARM_I)
        p_b = np.array([0.1, 0.0]) + q[3:5] + _rotate(-0.2 + q[5], ARM_J)
        delta = np.linalg.norm(p_j - p_b) - (R_B - R_J)
        return k * max(delta, 0.0) ** 2.5 / 2.5

    p_b = np.array([0.1, 0.0]) + _rotate(-0.2 + rot_j, ARM_J)
    p_j = p_b + (R_B - R_J + 2e-6) * np.array([math.cos(0.8), math.sin(0.8)])
    q = np.concatenate([p_j - _rotate(0.3 + rot_i, ARM_I), [rot_i, 0.0, 0.0, rot_j]])
    forces = np.array(handle.force_function(mbs, 0.0, handle.object_index, q, np.zeros(6)))
    h = 1e-9
    gradient = [(potential(q + h * e) - potential(q - h * e)) / (2 * h) for e in np.eye(6)]
    assert np.abs(forces).max() > 1.0
    np.testing.assert_allclose(forces, -np.array(gradient), rtol=1e-6, atol=1e-6 * np.abs(forces).max())


def test_power_of_generalized_forces_equals_contact_dissipation():
    # for any velocities, Q . q_t = -(F_N delta_dot + F_T v_T) (docs/physics.md eq. (27)):
    # the friction moments on both bodies included
    mbs, handle = _two_body_system(friction="coulomb:0.2", law="lankarani-nikravesh", cr=0.8)
    q = _contact_state(3e-6)
    handle.history.in_contact, handle.history.v0 = True, 1.0  # a contact that began at 1 m/s
    rng = np.random.default_rng(7)
    for _ in range(5):
        q_t = rng.normal(size=6) * np.array([0.1, 0.1, 10, 0.1, 0.1, 10])
        forces = np.array(handle.force_function(mbs, 0.0, handle.object_index, q, q_t))
        kin = handle.kinematics(q, q_t)
        resp = handle.joint.response(kin, handle.history)
        assert resp.f_t != 0.0
        assert forces @ q_t == pytest.approx(-(resp.f_n * kin.delta_dot + resp.f_t * kin.v_t), rel=1e-10)


@pytest.mark.parametrize("friction", ["none", "paper"])
def test_symbolic_backend_evaluates_the_python_formulas(friction):
    # the compiled expression and the Python callback are the same formulas: on states in
    # and out of contact, with each kind of contact history, they agree to round-off
    mbs, handle = _two_body_system(friction=friction, law="wang-liu", cr=0.6, backend="symbolic")
    assert handle.backend == "symbolic"
    rng = np.random.default_rng(3)
    histories = [(False, 0.0, float("-inf"), 0.0), (False, 0.0, -2e-6, 0.4), (True, 0.25, 1e-6, 0.1),
                 (True, 1e-5, 1e-6, 0.0)]  # (in contact, v0, last delta, last delta_dot)
    for in_contact, v0, delta0, rate0 in histories:
        h = handle.history
        h.in_contact, h.v0, h.delta, h.delta_dot = in_contact, v0, delta0, rate0
        handle._compiled.push(h)
        for delta in (-3e-6, 1e-7, 4e-6):
            q = _contact_state(delta).tolist()
            for _ in range(3):
                q_t = (rng.normal(size=6) * np.array([0.1, 0.1, 3, 0.1, 0.1, 3])).tolist()
                expected = np.array(handle.force_function(mbs, 0.0, handle.object_index, q, q_t))
                got = np.array(handle._compiled.function.Evaluate(mbs, 0.0, handle.object_index, q, q_t))
                np.testing.assert_allclose(got, expected, rtol=1e-9, atol=1e-9 * max(1.0, np.abs(expected).max()))


def test_unknown_backend_is_refused():
    with pytest.raises(ValueError, match="unknown `backend` 'cpp'; known: python, symbolic"):
        _two_body_system(backend="cpp")


def test_explicit_solver_with_constraints_is_refused():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=1.0, inertia=1e-3))
    m0 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground))
    m1 = mbs.AddMarker(MarkerBodyRigid(bodyNumber=body))
    mbs.AddObject(ObjectJointRevolute2D(markerNumbers=[m0, m1]))
    exuclear.add_clearance_joint(mbs, body, ground, journal_radius=R_J, bearing_radius=R_B, length=L, cr=0.9)
    mbs.Assemble()
    with pytest.raises(ValueError, match="explicit.*JointRevolute2D"):
        exuclear.simulate(mbs, exuclear.SolverSettings(end_time=1e-3, method="dopri5"))
    assert exuclear.simulate(mbs, exuclear.SolverSettings(end_time=1e-3, method="generalized-alpha")).success


def test_user_post_step_function_is_kept_and_a_later_one_refused():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0.0, 0.0, 0.0]))
    body = mbs.AddObject(ObjectRigidBody2D(nodeNumber=node, mass=1.0, inertia=1e-3))
    calls, attempts = [], []
    mbs.SetPostStepUserFunction(lambda mbs_, t: calls.append(t) or True)
    mbs.SetPreStepUserFunction(lambda mbs_, t: attempts.append(t) or True)
    exuclear.add_clearance_joint(mbs, body, ground, journal_radius=R_J, bearing_radius=R_B, length=L, cr=0.9)
    mbs.Assemble()
    settings = exuclear.SolverSettings(end_time=1e-3, method="rk44", step=1e-4)
    assert exuclear.simulate(mbs, settings).success
    assert len(calls) == 11  # the initial state and one per step of 1e-4 s
    assert len(attempts) == 10
    mbs.SetPostStepUserFunction(lambda mbs_, t: True)
    with pytest.raises(RuntimeError, match="pre- or post-step user function"):
        exuclear.simulate(mbs, settings)


GOOD = dict(journal_radius=R_J, bearing_radius=R_B, length=L, cr=0.9)


@pytest.mark.parametrize("change, message", [
    (dict(journal_radius=10e-3), "journal_radius` must be smaller"),
    (dict(journal_radius=11e-3), "journal_radius` must be smaller"),
    (dict(length=0.0), "`length` must be positive"),
    (dict(length=float("nan")), "`length` must be finite"),
    (dict(cr=0.0), r"`cr` must lie in \(0.0, 1.0\]"),
    (dict(cr=1.2), r"`cr` must lie in \(0.0, 1.0\]"),
    (dict(cr=float("nan")), "`cr` must be finite"),
    (dict(cr=None), "`cr` .* is required"),
    (dict(law="hertzian"), "unknown `law` 'hertzian'; known: flores, hertz"),
    (dict(journal_material="brass"), "unknown `material` 'brass'; known: aluminium, copper"),
    (dict(E_star=-1.0), "`E_star` must be positive"),
    (dict(journal_material=exuclear.Material(2e11, 0.3)), None),
    (dict(friction="coulomb:x"), "coulomb:MU needs a number"),
    (dict(friction="viscous"), "unknown `friction`"),
    (dict(v_min=0.0), "`v_min` must be positive"),
])
def test_bad_joint_parameters(change, message):
    if message is None:
        exuclear.make_joint(**{**GOOD, **change})
        return
    with pytest.raises(ValueError, match=message):
        exuclear.make_joint(**{**GOOD, **change})


@pytest.mark.parametrize("E, nu, message", [(0.0, 0.3, "`E` must be positive"), (2e11, 0.5, "`nu` must lie"),
                                            (2e11, -1.0, "`nu` must lie"), (float("nan"), 0.3, "`E` must be finite")])
def test_bad_material(E, nu, message):
    with pytest.raises(ValueError, match=message):
        exuclear.Material(E, nu)


def test_clearance_must_be_positive():
    with pytest.raises(ValueError, match="`clearance` must be positive, got -0.0001"):
        exuclear.BearingGeometry.from_clearance(10e-3, -1e-4, 15e-3)


def test_bad_bodies():
    mbs = exu.SystemContainer().AddSystem()
    ground = mbs.AddObject(ObjectGround())
    with pytest.raises(ValueError, match="both the ground"):
        exuclear.add_clearance_joint(mbs, ground, ground, **GOOD)
    with pytest.raises(ValueError, match="not an object"):
        exuclear.add_clearance_joint(mbs, 99, ground, **GOOD)
    with pytest.raises(ValueError, match="journal_point"):
        exuclear.add_clearance_joint(mbs, ground, ground, journal_point=(0.0,), **GOOD)


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "models.journal_bearing", *args], capture_output=True, text=True)


def test_cli_json():
    import json

    proc = _cli("--law", "wang-liu", "--cr", "0.9", "--length", "0.015", "--journal", "steel", "--bearing", "steel",
                "--json")
    assert proc.returncode == 0, proc.stderr
    result = json.loads(proc.stdout)
    assert {"departure_velocity", "max_force", "max_penetration", "contact_duration"} <= set(result)
    assert result["departure_velocity"] == pytest.approx(0.269, rel=0.01)  # the paper, section 5.1


@pytest.mark.parametrize("args, message", [(("--cr", "1.5"), "`cr` must lie"), (("--law", "foo"), "unknown `law`"),
                                           (("--journal", "wood"), "unknown `material`"),
                                           (("--length", "-1"), "`length` must be positive"),
                                           (("--cr", "nan"), "`cr` must be finite")])
def test_cli_bad_input_exits_2_without_traceback(args, message):
    proc = _cli(*args)
    assert proc.returncode == 2
    assert message in proc.stderr
    assert "Traceback" not in proc.stderr


def test_unphysical_penetration_stops_the_run_with_a_message():
    # a rubber-soft "steel" (E = 1 MPa) lets the 0.3 m/s journal sink far past half the
    # 0.1 mm clearance: the run must stop there, say when and where, and keep the outputs
    from models.journal_bearing import JournalBearingParams, run

    with pytest.warns(exuclear.UnitWarning):  # deliberately soft
        soft = exuclear.Material(1e6, 0.3, "soft")
    params = JournalBearingParams.paper(journal_material=soft, bearing_material=soft, end_time=1e-2)
    result, out = run(params)
    assert not result.success
    assert "joint 'journal-bearing': penetration" in result.message
    assert "exceeds the limit 5e-05 m (50% of the clearance)" in result.message
    assert "at t = " in result.message
    assert len(out["time"]) > 10 and out["penetration"].max() > 5e-5
    assert out["time"][-1] < 1e-2  # stopped early


@pytest.mark.parametrize("rtol, atol, min_step, message", [
    # the impact needs steps below 5e-7 s at rtol 1e-8: Exudyn goes on at its minimum
    (1e-8, 1e-14, 5e-7, "step collapsed to the minimum step"),
    # at rtol 1e-12 and a 1e-7 s minimum Exudyn's DOPRI5 retries one step forever
    (1e-12, 1e-18, 1e-7, "retried one step 200 times"),
])
def test_step_size_collapse_stops_the_run(rtol, atol, min_step, message):
    from models.journal_bearing import JournalBearingParams, run

    settings = exuclear.SolverSettings(end_time=1e-4, method="dopri5", step=1e-5, rtol=rtol, atol=atol,
                                       min_step=min_step)
    result, out = run(JournalBearingParams.paper(end_time=1e-4), settings)
    assert not result.success
    assert message in result.message


@pytest.mark.parametrize("make, fragment", [
    (lambda: exuclear.Material(3e6, 0.4), "was it given in MPa or GPa"),          # 3 GPa typed as MPa
    (lambda: exuclear.BearingGeometry(9.9, 10.0, 15.0), None),                    # mm throughout: c/R_J = 1 %
    (lambda: exuclear.BearingGeometry(5e-3, 10e-3, 15e-3), "was a value given in mm"),
])
def test_likely_unit_mistakes_warn(make, fragment):
    import warnings

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        make()
    messages = [str(w.message) for w in caught if issubclass(w.category, exuclear.UnitWarning)]
    if fragment is None:
        assert messages == []
    else:
        assert len(messages) == 1 and fragment in messages[0]


def test_cli_warning_is_one_line():
    proc = _cli("--journal-radius", "0.005", "--json")
    assert proc.returncode == 0
    assert proc.stderr.strip().startswith("warning: the radial clearance")
    assert "Traceback" not in proc.stderr and "UnitWarning" not in proc.stderr
