"""Sphinx configuration of exuclear's documentation site.

Build it with ``python -m sphinx -W -b html docs docs/_build/html`` (``pip install -e ".[docs]"``).
The Markdown pages are read by MyST, the API pages are generated from the docstrings
(autodoc, autosummary, napoleon), and the gallery runs ``docs/examples/*.py`` with
sphinx-gallery, so a broken example breaks the build.
"""
from __future__ import annotations

import os
import socket
import sys
import threading
import typing
import warnings
from pathlib import Path

import exuclear

DOCS = Path(__file__).resolve().parent

project = "exuclear"
author = "the exuclear developers"
copyright = "the exuclear developers"
release = exuclear.__version__
version = release

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.intersphinx",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
# docs/examples/ holds the gallery's sources; sphinx-gallery turns them into auto_examples/
exclude_patterns = ["_build", "examples", "**.ipynb_checkpoints"]

# -- MyST ------------------------------------------------------------------------------
# dollarmath: $...$ and $$...$$ for pages that want LaTeX; physics.md writes its equations
# as plain-text code blocks, which MyST shows as they are.  colon_fence: ::: directives.
myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3  # "#3-friction"-style links to headings

# -- autodoc / autosummary / napoleon --------------------------------------------------
autosummary_generate = True
autosummary_imported_members = False
autodoc_default_options = {"members": True, "show-inheritance": True}
autodoc_member_order = "bysource"
autodoc_typehints = "description"  # hints next to the parameters, not in a long signature
autodoc_preserve_defaults = True  # show `law="wang-liu"`, not the evaluated object
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False
# "Attributes" sections as fields of their class, not as attribute entries that collide with
# the NamedTuple fields and properties autodoc documents too
napoleon_use_ivar = True

# -- intersphinx -----------------------------------------------------------------------
# Links to numpy, scipy and Python.  Fetching their inventories needs the network; an
# unreachable inventory is a Sphinx warning, and -W makes it an error.  So the mapping is
# used only when docs.python.org answers within INTERSPHINX_PROBE_S seconds, or when
# EXUCLEAR_DOCS_OFFLINE=0 forces it; EXUCLEAR_DOCS_OFFLINE=1 skips the probe and the links
# (names then print as plain text, nothing else changes).
INTERSPHINX = {
    "python": ("https://docs.python.org/3", None),
    "numpy": ("https://numpy.org/doc/stable", None),
    "scipy": ("https://docs.scipy.org/doc/scipy", None),
}
INTERSPHINX_PROBE_S = 3.0  # a DNS lookup and a TCP handshake; offline it fails or times out


def _online(host: str = "docs.python.org", port: int = 443) -> bool:
    """Whether ``host`` accepts a connection within INTERSPHINX_PROBE_S seconds.  The probe
    runs in a thread because a DNS lookup ignores socket timeouts."""
    answer: list[bool] = []

    def probe() -> None:
        try:
            socket.create_connection((host, port), timeout=INTERSPHINX_PROBE_S).close()
            answer.append(True)
        except OSError:
            answer.append(False)

    thread = threading.Thread(target=probe, daemon=True)
    thread.start()
    thread.join(INTERSPHINX_PROBE_S)
    return bool(answer and answer[0])


_offline = os.environ.get("EXUCLEAR_DOCS_OFFLINE")
if _offline == "0" or (_offline != "1" and _online()):
    intersphinx_mapping = INTERSPHINX
else:
    intersphinx_mapping = {}
    print("exuclear docs: offline (EXUCLEAR_DOCS_OFFLINE or no answer from docs.python.org): "
          "no links to Python, numpy and scipy", file=sys.stderr)
intersphinx_timeout = 10

# -- sphinx-gallery --------------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": "examples",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"/plot_",  # run every example: a broken one breaks the build
    "ignore_pattern": r"__init__\.py",
    "within_subsection_order": "FileNameSortKey",
    "download_all_examples": False,
    "remove_config_comments": True,
    "matplotlib_animations": False,
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "show_memory": False,
}
# No display: figures are drawn with Agg (sphinx-gallery sets it too).
os.environ.setdefault("MPLBACKEND", "Agg")
# Exudyn's own DeprecationWarnings are not the examples' business (as in pyproject's pytest settings).
warnings.filterwarnings("ignore", category=DeprecationWarning, module=r"exudyn.*")

