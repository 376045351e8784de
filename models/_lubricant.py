"""The oil of a scene's clearance joint: its parameter fields' values and what the scenes
read from a lubricated joint's outputs (docs/physics.md section 10)."""
from __future__ import annotations

from dataclasses import fields

import numpy as np

from exuclear.film import FILM_MODELS, Lubrication

#: The film models a scene's ``film_model`` field takes (:data:`exuclear.film.FILM_MODELS`).
FILM_MODEL_NAMES = tuple(FILM_MODELS)
#: What a scene's ``film_model`` field falls back to: the library's default (:class:`exuclear.Lubrication`).
FILM_MODEL_DEFAULT = next(f.default for f in fields(Lubrication) if f.name == "model")


def lubrication(viscosity: float | None, film_model: str) -> Lubrication | None:
    """The lubricant of a scene's joint from its ``viscosity`` [Pa s] and ``film_model`` fields:
    None (a dry joint) where ``viscosity`` is None.  A film model other than the default
    without a viscosity is refused (``ValueError``), not ignored: a dry joint has no film."""
    if viscosity is None:
        if film_model != FILM_MODEL_DEFAULT:
            raise ValueError(f"`film_model` {film_model!r} needs a `viscosity` (--viscosity): without one the "
                             "joint is dry and has no film")
        return None
    return Lubrication(viscosity=viscosity, model=film_model)


def joint_force(out: dict[str, np.ndarray]) -> np.ndarray:
    """Magnitude of the force a lubricated joint carries [N]: the film's plus the metal
    contact's, ``F = F_film - F_N n - F_T t`` on the journal (docs/physics.md eqs. (68), section 4),
    from the joint's outputs (``n = e / |e|``, ``t = (n_y, -n_x)``; no contact force at ``e = 0``)."""
    ecc = np.hypot(out["ecc_x"], out["ecc_y"])
    safe = np.where(ecc > 0.0, ecc, 1.0)
    nx, ny = out["ecc_x"] / safe, out["ecc_y"] / safe
    f_n, f_t = out["normal_force"], out["tangential_force"]
    return np.hypot(out["film_fx"] - f_n * nx - f_t * ny, out["film_fy"] - f_n * ny + f_t * nx)
