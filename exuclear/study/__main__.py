"""``python -m exuclear.study``: the command line of :mod:`exuclear.study.cli`.

Nothing imports this module, so runpy never finds it in ``sys.modules`` before running it;
what travels to worker processes (study functions, classes) comes from the package's own
modules.  The guard keeps spawned workers, which import the main module under another
name, from running the command line again.
"""
import sys

from exuclear.study.cli import main

if __name__ == "__main__":
    sys.exit(main())
