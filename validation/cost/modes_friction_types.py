"""The impulse contact mode's Coulomb friction on each joint type against Newton's laws
(issue 52): a planar slider's corners, a pin in its slot, a spatial journal's slices, a ball
in its socket, a box's corners (``_friction_scenes``, whose docstring names the laws).

Prints one row per scene: the case, the law, and how far the mode's run is from it.  The
zoo's models of these types with a friction law are rows of ``python -m validation.cost
modes --friction paper --models ...``.

::

    python -m validation.cost modes_friction_types
"""
from __future__ import annotations

import argparse

from validation._tables import markdown_table
from validation.cost._friction_scenes import friction_type_rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost modes_friction_types",
                                 description=__doc__.split("\n")[0])
    ap.parse_args(argv)
    print(markdown_table(["case", "law", "impulse mode"], friction_type_rows()))
    return 0
