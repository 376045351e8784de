"""The impulse contact mode at a joint's ends against the compliant joint converged (issue
52): the spatial revolute joint's end faces and a translational joint's finite guide
(``_end_scenes``, whose docstring names the scenes and their exact references; the tests in
tests/test_impulse_ends.py assert on those).

Prints, for each comparison scene, the impulse mode and the compliant joint at the scene's
step and at a quarter of it: the largest distance of the body's positions from the
compliant joint's converged run, in clearances, and the impulse mode's impacts (resting
contacts' onsets included).

::

    python -m validation.cost modes_ends
"""
from __future__ import annotations

import argparse

from validation._tables import markdown_table
from validation.cost._end_scenes import compared_rows


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m validation.cost modes_ends", description=__doc__.split("\n")[0])
    ap.parse_args(argv)
    print(markdown_table(["scene", "run", "distance from the converged compliant run [c]", "impacts"],
                         compared_rows()))
    return 0
