"""``python -m validation.cost``: one command line for the cost, timing and step-accuracy
scripts; it lists every script and hands each its own options."""
import pytest

from validation import cost


def test_the_listing_names_every_script_with_its_summary(capsys):
    assert cost.main([]) == 0
    listing = capsys.readouterr().out
    for name in cost.SCRIPTS:
        assert f"  {name} " in listing
        assert cost.summary(name) in listing
    # the scripts that moved here from validation/ (each was python -m validation.<old name>), wear's and
    # the contact modes' (and the impulse mode's native hold)
    assert set(cost.SCRIPTS) == {"benchmark", "film", "fine_steps", "friction", "jacobian",
                                 "jacobian_steps", "modes", "modes_ends", "modes_friction", "modes_friction_types",
                                 "modes_gliding", "modes_profile", "native_hold", "newton", "spectral_radius", "speed_sweep",
                                 "study_benchmark", "wear", "work_precision"}


def test_an_unknown_script_is_refused_with_the_known_ones(capsys):
    assert cost.main(["film_cost"]) == 2  # argparse's status for a bad option
    assert "unknown script 'film_cost'; known: benchmark" in capsys.readouterr().err


@pytest.mark.parametrize("name", cost.SCRIPTS)
def test_each_script_takes_its_options_from_the_dispatcher(name, capsys):
    with pytest.raises(SystemExit) as exit_:
        cost.main([name, "--help"])
    assert exit_.value.code == 0
    assert f"usage: python -m validation.cost {name}" in capsys.readouterr().out
