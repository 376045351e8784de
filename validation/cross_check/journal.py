"""The journal-bearing impacts: the library against the reference on every law and
restitution of the sweep (:data:`.common.CR_SWEEP`)."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from exuclear.models import journal_bearing as jb_model
from exuclear.models.journal_bearing import JournalBearingParams
from validation.cross_check.common import CR_SWEEP, JB_CRITERIA, _relative
from validation.reference import journal_bearing as jb_reference


@dataclass
class ImpactRow:
    """Library against reference on one journal-bearing impact."""

    law: str
    cr: float
    library: dict[str, float]
    reference: dict[str, float]
    errors: dict[str, float]
    wall_library: float
    wall_reference: float
    success: bool
    message: str

    @property
    def failed(self) -> list[str]:
        """Criteria (keys of :data:`JB_CRITERIA`) that the row misses."""
        return [c.key for c in JB_CRITERIA if not abs(self.errors[c.key]) <= c.limit]

    @property
    def passed(self) -> bool:
        return self.success and not self.failed


def impact_cases(laws: Sequence[str]) -> tuple[list[tuple[str, float]], list[str]]:
    """(law, cr) pairs of the sweep that each law accepts, and notes on those it rejects."""
    cases, skipped = [], []
    for law in laws:
        for cr in CR_SWEEP:
            try:
                JournalBearingParams.paper(law=law, cr=cr).joint()
            except ValueError as err:
                skipped.append(f"{law}, cr = {cr:g}: {err}")
                continue
            cases.append((law, cr))
    return cases, skipped

def compare_impact(law: str, cr: float) -> ImpactRow:
    """Run one impact in the library (its own settings) and in the reference (defaults)."""
    params = JournalBearingParams.paper(law=law, cr=cr)
    lib, _ = jb_model.run(params)
    ref = jb_reference.simulate(params)
    library = {"departure": lib.departure_velocity, "peak_force": lib.max_force,
               "peak_penetration": lib.max_penetration, "duration": lib.contact_duration}
    reference = {"departure": ref["departure_velocity"], "peak_force": ref["max_force"],
                 "peak_penetration": ref["max_penetration"], "duration": ref["contact_duration"]}
    errors = {k: _relative(library[k], reference[k]) for k in library}
    message = "; ".join(m for ok, m in ((lib.success, f"library: {lib.message}"),
                                        (ref["success"], f"reference: {ref['message']}")) if not ok)
    return ImpactRow(law, cr, library, reference, errors, lib.wall_time, ref["wall_time"],
                     lib.success and ref["success"], message)
