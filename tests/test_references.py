"""Every file, command and section that the code and the docs name exists.

A maintainer follows ``validation/cross_check/common.py``, ``python -m validation.cost
film`` or "docs/physics.md section 6.2" from a comment; a file that moved or a section that
was renumbered leaves such a mention dangling.  These tests read every ``.py`` and ``.md``
file of the repository (the tests' comments among them) and the compiled kernel's C++
sources (``.hpp``, ``.cpp``: their comments name the Python they mirror), and resolve:

- path mentions under ``docs/``, ``validation/``, ``exuclear/`` and ``models/`` (a file or
  a folder of the repository, ``*`` as a wildcard);
- ``python -m`` commands under those packages (a module or package that Python finds),
  and dotted names under ``validation`` and ``exuclear``, resolved part by part (each a
  module, or a name of what precedes it: ``exuclear.engine.steering.HELD_CONTACT_PERIODS``);
- "physics.md section N" / "sections N and M" and bare "section N.M" against the headings
  of docs/physics.md (a bare "section N.M" of the paper, "the paper's section 5.2", is the
  paper's, not physics.md's, and is skipped);
- the ``#anchor`` links of docs/*.md against the headings of the same file.

README.md is skipped while it is rewritten.  The zoo's citations of Exudyn's own files
(``main/pythonDev/Examples/...``) name another repository and match none of the prefixes.
"""
from __future__ import annotations

import importlib.util
import pathlib
import re
import types

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[1]
PHYSICS = ROOT / "docs" / "physics.md"

#: Folders that hold no source of the project (virtual environment, build and run outputs).
SKIP_DIRS = {".git", ".venv", ".ruff_cache", ".pytest_cache", "__pycache__", "build", "dist", "results", "solution"}
#: What is read: Python (code, docstrings, comments), Markdown, and the compiled kernel's C++.
SOURCE_SUFFIXES = (".py", ".md", ".hpp", ".cpp")
#: Files not read: this file quotes dangling examples.
SKIP_FILES = {"tests/test_references.py"}

#: Mentions known to dangle, each with its correct target (empty: every mention resolves).
KNOWN_ELSEWHERE: dict[tuple[str, str], str] = {}

PATH = re.compile(r"(?<![\w./-])((?:docs|validation|exuclear|models)/[\w.*/-]*[\w*/])")
COMMAND = re.compile(r"python3? -m ((?:validation|exuclear|models)(?:\.\w+)*)")
#: A dotted name under validation or exuclear: ``validation.cost.film``, ``exuclear.make_joint``.
#: A quoted one is a string key (``"exuclear.joints"``), not a module.
DOTTED = re.compile(r"""(?<![\w./\-"'])((?:validation|exuclear)(?:\.\w+)+)""")
#: An upper-case placeholder in a command or name, as in ``python -m exuclear.models.NAME``.
PLACEHOLDER = re.compile(r"\.[A-Z][A-Z_]*\b")
SECTION_LIST = r"(\d+(?:\.\d+)*(?:(?:,\s*|\s*-\s*|\s+and\s+|\s+to\s+)\d+(?:\.\d+)*)*)"
PHYSICS_SECTION = re.compile(r"physics\.md`*\)?,?\s+sections?\s+" + SECTION_LIST)
BARE_SECTION = re.compile(r"(?<![\w.])sections?\s+(\d+\.\d+)\b")
#: Words right before a bare "section N.M" that make it another document's.
NOT_PHYSICS = re.compile(r"(paper's|paper|its|their|Mechanics\*?|\d{4}),?\s*$")
ANCHOR_LINK = re.compile(r"\]\(#([^)]+)\)")


def _sources() -> list[pathlib.Path]:
    out = []
    for path in sorted(ROOT.rglob("*")):
        rel = path.relative_to(ROOT)
        if path.suffix not in SOURCE_SUFFIXES or not path.is_file():
            continue
        if any(part in SKIP_DIRS or part.endswith(".egg-info") for part in rel.parts):
            continue
        if rel.as_posix() not in SKIP_FILES:
            out.append(path)
    return out


SOURCES = _sources()


def _rel(path: pathlib.Path) -> str:
    return path.relative_to(ROOT).as_posix()


#: What the doc build writes (docs/conf.py): named in the docs, absent from a checkout.
GENERATED = ("docs/_build", "docs/api/exuclear.rst", "docs/auto_examples")


