"""The contact history (docs/physics.md section 2.3, eqs. (18)-(19)) and the impact records.

References: linear interpolation to zero penetration (closed form for a rate linear in
the penetration, and for the crossing time of a penetration linear in time).
"""
import pytest

from exuclear import make_joint
from exuclear.geometry import ContactKinematics
from exuclear.history import ContactState, ImpactRecord

JOINT = make_joint(journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, law="wang-liu", cr=0.9)


def Kin(delta, delta_dot):  # noqa: N802 - a contact state along x, no slip
    return ContactKinematics(0.0, 0.0, 0.0, 1.0, 0.0, delta, delta_dot, 0.0)


def _run(states):
    """Accept (delta, rate, time) states in turn; the last state and the records."""
    state, records = ContactState(), []
    for delta, rate, t in states:
        state, record = state.accept(Kin(delta, rate), JOINT, t)
        if record is not None:
            records.append(record)
    return state, records


def test_onset_rate_and_time_are_interpolated_to_zero_penetration():
    # delta_dot linear in delta: from (-1e-6, 0.2) to (+3e-6, 0.6) the onset rate is 0.3;
    # delta linear in time from t = 1.0 to 1.4: the crossing is at t = 1.1
    state, _ = _run([(-1e-6, 0.2, 1.0), (3e-6, 0.6, 1.4)])
    assert state.in_contact and state.onsets == 1
    assert state.v0 == pytest.approx(0.3) and state.onset_time == pytest.approx(1.1)
    kept, _ = state.accept(Kin(4e-6, -0.1), JOINT, 1.5)
    assert kept.v0 == state.v0 and kept.onsets == 1  # v0 is kept for the whole contact


def test_accepting_is_a_function_of_the_state_it_starts_from():
    # a step computed again starts from the same state and gives the same result
    base, _ = _run([(-1e-6, 0.2, 1.0)])
    assert base.accept(Kin(3e-6, 0.6), JOINT, 1.4) == base.accept(Kin(3e-6, 0.6), JOINT, 1.4)


def test_a_contact_that_ends_leaves_its_record():
    # delta from 2e-6 (t = 2.0) to -2e-6 (t = 2.2): separation at t = 2.1
    state, records = _run([(-1e-6, 0.2, 1.0), (3e-6, 0.6, 1.4), (5e-6, 0.1, 1.8), (2e-6, -0.2, 2.0),
                           (-2e-6, -0.3, 2.2)])
    assert not state.in_contact and state.closed == 1 and state.normal_force == 0.0
    (record,) = records
    assert isinstance(record, ImpactRecord)
    assert record.onset_time == pytest.approx(1.1) and record.duration == pytest.approx(1.0)
    assert record.max_penetration == 5e-6  # the largest at an accepted step
    # the peak force: the law's force at the accepted states in contact, with this contact's v0
    forces = [JOINT.law.normal_force(d, r, 0.3) for d, r in ((3e-6, 0.6), (5e-6, 0.1), (2e-6, -0.2))]
    assert record.peak_force == pytest.approx(max(forces), rel=1e-12)


def test_a_joint_that_starts_in_contact_takes_its_current_rate():
    state, _ = _run([(1e-6, 0.25, 0.0)])
    assert state.in_contact and state.v0 == 0.25 and state.onset_time == 0.0


def test_overlapping_slice_records_merge_into_physical_impacts():
    from exuclear.history import ImpactRecord, merge_overlapping

    # (onset, v0, peak, duration, max penetration): two slices of one impact, a third slice
    # touching through the second (transitive), then a separate impact
    a = ImpactRecord(1.0, 0.5, 10.0, 0.2, 1e-6)
    b = ImpactRecord(1.1, 0.4, 20.0, 0.3, 2e-6)
    c = ImpactRecord(1.35, 0.1, 5.0, 0.1, 0.5e-6)
    d = ImpactRecord(2.0, 0.3, 7.0, 0.1, 1e-6)
    merged = merge_overlapping([d, c, b, a])
    assert merged[1] == d and merged[0][:3] == (1.0, 0.5, 35.0) and merged[0].max_penetration == 2e-6
    assert merged[0].duration == pytest.approx(0.45, rel=1e-15)  # 1.45 - 1.0 in floating point
    assert merge_overlapping([]) == []
