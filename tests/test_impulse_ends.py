"""The impulse contact mode at the ends of a joint: the spatial revolute joint's end faces
(exuclear.engine.impulse_pairs.FacePair, two more contacts of the joint's group) and a
translational joint's finite guide (exuclear.engine.impulse_guide: a corner beyond the end
has no wall).  The scenes are those of ``python -m validation.cost modes_ends``
(validation/cost/_end_scenes.py, whose docstring names the references)."""
import numpy as np
import pytest

from exuclear.contact.law import ContactLaw
from exuclear.contact.stiffness import GivenStiffness
from exuclear.engine.impulse_friction import LOAD_TOLERANCE
from exuclear.spatial import ShoulderGeometry
from exuclear.timescales import closed_form_impact, impact_restitution
from validation.cost._end_scenes import (
    AXIAL_PLAY,
    AXIAL_SPEED,
    FACE_MU,
    GUIDE,
    GUIDE_CLEARANCE,
    SHOULDER,
    SLIDER_INERTIA,
    SLIDER_MASS,
    SIDE,
    front_leaves,
    one_corner,
    entering,
    guide_slider,
    past_the_end,
    rattle,
    rear_leaves,
    resting_on_face,
    spinning_impact,
    spinning_on_face,
    thrown_along,
)
from validation.cost._joint_type_scenes import G, solve
from validation.cost._spatial_scenes import BEARING, INERTIA, MASS
from validation.cost._translational_scenes import first_jump, jumps

#: Newton's tolerance on the velocity condition bounds a jump's error: the other joint
#: types' restitution tests hold it to the same relative 1e-9.
JUMP_TOLERANCE = 1e-9
FACES = ("end face at z = -0.015 m", "end face at z = 0.015 m")
REAR, FRONT = "corner rear-lower / lower and upper walls", "corner front-lower / lower and upper walls"


def test_a_shoulder_hits_its_end_face_with_the_laws_restitution():
    # no gravity: the journal thrown along its axis at 0.2 m/s from the centre hits the face
    # at z = -L/2 with its shoulder, then the other, each time jumping to -e(v) v, e the
    # law's restitution at the onset velocity; the closed form is that of the face's own law,
    # the flat punch K_f = 2 E* R_S (docs/physics.md eq. (52)) with the joint law's damping,
    # on the whole journal's mass; the slices never touch
    run = thrown_along()
    impacts = run.joint.impacts()
    law = run.joint.joint.law
    assert len(impacts) >= 4 and [i.pair for i in impacts[:2]] == list(FACES)
    assert all(i.restitution == impact_restitution(law, i.onset_velocity) for i in impacts)
    for before, after in zip(impacts, impacts[1:]):  # each onset at the last rebound's speed
        assert after.onset_velocity == pytest.approx(before.restitution * before.onset_velocity, rel=JUMP_TOLERANCE)
    assert first_jump(run, 2) == pytest.approx(impact_restitution(law, 0.2), rel=JUMP_TOLERANCE)
    face = ContactLaw(GivenStiffness(law.geometry, 1.0, 2.0 * law.E_star * SHOULDER, 1.0), law.damping_model,
                      law.v_min)
    peak, duration, depth = closed_form_impact(face, MASS, 0.2)
    first = impacts[0]
    assert first.effective_mass == pytest.approx(MASS, rel=JUMP_TOLERANCE)
    assert (first.peak_force, first.duration, first.max_penetration) == pytest.approx((peak, duration, depth),
                                                                                      rel=JUMP_TOLERANCE)
    assert np.abs(run.states[:, 1:3]).max() == 0.0  # no motion across the axis at all


def test_a_journal_resting_on_its_end_face_carries_the_axial_load():
    # gravity along -z presses the journal's shoulder on the face at z = +L/2 from t = 0: one
    # onset, no impact after it, and the face carries m g (to round-off once the condition
    # has taken back the first steps' penetration); nothing else is held
    run = resting_on_face()
    impacts = run.joint.impacts()
    assert [(i.pair, i.onset_time, i.restitution) for i in impacts] == [(FACES[1], 0.0, 0.0)]
    for name, out in run.joint.outputs().items():
        held = out["time"] > 100 * run.step
        expected = MASS * G if name == FACES[1] else 0.0
        assert out["normal_force"][held] == pytest.approx(expected, rel=1e-9, abs=1e-12)