def _path_exists(mention: str, source: pathlib.Path | None = None) -> bool:
    """A file or folder of the repository; ``models/four_bar`` may name ``models/four_bar.py``.
    In a Markdown page a link may also be relative to the page (``docs/index.md`` linking
    ``validation/zoo.md`` means ``docs/validation/zoo.md``)."""
    mention = mention.rstrip(".")
    if any(mention.startswith(out) for out in GENERATED):
        return True
    if "*" in mention:
        return any(ROOT.glob(mention))
    bases = [ROOT] + ([source.parent] if source is not None and source.suffix == ".md" else [])
    if (ROOT / "docs" / f"{mention}.md").exists():  # a Sphinx document name (docs/index.md's toctree)
        return True
    return any((base / mention).exists() or (base / f"{mention}.py").exists() or (base / f"{mention}.md").exists()
               for base in bases)


def slug(heading: str) -> str:
    """The anchor GitHub gives a Markdown heading: lower case, punctuation dropped, spaces
    to hyphens."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def headings(path: pathlib.Path) -> list[tuple[int, str]]:
    """The Markdown headings of ``path`` outside code blocks: (level, text)."""
    out, fenced = [], False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            fenced = not fenced
        m = re.match(r"(#{1,6})\s+(.*)", line)
        if m and not fenced:
            out.append((len(m.group(1)), m.group(2)))
    return out


def physics_sections() -> set[str]:
    """Section numbers of docs/physics.md: "6" for "## 6. The paper's scenes", "6.2" for
    "### 6.2 Slider-crank ..."."""
    numbers = set()
    for _, text in headings(PHYSICS):
        m = re.match(r"(\d+(?:\.\d+)*)\.?\s", text)
        if m:
            numbers.add(m.group(1))
    return numbers


def _section_numbers(listing: str) -> list[str]:
    """"6.1 and 6.2" -> [6.1, 6.2]; "1-4" -> [1, 4] (a range's ends)."""
    return re.findall(r"\d+(?:\.\d+)*", listing)


def _line(text: str, pos: int) -> int:
    return text.count("\n", 0, pos) + 1


def _dangling(check) -> list[str]:
    out = []
    for path in SOURCES:
        text = path.read_text(encoding="utf-8")
        for pos, mention, target in check(path, text):
            if (_rel(path), mention) in KNOWN_ELSEWHERE:
                continue
            out.append(f"{_rel(path)}:{_line(text, pos)}: {mention!r}" + (f" ({target})" if target else ""))
    return out


#: A path at a commit, ``4ed4aac:exuclear/engine/following.py`` (what ``git show`` reads): the
#: code that a design page records after it left the tree.
AT_COMMIT = re.compile(r"\b[0-9a-f]{7,40}:$")


def test_path_mentions_resolve():
    def check(path, text):
        for m in PATH.finditer(text):
            if AT_COMMIT.search(text[max(0, m.start(1) - 41):m.start(1)]):
                continue
            if not _path_exists(m.group(1), path):
                yield m.start(1), m.group(1), "no such file or folder"

    dangling = _dangling(check)
    assert not dangling, "dangling path mentions:\n" + "\n".join(dangling)


def test_commands_resolve():
    def check(path, text):
        for m in COMMAND.finditer(text):
            if not PLACEHOLDER.search(m.group(1)) and importlib.util.find_spec(m.group(1)) is None:
                yield m.start(1), m.group(0), "no such module"

    dangling = _dangling(check)
    assert not dangling, "dangling commands:\n" + "\n".join(dangling)


#: Modules that exist only where they could be built: the compiled kernel (setup.py builds it
#: from exuclear/_kernel/bindings.cpp; without a compiler exuclear runs its Python kernel).
OPTIONAL_MODULES = {"exuclear._ckernel"}


def _dotted_exists(name: str) -> bool:
    """Each part after the package is a module of what precedes it, or a name of it (an
    attribute, or a dataclass field or annotation without a default): ``exuclear.engine.newton``
    names no module of ``exuclear.engine``; ``exuclear.SolverSettings.end_time`` is a field.
    A module is imported only where a further part must be found in it."""
    parts = name.split(".")
    if ".".join(parts[:2]) in OPTIONAL_MODULES:
        return True
    obj: object = importlib.import_module(parts[0])
    for k, part in enumerate(parts[1:], start=2):
        dotted = ".".join(parts[:k])
        spec = None
        if isinstance(obj, types.ModuleType) and hasattr(obj, "__path__"):
            spec = importlib.util.find_spec(dotted)
        if spec is not None:
            if k == len(parts):
                return True
            obj = importlib.import_module(dotted)
            continue
        if hasattr(obj, part):
            obj = getattr(obj, part)
            continue
        return part in getattr(obj, "__dataclass_fields__", {}) or part in getattr(obj, "__annotations__", {})
    return True


def test_dotted_module_mentions_resolve():
    def check(path, text):
        for m in DOTTED.finditer(text):
            if text[max(0, m.start() - 5):m.start()] == "e.g. ":
                continue  # an example of a name, not a mention
            if not PLACEHOLDER.search(m.group(1)) and not _dotted_exists(m.group(1)):
                yield m.start(1), m.group(1), "no such module or name"

    dangling = _dangling(check)
    assert not dangling, "dangling dotted names:\n" + "\n".join(dangling)


def test_physics_section_mentions_resolve():
    known = physics_sections()

    def check(path, text):
        spans = []
        for m in PHYSICS_SECTION.finditer(text):
            spans.append(m.span())
            for number in _section_numbers(m.group(1)):
                if number not in known:
                    yield m.start(1), f"physics.md section {number}", "no such heading in docs/physics.md"
        if path == PHYSICS or "physics.md" in text:
            for m in BARE_SECTION.finditer(text):
                if any(a <= m.start() < b for a, b in spans):
                    continue  # read above as a physics.md mention
                before = text[max(0, m.start() - 30):m.start()]
                if m.group(1) not in known and not NOT_PHYSICS.search(before):
                    yield m.start(1), f"section {m.group(1)}", "no such heading in docs/physics.md"

    assert known >= {"1", "6", "6.1", "6.2", "10.9"}  # the parser reads the headings
    dangling = _dangling(check)
    assert not dangling, "dangling section mentions:\n" + "\n".join(dangling)


@pytest.mark.parametrize("doc", sorted((ROOT / "docs").glob("*.md")), ids=lambda p: p.name)
def test_anchor_links_resolve(doc):
    anchors = {slug(text) for _, text in headings(doc)}
    links = ANCHOR_LINK.findall(doc.read_text(encoding="utf-8"))
    assert not [a for a in links if a not in anchors]


def test_the_physics_contents_list_every_section():
    """The contents at the top of docs/physics.md link every section and subsection."""
    text = PHYSICS.read_text(encoding="utf-8")
    first = text.index("\n## ")  # the contents come before the first section
    links = set(ANCHOR_LINK.findall(text[:first]))
    assert [text for level, text in headings(PHYSICS) if level > 1 and slug(text) not in links] == []


def test_the_checks_catch_what_they_are_for():
    """The patterns find the mentions this test exists for (the stale ones issue 31 found)."""
    assert PATH.findall("see validation/slider_crank.py's closed form") == ["validation/slider_crank.py"]
    assert not _path_exists("validation/slider_crank.py") and _path_exists("validation/slider_crank/")
    assert COMMAND.findall("python -m validation.film_cost") == ["validation.film_cost"]
    assert importlib.util.find_spec("validation.cost.film") is not None
    listing = PHYSICS_SECTION.search("docs/physics.md sections 6.1 and\n5.2 (slider-crank)").group(1)
    assert _section_numbers(listing) == ["6.1", "5.2"]
    assert "5.2" not in physics_sections()
    assert NOT_PHYSICS.search("the paper's example 2, its ") and NOT_PHYSICS.search("the paper, ")
    assert not _dotted_exists("validation.benchmark") and _dotted_exists("validation.cost.benchmark")
    assert not _dotted_exists("exuclear.engine.newton") and _dotted_exists("exuclear.engine.steering.steer_newton")
    assert any(p.suffix == ".hpp" for p in SOURCES)  # the kernel's comments are read
    assert AT_COMMIT.search("git show 4ed4aac:") and not AT_COMMIT.search("the file docs:")
    assert PLACEHOLDER.search("exuclear.models.NAME")
    assert slug("### 2.3 The onset velocity `v0`, its floor and its interpolation"[4:]) == \
        "23-the-onset-velocity-v0-its-floor-and-its-interpolation"
