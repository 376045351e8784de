"""Parameter studies: one function of a parameter set, run over many sets, into one table.

A *study function* takes one parameter set (a ``dict``) and returns a summary (a
``dict`` of scalars, and of arrays where asked).  :func:`run_study` runs it over a list
of parameter sets (:func:`grid`, :func:`sample`, or any list of dicts) and returns a tidy
:class:`pandas.DataFrame`, one row per run: the parameters, the summary, ``success``,
``message``, ``wall_time`` [s] and ``run_id``.

Execution goes through a :class:`concurrent.futures.Executor`:

- local worker processes by default, one per core (``workers=1``: in this process);
- a Dask cluster when ``scheduler`` is an address (``"tcp://host:8786"``, passed to
  ``dask.distributed.Client``) or ``"local"`` (a ``LocalCluster`` of ``workers``
  processes); needs the ``cluster`` extra (``pip install exuclear[cluster]``);
- any executor the caller passes (``executor=``; the caller keeps it).

Runs are sent in batches sized so that one task lasts about :data:`TASK_SECONDS`.

Nothing is lost: with ``out="study.csv"`` every finished run is appended to the CSV at
once; a run that raises is a row with ``success`` False and the error as ``message``,
and a run that kills its worker process is retried alone and then recorded the same
way; Ctrl-C (or a ``KeyboardInterrupt`` from a run) stops the study, keeps the finished
rows and raises ``KeyboardInterrupt``; running the same study again skips the runs whose
``run_id`` (a hash of the parameter set) is already in the table.  Runs must be
deterministic (the same parameter set gives the same summary), and then a row does not
depend on the executor that ran it, except for ``wall_time``.

A *scene* is a module with a ``study`` function, its parameter defaults
``STUDY_PARAMETERS`` and (optionally) its check ``check_study`` and ``STUDY_COLUMNS``
(:class:`Column` of its parameters and metrics: help, units, the option names of the
scene's own command line); :func:`scene` makes it a
:class:`Study`, from a dotted module path or from a short name.  The library never imports
its scenes: short names come from the entry-point group :data:`SCENE_ENTRY_POINTS`, which
installed distributions fill (exuclear's own scenes declare ``slider-crank``,
``journal-bearing`` and ``guided-slider-crank`` in its ``pyproject.toml``; a user's package
can add its own).  The
command line::

    python -m exuclear.study slider-crank --cr 0.3:0.9:0.2 --clearance 5e-5,1e-4,2e-4 \\
        --rpm 200:5000:50 --workers 2 --out study.csv
    python -m exuclear.study plot study.csv --metric peak_force --x rpm --by cr --out study.png

The package holds one role per module: :mod:`.spec` (studies and parameter sets),
:mod:`.batch` (one batch of runs in a worker), :mod:`.executors` (where batches run),
:mod:`.table` (the CSV on disk), :mod:`.runner` (:func:`run_study`), :mod:`.scenes`
(scenes by name), :mod:`.cli` (the command line) and the opt-in :mod:`.plot`
(matplotlib, imported only by whoever plots).
"""
from ..columns import Column
from .batch import CARRIED_WARNINGS, warned
from .cli import main
from .runner import IN_FLIGHT_PER_WORKER, TASK_SECONDS, TASKS_PER_WORKER, prepare, run_study
from .scenes import SCENE_ENTRY_POINTS, scene, scene_names
from .spec import RANGE_DIGITS, RUN_ID_DIGITS, Params, Study, grid, parse_bounds, parse_values, run_id, sample
from .table import STATUS_COLUMNS, STATUS_LABELS, load_table

__all__ = [
    # studies and parameter sets
    "Study", "Params", "grid", "sample", "parse_values", "parse_bounds", "run_id", "RUN_ID_DIGITS", "RANGE_DIGITS",
    # running and the table
    "run_study", "prepare", "TASK_SECONDS", "IN_FLIGHT_PER_WORKER", "TASKS_PER_WORKER", "load_table", "warned",
    "CARRIED_WARNINGS", "STATUS_COLUMNS", "STATUS_LABELS", "Column",
    # scenes and the command line
    "scene", "scene_names", "SCENE_ENTRY_POINTS", "main",
]
