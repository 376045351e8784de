"""The scenes a study can run by name: any module with a ``study`` function and its
``STUDY_PARAMETERS``, found by dotted path or by a short name of the entry-point group
:data:`SCENE_ENTRY_POINTS`.  The library never imports a scene by itself."""
from __future__ import annotations

import importlib

from .spec import Study

#: Entry-point group of the scenes known by short name (``name = "package.module"``).
SCENE_ENTRY_POINTS = "exuclear.scenes"


def scene_names() -> dict[str, str]:
    """The scenes known by short name: name -> module path, from the installed
    distributions' entry points in the group :data:`SCENE_ENTRY_POINTS` (the first of a
    name wins, as on ``sys.path``)."""
    from importlib.metadata import entry_points

    found: dict[str, str] = {}
    for point in entry_points(group=SCENE_ENTRY_POINTS):
        found.setdefault(point.name, point.value)
    return found


def scene(name: str) -> Study:
    """The study of a scene: a short name of :func:`scene_names` (``"slider-crank"``), or
    a dotted path of any module with a ``study`` function, ``STUDY_PARAMETERS`` (defaults)
    and ``check_study``."""
    if "." in name:
        module_name = name
    else:
        known = scene_names()
        if name not in known:
            raise ValueError(f"unknown scene {name!r}; known: {', '.join(sorted(known)) or 'none installed'}, "
                             "or a module path (package.module)")
        module_name = known[name]
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as err:
        raise ValueError(f"unknown scene {name!r} (no module {module_name}: {err})") from None
    missing = [n for n in ("study", "STUDY_PARAMETERS") if not hasattr(module, n)]
    if missing:
        raise ValueError(f"module {module_name} is not a scene: it has no {', '.join(missing)}")
    return Study(module.study, dict(module.STUDY_PARAMETERS), getattr(module, "check_study", None), name,
                 dict(getattr(module, "STUDY_COLUMNS", {})))
