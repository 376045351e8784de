"""The zoo (validation/exudyn_examples): every registered model, short, those of the group
"beyond" too (more of Exudyn's examples, which the zoo's default table leaves out).

Three checks per model, parametrized over the registry so that a new model is picked up
without editing this file:

- the ideal model (the example as written) runs to its end, and a conservative one keeps
  its energy (``ZooModel.energy``);
- the clearance model through ``exuclear.simulate`` (``step="auto"``) runs to its end,
  its recorded eccentricity never exceeds ``c`` plus the largest penetration the element
  recorded, its penetration stays below a tenth of the clearance, and its probe stays
  within ``ZooModel.probe_bound`` (c + penetration) of the ideal model's;
- the clearance model with the example's own settings through plain ``mbs.SolveDynamic``
  runs to its end with a penetration below a tenth of the clearance.  Where that fails
  today it is marked ``xfail(strict=True)``, so the mark turns red when it is fixed.
"""
from __future__ import annotations

import warnings
from dataclasses import replace

import exudyn as exu
import numpy as np
import pytest

import exuclear
from validation.exudyn_examples import REGISTRY
from validation.exudyn_examples._common import group_names, joint_peaks
from validation.exudyn_examples._runs import PENETRATION_WRONG

#: The zoo's table and the group "beyond" (validation/exudyn_examples/beyond).
ZOO, BEYOND = group_names("zoo"), group_names("beyond")
NAMES = ZOO + BEYOND

#: Simulated time of the ideal and the simulate checks [s]: a first contact of every model
#: (the journal starts centred and crosses its gap in 2 to 5 ms under gravity) and some
#: sliding, in a second or less per model.
SHORT = 0.05
#: Simulated time of the own-settings check [s]: long enough for today's failures of the
#: examples' own steps to show (the earliest stops at 0.0718 s).
OWN = 0.1

#: Energy conservation of the ideal models: |change of kinetic + potential| at most this
#: fraction of the potential energy exchanged.  The trapezoidal rule conserves the energy
#: of a conservative system up to the Newton tolerance; generalized-alpha with spectral
#: radius 0.9 damps frequencies near 1/step only, and the pendulums move at about 1 Hz.
#: Measured: 1e-7 (3D rigid-body tutorial) and below.
ENERGY_RTOL = 1e-5

#: Where ``exuclear.simulate`` fails today on a model: the reason, for a strict xfail.  None
#: since step="auto" lets the joints control implicit steps (issue 20); before, the friction
#: variants failed at the automatic fixed step (5e-5 s) in their first sliding contact.
SIMULATE_FAILS: dict[str, str] = {}

#: Where the example's own settings fail today (issue 20: the plain mbs.SolveDynamic path
#: at a step that does not resolve the contact), measured at t = OWN.  Six models failed
#: here before the joint's own step control (issue 20) and now pass: double_pendulum_2d,
#: double_pendulum_3d_rxyz, rigid_body_tutorial3 (+ _friction), beam_pendulum_2d (to
#: t = 0.1 s) and piston_engine.
OWN_SETTINGS_FAIL = {
    "scissor_pin_slot": "the example's fixed step of 0.02 s (timeIntegration.adaptiveStep False): Exudyn's Newton does "
                        "not converge in the first step that brings the pin to the slot's wall and the run stops at "
                        "t = 0.02 s; the joint's note says so and advises adaptiveStep = True, with which the same "
                        "settings reach 1 s (70 impacts, 0.017 c)",
    "kinematic_tree_chain": "issue 20: explicit Euler (no error estimate) at 1e-2 s: the joint shortens the steps, but "
                            "explicit Euler does not hold the stiff contact: the penetration runs away (thousands "
                            "of c, until Exudyn's solver gives up), which the joint's AccuracyWarning says",
    "slider_crank_2d": "the example's Newton relativeTolerance 1e-10 (Exudyn's default 1e-8), which the joint keeps, "
                       "lies below the round-off floor that the stiff contact leaves under the residual; the joint's "
                       "absolute tolerance 1e-8 (in place of Exudyn's 1e-10) ends Newton at the floor until the pin's "
                       "load grows: the run stops at t = 0.061 s instead of 0.027 s ('SolveDynamic terminated'); the "
                       "joint's note names the stop and relativeTolerance >= 1e-8 (test_a_run_exudyn_ends_in_contact_"
                       "is_told_with_the_tolerance_that_works); the step (1e-5 s) resolves the contact: with "
                       "relativeTolerance 1e-8 or absoluteTolerance 1e-7 the same run reaches 0.1 s",
}


