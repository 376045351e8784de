"""Slider-crank from 3D bodies (issue 11, target "3D bodies"): the spatial formulation of
models/slider_crank.py against the 2D ones (docs/physics.md section 6.2)."""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

import exuclear
from exuclear.models.slider_crank import SliderCrankParams, build, default_settings, out_of_plane, run

#: The paper's case: cr 0.9, steel on steel, no friction, two revolutions.
PAPER = SliderCrankParams.paper()

#: Settings converged well below 1 % of c over the two revolutions, measured against the
#: minimal formulation at DOPRI5 rtol 1e-11 with steps <= 2e-6 s:
#: - minimal, DOPRI5 at rtol 1e-10 with steps <= 1e-5 s: 2e-5 c;
#: - spatial and redundant, generalized-alpha with impact-aware steps of 1e-5 s and
#:   1e-7 s from each contact onset: 0.31 % of c (the default 2e-5 s / 1e-6 s: 0.49 %).
#: Outputs every 1e-6 s (every step where steps are longer).
CONVERGED = {"minimal": {"step": 1e-5, "rtol": 1e-10, "atol": 1e-13},
             "redundant": {"step": 1e-5, "impact_step": 1e-7},
             "spatial": {"step": 1e-5, "impact_step": 1e-7}}


def _run(params: SliderCrankParams, **changes: object):
    result = run(params, replace(default_settings(params), output_step=1e-6, **changes))
    assert result.success, result.message
    return result


def _at(columns: dict[str, np.ndarray], t: np.ndarray, key: str) -> np.ndarray:
    """A column interpolated linearly to the times ``t`` (steps <= 1e-5 s: the error is
    below x'' h^2 / 8 = 200 m/s^2 * 1e-10 s^2 / 8 = 2.5e-9 m)."""
    return np.interp(t, columns["time"], columns[key])


@pytest.fixture(scope="module")
def converged():
    return {f: _run(replace(PAPER, formulation=f), **CONVERGED[f]) for f in CONVERGED}


@pytest.mark.parametrize("other", ["redundant", "minimal"])
def test_spatial_matches_the_planar_formulations(converged, other):
    spatial, planar = converged["spatial"].columns, converged[other].columns
    t = spatial["time"]
    assert t[-1] == pytest.approx(PAPER.end_time)
    de = np.hypot(spatial["ecc_x"] - _at(planar, t, "ecc_x"), spatial["ecc_y"] - _at(planar, t, "ecc_y"))
    # the target: the journal path within 1 % of the clearance over two revolutions
    # (measured 0.31 % against the minimal formulation, 5e-6 % against the redundant one)
    assert de.max() < 0.01 * PAPER.clearance
    if other == "redundant":
        # the same integrator and steps on the same planar equations: only the Newton
        # iterates differ (measured 2e-7 c with Exudyn's Newton tolerances, 5e-6 c with
        # a residual tolerance of 1e-6); 0.1 % of c is far below any discretisation error
        assert de.max() < 1e-3 * PAPER.clearance
    # every impact of the run (22, all in the first quarter revolution; the journal then
    # stays in contact), counted at accepted steps
    assert converged["spatial"].impacts == converged[other].impacts == 22
    # slider x from the eccentricity: the slider is the journal's x minus e_x, the journal
    # is at r cos(theta) + l cos(phi) with r sin(theta) + l sin(phi) = e_y, so to first
    # order |dx| <= |de_x| + tan(phi) |de_y| + r (1 + tan(phi)) |dtheta|
    #           <= |de| / cos(phi_max) + r (1 + tan(phi_max)) |dtheta|,
    # cos(phi_max) = sqrt(l^2 - r^2) / l; plus the interpolation of both series (_at)
    r, l = PAPER.crank_length, PAPER.rod_length
    cos_max = math.sqrt(l**2 - r**2) / l
    dtheta = np.radians(np.abs(spatial["crank_angle"] - _at(planar, t, "crank_angle")))
    dx = np.abs(spatial["slider_x"] - _at(planar, t, "slider_x"))
    bound = de / cos_max + r * (1.0 + math.tan(math.acos(cos_max))) * dtheta + 5e-9
    assert np.all(dx <= bound)
    assert dx.max() < 0.012 * PAPER.clearance  # hence within 1.2 % of c (measured 0.31 %)


def test_out_of_plane_motion_stays_at_round_off():
    # no load acts out of the plane (gravity along -Y, contact in the plane normal to z):
    # z of every body's centre and its tilt stay at round-off, 1e-12 m (1e-8 of c) and
    # 1e-12 rad (measured exactly 0)
    params = replace(PAPER, formulation="spatial")
    model = build(params)
    # the clearance joint adds no constraint: 5 (revolute O) + 5 (revolute A) + 5
    # (prismatic guide) + 1 (drive) algebraic equations on 3 x 6 coordinates
    assert (model.mbs.systemData.ODE2Size(), model.mbs.systemData.AEsize()) == (18, 16)
    sim = exuclear.simulate(model.mbs, default_settings(params))
    assert sim.success, sim.message
    motion = out_of_plane(model)
    assert set(motion) == {f"{b}_{q}" for b in ("crank", "rod", "slider") for q in ("z", "tilt")}
    assert max(motion.values()) < 1e-12


def test_ideal_and_other_clearance_joints_match_the_redundant_formulation():
    # the ideal mechanism (B an in-plane pin) over half a revolution, and clearance at O,
    # A and B (axial translation and tilt held at O and A) over the first impacts: the
    # same integrator and steps as the redundant formulation, so only Newton's iterates
    # differ; bounds 1e-9 m on positions, 1e-4 of the 3 N m drive moment, 0.1 % of c
    ideal = replace(PAPER, ideal=True, revolutions=0.5)
    a, b = run(replace(ideal, formulation="spatial")).columns, run(replace(ideal, formulation="redundant")).columns
    assert np.abs(a["slider_x"] - b["slider_x"]).max() < 1e-9
    assert np.abs(a["crank_moment"] - b["crank_moment"]).max() < 1e-4 * 3.0
    every = replace(PAPER, clearance_joints=("O", "A", "B"), revolutions=0.1)
    a, b = run(replace(every, formulation="spatial")), run(replace(every, formulation="redundant"))
    assert a.success and b.success
    assert a.impacts == b.impacts > 0
    de = np.hypot(a.columns["ecc_x"] - b.columns["ecc_x"], a.columns["ecc_y"] - b.columns["ecc_y"])
    assert de.max() < 1e-3 * PAPER.clearance


def test_command_line(capsys):
    from exuclear.models.slider_crank import main

    assert main(["--formulation", "spatial", "--revolutions", "0.05"]) == 0
    out = capsys.readouterr().out
    assert "spatial coordinates, generalized-alpha" in out and "impacts" in out
