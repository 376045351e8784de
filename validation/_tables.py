"""What the validation reports share: Markdown tables, CSV files and report templates."""
from __future__ import annotations

import os
import string
from collections.abc import Mapping, Sequence


def markdown_table(header: Sequence[str], rows: Sequence[Sequence[object]]) -> str:
    """A Markdown table; cells are written with ``str`` and their ``|`` escaped.

    Kept by hand rather than ``pandas.DataFrame.to_markdown``: that needs the ``tabulate``
    package, and it reads number-like cells as numbers and rewrites them (six significant
    digits by default) and pads every column, while the scripts format each cell
    themselves; these four lines keep their text as it is, without another dependency.
    """
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c).replace("|", "\\|") for c in row) + " |" for row in rows]
    return "\n".join(lines)


def write_csv(path: str, records: Sequence[dict[str, object]]) -> str:
    """Write ``records`` (dicts with the same keys) as a CSV file; returns ``path``.

    Through :meth:`pandas.DataFrame.to_csv`, with every value written as Python's
    ``str`` writes it (object columns: an integer column with a NaN stays integers),
    ``None`` as an empty cell, NaN as ``nan`` and the CSV standard's CRLF line ends: the
    files of the former ``csv.DictWriter`` byte for byte.
    """
    import pandas as pd

    table = pd.DataFrame([{k: "" if v is None else v for k, v in r.items()} for r in records],
                         columns=list(records[0]), dtype=object)
    table.to_csv(path, index=False, na_rep="nan", lineterminator="\r\n", encoding="utf-8")
    return path


def template_blocks(path: str) -> Mapping[str, string.Template]:
    """The named blocks of a template file, as :class:`string.Template` (``$name`` fields;
    ``substitute`` raises ``KeyError`` for a missing one): each begins with a line
    ``<!-- block: NAME -->`` and runs to the next such line (the text before the first
    block is ignored), with the surrounding blank lines stripped.  A report is one block
    and the sentences that a script picks by its results are others."""
    blocks: dict[str, list[str]] = {}
    current: list[str] | None = None
    with open(path, encoding="utf-8") as f:
        for line in f.read().splitlines():
            stripped = line.strip()
            if stripped.startswith("<!-- block:") and stripped.endswith("-->"):
                current = blocks.setdefault(stripped[len("<!-- block:"):-len("-->")].strip(), [])
            elif current is not None:
                current.append(line)
    return {name: string.Template("\n".join(lines).strip("\n")) for name, lines in blocks.items()}


def template_path(script: str, name: str) -> str:
    """The template ``name`` next to the script file ``script`` (its ``__file__``)."""
    return os.path.join(os.path.dirname(os.path.abspath(script)), name)
