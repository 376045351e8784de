"""What the kernel reads from a joint's parameters and its run start: the fields of the
parameter matrix by name (:func:`exuclear.engine.layout.read`, over the one table
:data:`exuclear.engine.layout.LAYOUT`) the run-start record
(:class:`exuclear.engine.layout.RunStart`) and the step control's fields
(:data:`exuclear.engine.layout.STEP_CONTROL`).  The compiled kernel's ``layout.hpp`` decodes the
same table into its ``Params``."""
from __future__ import annotations

from ..layout import STEP_CONTROL, RunStart, read

__all__ = ["STEP_CONTROL", "RunStart", "read"]


