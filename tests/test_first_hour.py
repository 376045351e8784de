"""A newcomer's first hour (issue 48): what a user meets on the first model they build,
each test named after what it proves.  The four-bar of the guide's first model
(``validation/first_hour.py``) is the model of the solver tests."""
from __future__ import annotations

import warnings

import pytest

import exuclear

STEEL_JOINT = dict(journal_radius=9.9e-3, bearing_radius=10e-3, length=15e-3, journal_material="steel",
                   bearing_material="steel")


# -- 5. the main job is quiet about its own choices; warnings point at the caller -------------------


def test_the_main_job_is_quiet_about_its_own_choices_and_its_table_marks_a_law_out_of_range():
    from validation import journal_bearing as script

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # any warning fails the test
        script.restitution_params()
        row = script.restitution_row(script.ImpactRunner(workers=1), "wang-liu")
    # Wang-Liu's damping (Zhiying-Qishao) is established for cr >= 0.3 (its cr_valid_from):
    # the grid's 0.1 and 0.2 lie below, and the table says so where the values are
    assert row.outside == (0.1, 0.2)
    table = script.restitution_md([row])
    assert "| wang-liu [1] | " in table and table.count("*") >= 2
    assert "[1] wang-liu at cr = 0.1, 0.2 (marked *): outside its source's range" in table


def test_a_validity_warning_points_at_the_user_s_line():
    with pytest.warns(exuclear.ValidityWarning, match="established for cr >= 0.3") as caught:
        exuclear.make_joint(law="wang-liu", cr=0.1, **STEEL_JOINT)
    assert caught[0].filename == __file__
    with pytest.warns(exuclear.ValidityWarning, match="friction coefficient") as caught:
        exuclear.make_joint(law="wang-liu", cr=0.9, friction="coulomb:1.5", **STEEL_JOINT)
    assert caught[0].filename == __file__


# -- 8. smaller: law names in any case ------------------------------------------------------------


def test_law_and_friction_names_are_case_insensitive():
    lower = exuclear.make_joint(law="wang-liu", cr=0.7, friction="coulomb:0.1", **STEEL_JOINT)
    assert exuclear.make_joint(law="Wang-Liu", cr=0.7, friction="Coulomb:0.1", **STEEL_JOINT) == lower
    pair = exuclear.make_joint(law="hertz+lankarani-nikravesh", cr=0.7, **STEEL_JOINT)
    assert exuclear.make_joint(law="Hertz+Lankarani-Nikravesh", cr=0.7, **STEEL_JOINT) == pair
    with pytest.raises(ValueError, match="unknown `law` 'wang liu'; known: "):
        exuclear.make_joint(law="wang liu", cr=0.7, **STEEL_JOINT)
