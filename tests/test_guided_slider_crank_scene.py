"""The Flores-Leine-Glocker slider-crank scene (models/guided_slider_crank.py) against the
independent SciPy reference (validation/reference/guided_slider_crank.py) over its first
contacts, and its energy with elastic corners."""
from __future__ import annotations

import dataclasses
import warnings

import numpy as np
import pytest

import exuclear
from exuclear.prismatic import CORNER_SIGNS, PAIRS, WALL_SIDES, pair_name
from models import guided_slider_crank as scene
from validation.reference import guided_slider_crank as ref

#: The span the two agree over closely: the first seven contacts (the slider's rear and front
#: upper corners striking the upper wall), before the slow rattling contacts of some 0.02 m/s
#: whose onsets amplify any difference.
FIRST_CONTACTS_END = 8.5e-3


def test_the_parameters_are_the_references():
    mine = dataclasses.asdict(scene.GuidedSliderCrankParams.benchmark())
    theirs = dataclasses.asdict(ref.GuidedSliderCrank.benchmark())
    assert {k: v for k, v in mine.items() if k != "backend"} == theirs


def _pair_of_reference(pair: int) -> int:
    """The scene's pair number of the reference's ``pair`` (corner signs and wall)."""
    k, wall = ref.PAIRS[pair]
    signs = tuple(float(s) for s in ref.CORNERS[k])
    return PAIRS.index((CORNER_SIGNS.index(signs), WALL_SIDES.index(float(wall))))


def test_first_contacts_agree_with_the_scipy_reference():
    p = scene.GuidedSliderCrankParams.benchmark()
    mine = scene.run(p, scene.default_settings(p, FIRST_CONTACTS_END))
    theirs = ref.simulate(ref.GuidedSliderCrank.benchmark(), FIRST_CONTACTS_END, output_step=1e-5)
    assert mine.success and theirs.success
    onsets = [(t, _pair_of_reference(pair), v0) for t, pair, v0 in theirs.impacts]
    assert len(mine.impacts) >= 6
    for (t, pair, v0), r in zip(onsets, mine.impacts):
        assert r.pair == pair_name(pair)
        # the onset interpolated between the scene's steps of 1e-6 s; measured 1e-6 s
        assert r.onset_time == pytest.approx(t, abs=3e-6)
        # the approach speed at the onset: measured 0.1 % at the first six, 4 % at the seventh
        assert r.onset_velocity == pytest.approx(v0, rel=0.05)
    y = np.interp(mine.time, theirs.time, theirs.slider[:, 1])
    speed = np.interp(mine.time, theirs.time, theirs.u[:, 0])
    # the slider's place across the guide: measured 9e-5 c over these contacts
    assert np.abs(mine.slider[:, 1] - y).max() < 1e-3 * p.clearance
    # the crank's speed (it falls from 150 rad/s to some 100): measured 3.5e-3 rad/s
    assert np.abs(mine.crank_speed - speed).max() < 1e-2


def test_elastic_corners_keep_the_energy():
    p = scene.GuidedSliderCrankParams.benchmark(damping="none", friction="none")
    built = scene.build(p)
    start = scene.energy(built)
    settings = dataclasses.replace(scene.default_settings(p, 0.02), spectral_radius=1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", exuclear.AccuracyWarning)
        result = exuclear.simulate(built.mbs, settings)
    assert result.success, result.message
    assert len(built.joint.impacts()) >= 2
    # generalized-alpha without numerical damping (spectral radius 1) at 1e-6 s: measured 1.5e-8
    assert scene.energy(built) == pytest.approx(start, rel=1e-6)


def test_the_convergence_check_reads_the_corners_paths():
    # the scene at its step and at a quarter of it over its first four contacts: the corners'
    # largest departure is the path the check compares (measured 1e-3 c), within its 1 % bound
    p = scene.GuidedSliderCrankParams.benchmark()

    def run(settings):
        built = scene.build(p)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", exuclear.AccuracyWarning)
            result = exuclear.simulate(built.mbs, settings)
        return exuclear.RunRecord.from_handles(result, {"guide": built.joint})

    check = exuclear.check_convergence(run, scene.default_settings(p, 0.007))
    joint = check.joints["guide"]
    assert joint.de.ndim == 1 and joint.path_agrees and joint.max_de < 0.01
    assert joint.impacts == joint.impacts_ref == 4
