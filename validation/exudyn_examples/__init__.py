"""The zoo: Exudyn's public example models, each with one revolute joint replaced by a
clearance joint, to judge exuclear on other people's models (``_common.py`` holds the
interface and the runner; ``python -m validation.exudyn_examples`` runs them)."""
from ._common import IMPORT_ERRORS, REGISTRY, ZooModel, load_models, register, run_model, run_zoo

__all__ = ["IMPORT_ERRORS", "REGISTRY", "ZooModel", "load_models", "register", "run_model", "run_zoo"]
