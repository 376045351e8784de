"""Math backends: the few operations the joint's formulas need beyond + - * / **.

A formula written against this interface runs on Python floats (:data:`FLOAT_OPS`) or,
with the adapter's symbolic operations, is recorded once as an Exudyn symbolic
expression and then evaluated in compiled code.  Branches are written as
``ops.where(condition, if_true, if_false)``; with floats both sides are evaluated
(they must stay finite), symbolically only the chosen one.
"""
from __future__ import annotations

import math


class FloatOps:
    """The operations on Python floats."""

    sqrt = staticmethod(math.sqrt)
    sin = staticmethod(math.sin)
    cos = staticmethod(math.cos)
    abs = staticmethod(abs)
    min = staticmethod(min)
    max = staticmethod(max)

    @staticmethod
    def sign(x: float) -> float:
        """-1, 0 or 1."""
        return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)

    @staticmethod
    def where(condition: bool, if_true: float, if_false: float) -> float:
        return if_true if condition else if_false


FLOAT_OPS = FloatOps()
