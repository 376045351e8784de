"""3-vectors as plain floats: the cross and dot product, the length, the angle between two,
and the secant of a held normal (:func:`secant_normal`).

Any sequence of three numbers goes in (tuples, lists, numpy arrays); tuples and floats come
out.  The contact kinematics that run inside the force callback (:mod:`exuclear.spatial`,
:mod:`exuclear.prismatic`) and the impulse mode's decisions after each Newton iteration
(:mod:`exuclear.engine.impulse`) take these, not numpy's generic ``cross`` and ``norm``, which
cost tens of times more on three numbers than the arithmetic itself.
"""
from __future__ import annotations

import math
from collections.abc import Sequence

V3 = tuple[float, float, float]
#: The largest secant slope :func:`secant_normal` steps along: at 0.5 the secant goes at most
#: twice the miss beyond the reached normal.
SECANT_SLOPE = 0.5


def cross(a: Sequence[float], b: Sequence[float]) -> V3:
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a: Sequence[float], b: Sequence[float]) -> float:
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def norm(a: Sequence[float]) -> float:
    """The length ``|a|``."""
    return math.sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2])


def angle(a: Sequence[float], b: Sequence[float]) -> float:
    """The angle [rad] between ``a`` and ``b``, in [0, pi]: ``atan2(|a x b|, a . b)``, exact
    for small and large angles alike (``acos`` of the normalised dot product loses the
    small ones to round-off)."""
    return math.atan2(norm(cross(a, b)), dot(a, b))


def secant_normal(held0: Sequence[float], reached0: Sequence[float], held1: Sequence[float],
                  reached1: Sequence[float]) -> V3 | None:
    """The unit normal at which a step held in a normal would reach that same normal, from
    two computations of it: held in ``held0`` and ``held1`` (unit), reaching the directions
    ``reached0`` and ``reached1`` (unit).  The secant of the reached normal's change per
    change of the held one, ``s``, along the held ones' difference: ``held1 + (reached1 -
    held1) / (1 - s)``.  None where the held normals coincide or ``s`` is at least
    :data:`SECANT_SLOPE` (the secant would step past the reached normal by more than its miss)."""
    step = [b - a for a, b in zip(held0, held1)]
    moved = dot(step, step)
    if moved == 0.0:
        return None
    slope = dot([b - a for a, b in zip(reached0, reached1)], step) / moved
    if slope >= SECANT_SLOPE:
        return None
    aim = [h + (r - h) / (1.0 - slope) for h, r in zip(held1, reached1)]
    length = norm(aim)
    return (aim[0] / length, aim[1] / length, aim[2] / length)
