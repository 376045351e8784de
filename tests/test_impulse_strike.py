"""The impulse mode at a prescribed motion's strike on a flexible body
(exuclear.engine.impulse_run.stopped): Exudyn's rotating ANCF cable
(validation/exudyn_examples/beyond/ancf_rotating_cable.py), whose hub's prescribed angle has a
kink at 2 s (its rate jumps from 0 to pi^2 rad/s).  Under the trapezoidal rule, which the
mode needs, the hub's rate and the pin's force then alternate from step to step for good,
the force through zero: no clearance joint can hold that, and the mode's stop says so."""
import warnings

import exudyn as exu
import numpy as np
import pytest

from exuclear.engine.impulse import ImpulseJointHandle
from exuclear.engine.impulse_run import ALTERNATING_STEPS, LOST_THE_CONTACT, stopped

pytest.importorskip("validation.exudyn_examples")
from validation.exudyn_examples.beyond import ancf_rotating_cable as cable  # noqa: E402

#: The runs' end [s]: 15 of the example's 2 ms steps after the strike at 2 s.
END_TIME = 2.03
#: The cable's and the hub's weight [N] (7800 kg/m^3, 2 m of 10 mm x 10 mm; a 1 g hub).
WEIGHT = (cable.DENSITY * cable.WIDTH * cable.HEIGHT * cable.LENGTH + cable.HUB_DENSITY * cable.HUB_SIZE ** 3) * 9.81


def run(clearance, **options):
    model = cable.build(clearance, end_time=END_TIME, **options)
    model.simulation_settings.timeIntegration.generalizedAlpha.spectralRadius = 1.0  # the trapezoidal rule
    return model


def test_the_ideal_hubs_rate_and_pin_force_alternate_after_the_strike():
    # the trapezoidal rule moves the hub's angle by h (w0 + w1) / 2 a step, and the drive
    # prescribes the angle at each step's end: w1 = 2 (theta1 - theta0) / h - w0.  From rest
    # at 2 s the rate alternates between about 2 pi^2 and 0, undamped; the cable's inertia
    # turns that into a pin force that changes sign each step
    model = run(False)
    mbs = model.mbs
    pin = next(i for i in range(mbs.systemData.NumberOfObjects()) if mbs.GetObject(i)["objectType"] == "JointRevolute2D")
    hub = next(i for i in range(mbs.systemData.NumberOfNodes()) if mbs.GetNode(i)["nodeType"] == "RigidBody2D")
    rows = []

    def record(mbs_, t):
        rows.append((t, mbs_.GetNodeOutput(hub, exu.OutputVariableType.AngularVelocity)[2],
                     mbs_.GetObjectOutput(pin, exu.OutputVariableType.Force)[1]))
        return True

    mbs.SetPostStepUserFunction(record)
    assert mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    t, rate, force = np.array(rows).T
    window = t > 1.99
    t, rate, force = t[window], rate[window], force[window]
    angle = np.array([cable.hub_angle(x) for x in t])
    # the rule's recursion, exact: what is left is the angle's Newton residual at each step's
    # end over the step (measured 2.2e-12 rad/s); bounded at 1e-9 rad/s, 5e-11 of 2 pi^2
    np.testing.assert_allclose(rate[1:] + rate[:-1], 2.0 * np.diff(angle) / np.diff(t), rtol=0.0, atol=1e-9)
    struck = t > cable.SWING_START + 1e-3  # the steps that end after the strike
    assert struck.sum() == 15
    # the rate about pi^2 cos(pi t): its mean over two steps (the drive's secant slope) within
    # the change of pi^2 cos(pi t) over the window, 0.44 %
    np.testing.assert_allclose(0.5 * (rate[struck][1:] + rate[struck][:-1]), np.pi ** 2, rtol=5e-3)
    # ... and it alternates by pi^2 either side of it
    assert np.all(np.abs(np.diff(rate[struck])) > 0.99 * 2 * np.pi ** 2)
    # the pin's force (on the hub, as Exudyn reports it) changes sign at every step after the
    # strike, by more than the weight the pin carried before it
    assert np.all(force[struck][1:] * force[struck][:-1] < 0.0)
    assert np.abs(force[struck]).min() > 10.0 * WEIGHT


def test_the_mode_stops_at_the_strike_and_names_the_alternation():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the joint's notes on the clearance ratio: the example's
        model = run(True, contact_mode="impulse")
    assert isinstance(model.joint, ImpulseJointHandle)
    with pytest.raises(Exception):  # the joint's ValueError, raised inside Exudyn's solver
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    with pytest.raises(ValueError) as stop:
        model.joint.impacts()
    told = str(stop.value)
    # within five of the example's 2 ms steps of the strike (the mode shortens the steps there)
    assert cable.SWING_START < float(told.split("stops the run at t = ")[1].split(" s")[0]) < cable.SWING_START + 0.01
    assert f"changed sign at each of its last {ALTERNATING_STEPS} held steps" in told
    assert "a clearance joint cannot pull; shorter steps do not take it out: use contact_mode='compliant'" in told
    assert LOST_THE_CONTACT not in told


def test_a_stop_names_the_alternation_only_where_the_held_multiplier_alternated():
    reason = "the journal is 3e-05 m into the wall"
    alternating = [(1.0 + 1e-6 * k, (-1.0) ** k * 100.0) for k in range(ALTERNATING_STEPS)]
    end = alternating[-1][0] + 1e-6
    assert "changed sign at each" in stopped("pin", end, reason, LOST_THE_CONTACT, alternating, 1e-3)
    # a load that turned once; multipliers held longer than a step before the stop; a settled
    # system (no multipliers given); a stop that is not a penetration's
    turned = [(t, abs(f)) for t, f in alternating[:-1]] + [alternating[-1]]
    for held, at, steps in ((turned, end, LOST_THE_CONTACT), (alternating, end + 2e-3, LOST_THE_CONTACT),
                            ((), end, LOST_THE_CONTACT), (alternating, end, "")):
        told = stopped("pin", at, reason, steps, held, 1e-3)
        assert "changed sign" not in told and told.endswith("; or use contact_mode='compliant'")
        assert (LOST_THE_CONTACT in told) == bool(steps)