def _marked(names: list[str], known: dict[str, str]) -> list:
    return [pytest.param(n, marks=pytest.mark.xfail(strict=True, reason=known[n]), id=n) if n in known
            else pytest.param(n, id=n) for n in names]


def _run_ideal(name: str, end_time: float):
    model = REGISTRY[name](False, end_time)
    before = model.energy(model.mbs) if model.energy is not None else None
    assert model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    return model, before


@pytest.mark.parametrize("name", NAMES)
def test_ideal_model_runs_and_keeps_its_energy(name):
    model, before = _run_ideal(name, SHORT)
    assert model.mbs.systemData.GetTime() == pytest.approx(SHORT, rel=1e-9)
    assert np.all(np.isfinite(model.probe(model.mbs)))
    if before is None:
        pytest.skip("the model gives no energy (ZooModel.energy is None): only the run is checked")
    (t0, v0), (t1, v1) = before, model.energy(model.mbs)
    exchanged = abs(v1 - v0)
    assert exchanged > 0.0, "nothing moved"
    assert abs((t1 + v1) - (t0 + v0)) <= ENERGY_RTOL * exchanged


#: Fixed steps that work with friction: the friction law's regularisation (the paper's
#: modified Coulomb law) needs a far smaller fixed step than the contact period (measured:
#: 2e-5 s and 1e-5 s fail at the first sliding contact, 2e-6 s runs).
WORKING_SETTINGS = [pytest.param(name, {"step": 2e-6}, id=f"{name}-step 2e-6 s")
                    for name in ("double_pendulum_2d_friction", "rigid_body_tutorial3_friction")]


@pytest.mark.parametrize(("name", "changes"), [pytest.param(p.values[0], {}, marks=p.marks, id=p.id)
                                                for p in _marked(NAMES, SIMULATE_FAILS)] + WORKING_SETTINGS)
def test_clearance_model_through_simulate_stays_in_its_bearing(name, changes):
    ideal, _ = _run_ideal(name, SHORT)
    probe_ideal = np.asarray(ideal.probe(ideal.mbs), dtype=float)
    model = REGISTRY[name](True, SHORT)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(model.mbs, replace(model.solver_settings, **changes))
    assert result.success, result.message
    c = model.clearance
    pen, _force = joint_peaks(model.joint)
    # the automatic step resolves the contact: the penetration is what the load needs
    # (measured 0.005 c to 0.04 c), far from a tenth of the gap
    assert pen <= PENETRATION_WRONG * c
    out = model.joint.outputs()
    if "ecc_x" in out and np.ndim(out["ecc_x"]) == 1:  # a spherical joint: ecc_z too
        # penetration = eccentricity - c (docs/physics.md): the element's per-step maximum
        # bounds the eccentricity at every output time; 1e-12 m for round-off
        ecc = np.sqrt(out["ecc_x"] ** 2 + out["ecc_y"] ** 2 + out.get("ecc_z", 0.0) ** 2)
        assert ecc.max() <= c + pen + 1e-12
    if model.probe_bound is not None:
        diff = float(np.linalg.norm(np.asarray(model.probe(model.mbs), dtype=float) - probe_ideal))
        assert diff <= model.probe_bound * (c + pen), f"probe differs by {diff / c:.3g} c"


@pytest.mark.parametrize("name", _marked(NAMES, OWN_SETTINGS_FAIL))
def test_clearance_model_with_the_examples_own_settings(name):
    model = REGISTRY[name](True, OWN)
    try:
        ok = model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    except Exception as err:  # Exudyn's own error types
        pytest.fail(f"SolveDynamic raised: {str(err).splitlines()[-1][:300]}")
    assert ok
    assert model.mbs.systemData.GetTime() == pytest.approx(OWN, rel=1e-9)
    pen, _force = joint_peaks(model.joint)
    assert pen <= PENETRATION_WRONG * model.clearance, f"penetration {pen / model.clearance:.3g} c"