# -- HTML ------------------------------------------------------------------------------
html_theme = "furo"
html_title = f"exuclear {release}"
html_theme_options = {
    "source_repository": "https://github.com/exuclear/exuclear",
    "source_branch": "main",
    "source_directory": "docs/",
}

# -- the API page of exuclear's own names ----------------------------------------------
# docs/api/exuclear.rst lists exuclear.__all__ as the package has it when the docs are
# built (grouped by kind), so that a name added to or removed from __all__ appears or
# disappears without editing the page.  It is written here, before autosummary scans the
# sources for the stubs it generates.


def _kind(name: str) -> str:
    obj = getattr(exuclear, name)
    if isinstance(obj, type) and issubclass(obj, Warning):
        return "Warnings"
    if isinstance(obj, type):
        return "Classes"
    if callable(obj):
        return "Functions"
    return "Constants"


def write_api_page() -> None:
    groups: dict[str, list[str]] = {"Functions": [], "Classes": [], "Constants": [], "Warnings": []}
    for name in exuclear.__all__:
        groups[_kind(name)].append(name)
    lines = [
        ".. This file is written by docs/conf.py from exuclear.__all__ at every build; do not edit.",
        "",
        "The ``exuclear`` namespace",
        "==========================",
        "",
        ".. automodule:: exuclear",
        "   :no-members:",
        "",
        f"``exuclear.__all__`` has {len(exuclear.__all__)} names; each has its own page.",
        "",
    ]
    for title, names in groups.items():
        if not names:
            continue
        lines += [title, "-" * len(title), "", ".. autosummary::", "   :toctree: generated", "", *(f"   {n}" for n in names), ""]
    target = DOCS / "api" / "exuclear.rst"
    text = "\n".join(lines)
    if not target.exists() or target.read_text(encoding="utf-8") != text:  # unchanged: no rebuild of the page
        target.write_text(text, encoding="utf-8")


write_api_page()


# -- one entry per object -------------------------------------------------------------
# A name of exuclear.__all__ is documented once, on its own page (exuclear.NAME); the
# module pages (exuclear.contact, ...) leave it out, so that a reference to it has one
# target.  Constants take their doc comment (``#:``) from the module that defines them,
# not the docstring of their type (dict, tuple).


def _public_objects() -> dict[int, str]:
    return {id(getattr(exuclear, name)): name for name in exuclear.__all__}


def _skip_public(app, what, name, obj, skip, options):  # noqa: ARG001 - Sphinx's signature
    if what == "module" and id(obj) in _public_objects() and not isinstance(obj, (int, float, str, tuple)):
        return True
    return None


def _comment_doc(name: str) -> list[str] | None:
    """The ``#:`` comment of ``exuclear.NAME`` in the exuclear module that defines it."""
    from sphinx.pycode import ModuleAnalyzer

    obj = getattr(exuclear, name)
    for modname, module in sorted(sys.modules.items()):
        if not modname.startswith("exuclear.") or getattr(module, name, None) is not obj:
            continue
        try:
            docs = ModuleAnalyzer.for_module(modname).find_attr_docs()
        except Exception:  # noqa: BLE001 - a module without source: try the next one
            continue
        if ("", name) in docs:
            return [line for line in docs[("", name)] if line is not None]
    return None


def _constant_doc(app, what, name, obj, options, lines):  # noqa: ARG001 - Sphinx's signature
    if what in ("attribute", "property") and lines and lines[0].startswith("Alias for field number"):
        # a NamedTuple field's generated docstring says nothing a reader needs: the record's
        # own docstring describes its fields
        lines[:] = []
        return
    if what in ("data", "attribute") and name.startswith("exuclear.") and name.count(".") == 1:
        short = name.split(".", 1)[1]
        if short in exuclear.__all__ and not callable(obj):
            doc = _comment_doc(short)
            lines[:] = doc if doc is not None else []


def _public_bases(app, name, obj, options, bases):  # noqa: ARG001 - Sphinx's signature
    # a record that extends another's fields (exuclear.history.PairImpact, exuclear.slot.SlotKinematics)
    # is built on a private NamedTuple of those fields: its page says NamedTuple, as for the others
    bases[:] = [typing.NamedTuple if b.__name__.startswith("_") and hasattr(b, "_fields") else b for b in bases]


def setup(app):
    app.connect("autodoc-skip-member", _skip_public)
    app.connect("autodoc-process-docstring", _constant_doc)
    app.connect("autodoc-process-bases", _public_bases)
