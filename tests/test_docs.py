"""The documentation is a product: the site builds without a warning, documents every
public name, and runs its gallery (docs/conf.py, docs/examples).

The build takes about a minute on two cores (the gallery's thirteen examples are most of it),
so it is marked slow; it is skipped, saying so, where the ``docs`` extra is not installed
(``pip install -e ".[docs]"``).  The page of Getting started is checked by running its
code.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import exuclear

ROOT = Path(__file__).resolve().parent.parent
DOCS = ROOT / "docs"
#: The gallery has at least this many examples (issue 32).
MIN_EXAMPLES = 8
#: The Python modules a user reaches besides exuclear itself; each has an API page.
MODULES = ("contact", "friction", "film", "geometry", "spherical", "prismatic", "slot", "materials", "timescales", "history", "nonlinear")


def _require(module: str) -> None:
    try:
        __import__(module)
    except ImportError:
        pytest.skip(f"{module} is not installed: the documentation build needs the docs extra "
                    "(pip install -e \".[docs]\")")


@pytest.fixture(scope="module")
def site(tmp_path_factory) -> Path:
    for module in ("sphinx", "furo", "myst_parser", "sphinx_gallery", "matplotlib"):
        _require(module)
    # a copy of docs/ without what earlier builds generated in it (sphinx-gallery keeps
    # its outputs next to the sources and skips unchanged examples), so that this build
    # runs every example
    source = tmp_path_factory.mktemp("docs") / "docs"
    shutil.copytree(DOCS, source, ignore=shutil.ignore_patterns("_build", "auto_examples", "generated",
                                                                 "sg_execution_times.rst", "__pycache__"))
    # the pages that include the code of a validation script (literalinclude ../../validation/...)
    (source.parent / "validation").mkdir()
    shutil.copy(ROOT / "validation" / "first_hour.py", source.parent / "validation" / "first_hour.py")
    out = tmp_path_factory.mktemp("site")
    env = {**os.environ, "MPLBACKEND": "Agg"}
    env.setdefault("EXUCLEAR_DOCS_OFFLINE", "1")  # no network probe in the tests: intersphinx off
    done = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-b", "html", "-q", str(source),
                           str(out)], capture_output=True, text=True, cwd=ROOT, env=env, timeout=900)
    assert done.returncode == 0, f"sphinx -W failed:\n{done.stderr[-5000:]}"
    return out


@pytest.mark.slow
def test_every_public_name_has_its_entry(site):
    page = (site / "api" / "exuclear.html").read_text(encoding="utf-8")
    for name in exuclear.__all__:
        entry = site / "api" / "generated" / f"exuclear.{name}.html"
        assert entry.exists(), f"no API page for exuclear.{name}"
        assert f'id="exuclear.{name}"' in entry.read_text(encoding="utf-8"), f"exuclear.{name} is not documented"
        assert f"exuclear.{name}.html" in page, f"the exuclear page does not link exuclear.{name}"


@pytest.mark.slow
def test_every_user_module_has_its_page(site):
    for module in MODULES:
        html = (site / "api" / f"{module}.html").read_text(encoding="utf-8")
        assert f'id="module-exuclear.{module}"' in html
        # at least one documented member, so that a module whose names moved elsewhere
        # (re-exported without __all__) does not leave an empty page
        assert re.search(rf'id="exuclear\.{module}\.\w+', html), f"exuclear.{module}'s page documents nothing"


@pytest.mark.slow
def test_gallery_runs_its_examples_with_figures(site):
    pages = sorted((site / "auto_examples").glob("plot_*.html"))
    sources = sorted((DOCS / "examples").glob("plot_*.py"))
    assert len(sources) >= MIN_EXAMPLES and len(pages) == len(sources)
    for page in pages:
        html = page.read_text(encoding="utf-8")
        images = re.findall(r'src="\.\./(_images/sphx_glr_[^"]+\.png)"', html)
        assert images, f"{page.name} shows no figure"
        for image in images:
            assert (site / image).stat().st_size > 5000, f"{page.name}: {image} is empty"
    # executed by this build, not taken from an earlier one: the source tree is a fresh copy
    times = (site / "sg_execution_times.html").read_text(encoding="utf-8")
    assert len(re.findall(r"plot_\w+\.py", times)) >= len(sources)


@pytest.mark.slow
def test_every_page_is_reachable_from_the_index(site):
    # -W already refuses a page outside every toctree; this checks the pages of issue 32 exist
    for page in ("index", "getting_started", "changelog", "physics", "bad_input", "layout", "api/index",
                 "auto_examples/index", "guide/your_model", "validation/paper"):
        assert (site / f"{page}.html").exists(), page


def _python_blocks(path: Path) -> str:
    return "\n".join(re.findall(r"```python\n(.*?)```", path.read_text(encoding="utf-8"), flags=re.S))


def test_getting_started_code_runs_and_prints_what_it_says(capsys):
    exec(compile(_python_blocks(DOCS / "getting_started.md"), "getting_started.md", "exec"), {})  # noqa: S102
    out = capsys.readouterr().out
    # the page's comment: peak force 1187 N, departure velocity -0.2688 m/s (the paper: 0.269 m/s)
    assert "departure velocity -0.2688 m/s" in out and "peak force 11" in out
    assert "[]" in out  # joint.notes: nothing the joint could not resolve


# -- names and cross-references resolve (issue 48) --------------------------------------------------

#: Where a user reads names: the front door, the pages, the gallery, and the docstrings and
#: comments of the library, the scenes and the validation.
_TEXTS = ("README.md", "docs/**/*.md", "docs/examples/*.py", "exuclear/**/*.py", "models/*.py", "validation/**/*.py")
#: ``exuclear.X.Y``, not inside a string key (``"exuclear.joints"``), a path or a longer name.
_NAME = re.compile(r"(?<![\w/.\"'])exuclear(?:\.[A-Za-z_]\w*)+")
#: Placeholders that stand for any name (``exuclear.models.NAME``).
_PLACEHOLDERS = {"NAME"}


def _texts() -> list[Path]:
    skip = {"_build", "auto_examples", "generated", "__pycache__"}
    return sorted({p for pattern in _TEXTS for p in ROOT.glob(pattern) if not skip & set(p.parts)})


def _resolves(dotted: str) -> bool:
    import importlib

    parts = dotted.split(".")
    for k in range(len(parts), 0, -1):
        try:
            obj = importlib.import_module(".".join(parts[:k]))
        except ImportError:
            continue
        try:
            for part in parts[k:]:
                obj = getattr(obj, part)
        except AttributeError:
            return False
        return True
    return False


def test_every_exuclear_name_in_the_readme_pages_and_docstrings_resolves():
    unresolved = {}
    for path in _texts():
        for match in _NAME.finditer(path.read_text()):
            name = match.group(0)
            if not _PLACEHOLDERS & set(name.split(".")) and not _resolves(name):
                unresolved.setdefault(name, str(path.relative_to(ROOT)))
    assert not unresolved, f"names that do not resolve (name: first file): {unresolved}"


def _headings(path: Path) -> set[str]:
    return {line.lstrip("#").strip() for line in path.read_text().splitlines() if line.startswith("#")}


def test_every_cross_reference_points_at_a_page_or_section_that_exists():
    section = re.compile(r"(README|docs/[\w/]+\.md)[,:]? \"([^\"\n]+)\"")  # (README, "Section")
    numbered = re.compile(r"docs/physics\.md,? section (\d+(?:\.\d+)*)")  # docs/physics.md section 9.8
    page = re.compile(r"(?<![\w/.:])(docs/[\w/]+\.md)")  # not a commit's path, 4ed4aac:docs/...
    physics = {h.split(" ", 1)[0].rstrip(".") for h in _headings(DOCS / "physics.md") if h[:1].isdigit()}
    broken = []
    for path in _texts():
        text = path.read_text()
        where = str(path.relative_to(ROOT))
        for target, title in section.findall(text):
            file = ROOT / ("README.md" if target == "README" else target)
            if not file.exists() or title not in _headings(file):
                broken.append(f"{where}: {target}, {title!r}")
        broken += [f"{where}: docs/physics.md section {n}" for n in numbered.findall(text) if n not in physics]
        broken += [f"{where}: {p}" for p in page.findall(text) if not (ROOT / p).exists()]
        if path.suffix == ".md":  # links between pages
            for link in re.findall(r"\]\(([^)#:]+\.(?:md|rst))(?:#[^)]*)?\)", text):
                if not link.startswith("auto_examples/") and not (path.parent / link).exists():  # auto_examples: built
                    broken.append(f"{where}: link {link}")
    assert not broken, "cross-references to nothing:\n" + "\n".join(broken)