#: Issue 20, item 4: friction converges in implicit runs at the joint's own steps, for every
#: friction law (exuclear.friction: Coulomb and the paper's modified Coulomb law), in a 2D
#: and a 3D rigid-body model with their examples' own settings (generalized-alpha and
#: trapezoidal at 1e-3 s).  0.3 s: the first impacts and some 0.25 s of sliding.
FRICTION_RUNS = [pytest.param(model, law, id=f"{model}-{law}")
                 for model in ("double_pendulum_2d", "rigid_body_tutorial3") for law in ("coulomb:0.2", "paper")]


@pytest.mark.parametrize(("name", "friction"), FRICTION_RUNS)
def test_every_friction_law_runs_with_the_examples_own_settings(name, friction):
    model = REGISTRY[name](True, 0.3, friction=friction)
    assert model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    assert model.mbs.systemData.GetTime() == pytest.approx(0.3, rel=1e-9)
    assert not model.joint.notes
    pen, _force = joint_peaks(model.joint)
    assert pen <= PENETRATION_WRONG * model.clearance
    out = model.joint.outputs()
    law = exuclear.friction.friction_law(friction)
    sliding = (out["normal_force"] > 0.0) & (np.abs(out["slip_velocity"]) > 1e-4)
    assert sliding.sum() >= 10, "the journal should slide along its wall"
    # the recorded friction force is the law's at the recorded slip: F_T = mu(v_T) F_N
    # (docs/physics.md eq. (20)), against the slip
    mu = np.array([law.coefficient(v) for v in out["slip_velocity"][sliding]])
    np.testing.assert_allclose(np.abs(out["tangential_force"][sliding]), np.abs(mu) * out["normal_force"][sliding],
                               rtol=1e-9)


def test_registry_is_complete():
    """Every model module imported, and each entry says what it follows and replaces."""
    from validation.exudyn_examples import IMPORT_ERRORS

    assert not IMPORT_ERRORS
    for entry in REGISTRY.values():
        assert entry.example and entry.bodies and entry.replaced, entry.name


def test_the_group_beyond_stays_out_of_the_default_table():
    # the default run (python -m validation.exudyn_examples, group "zoo") keeps its models;
    # the group "beyond" holds the modules of its subpackage, and a model of either group is
    # found by name (the validation scripts' --models)
    from validation.exudyn_examples._common import GROUPS, group_of, model_names

    assert BEYOND and not set(BEYOND) & set(ZOO)
    assert all(REGISTRY[n].module.__name__.startswith(GROUPS["beyond"] + ".") for n in BEYOND)
    assert all(REGISTRY[n].group == "zoo" for n in ZOO)
    assert model_names(f"{ZOO[0]},{BEYOND[0]}") == [ZOO[0], BEYOND[0]]
    with pytest.raises(ValueError, match="in no zoo group's package"):
        group_of("validation.other.model")


#: Issue 20's 3D double pendulum (Euler parameters), 1 s with plain mbs.SolveDynamic at a
#: given step.  With Exudyn's default adaptiveStep the joint shortens the steps that do not
#: resolve its contacts: right at 1e-4 s and 2e-4 s (measured: 0.007 c, 1.5x and 2.1x the
#: ideal model's wall time).  With adaptiveStep=False: right at 2.5e-5 s; at 2e-4 s Exudyn's
#: Newton fails at t = 0.03 s ("SolveDynamic terminated"; before issue 20: the joint's
#: "check your Python code!" at 0.062 s) and the joint's note names it and a step.
ISSUE_20_STEPS = [pytest.param(2.5e-5, False, id="2.5e-5 s fixed"),
                  pytest.param(1e-4, True, id="1e-4 s adaptive"),
                  pytest.param(2e-4, True, id="2e-4 s adaptive"),
                  pytest.param(2e-4, False, id="2e-4 s fixed", marks=pytest.mark.xfail(
                      strict=True, reason="issue 20: at a fixed 2e-4 s Exudyn's Newton fails at t = 0.03 s; the "
                                          "joint's AccuracyWarning names it and a step (test below)"))]


