"""The floor ``v_min`` of the onset velocity on the low-speed cases."""
from __future__ import annotations

import math
import time
from dataclasses import dataclass

import exuclear
from exuclear.models import journal_bearing as jb_model
from exuclear.models import slider_crank as sc_model
from exuclear.models.journal_bearing import JournalBearingParams
from exuclear.models.slider_crank import SliderCrankParams
from validation.hard_cases.common import DROPPED_TIME, QUICK_REVOLUTIONS, REVOLUTIONS, SLOW_ATOL, SLOW_IMPACT_TIME, SLOW_RTOL, SLOW_STEP
from validation.hard_cases.journal import JournalRun, final_error, resting_params, run_journal, settle_time

# =======================================================================================
# the floor v_min
# =======================================================================================

#: Floors compared [m/s]; 1e-3 is the default (docs/physics.md eq. (17)).
FLOORS = (1e-4, 1e-3, 1e-2)
#: Impact speeds of the effective-restitution comparison [m/s] (Wang-Liu, cr = 0.5: a
#: damped law, where the floor shows).
FLOOR_SPEEDS = (1e-6, 1e-4, 1e-3, 1e-2, 0.3)
FLOOR_CR = 0.5
#: Gravity of the loaded resting journal [m/s^2]: 0.04 kg * 2500 m/s^2 = 100 N, a
#: contact force of the slider-crank's permanent contact, on the light journal: there
#: the damping term of a contact begun at v0 < v_min is stiffest, D F / (v_min m).
LOADED_GRAVITY = 2500.0


@dataclass
class FloorRow:
    """The cases of the floor study at one ``v_min``."""

    v_min: float
    restitution: dict[float, float]     # impact speed -> effective restitution
    resting_settle: float               # [s]
    resting_steps: int
    loaded_steps: int
    loaded_settle: float
    dropped_impacts: int
    dropped_last: float                 # [s]
    dropped_error: float
    crank_steps: int
    crank_impacts: int
    crank_peak: float
    wall: float


def floor_row(v_min: float, quick: bool) -> tuple[FloorRow, JournalRun, JournalRun]:
    """The low-speed cases at the floor ``v_min``; with the resting and the dropped run (for the figure)."""
    start = time.perf_counter()
    c = JournalBearingParams.paper().joint().geometry.clearance
    speeds = FLOOR_SPEEDS[:3] if quick else FLOOR_SPEEDS
    restitution = {}
    for v in speeds:
        p = JournalBearingParams.paper(cr=FLOOR_CR, impact_velocity=v, v_min=v_min,
                                       end_time=SLOW_IMPACT_TIME if v < 1e-2 else jb_model.DEFAULT_END_TIME)
        settings = exuclear.SolverSettings(end_time=p.end_time, method="dopri5", step=SLOW_STEP if v < 1e-2 else 1e-7,
                                           rtol=SLOW_RTOL, atol=SLOW_ATOL, output_step=1e-7)
        restitution[v] = jb_model.run(p, settings)[0].effective_restitution
    resting = run_journal(resting_params(v_min=v_min))
    loaded = run_journal(resting_params(v_min=v_min, gravity=LOADED_GRAVITY))
    dropped = run_journal(resting_params(start_gap=c, v_min=v_min, end_time=DROPPED_TIME))
    crank = sc_model.run(SliderCrankParams.paper(v_min=v_min, revolutions=QUICK_REVOLUTIONS if quick else REVOLUTIONS))
    row = FloorRow(v_min, restitution, settle_time(resting), resting.sim.steps, loaded.sim.steps,
                   settle_time(loaded), len(dropped.onsets), dropped.onsets[-1] if dropped.onsets else math.nan,
                   final_error(dropped), crank.steps, crank.impacts, crank.peak_force, time.perf_counter() - start)
    return row, resting, dropped