def test_an_elastic_axial_rattle_keeps_its_energy():
    # cr 1, no gravity: thrown along and across its axis while it tilts, the journal hits both
    # end faces and its bearing's wall with its end slices.  Each jump keeps the normal
    # velocity's size exactly; the energy stays within 1 % (the target) and within
    # 1e-4 at this step (the other joints' elastic tests' bound), less at a quarter of it
    run, energy = rattle()
    impacts = run.joint.impacts()
    pairs = {i.pair for i in impacts}
    assert set(FACES) <= pairs and any(p.startswith("slice") for p in pairs)
    assert all(i.restitution == 1.0 for i in impacts)
    drift = np.abs(energy - 1.0).max()
    assert drift < 1e-4
    _, finer = rattle(step=2.5e-6)
    assert np.abs(finer - 1.0).max() < drift


#: The spin's deceleration [rad/s^2] under the end face's friction couple mu m g R_e
#: (docs/physics.md eq. (51)), R_e the annulus's friction radius.
FRICTION_RADIUS = ShoulderGeometry(AXIAL_PLAY, SHOULDER, BEARING).friction_radius
SPIN_DOWN = FACE_MU * MASS * G * FRICTION_RADIUS / np.asarray(INERTIA.inertiaTensor)[2, 2]


def test_a_journal_spinning_on_its_end_face_slows_at_the_friction_couple_and_sticks():
    # gravity -z presses the journal on its face while it spins at 50 rad/s: the face's
    # friction couple mu m g R_e slows it linearly (the compliant joint's check,
    # tests/test_axial_clearance.py) until it stops at 0.113 s, then it sticks; each step's
    # sliding load is accepted within LOAD_TOLERANCE of mu F_N, which bounds the spin's error
    run = spinning_on_face()
    t, spin = run.states[:, 0], run.states[:, 9]
    stop = 50.0 / SPIN_DOWN
    sliding = t < stop
    assert np.all(np.abs(spin - (50.0 - SPIN_DOWN * t))[sliding] <= LOAD_TOLERANCE * SPIN_DOWN * t[sliding] + 1e-12)
    out = run.joint.outputs()[FACES[1]]
    stuck = out["time"] > stop + run.step
    assert np.abs(spin[1:][stuck]).max() < 1e-12  # rad/s: held by the sticking condition
    assert np.all(out["sticking"][stuck] == 1.0) and not out["sticking"][out["time"] < stop - run.step].any()
    assert len(run.joint.impacts()) == 1 and not run.joint.notes


def test_a_spinning_journals_axial_impact_takes_mu_times_its_impulse_from_the_spin():
    # no gravity: thrown along its axis while spinning at 50 rad/s, the journal's shoulder hits
    # its face; the spin slides through the impact (its slip R_e w = 0.55 m/s does not stop),
    # so the friction couple's angular impulse is mu (1 + e) m v R_e (Brach's impact law with
    # Coulomb's bound), within the sliding load's LOAD_TOLERANCE; the normal jump is the law's
    run = spinning_impact()
    impact = run.joint.impacts()[0]
    k = int(np.argmin(np.abs(run.states[:, 0] - impact.onset_time)))
    before, after = run.states[k], run.states[k + 1]
    e = impact.restitution
    assert -after[6] / before[6] == pytest.approx(e, rel=JUMP_TOLERANCE)
    change = FACE_MU * (1.0 + e) * MASS * AXIAL_SPEED * FRICTION_RADIUS / np.asarray(INERTIA.inertiaTensor)[2, 2]
    assert before[9] - after[9] == pytest.approx(change, rel=LOAD_TOLERANCE)


def _leaving(step):
    """The slider's run out of its guide, the reference of its one-corner phase at its
    states, and the phase's states."""
    run = past_the_end(step=step)
    t = run.states[:, 0]
    t1, y0 = front_leaves(), -GUIDE_CLEARANCE
    phase = (t > t1) & (t < rear_leaves(t1, y0) - step)  # the steps that end with the rear corner inside
    theta, height, reaction = one_corner(np.concatenate(([t1], t[phase])), y0)
    return run, phase, (theta[1:], height[1:], reaction[1:])


