"""The zoo: Exudyn's public example models, each with one revolute joint replaced by a
clearance joint, to judge exuclear on other people's models (``_common.py`` holds the
interface and the registry, ``_runs.py`` the runs of one model and their verdicts,
``_table.py`` the table and report of all; ``python -m validation.exudyn_examples`` runs
them)."""
from ._common import IMPORT_ERRORS, REGISTRY, ZooModel, load_models, register
from ._runs import run_model
from ._table import run_zoo

__all__ = ["IMPORT_ERRORS", "REGISTRY", "ZooModel", "load_models", "register", "run_model", "run_zoo"]
