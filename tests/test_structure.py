"""The package's structure: imports point one way, and no source file is too long to read at once.

Imports are read from the source (``ast``), at module level and inside functions, relative
and absolute; only the blocks under ``if TYPE_CHECKING:`` are left out, since they never run.
A module that imports another, however late, needs it to be importable first: a cycle,
even through a function's local import, is two modules that cannot be read one after the
other.  The helpers take a folder, so that each part of the repository can be held to them.
"""
from __future__ import annotations

import ast
import re
from pathlib import Path

import pytest

import exuclear

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "exuclear"
#: Lines a source file of the library, the scenes and the validation may hold (STYLE.md: "each file small
#: enough to read at once").
MAX_LINES = 600


def module_name(path: Path, root: Path = ROOT) -> str:
    """``exuclear/engine/handle.py`` -> ``exuclear.engine.handle``; a package's ``__init__.py`` -> the package."""
    parts = list(path.relative_to(root).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def modules(folder: Path, root: Path = ROOT) -> dict[str, Path]:
    """Every module under ``folder`` (Python files), by dotted name."""
    return {module_name(p, root): p for p in sorted(folder.rglob("*.py"))}


def _type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING")


def _import_nodes(tree: ast.AST) -> list[ast.Import | ast.ImportFrom]:
    """The import statements of a module anywhere in it, except under ``if TYPE_CHECKING:``."""
    found: list[ast.Import | ast.ImportFrom] = []

    def visit(node: ast.AST) -> None:
        if isinstance(node, ast.If) and _type_checking(node):
            for child in node.orelse:
                visit(child)
            return
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            found.append(node)
        for child in ast.iter_child_nodes(node):
            visit(child)

    visit(tree)
    return found


def imports(name: str, path: Path, known: dict[str, Path]) -> set[str]:
    """The modules of ``known`` that module ``name`` (at ``path``) imports: ``import a.b``
    names ``a.b``; ``from a import b`` names ``a.b`` where that is a module, else ``a``."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    targets: set[str] = set()
    for node in _import_nodes(ast.parse(path.read_text(), str(path))):
        if isinstance(node, ast.Import):
            targets.update(alias.name for alias in node.names)
            continue
        base = node.module or ""
        if node.level:
            parent = package.split(".")
            parent = parent[:len(parent) - (node.level - 1)]
            base = ".".join(parent + ([base] if base else []))
        for alias in node.names:
            sub = f"{base}.{alias.name}"
            targets.add(sub if sub in known else base)
    return {t for t in targets if t in known and t != name}


def import_graph(folder: Path, root: Path = ROOT) -> dict[str, set[str]]:
    """Module -> the modules under ``folder`` it imports."""
    known = modules(folder, root)
    return {name: imports(name, path, known) for name, path in known.items()}


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The import cycles of ``graph``: its strongly connected components of more than one
    module (Tarjan's algorithm), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []

    def connect(v: str) -> None:
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            connect(v)
    return found


def long_files(folder: Path, limit: int = MAX_LINES, suffixes: tuple[str, ...] = (".py", ".hpp", ".cpp")) -> dict[str, int]:
    """The source files under ``folder`` of more than ``limit`` lines, with their line counts."""
    counts = {str(p.relative_to(ROOT)): len(p.read_text().splitlines()) for p in sorted(folder.rglob("*"))
              if p.suffix in suffixes}
    return {p: n for p, n in counts.items() if n > limit}


def test_the_helpers_find_a_cycle_through_a_local_import_and_skip_type_checking(tmp_path):
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from . import b\n")
    (pkg / "b.py").write_text("def f():\n    from .c import g\n")
    (pkg / "c.py").write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .a import x\n"
                              "import pkg.a\n")
    (pkg / "d.py").write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from .a import x\n")
    graph = import_graph(pkg, tmp_path)
    assert graph["pkg.a"] == {"pkg.b"} and graph["pkg.b"] == {"pkg.c"} and graph["pkg.d"] == set()
    assert cycles(graph) == [["pkg.a", "pkg.b", "pkg.c"]]
    (pkg / "c.py").write_text("")
    assert cycles(import_graph(pkg, tmp_path)) == []


def test_no_module_of_exuclear_imports_one_that_imports_it_back():
    assert cycles(import_graph(PACKAGE)) == []


@pytest.mark.parametrize("folder", ["exuclear", "models", "validation"])
def test_no_source_file_is_too_long_to_read_at_once(folder):
    assert long_files(ROOT / folder) == {}


def test_public_api_has_at_most_32_names():
    # a reader can hold the API at once; tables and constants live in their modules
    # the joint family's four builders (revolute, spherical, translational, pin-in-slot) raised it from 30
    assert len(exuclear.__all__) <= 32


def test_the_library_knows_no_scene_figure():
    # the scenes' figures live with the scenes (exuclear.models.figures)
    assert not (PACKAGE / "plotting.py").exists()
    assert not (PACKAGE / "study_plot.py").exists()


def test_the_two_kernels_split_into_modules_of_the_same_names():
    # exuclear/_kernel/layout.hpp ... bindings.cpp mirror exuclear/engine/_python_kernel/layout.py ... bindings.py
    compiled = {p.stem for p in (PACKAGE / "_kernel").iterdir() if p.suffix in (".hpp", ".cpp")}
    python = {p.stem for p in (PACKAGE / "engine" / "_python_kernel").glob("*.py")} - {"__init__"}
    assert compiled == python == {"layout", "kinematics", "laws", "contacts", "film", "wear", "joint_state",
                                  "step_control", "bindings"}


#: A calendar date or a day's narrative: history, which belongs in commits and closing notes.
DATED = re.compile(r"\b20\d\d-[01]\d-[0-3]\d\b|\b(?:today|yesterday|this (?:morning|afternoon|evening))\b", re.I)


@pytest.mark.parametrize("folder", ["exuclear", "models"])
def test_the_code_says_what_and_why_not_when(folder):
    dated = [f"{p.relative_to(ROOT)}:{n}" for p in sorted((ROOT / folder).rglob("*"))
             if p.suffix in (".py", ".hpp", ".cpp")
             for n, line in enumerate(p.read_text().splitlines(), 1) if DATED.search(line)]
    assert dated == []


def test_the_python_kernel_imports_no_engine_layer_above_it():
    # constants flow down: the kernel layer (engine/_python_kernel) reads the parameter table
    # (engine.layout) and the physics, never the steering, handle or connector that drive it
    graph = import_graph(PACKAGE)
    layer = "exuclear.engine._python_kernel"
    above = {m for m in graph if m.startswith("exuclear.engine") and not m.startswith(layer)} - {"exuclear.engine.layout"}
    assert {(m, t) for m in graph if m.startswith(layer) for t in graph[m] if t in above} == set()