@pytest.mark.parametrize(("step", "adaptive"), ISSUE_20_STEPS)
def test_issue_20_double_pendulum_at_a_given_step(step, adaptive):
    model = REGISTRY["double_pendulum_3d_ep"](True)
    ti = model.simulation_settings.timeIntegration
    ti.numberOfSteps = round(ti.endTime / step)
    ti.adaptiveStep = adaptive  # False: the step as given, a failed step fails the run
    try:
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    except Exception as err:  # Exudyn's own error types
        pytest.fail(f"SolveDynamic raised: {str(err).splitlines()[-1][:300]}")
    assert model.mbs.systemData.GetTime() == pytest.approx(1.0, rel=1e-9)
    pen, _force = joint_peaks(model.joint)
    # at 2.5e-5 s (below simulate's automatic 4.3e-5 s) the contact is resolved: 0.006 c
    # as at the automatic step, far below a tenth of the gap; so with the joint's own steps
    assert pen <= PENETRATION_WRONG * model.clearance


def test_issue_20_double_pendulum_at_a_fixed_step_too_long_is_told():
    model = REGISTRY["double_pendulum_3d_ep"](True, 0.1)
    ti = model.simulation_settings.timeIntegration
    ti.numberOfSteps = round(ti.endTime / 2e-4)
    ti.adaptiveStep = False
    # the joint tells at its first unresolved step, before Exudyn's Newton fails (its
    # generic error), never through the joint's own exception
    with pytest.warns(exuclear.AccuracyWarning, match=r"joint 'elbow'.*adaptiveStep is False.*use a step of at most"):
        with pytest.raises(Exception) as stopped:
            model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    assert "check your Python code" not in str(stopped.value)
    assert model.joint.notes


def test_kinematic_tree_chain_at_its_explicit_euler_step_is_told():
    # the one own-settings run that is not right (OWN_SETTINGS_FAIL): it ends, and the joint
    # says what went wrong, with its name and a step, never through "check your Python code!"
    model = REGISTRY["kinematic_tree_chain"](True, OWN)
    with pytest.warns(exuclear.AccuracyWarning, match=r"joint 'J1'.*use a step of at most"):
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    assert model.mbs.systemData.GetTime() == pytest.approx(OWN, rel=1e-9)


def test_a_run_exudyn_ends_in_contact_is_told_with_the_tolerance_that_works():
    # the zoo's slider-crank with SliderCrank.py's relativeTolerance 1e-10 and an absolute
    # tolerance of 1e-11 (the joint keeps both: the user set them): below the crank pin's
    # round-off, Exudyn's Newton gives up near 0.025 s and says only "SolveDynamic
    # terminated"; the joint names itself, the time, its regime and the tolerances to use, and
    # those let the same run reach its end
    from validation.exudyn_examples import slider_crank_2d

    model = slider_crank_2d.build(True, 0.05)
    model.simulation_settings.timeIntegration.newton.absoluteTolerance = 1e-11
    with pytest.raises(Exception, match="SolveDynamic terminated"):
        model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    with pytest.warns(exuclear.AccuracyWarning, match=r"ended the run at t = 0\.02\d* s of 0\.05 s"):
        notes = model.joint.notes
    assert len(notes) == 1 and "'crank pin'" in notes[0] and "in metal contact" in notes[0]
    assert "relativeTolerance >= 1e-08, now 1e-10" in notes[0] and "absoluteTolerance >= 1e-08" in notes[0]
    model = slider_crank_2d.build(True, 0.05)
    model.simulation_settings.timeIntegration.newton.relativeTolerance = 1e-8
    model.simulation_settings.timeIntegration.newton.absoluteTolerance = 1e-8
    model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    assert model.mbs.systemData.GetTime() == pytest.approx(0.05)
    assert model.joint.notes == []