def test_a_slider_leaving_a_finite_guide_tilts_on_its_last_corner_then_flies():
    # gravity -y, frictionless: the slider slides out of the guide at 2.5 m/s (x = 2.5 t
    # exactly: no force along x).  While both lower corners are inside, each carries m g / 2
    # (round-off); from the step its front corner passes the end, that corner is open and
    # the block tilts on its rear corner as Newton's laws say (the SciPy reference), its
    # reaction from 0.4 m g (m g / (1 + m r_x^2 / I)) down; once the rear corner has passed
    # the end, the block flies free: a parabola.  No impact after the onsets at t = 0
    run, phase, (theta, height, reaction) = _leaving(1e-4)
    t, states, h = run.states[:, 0], run.states, run.step
    outputs = run.joint.outputs()
    rear, front = outputs[REAR], outputs[FRONT]
    assert [(i.onset_time, i.restitution) for i in run.joint.impacts()] == [(0.0, 0.0), (0.0, 0.0)]
    assert np.abs(states[:, 1] - 2.5 * t).max() < 1e-12  # m: round-off of x over 0.06 s
    both = (rear["time"] > 100 * h) & (rear["time"] < front_leaves() - 0.5 * h)
    for out in (rear, front):
        assert out["normal_force"][both] == pytest.approx(SLIDER_MASS * G / 2, rel=1e-9)
    assert np.all(front["normal_force"][rear["time"] > front_leaves() + 0.5 * h] == 0.0)
    assert reaction[0] == pytest.approx(SLIDER_MASS * G / (1.0 + SLIDER_MASS * (SIDE / 2) ** 2 / SLIDER_INERTIA),
                                        rel=1e-3)  # the reference's first state is one step after the leaving
    # the one-corner phase: the step in which the front corner passes the end is computed
    # free, but starts from accelerations that carry the corner's support (the trapezoidal
    # rule's), which leaves the tilt's rate off by at most h |theta''| / 2 (theta'' = 235
    # rad/s^2 at the start; the passing falls on a step's end here, the worst case) and the
    # angle by that times the phase's 20 ms; twice that bound (the tilting motion lets a
    # rate's error grow), and first order: half the error at half the step
    alpha = 235.0
    error = np.abs(states[phase, 3] - theta).max()
    assert error < h * alpha * 0.0205
    finer, finer_phase, (finer_theta, _, finer_reaction) = _leaving(h / 2)
    assert np.abs(finer.states[finer_phase, 3] - finer_theta).max() == pytest.approx(error / 2, rel=0.05)
    assert np.abs(states[phase, 2] - height).max() < error * SIDE  # m: the centre's height follows the angle
    # the reaction (a three-step mean, from 5 steps after the leaving) carries the state's
    # error: first order as well, and within 0.1 % of m g at this step
    off = [np.abs(run_.joint.outputs()[REAR]["normal_force"][mask[1:]] - reference)[5:].max()
           for run_, mask, reference in ((run, phase, reaction), (finer, finer_phase, finer_reaction))]
    assert off[0] < 1e-3 * SLIDER_MASS * G
    assert off[1] == pytest.approx(off[0] / 2, rel=0.05)
    # free flight, from 60 steps after the rear corner let go (the settling's transient of
    # the support's end halves each step: 2^-60): a parabola to round-off
    left = rear["time"][rear["normal_force"] > 0.0].max()
    free = t > left + 60 * h
    assert np.diff(states[free, 2], 2) == pytest.approx(-G * h * h, rel=1e-9)
    assert np.abs(np.diff(states[free, 3], 2)).max() < 1e-14  # rad: the spin stays


def test_a_corner_that_comes_back_inside_the_guide_is_caught_as_an_impact():
    # no gravity: the slider flies from beyond the guide's end into it while it drops; its
    # rear-lower corner, inside since 1 ms, hits the lower wall at 2 ms, an impact with the
    # law's restitution (its normal rate jumps to -e(v) v, in the rows of the step's start),
    # while the front-lower corner, beyond the end, has no wall (its penetration -inf)
    run = entering()
    impacts = run.joint.impacts()
    assert impacts[0].pair == "corner rear-lower / lower wall"
    assert impacts[0].onset_time == pytest.approx(2e-3, abs=run.step)
    impact, before, after, restitution = jumps(run)[0]
    assert impact.restitution == restitution
    assert -after / before == pytest.approx(restitution, rel=JUMP_TOLERANCE)
    front = run.joint.outputs()[FRONT]
    assert np.all(front["penetration"] == -np.inf)  # beyond the end for the whole run


def test_a_corner_that_comes_back_below_the_walls_level_stops_the_run_naming_the_guides_end():
    # the slider, 0.6 mm below the guide's mid-plane (its lower corners 0.5 mm below the lower
    # wall's level), flies back into the guide: its rear-lower corner would enter 5 clearances
    # into the wall, striking the guide's end, which the joint does not model; no step is
    # short enough, so the run stops and says so (the compliant joint warns of the penetration)
    mbs, joint, _ = guide_slider(0.5 * GUIDE + 0.5 * SIDE + 1e-3, -6e-4, (-1.0, 0.0, 0.0), 0.0)
    with pytest.raises(ValueError, match="corner rear-lower came back into the guide 0.0005 m into its wall: it "
                                         "struck the guide's end"):
        solve(mbs, 1e-4, 0.005)
