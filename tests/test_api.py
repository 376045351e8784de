"""The public API (issue 22): a small ``__all__``, one way to build a law, no global side effects.

- ``exuclear.__all__`` names the API, about 30 names; the internals stay importable from
  their modules;
- ``exuclear.contact_law`` is the one way to build a law, and a law built so is taken as
  it is: ``make_joint`` refuses the arguments the law already carries, instead of
  ignoring them;
- ``import exuclear`` imports none of the heavy optional dependencies, and the plotting
  helpers never choose or switch matplotlib's backend.
"""
from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

import exuclear
from exuclear.contact import V_MIN_DEFAULT

PAPER = {"journal_radius": 9.9e-3, "bearing_radius": 10e-3, "length": 15e-3}


def test_all_is_small_and_every_name_exists():
    # at most 32 names (30 and the translational and pin-in-slot builders of the joint family),
    # so that a reader can hold the API at once; constants and tables (BACKENDS, METHODS,
    # OUTPUT_COLUMNS, V_MIN_DEFAULT, ...) live in their modules
    assert len(exuclear.__all__) <= 32
    assert len(set(exuclear.__all__)) == len(exuclear.__all__)
    for name in exuclear.__all__:
        assert hasattr(exuclear, name), name


@pytest.mark.parametrize("module, name", [
    ("exuclear.contact", "WangLiu"), ("exuclear.contact", "compose_law"), ("exuclear.contact", "STIFFNESS_MODELS"),
    ("exuclear.friction", "smooth_step"), ("exuclear.friction", "ModifiedCoulomb"),
    ("exuclear.geometry", "contact_kinematics"), ("exuclear.geometry", "JointLoads"),
    ("exuclear.joint", "JointResponse"), ("exuclear.history", "ImpactRecord"),
    ("exuclear.engine", "DATA_COLUMNS"), ("exuclear.engine", "simulation_settings"), ("exuclear.engine", "KernelWarning"),
    ("exuclear.convergence", "refined_settings"), ("exuclear.spectrum", "amplitude_spectrum"),
    ("exuclear.contact", "V_MIN_DEFAULT"), ("exuclear.settings", "METHODS"), ("exuclear.engine", "BACKENDS"),
    ("exuclear.engine", "DEFAULT_BACKEND"), ("exuclear.engine", "OUTPUT_COLUMNS"),
])
def test_internals_stay_importable_from_their_modules(module, name):
    __import__(module)
    assert hasattr(sys.modules[module], name)
    assert name not in exuclear.__all__


def test_a_law_by_name_equals_the_named_class():
    # contact_law is the one way; the named classes are its implementation (same parameters)
    from exuclear.contact import WangLiu

    geometry = exuclear.BearingGeometry(**PAPER)
    assert exuclear.contact_law("wang-liu", geometry, 1e11, 0.9) == WangLiu(geometry, 1e11, 0.9)


@pytest.mark.parametrize("extra, named", [
    ({"cr": 0.5}, "`cr`"), ({"journal_material": "aluminium"}, "`journal_material`"),
    ({"bearing_material": "steel"}, "`bearing_material`"), ({"E_star": 1e11}, "`E_star`"), ({"v_min": 1e-2}, "`v_min`"),
])
def test_a_ready_law_refuses_what_it_already_carries(extra, named):
    # joint.py's docstring said these "must not be given"; they used to be ignored silently
    law = exuclear.contact_law("wang-liu", exuclear.BearingGeometry(**PAPER), 1e11, 0.9)
    with pytest.raises(ValueError, match=named):
        exuclear.make_joint(**PAPER, law=law, **extra)
    assert exuclear.make_joint(**PAPER, law=law, friction="paper").law is law


def test_materials_and_v_min_default_as_before():
    by_default = exuclear.make_joint(**PAPER, cr=0.9).law
    spelled_out = exuclear.make_joint(**PAPER, cr=0.9, journal_material="steel", bearing_material="steel",
                                      v_min=V_MIN_DEFAULT).law
    assert by_default == spelled_out


def _run(code: str) -> str:
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    return subprocess.run([sys.executable, "-c", code], check=True, capture_output=True, text=True, env=env).stdout


def test_import_is_cheap():
    # the optional and heavy dependencies are imported where a function needs them
    heavy = ["matplotlib", "pandas", "tqdm", "scipy", "dask", "distributed"]
    out = _run(f"import sys, json, exuclear; print(json.dumps([m for m in {heavy!r} if m in sys.modules]))")
    assert json.loads(out.splitlines()[-1]) == []


def test_plots_leave_the_backend_alone(tmp_path):
    # a user's backend (here svg, set before the plots) is still the backend after them,
    # and pyplot is not even imported by plots that only write files
    pytest.importorskip("matplotlib")
    code = f"""
import sys, matplotlib
matplotlib.use("svg")
import numpy as np, pandas as pd
from exuclear.models import figures
from exuclear.study.plot import plot_metric
t = np.linspace(0.0, 0.05, 500)
cols = {{k: np.sin(50 * t) for k in ("slider_x", "slider_v", "slider_a", "contact_force", "crank_moment")}}
cols.update(time=t, crank_angle=t * 3000.0, ecc_x=1e-6 * t, ecc_y=1e-6 * t)
figures.slider_crank_figures([("a", cols)], cols, 1e-4, {str(tmp_path)!r}, "s")
plot_metric(pd.DataFrame({{"x": [1, 2], "m": [1.0, 2.0], "success": [True, True]}}), "m", "x",
            path={str(tmp_path / "m.png")!r})
print(matplotlib.get_backend(), "matplotlib.pyplot" in sys.modules)
"""
    assert _run(code).split() == ["svg", "False"]
    assert (tmp_path / "m.png").is_file() and (tmp_path / "s_spectrum.png").is_file()
