"""The library stands without its scenes (issue 22): what is installed, who imports whom,
and the one shape every scene shares."""
from __future__ import annotations

import ast
import dataclasses
import subprocess
import sys
from pathlib import Path

import pytest

import exuclear.models
from exuclear.models import four_bar, journal_bearing, misaligned_shaft, slider_crank
from exuclear.models.scene import Scene
from exuclear.study import scene, scene_names

ROOT = Path(__file__).resolve().parents[1]
SCENES = {journal_bearing: journal_bearing.JournalBearingParams.paper(),
          slider_crank: slider_crank.SliderCrankParams.paper(),
          four_bar: four_bar.FourBarParams.crank_rocker(),
          misaligned_shaft: misaligned_shaft.ShaftParams.default()}


def _imports(path: Path, package: str) -> set[str]:
    """Absolute module names a file of ``package`` imports (anywhere in it, relative
    imports resolved)."""
    names = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parent = ".".join(package.split(".")[:len(package.split(".")) - node.level + 1])
                base = parent + (f".{base}" if base else "")
                names.update(f"{base}.{alias.name}" for alias in node.names)  # `from . import x`
            names.add(base)
    return names


def test_the_scenes_are_installed_under_the_library_only():
    tomllib = pytest.importorskip("tomllib")
    config = tomllib.loads((ROOT / "pyproject.toml").read_text())["tool"]["setuptools"]
    packages = set(config["packages"])
    on_disk = {".".join(p.parent.relative_to(ROOT).parts) for p in (ROOT / "exuclear").rglob("__init__.py")}
    assert on_disk | {"exuclear.models"} == packages  # every package of exuclear/ is installed
    assert config["package-dir"] == {"exuclear.models": "models"}
    assert all(name.split(".")[0] == "exuclear" for name in packages)  # no top-level `models`
    assert Path(exuclear.models.__file__).parent == ROOT / "models"


def test_a_scene_runs_from_any_directory_and_models_is_not_a_top_level_name(tmp_path):
    code = ("import importlib.util, sys; from exuclear.models import slider_crank; "
            "sys.exit(importlib.util.find_spec('models') is not None)")
    assert subprocess.run([sys.executable, "-c", code], cwd=tmp_path).returncode == 0
    proc = subprocess.run([sys.executable, "-m", "exuclear.models.slider_crank", "--help"], cwd=tmp_path,
                          capture_output=True, text=True)
    assert proc.returncode == 0 and "--crank-length" in proc.stdout


def test_the_library_never_imports_its_scenes():
    for path in (ROOT / "exuclear").rglob("*.py"):
        package = ".".join(path.parent.relative_to(ROOT).parts)
        assert not any(name.startswith("exuclear.models") or name.split(".")[0] == "models"
                       for name in _imports(path, package)), path


def test_the_scenes_use_no_private_library_module_and_do_not_import_each_other_in_a_cycle():
    graph = {}
    for path in (ROOT / "models").glob("*.py"):
        names = _imports(path, "exuclear.models")
        private = [n for n in names if n.startswith("exuclear.") and not n.startswith("exuclear.models")
                   and any(part.startswith("_") for part in n.split(".")[1:])]
        private += [f"exuclear.{node.attr}" for node in ast.walk(ast.parse(path.read_text()))
                    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
                    and node.value.id == "exuclear" and node.attr.startswith("_")]  # e.g. exuclear._private.x
        assert not private, (path.name, private)
        graph[path.stem] = {n.split(".")[2] for n in names if n.startswith("exuclear.models.")} - {path.stem}
    done, visiting = set(), []

    def visit(module: str) -> None:
        assert module not in visiting, f"import cycle: {' -> '.join([*visiting, module])}"
        if module in done or module not in graph:
            return
        visiting.append(module)
        for other in graph[module]:
            visit(other)
        visiting.pop()
        done.add(module)

    for module in graph:
        visit(module)


def test_the_study_runner_finds_the_scenes_by_entry_point_and_by_module_path():
    assert {"slider-crank": "exuclear.models.slider_crank", "journal-bearing": "exuclear.models.journal_bearing",
            "guided-slider-crank": "exuclear.models.guided_slider_crank"}.items() <= scene_names().items()
    assert scene("slider-crank").function is slider_crank.study
    assert scene("exuclear.models.journal_bearing").function is journal_bearing.study
    with pytest.raises(ValueError, match="unknown scene 'four-bar'; known: guided-slider-crank, journal-bearing, slider-crank"):
        scene("four-bar")


@pytest.mark.parametrize("module", list(SCENES), ids=lambda m: m.__name__.rsplit(".", 1)[-1])
def test_every_scene_has_the_same_shape(module):
    params = SCENES[module]
    built = module.build(params)
    assert isinstance(built, Scene) and built.params is params and built.joints and built.build_time > 0.0
    assert module.default_settings(params).end_time > 0.0
    # one option per field the command line sets, under the field's own name
    parser = module._parser()
    options = {o for action in parser._actions for o in action.option_strings}
    for field in dataclasses.fields(params):
        if field.metadata.get("cli"):
            assert "--" + field.name.replace("_", "-") in options, field.name


def test_the_paper_values_live_in_one_place():
    from exuclear.models import _defaults

    assert slider_crank.PAPER_CRANK_SPEED is _defaults.PAPER_CRANK_SPEED
    assert slider_crank.SliderCrankParams.paper().crank_speed == _defaults.PAPER_CRANK_SPEED
    assert slider_crank.STUDY_PARAMETERS["rpm"] == _defaults.PAPER_RPM


@pytest.mark.parametrize(("module", "argv", "expected"), [
    (journal_bearing, ["--journal", "aluminium", "--bearing", "copper", "--length", "0.02", "--velocity", "0.5"],
     {"journal_material": "aluminium", "bearing_material": "copper", "length": 0.02, "impact_velocity": 0.5}),
    (slider_crank, ["--journal", "aluminium", "--length", "0.02", "--crank-length", "0.06", "--ideal"],
     {"journal_material": "aluminium", "bearing_length": 0.02, "crank_length": 0.06, "ideal": True}),
    (four_bar, ["--bearing", "aluminium", "--length", "0.02", "--crank-angle0", "0.5"],
     {"bearing_material": "aluminium", "bearing_length": 0.02, "crank_angle0": 0.5}),
    (misaligned_shaft, ["--slices", "8", "--misalignment", "2e-4"], {"slices": 8, "misalignment": 2e-4}),
], ids=lambda v: v.__name__.rsplit(".", 1)[-1] if hasattr(v, "__name__") else "")
def test_options_set_the_fields_by_their_names_and_today_s_short_names(module, argv, expected):
    from exuclear.models._params import changes_from_args

    params = type(SCENES[module])
    changes = changes_from_args(module._parser().parse_args(argv), params)
    assert {name: changes[name] for name in expected} == expected
    defaults = {f.name: getattr(SCENES[module], f.name) for f in dataclasses.fields(params) if f.name not in expected}
    assert {name: changes[name] for name in changes if name in defaults} == {
        name: value for name, value in defaults.items() if name in changes}  # the others keep the named constructor's