def test_every_step_that_lands_beyond_the_wall_is_redone_shorter():
    # the scissor's pin crosses its slot many times; at 2.05 s it leaves the lower wall and a
    # step of 10 ms (simulate's longest, end_time / 1000) carries it 27 m "into" the upper
    # one.  Each such step gets its own shorter retries (PENETRATION_RETRIES), also after the
    # run's first four, and a step the joint redoes is not taken for an accepted penetration:
    # the run goes on, and the pin stays in its slot
    model = REGISTRY["scissor_pin_slot"](True, 2.2)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(model.mbs, model.solver_settings)
    assert result.success, result.message
    pen, _force = joint_peaks(model.joint)
    assert pen <= PENETRATION_WRONG * model.clearance
    out = model.joint.outputs()
    # the pin's distance from the slot's centre segment is c + penetration at most (the
    # output's per-step maximum bounds it); 1e-12 m for round-off
    assert np.hypot(out["ecc_x"], out["ecc_y"]).max() <= model.clearance + pen + 1e-12


def test_lubricated_big_end_is_carried_by_its_film():
    # the piston engine's lubricated variant (issue 23) with the example's own settings: the
    # film alone carries the big end (eccentricity ratio below eps_film = 0.9, where the
    # joint's film acts unblended: docs/physics.md eq. (70)), so the metal contact never acts
    from exuclear.engine.outputs import REGIME_FILM

    model = REGISTRY["piston_engine_lubricated"](True, OWN)
    assert model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    out = model.joint.outputs()
    assert (out["regime"] == REGIME_FILM).all()
    assert out["eccentricity_ratio"].max() < model.joint.joint.film.eps_film
    assert out["film_force"].max() > 0.0 and out["normal_force"].max() == 0.0


def test_model_names_of_the_validation_scripts_are_checked():
    from validation.exudyn_examples._common import model_names

    assert model_names("four_bar_3d,piston_engine") == ["four_bar_3d", "piston_engine"]
    with pytest.raises(ValueError, match=r"unknown model\(s\) pendulum; known: ancf_pendulum"):
        model_names("four_bar_3d,pendulum")


def _objects_of_type(mbs, object_type: str) -> list[int]:
    return [i for i in range(mbs.systemData.NumberOfObjects()) if mbs.GetObject(i)["objectType"] == object_type]


def test_cable_hub_resting_on_its_pin_carries_what_the_ideal_pin_carries():
    # the group "beyond"'s ANCF cable on its hub, with the example's own settings, 1.95 s:
    # before its drive starts (2 s) the hub rests on the bottom of its bearing under the
    # cable's weight, one impact and then lasting contact; the contact force then equals the
    # ideal pin's reaction at the same time (the issue's resting-contact row).  The cable's
    # vertical vibration has not died out (its reaction 14.93 N, 2.5 % below the cable's
    # weight of 15.3 N); the journal's offset of c + penetration (1e-5 of the cable's length)
    # changes that vibration by about as much: 1e-3 leaves room for its phase (measured 2e-5)
    end = 1.95
    ideal = REGISTRY["ancf_rotating_cable"](False, end)
    assert ideal.mbs.SolveDynamic(ideal.simulation_settings, solverType=ideal.solver_type)
    (pin,) = _objects_of_type(ideal.mbs, "JointRevolute2D")
    reaction = np.linalg.norm(ideal.mbs.GetObjectOutput(pin, exu.OutputVariableType.Force))
    model = REGISTRY["ancf_rotating_cable"](True, end)
    assert model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
    assert model.mbs.systemData.GetTime() == pytest.approx(end, rel=1e-9)
    assert len(model.joint.impacts()) == 1 and model.joint.state().in_contact
    out = model.joint.outputs()
    assert out["normal_force"][-1] == pytest.approx(reaction, rel=1e-3)
    assert not model.joint.notes


def test_cable_hub_struck_by_its_drive_is_told():
    # at 2 s the hub's prescribed angle pi sin(pi t) starts with a rate of pi^2 rad/s: a jump
    # that strikes the 1 g hub into its wall within one step, which no step the run allows
    # resolves (the joint's shortest is ten times Exudyn's minimum step); the run goes on,
    # and the joint names itself and the setting that lets it shorten further
    model = REGISTRY["ancf_rotating_cable"](True, 2.02)
    with pytest.warns(exuclear.AccuracyWarning, match=r"joint 'hub pin': at t = 2 s .*minimumStepSize"):
        assert model.mbs.SolveDynamic(model.simulation_settings, solverType=model.solver_type)
        assert model.joint.notes
    assert model.mbs.systemData.GetTime() == pytest.approx(2.02, rel=1e-9)
