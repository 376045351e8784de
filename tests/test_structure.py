"""A structure a new maintainer can see and change (issue 31): files small enough to read at
once, a small public API, and no import cycle inside the study runner."""
from __future__ import annotations

import ast
from pathlib import Path

import exuclear

ROOT = Path(__file__).resolve().parents[1]

#: Longest file of the library's physics and tools packages and of the scenes [lines]: one
#: role per file, readable at once (STYLE.md, "Layout shows the architecture").
MAX_LINES = 600


def test_library_packages_have_no_file_over_600_lines():
    files = [*(ROOT / "exuclear" / "contact").glob("*.py"), *(ROOT / "exuclear" / "study").glob("*.py"),
             *(ROOT / "exuclear").glob("film*.py"), *(ROOT / "exuclear" / "film").glob("*.py"),
             *(ROOT / "models").glob("*.py")]
    assert len(files) > 20  # the packages are where this test looks for them
    too_long = {str(path.relative_to(ROOT)): n for path in files if (n := len(path.read_text().splitlines())) > MAX_LINES}
    assert not too_long, too_long


def test_public_api_has_at_most_30_names():
    # a reader can hold the API at once; tables and constants live in their modules
    assert len(exuclear.__all__) <= 30


def test_library_study_package_imports_no_module_of_its_own_in_a_cycle():
    package = ROOT / "exuclear" / "study"
    own = {path.stem for path in package.glob("*.py")}
    graph = {}
    for path in package.glob("*.py"):
        uses = set()
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and node.level == 1 and node.module in own:
                uses.add(node.module)
            elif isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("exuclear.study."):
                uses.add(node.module.split(".")[2])
        graph[path.stem] = uses - {path.stem}
    done: set[str] = set()

    def visit(module: str, trail: tuple[str, ...]) -> None:
        assert module not in trail, f"import cycle: {' -> '.join([*trail, module])}"
        if module in done:
            return
        for other in graph.get(module, ()):
            visit(other, (*trail, module))
        done.add(module)

    for module in graph:
        visit(module, ())


def test_library_knows_no_scene_figure():
    # the scenes' figures live with the scenes (exuclear.models.figures)
    assert not (ROOT / "exuclear" / "plotting.py").exists()
    assert not (ROOT / "exuclear" / "study_plot.py").exists()
