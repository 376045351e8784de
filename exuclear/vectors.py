"""3-vectors as plain floats: the cross and dot product, the length, the angle between two.

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

